// vgroove sim: the first reflections of a block of rays in their own symmetric grooves
// (symmetric_block.h). Compiled with -fno-trapping-math (sim/CMakeLists.txt): both sides of a
// select may be computed; no value changes.
#include "vgroove/sim/symmetric_block.h"

#include "vgroove/common/simd.h"

#include <cmath>
#include <cstring>

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

namespace {

// Four lanes (common/simd.h): comparisons give masks of 64-bit integers, 0 or -1.
using V = simd::V4;
using VI = simd::I4;
using simd::load;
using simd::splat;
[[gnu::always_inline]] inline V vabs(V a) { return simd::abs(a); }

}  // namespace

// Four rays per instruction in the AVX2 copy (common/simd.h); every lane rounds as trace() does.
VGROOVE_TARGET_CLONES
void first_reflections(const SymmetricBlock& in, int n, SymmetricHits& out) {
  const V zero = splat(0.0), one = splat(1.0), minus_one = splat(-1.0);
  // Lanes [j, j + 4): full groups from the block, the last partial one from copies padded with
  // its first lane (whose results are not stored twice).
  for (int j = 0; j < n; j += 4) {
    const int count = n - j < 4 ? n - j : 4;
    double pad[6][4];
    const double* src[6] = {in.x + j, in.dx + j, in.dy + j, in.left_x + j, in.right_x + j, in.rim_height + j};
    if (count < 4) {
      for (int a = 0; a < 6; ++a) {
        for (int l = 0; l < 4; ++l) pad[a][l] = src[a][l < count ? l : 0];
        src[a] = pad[a];
      }
    }
    const V x = load(src[0]), dx = load(src[1]), dy = load(src[2]);
    const V lx = load(src[3]), rx = load(src[4]), c = load(src[5]);
    const V s_half = -lx;  // sin(half): the normals' y
    // trace(): inside the opening (the rims' x are the edges' x times the unit length).
    const VI inside = (x > lx) & (x < rx);
    // sn = cross(origin, d), origin = (x, rim_height); den_f = cross(e_f, d).
    const V sn = x * dy - c * dx;
    const V den_l = lx * dy - c * dx, den_r = rx * dy - c * dx;
    // trace(): one facet excluded by the numerator's sign (sn den < 0), and hit_facet_with on the
    // other; otherwise (rays more grazing than a facet) hit_facet_from_rim_line on both, the left
    // taken if met and not farther than the right. A missed facet gives s = -1.
    const V tn_l = x * c - c * lx, tn_r = x * c - c * rx;
    const VI away_l = sn * den_l < 0.0, away_r = sn * den_r < 0.0;
    const VI both = ~(away_l ^ away_r);
    VI right;
    V s;
    if (!(both[0] | both[1] | both[2] | both[3])) {
      // Every lane with one facet excluded (all rays at normal incidence): one division.
      // The general form below gives these lanes the same s, and the same facet where one is met.
      right = away_l;
      const V den = right ? den_r : den_l, tn = right ? tn_r : tn_l;
      const VI miss = (den == 0.0) | (tn * den < 0.0) | (vabs(sn) > 1.0 * vabs(den));
      s = miss ? minus_one : sn / (den != 0.0 ? den : one);
    } else {
      // hit_facet_from_rim_line on each facet: missed (s = -1, t = 0) when den = 0, cross(p, e)
      // den < 0, sn den < 0 or |sn| > length |den|; else s = sn / den, t = cross(p, e) / den.
      const VI miss_l = (den_l == 0.0) | (tn_l * den_l < 0.0) | away_l | (vabs(sn) > 1.0 * vabs(den_l));
      const VI miss_r = (den_r == 0.0) | (tn_r * den_r < 0.0) | away_r | (vabs(sn) > 1.0 * vabs(den_r));
      const V q_l = den_l != 0.0 ? den_l : one, q_r = den_r != 0.0 ? den_r : one;
      const V s_l = miss_l ? minus_one : sn / q_l, s_r = miss_r ? minus_one : sn / q_r;
      const V t_l = miss_l ? zero : tn_l / q_l, t_r = miss_r ? zero : tn_r / q_r;
      // Both cases in one flag: the left excluded gives the right; else the left unless missed or
      // farther (with the right excluded, s_r = -1: the left if met, else s = -1 either way).
      right = away_l | ~(s_l >= 0.0) | ~((s_r < 0.0) | (t_l <= t_r));
      s = right ? s_r : s_l;
    }
    const V ex = right ? rx : lx;  // the hit facet's edge (ex, c)
    // s < 0 (no facet met) or NaN: path 2, as the apex and the rims (s = 0, 1).
    // bounce(): not on the apex or the rim; reflect with I - 2 n n^T (finish_groove's products).
    const VI ok = inside & (s > 0.0) & (s != 1.0);
    const V nx = right ? -c : c;
    const V r_xx = 1.0 - 2.0 * nx * nx, r_xy = -2.0 * nx * s_half, r_yy = 1.0 - 2.0 * s_half * s_half;
    const V d1x = r_xx * dx + r_xy * dy, d1y = r_xy * dx + r_yy * dy;
    // The other facet o: den' = cross(e_o, d'); it leaves unless den' turn > 0, turn = cross(e_f, e_o).
    const V ox = right ? lx : rx;
    const V den1 = ox * d1y - c * d1x;
    const V turn = ex * c - c * ox;
    const V cf = ex * d1y - c * d1x;  // cross(e_f, d')
    const VI leaves = ~(den1 * turn > 0.0) | (cf * den1 < 0.0) | (s * vabs(cf) > 1.0 * vabs(den1));
    const V s1 = s * (cf / (den1 != 0.0 ? den1 : one));
    const VI path = ok ? (leaves ? VI{0, 0, 0, 0} : VI{1, 1, 1, 1}) : VI{2, 2, 2, 2};
    const VI f = -right, on = 1 + right, k = VI{1, 1, 1, 1};
    if (count == 4) {
      std::memcpy(out.s + j, &s1, sizeof s1);
      std::memcpy(out.d1x + j, &d1x, sizeof d1x);
      std::memcpy(out.d1y + j, &d1y, sizeof d1y);
      std::memcpy(out.f + j, &f, sizeof f);
      std::memcpy(out.on + j, &on, sizeof on);
      std::memcpy(out.k + j, &k, sizeof k);
      std::memcpy(out.path + j, &path, sizeof path);
      continue;
    }
    for (int l = 0; l < count; ++l) {
      out.s[j + l] = s1[l], out.d1x[j + l] = d1x[l], out.d1y[j + l] = d1y[l];
      out.f[j + l] = f[l], out.on[j + l] = on[l], out.k[j + l] = 1, out.path[j + l] = path[l];
    }
  }
}

namespace {

[[gnu::always_inline]] inline VI load_i(const std::int64_t* p) { return simd::load(p); }

// One reflection of lanes [j, j + 4) of (in, h) on path 1 (next_reflections); the lanes still on
// path 1 after it, as -1 per lane.
[[gnu::always_inline]] inline VI reflect_four(const double* lx_p, const double* rx_p, const double* c_p, double* s_p,
                                              double* dx_p, double* dy_p, std::int64_t* k_p, std::int64_t* on_p,
                                              std::int64_t* path_p, std::int64_t max_bounces) {
  const V one = splat(1.0);
  const VI old_path = load_i(path_p);
  const VI live = old_path == 1;
  const V lx = load(lx_p), rx = load(rx_p), c = load(c_p);
  const V s_half = -lx;
  const VI on = load_i(on_p);
  const VI right = on != 0;
  const V ex = right ? rx : lx, ox = right ? lx : rx;  // the facet's edge, the other's
  const V s = load(s_p), dx = load(dx_p), dy = load(dy_p);
  const VI k = load_i(k_p);
  // bounce(): the apex or the rim exactly; the bounce limit; reflect; the other facet's tests.
  const VI vertex = (s == 0.0) | (s == 1.0);
  const VI limit = k == max_bounces;
  const V nx = right ? -c : c;
  const V r_xx = 1.0 - 2.0 * nx * nx, r_xy = -2.0 * nx * s_half, r_yy = 1.0 - 2.0 * s_half * s_half;
  const V d1x = r_xx * dx + r_xy * dy, d1y = r_xy * dx + r_yy * dy;
  const V den1 = ox * d1y - c * d1x;
  const V turn = ex * c - c * ox;
  const V cf = ex * d1y - c * d1x;
  const VI leaves = ~(den1 * turn > 0.0) | (cf * den1 < 0.0) | (s * vabs(cf) > 1.0 * vabs(den1));
  const VI path = vertex ? VI{3, 3, 3, 3} : (limit ? VI{4, 4, 4, 4} : (leaves ? VI{0, 0, 0, 0} : VI{1, 1, 1, 1}));
  const VI moved = live & ~vertex & ~limit;  // reflected this round (-1)
  const V s1 = (moved & ~leaves) ? s * (cf / (den1 != 0.0 ? den1 : one)) : s;
  const V x1 = moved ? d1x : dx, y1 = moved ? d1y : dy;
  const VI k1 = k - moved, on1 = moved ? 1 - on : on, path1 = live ? path : old_path;
  std::memcpy(s_p, &s1, sizeof s1);
  std::memcpy(dx_p, &x1, sizeof x1);
  std::memcpy(dy_p, &y1, sizeof y1);
  std::memcpy(k_p, &k1, sizeof k1);
  std::memcpy(on_p, &on1, sizeof on1);
  std::memcpy(path_p, &path1, sizeof path1);
  return live & (path == 1);
}

}  // namespace

VGROOVE_TARGET_CLONES
int next_reflections(const SymmetricBlock& in, int n, int max_bounces, SymmetricHits& h) {
  // Four lanes at a time, every comparison made and the results picked by selects; the last
  // partial group from copies padded with lanes on no path (-1), whose values are not stored.
  VI still = {0, 0, 0, 0};
  int j = 0;
  for (; j + 4 <= n; j += 4) {
    still -= reflect_four(in.left_x + j, in.right_x + j, in.rim_height + j, h.s + j, h.d1x + j, h.d1y + j, h.k + j,
                          h.on + j, h.path + j, max_bounces);
  }
  if (j < n) {
    const int count = n - j;
    double lx[4] = {0, 0, 0, 0}, rx[4] = {1, 1, 1, 1}, c[4] = {1, 1, 1, 1}, s[4] = {0.5, 0.5, 0.5, 0.5};
    double dx[4] = {0, 0, 0, 0}, dy[4] = {1, 1, 1, 1};
    std::int64_t k[4] = {1, 1, 1, 1}, on[4] = {0, 0, 0, 0}, path[4] = {-1, -1, -1, -1};
    for (int l = 0; l < count; ++l) {
      lx[l] = in.left_x[j + l], rx[l] = in.right_x[j + l], c[l] = in.rim_height[j + l];
      s[l] = h.s[j + l], dx[l] = h.d1x[j + l], dy[l] = h.d1y[j + l];
      k[l] = h.k[j + l], on[l] = h.on[j + l], path[l] = h.path[j + l];
    }
    still -= reflect_four(lx, rx, c, s, dx, dy, k, on, path, max_bounces);
    for (int l = 0; l < count; ++l) {
      h.s[j + l] = s[l], h.d1x[j + l] = dx[l], h.d1y[j + l] = dy[l];
      h.k[j + l] = k[l], h.on[j + l] = on[l], h.path[j + l] = path[l];
    }
  }
  return static_cast<int>(still[0] + still[1] + still[2] + still[3]);
}

void block_reflections(const SymmetricBlock& in, int n, int max_bounces, int rounds, SymmetricHits& h) {
  first_reflections(in, n, h);
  int active = 0;
  for (int j = 0; j < n; ++j) active += h.path[j] == 1;
  int r = 0;
  for (; r < rounds && 4 * active >= n; ++r) active = next_reflections(in, n, max_bounces, h);
  if (r == rounds || active < kBlockMinLanes) return;
  // The lanes on path 1, gathered: packed lane q is the block's lane lane[q], its groove in pin
  // and its state in ph (what next_reflections reads and writes).
  SymmetricBlock pin;
  SymmetricHits ph;
  int lane[kSymmetricBlock];
  int m = 0;
  // Packed lane `to` from lane j of (gi, gh), which is the block's lane `block_lane`.
  auto pack = [&](int to, int j, int block_lane, const SymmetricBlock& gi, const SymmetricHits& gh) {
    lane[to] = block_lane;
    pin.left_x[to] = gi.left_x[j], pin.right_x[to] = gi.right_x[j], pin.rim_height[to] = gi.rim_height[j];
    ph.s[to] = gh.s[j], ph.d1x[to] = gh.d1x[j], ph.d1y[to] = gh.d1y[j];
    ph.on[to] = gh.on[j], ph.k[to] = gh.k[j], ph.path[to] = 1;
  };
  for (int j = 0; j < n; ++j) {
    if (h.path[j] == 1) pack(m++, j, j, in, h);
  }
  auto put_back = [&](int q) {
    const int j = lane[q];
    h.s[j] = ph.s[q], h.d1x[j] = ph.d1x[q], h.d1y[j] = ph.d1y[q];
    h.on[j] = ph.on[q], h.k[j] = ph.k[q], h.path[j] = ph.path[q];
  };
  for (; r < rounds && active >= kBlockMinLanes; ++r) {
    if (4 * active < m) {
      // The lanes that settled go back to the block; the others are gathered again, in order.
      int w = 0;
      for (int q = 0; q < m; ++q) {
        if (ph.path[q] != 1) {
          put_back(q);
        } else {
          pack(w++, q, lane[q], pin, ph);  // w <= q: nothing unread is overwritten
        }
      }
      m = w;
    }
    active = next_reflections(pin, m, max_bounces, ph);
  }
  for (int q = 0; q < m; ++q) put_back(q);
}

}  // namespace vgroove::sim
