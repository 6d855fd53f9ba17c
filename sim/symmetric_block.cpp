// vgroove sim: the first reflections of a block of rays in their own symmetric grooves
// (symmetric_block.h). Compiled with -fno-trapping-math (sim/CMakeLists.txt): both sides of a
// select may be computed; no value changes.
#include "vgroove/sim/symmetric_block.h"

#include <cmath>

namespace vgroove::sim {

SymmetricGrooveData symmetric_groove_data(const Groove& g) {
  return {g.facet[0].edge.x(), g.facet[1].edge.x(), g.rim_height};
}

Groove symmetric_groove_from(const SymmetricGrooveData& d) {
  // make_symmetric_groove: edges direction_at(+-half) = (-+sin half, cos half), unit lengths,
  // normals (cos half, sin half) and (-cos half, sin half), rim height cos half.
  Groove g;
  const double c = d.rim_height, s = -d.left_x;  // cos(half), sin(half)
  g.facet[0].edge = Vec2(d.left_x, c);
  g.facet[1].edge = Vec2(d.right_x, c);
  for (Facet& f : g.facet) f.length = 1.0;
  g.facet[0].normal = Vec2(c, s);
  g.facet[1].normal = Vec2(-c, s);
  g.rim_height = c;
  g.theta_v = 0.0;  // not read by the tracer
  finish_groove(g);
  return g;
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
// One copy for AVX2 (four rays per instruction) and one for any x86-64, picked when the program
// starts. AVX2 without FMA: no product is fused, so every lane rounds as trace() does.
[[gnu::target_clones("avx2", "default")]]
#endif
void first_reflections(const SymmetricBlock& in, int n, SymmetricHits& out) {
  for (int j = 0; j < n; ++j) {
    const double x = in.x[j], dx = in.dx[j], dy = in.dy[j];
    const double lx = in.left_x[j], rx = in.right_x[j], c = in.rim_height[j];
    const double s_half = -lx;  // sin(half): the normals' y
    // trace(): inside the opening (the rims' x are the edges' x times the unit length).
    const std::int64_t inside = (x > lx) & (x < rx);
    // sn = cross(origin, d), origin = (x, rim_height); den_f = cross(e_f, d).
    const double sn = x * dy - c * dx;
    const double den_l = lx * dy - c * dx, den_r = rx * dy - c * dx;
    const std::int64_t away_l = sn * den_l < 0.0, away_r = sn * den_r < 0.0;
    // One facet excluded by the numerator's sign; otherwise trace() tests both (path 2).
    const std::int64_t right = away_l;
    const double ex = right ? rx : lx;  // the hit facet's edge (ex, c)
    const double den = right ? den_r : den_l;
    // hit_facet_with: den != 0, cross(p, e) den >= 0, |sn| <= length |den|; s = sn / den.
    const double tn = x * c - c * ex;
    const std::int64_t hit =
        (away_l ^ away_r) & (den != 0.0) & !(tn * den < 0.0) & !(std::abs(sn) > 1.0 * std::abs(den));
    const double s = sn / (den != 0.0 ? den : 1.0);
    // bounce(): not on the apex or the rim; reflect with I - 2 n n^T (finish_groove's products).
    const std::int64_t ok = inside & hit & (s > 0.0) & (s != 1.0);
    const double nx = right ? -c : c;
    const double r_xx = 1.0 - 2.0 * nx * nx, r_xy = -2.0 * nx * s_half, r_yy = 1.0 - 2.0 * s_half * s_half;
    const double d1x = r_xx * dx + r_xy * dy, d1y = r_xy * dx + r_yy * dy;
    // The other facet o: den' = cross(e_o, d'); it leaves unless den' turn > 0, turn = cross(e_f, e_o).
    const double ox = right ? lx : rx;
    const double den1 = ox * d1y - c * d1x;
    const double turn = ex * c - c * ox;
    const double cf = ex * d1y - c * d1x;  // cross(e_f, d')
    const std::int64_t leaves = !(den1 * turn > 0.0) | (cf * den1 < 0.0) | (s * std::abs(cf) > 1.0 * std::abs(den1));
    out.s[j] = s * (cf / (den1 != 0.0 ? den1 : 1.0));
    out.d1x[j] = d1x;
    out.d1y[j] = d1y;
    out.f[j] = right;
    out.on[j] = 1 - right;
    out.k[j] = 1;
    out.path[j] = ok ? (leaves ? 0 : 1) : 2;
  }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
[[gnu::target_clones("avx2", "default")]]
#endif
int next_reflections(const SymmetricBlock& in, int n, int max_bounces, SymmetricHits& h) {
  int active = 0;
  for (int j = 0; j < n; ++j) {
    const std::int64_t live = h.path[j] == 1;
    const double lx = in.left_x[j], rx = in.right_x[j], c = in.rim_height[j];
    const double s_half = -lx;
    const std::int64_t right = h.on[j];
    const double ex = right ? rx : lx, ox = right ? lx : rx;  // the facet's edge, the other's
    const double s = h.s[j], dx = h.d1x[j], dy = h.d1y[j];
    const std::int64_t k = h.k[j];
    // bounce(): the apex or the rim exactly; the bounce limit; reflect; the other facet's tests.
    const std::int64_t vertex = (s == 0.0) | (s == 1.0);
    const std::int64_t limit = k == max_bounces;
    const double nx = right ? -c : c;
    const double r_xx = 1.0 - 2.0 * nx * nx, r_xy = -2.0 * nx * s_half, r_yy = 1.0 - 2.0 * s_half * s_half;
    const double d1x = r_xx * dx + r_xy * dy, d1y = r_xy * dx + r_yy * dy;
    const double den1 = ox * d1y - c * d1x;
    const double turn = ex * c - c * ox;
    const double cf = ex * d1y - c * d1x;
    const std::int64_t leaves = !(den1 * turn > 0.0) | (cf * den1 < 0.0) | (s * std::abs(cf) > 1.0 * std::abs(den1));
    const std::int64_t path = vertex ? 3 : (limit ? 4 : (leaves ? 0 : 1));
    const std::int64_t moved = live & !vertex & !limit;  // reflected this round
    h.s[j] = moved & !leaves ? s * (cf / (den1 != 0.0 ? den1 : 1.0)) : s;
    h.d1x[j] = moved ? d1x : dx;
    h.d1y[j] = moved ? d1y : dy;
    h.k[j] = moved ? k + 1 : k;
    h.on[j] = moved ? 1 - right : right;
    h.path[j] = live ? path : h.path[j];
    active += static_cast<int>(live & (path == 1));
  }
  return active;
}

}  // namespace vgroove::sim
