#include "vgroove/sim/heightfield_tracer.h"

#include "vgroove/sim/effects.h"
#include "vgroove/sim/rng.h"
#include "vgroove/sim/triangle_watertight.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <type_traits>

namespace vgroove::sim {
namespace {

using Vec3 = Eigen::Vector3d;

// How far the hierarchy's boxes and heights are widened (header: rounding never skips a triangle).
constexpr double kBoxSlack = 0x1.0p-20;

// A triangle of the tiling: cell (cx, cy) in the current frame (any integers), half 0 or 1.
struct Tri {
  std::int64_t cx = 0, cy = 0;
  int half = 0;
  bool operator==(const Tri&) const = default;
};

// The incident triangles of a hit feature (1, 2 or 6), and the feature itself.
struct Feature {
  int kind = 0;                     // 0 interior, 1 edge, 2 vertex
  std::array<std::int64_t, 2> p{};  // the vertex (kind 2) or the edge's first vertex (kind 1)
  std::array<std::int64_t, 2> q{};  // the edge's second vertex (kind 1)
  std::array<Tri, 6> tris{};
  int count = 0;
};

struct Tracer {
  const HeightfieldSurface& s;
  const HeightfieldRayOptions& opt;
  std::int64_t n;
  int top;  // the hierarchy's last level

  Tracer(const HeightfieldSurface& s_, const HeightfieldRayOptions& opt_)
      : s(s_), opt(opt_), n(s_.field.n), top(s_.hierarchy.levels - 1) {}

  // The vertices of triangle t (counter-clockwise seen from above).
  std::array<std::array<std::int64_t, 2>, 3> corners(const Tri& t) const {
    if (t.half == 0) return {{{t.cx, t.cy}, {t.cx + 1, t.cy}, {t.cx + 1, t.cy + 1}}};
    return {{{t.cx, t.cy}, {t.cx + 1, t.cy + 1}, {t.cx, t.cy + 1}}};
  }
  Vec3 vertex(const std::array<std::int64_t, 2>& v) const {
    return Vec3(static_cast<double>(v[0]), static_cast<double>(v[1]), s.field.height(v[0], v[1]));
  }
  // Upward normal (-s_x, -s_y, 1), not normalized (sim/heightfield.h).
  Vec3 normal(const Tri& t) const {
    const double h00 = s.field.height(t.cx, t.cy), h11 = s.field.height(t.cx + 1, t.cy + 1);
    if (t.half == 0) {
      const double h10 = s.field.height(t.cx + 1, t.cy);
      return Vec3(-(h10 - h00), -(h11 - h10), 1.0);
    }
    const double h01 = s.field.height(t.cx, t.cy + 1);
    return Vec3(-(h11 - h01), -(h01 - h00), 1.0);
  }

  // Nearest hit search state of one segment.
  WatertightRay wr;
  Vec3 org, dir;
  const Feature* excluded = nullptr;
  double t_best = std::numeric_limits<double>::infinity();
  bool found = false;
  Tri best_tri;
  WatertightHit best_hit;

  bool is_excluded(const Tri& t) const {
    for (int q = 0; q < excluded->count; ++q)
      if (excluded->tris[static_cast<std::size_t>(q)] == t) return true;
    return false;
  }

  void test_triangle(const Tri& t) {
    if (is_excluded(t)) return;
    const auto c = corners(t);
    WatertightHit h;
    if (!intersect_watertight(wr, vertex(c[0]), vertex(c[1]), vertex(c[2]), t_best, h)) return;
    t_best = h.t();
    found = true;
    best_tri = t;
    best_hit = h;
  }

  // The ray's parameter interval over [x0, x1] x [y0, y1] (widened), clipped to [0, t_best].
  bool slab(double x0, double x1, double y0, double y1, double& lo, double& hi) const {
    lo = 0.0;
    hi = t_best;
    const double b[2][2] = {{x0 - kBoxSlack, x1 + kBoxSlack}, {y0 - kBoxSlack, y1 + kBoxSlack}};
    for (int a = 0; a < 2; ++a) {
      const double o = org[a], d = dir[a];
      if (d == 0.0) {
        if (o < b[a][0] || o > b[a][1]) return false;
        continue;
      }
      double t0 = (b[a][0] - o) / d, t1 = (b[a][1] - o) / d;
      if (t0 > t1) std::swap(t0, t1);
      lo = std::max(lo, t0);
      hi = std::min(hi, t1);
    }
    return lo <= hi;
  }

  // Node (i, j) of level k in the tile whose first cell is (bx, by).
  void descend(int k, std::int64_t bx, std::int64_t by, std::int64_t i, std::int64_t j) {
    const std::int64_t size = std::int64_t{1} << k;
    const double x0 = static_cast<double>(bx + i * size), y0 = static_cast<double>(by + j * size);
    double lo = 0.0, hi = 0.0;
    if (!slab(x0, x0 + static_cast<double>(size), y0, y0 + static_cast<double>(size), lo, hi)) return;
    const HeightBounds& b = s.hierarchy.node(k, static_cast<int>(i), static_cast<int>(j));
    const double z_lo = std::min(org.z() + lo * dir.z(), org.z() + hi * dir.z());
    if (z_lo > b.hi + kBoxSlack * std::max(1.0, std::abs(b.hi))) return;  // passes above the node
    if (k == 0) {
      test_triangle(Tri{bx + i, by + j, 0});
      test_triangle(Tri{bx + i, by + j, 1});
      return;
    }
    // Children nearest first along the ray (any order is correct: t_best prunes).
    const int fx = dir.x() < 0.0 ? 1 : 0, fy = dir.y() < 0.0 ? 1 : 0;
    for (int c = 0; c < 4; ++c) {
      const int cx = (c & 1) ^ fx, cy = (c >> 1) ^ fy;
      descend(k - 1, bx, by, 2 * i + cx, 2 * j + cy);
    }
  }

  // The nearest hit of the segment from org along dir, over the tiles it crosses; false when the
  // ray escapes. `lost` is set when it cannot be escaping or hitting (header).
  bool nearest_hit(bool& lost) {
    lost = false;
    found = false;
    t_best = std::numeric_limits<double>::infinity();
    wr = make_watertight_ray(org, dir);
    const HeightBounds& root = s.hierarchy.root();
    const double nd = static_cast<double>(n);
    std::int64_t tx = static_cast<std::int64_t>(std::floor(org.x() / nd));
    std::int64_t ty = static_cast<std::int64_t>(std::floor(org.y() / nd));
    const int sx = dir.x() > 0.0 ? 1 : (dir.x() < 0.0 ? -1 : 0);
    const int sy = dir.y() > 0.0 ? 1 : (dir.y() < 0.0 ? -1 : 0);
    const double inf = std::numeric_limits<double>::infinity();
    for (std::int64_t tiles = 0;; ++tiles) {
      // Where the ray leaves this tile (x and y boundaries), from the exact integer boundary.
      const double tnx = sx == 0 ? inf : ((static_cast<double>(tx + (sx > 0)) * nd) - org.x()) / dir.x();
      const double tny = sy == 0 ? inf : ((static_cast<double>(ty + (sy > 0)) * nd) - org.y()) / dir.y();
      // The tiles the ray's xy path crosses, in order (Amanatides-Woo over whole periods).
      const std::int64_t bx = tx * n, by = ty * n;
      descend(top, bx, by, 0, 0);
      const double t_exit = std::min(tnx, tny);
      if (found && t_best <= t_exit) return true;
      if (t_exit == inf) {  // vertical ray: one tile only
        if (found) return true;
        lost = !(dir.z() > 0.0);
        return false;
      }
      // Past this tile: escaping, lost, or on to the next tile.
      const double z_exit = org.z() + t_exit * dir.z();
      const double slack = kBoxSlack * std::max(1.0, std::abs(root.hi));
      if (dir.z() > 0.0 && z_exit > root.hi + slack) {
        if (found) return true;
        return false;
      }
      if (dir.z() < 0.0 && z_exit < root.lo - slack) {
        if (found) return true;
        lost = true;
        return false;
      }
      if (tiles >= opt.max_tiles) {
        if (found) return true;
        lost = true;
        return false;
      }
      // Leaving near a corner, the rounded crossing distances may order the two side tiles
      // wrongly: descend both before the diagonal one.
      if (sx != 0 && sy != 0 && tnx != tny && std::abs(tnx - tny) <= 0x1.0p-30 * std::max(tnx, tny)) {
        descend(top, (tx + sx) * n, ty * n, 0, 0);
        descend(top, tx * n, (ty + sy) * n, 0, 0);
        tx += sx;
        ty += sy;
        continue;
      }
      if (tnx <= tny) tx += sx;
      if (tny <= tnx) ty += sy;
    }
  }
};

// The hit's feature: which weights are exactly 0, and the triangles touching it.
Feature feature_of(const Tri& t, const WatertightHit& h, const std::array<std::array<std::int64_t, 2>, 3>& c) {
  Feature f;
  const bool u0 = h.U == 0.0, v0 = h.V == 0.0, w0 = h.W == 0.0;
  const int zeros = u0 + v0 + w0;
  if (zeros == 0) {
    f.kind = 0;
    f.tris[0] = t;
    f.count = 1;
    return f;
  }
  if (zeros >= 2) {  // the vertex whose weight is not 0
    f.kind = 2;
    f.p = !u0 ? c[0] : (!v0 ? c[1] : c[2]);
    const std::int64_t gx = f.p[0], gy = f.p[1];
    f.tris = {Tri{gx, gy, 0},         Tri{gx, gy, 1},         Tri{gx - 1, gy, 0},
              Tri{gx - 1, gy - 1, 1}, Tri{gx - 1, gy - 1, 0}, Tri{gx, gy - 1, 1}};
    f.count = 6;
    return f;
  }
  f.kind = 1;
  f.tris[0] = t;
  f.count = 2;
  // The edge opposite the vertex of weight 0, and the triangle across it (sim/heightfield.h).
  if (u0) {  // v1 v2
    f.p = c[1];
    f.q = c[2];
    f.tris[1] = t.half == 0 ? Tri{t.cx + 1, t.cy, 1} : Tri{t.cx, t.cy + 1, 0};
  } else if (v0) {  // v2 v0
    f.p = c[2];
    f.q = c[0];
    f.tris[1] = t.half == 0 ? Tri{t.cx, t.cy, 1} : Tri{t.cx - 1, t.cy, 0};
  } else {  // v0 v1
    f.p = c[0];
    f.q = c[1];
    f.tris[1] = t.half == 0 ? Tri{t.cx, t.cy - 1, 1} : Tri{t.cx, t.cy, 0};
  }
  return f;
}

// cross((ex, ey), (dx, dy)) for an integer edge with components in {-1, 0, 1}: exact sign.
double cross2(std::int64_t ex, std::int64_t ey, double dx, double dy) {
  return static_cast<double>(ex) * dy - static_cast<double>(ey) * dx;
}

// Does the direction d, leaving the feature, enter triangle t's xy sector there?
bool enters(const Feature& f, const std::array<std::array<std::int64_t, 2>, 3>& c, const Vec3& d) {
  if (f.kind == 0) return true;
  if (f.kind == 2) {
    int m = 0;
    while (c[static_cast<std::size_t>(m)] != f.p) ++m;
    const auto& a = c[static_cast<std::size_t>((m + 1) % 3)];
    const auto& b = c[static_cast<std::size_t>((m + 2) % 3)];
    return cross2(a[0] - f.p[0], a[1] - f.p[1], d.x(), d.y()) >= 0.0 &&
           cross2(b[0] - f.p[0], b[1] - f.p[1], d.x(), d.y()) <= 0.0;
  }
  // Edge p q: the third vertex r's side, or along the edge.
  int m = 0;
  while (c[static_cast<std::size_t>(m)] == f.p || c[static_cast<std::size_t>(m)] == f.q) ++m;
  const auto& r = c[static_cast<std::size_t>(m)];
  const std::int64_t ex = f.q[0] - f.p[0], ey = f.q[1] - f.p[1];
  const double side_r = cross2(ex, ey, static_cast<double>(r[0] - f.p[0]), static_cast<double>(r[1] - f.p[1]));
  const double side_d = cross2(ex, ey, d.x(), d.y());
  return side_d == 0.0 || (side_d > 0.0) == (side_r > 0.0);
}

template <bool kRecord, class Reflectance>
HeightfieldRayResult trace_ray(const HeightfieldSurface& s, const Vec3& org0, const Vec3& dir0,
                               const HeightfieldRayOptions& opt, const Reflectance& F) {
  if constexpr (kRecord) opt.cosines->clear();
  Tracer tr(s, opt);
  HeightfieldRayResult res;
  Feature none;
  none.count = 0;
  Feature feat = none;
  tr.org = org0;
  tr.dir = dir0;
  const double nd = static_cast<double>(s.field.n);
  for (;;) {
    // Move the origin into the first period: whole periods, exact; the excluded triangles move along.
    const std::int64_t kx = static_cast<std::int64_t>(std::floor(tr.org.x() / nd));
    const std::int64_t ky = static_cast<std::int64_t>(std::floor(tr.org.y() / nd));
    if (kx != 0 || ky != 0) {
      tr.org.x() -= static_cast<double>(kx * s.field.n);
      tr.org.y() -= static_cast<double>(ky * s.field.n);
      for (int q = 0; q < feat.count; ++q) {
        feat.tris[static_cast<std::size_t>(q)].cx -= kx * s.field.n;
        feat.tris[static_cast<std::size_t>(q)].cy -= ky * s.field.n;
      }
      for (auto* v : {&feat.p, &feat.q}) {
        (*v)[0] -= kx * s.field.n;
        (*v)[1] -= ky * s.field.n;
      }
    }
    tr.excluded = &feat;
    bool lost = false;
    if (!tr.nearest_hit(lost)) {
      res.how = lost ? HeightfieldFate::lost : HeightfieldFate::escaped;
      res.o = tr.dir;
      return res;
    }
    const Tri t = tr.best_tri;
    const auto c = tr.corners(t);
    const WatertightHit h = tr.best_hit;
    feat = feature_of(t, h, c);
    // The hit point: the vertex itself, or the weights' combination of the corners.
    Vec3 p;
    if (feat.kind == 2) {
      p = tr.vertex(feat.p);
    } else {
      p = (h.U * tr.vertex(c[0]) + h.V * tr.vertex(c[1]) + h.W * tr.vertex(c[2])) / h.det;
    }
    res.edge_hits += feat.kind == 1;
    res.vertex_hits += feat.kind == 2;
    // Reflect off the triangle hit, then off any touching triangle the direction enters from below.
    Tri refl = t;
    for (;;) {
      const Vec3 nrm = tr.normal(refl);
      const double dn = tr.dir.dot(nrm);
      const double nn = nrm.squaredNorm();
      // F = 1 and no cosines asked for: no cosine, no product. The cosine is clamped to 1 against rounding.
      if constexpr (kRecord || !std::is_same_v<Reflectance, UnitReflectance>) {
        const double cos_j = std::min(1.0, std::abs(dn) / std::sqrt(nn * tr.dir.squaredNorm()));
        if constexpr (kRecord) opt.cosines->push_back(cos_j);
        if constexpr (!std::is_same_v<Reflectance, UnitReflectance>) res.throughput *= F(cos_j);
      }
      tr.dir = tr.dir - (2.0 * dn / nn) * nrm;
      if (++res.bounces > opt.max_bounces) {
        res.how = HeightfieldFate::bounce_limit;
        return res;
      }
      bool again = false;
      for (int q = 0; q < feat.count && !again; ++q) {
        const Tri& u = feat.tris[static_cast<std::size_t>(q)];
        if (enters(feat, tr.corners(u), tr.dir) && tr.dir.dot(tr.normal(u)) < 0.0) {
          refl = u;
          again = true;
        }
      }
      if (!again) break;
    }
    tr.org = p;
  }
}

}  // namespace

HeightfieldSurface make_heightfield_surface(Heightfield f) {
  HeightfieldSurface s;
  s.hierarchy = make_heightfield_hierarchy(f);
  s.field = std::move(f);
  return s;
}

namespace {

template <bool kRecord>
HeightfieldRayResult trace_with(const HeightfieldSurface& s, const Vec3& org, const Vec3& dir,
                                const HeightfieldRayOptions& opt) {
  switch (opt.fresnel.kind) {
    case HeightfieldReflectance::unit:
      break;
    case HeightfieldReflectance::conductor:
      return trace_ray<kRecord>(s, org, dir, opt, ConductorReflectance{opt.fresnel.eta, opt.fresnel.kappa});
    case HeightfieldReflectance::dielectric:
      return trace_ray<kRecord>(s, org, dir, opt, DielectricReflectance{opt.fresnel.eta});
    case HeightfieldReflectance::schlick:
      return trace_ray<kRecord>(s, org, dir, opt, SchlickReflectance{opt.fresnel.F0});
  }
  return trace_ray<kRecord>(s, org, dir, opt, UnitReflectance{});
}

}  // namespace

HeightfieldRayResult trace_heightfield_ray(const HeightfieldSurface& s, const Vec3& org, const Vec3& dir,
                                           const HeightfieldRayOptions& opt) {
  // One test per ray: the traces without cosines are the code they were.
  return opt.cosines ? trace_with<true>(s, org, dir, opt) : trace_with<false>(s, org, dir, opt);
}

HeightfieldFirstHit first_heightfield_hit(const HeightfieldSurface& s, const Vec3& org, const Vec3& dir,
                                          const HeightfieldRayOptions& opt) {
  Tracer tr(s, opt);
  Feature none;
  none.count = 0;
  tr.excluded = &none;
  // The origin in the first period (whole periods: exact).
  const double nd = static_cast<double>(s.field.n);
  const auto kx = static_cast<std::int64_t>(std::floor(org.x() / nd));
  const auto ky = static_cast<std::int64_t>(std::floor(org.y() / nd));
  tr.org = org;
  tr.org.x() -= static_cast<double>(kx * s.field.n);
  tr.org.y() -= static_cast<double>(ky * s.field.n);
  tr.dir = dir;
  HeightfieldFirstHit r;
  bool lost = false;
  if (!tr.nearest_hit(lost)) {
    r.how = lost ? HeightfieldFate::lost : HeightfieldFate::escaped;
    return r;
  }
  const Tri t = tr.best_tri;
  const Feature f = feature_of(t, tr.best_hit, tr.corners(t));
  r.hit = true;
  r.cx = t.cx + kx * s.field.n;
  r.cy = t.cy + ky * s.field.n;
  r.half = t.half;
  r.edge = f.kind == 1;
  r.vertex = f.kind == 2;
  return r;
}

HeightfieldTally::HeightfieldTally(int theta_bins_, int phi_bins_, int max_k_, double phi_i_)
    : theta_bins(theta_bins_), phi_bins(phi_bins_), max_k(max_k_), phi_i(phi_i_) {
  by_k.assign(static_cast<std::size_t>(max_k + 2), 0);
  energy_by_k.assign(static_cast<std::size_t>(max_k + 2), 0.0);
  hist_by_k.assign(static_cast<std::size_t>(max_k + 2) * theta_bins * phi_bins, 0);
}

void HeightfieldTally::add(const HeightfieldRayResult& r) {
  ++rays;
  edge_hits += r.edge_hits;
  vertex_hits += r.vertex_hits;
  if (r.how == HeightfieldFate::bounce_limit) {
    ++bounce_limit;
    return;
  }
  if (r.how == HeightfieldFate::lost) {
    ++lost;
    return;
  }
  ++escaped;
  bounces += r.bounces;
  max_k_seen = std::max(max_k_seen, r.bounces);
  const int row = row_of(r.bounces);
  ++by_k[static_cast<std::size_t>(row)];
  energy_by_k[static_cast<std::size_t>(row)] += r.throughput;
  const Vec3 o = r.o.normalized();
  const double theta_w = 0.5 * std::numbers::pi / theta_bins, phi_w = 2.0 * std::numbers::pi / phi_bins;
  const int t = std::clamp(static_cast<int>(std::floor(std::acos(std::min(1.0, o.z())) / theta_w)), 0, theta_bins - 1);
  // Azimuth relative to the mirror azimuth phi_i - pi (the light at pi, as sim/microsurface3d.h).
  int p = static_cast<int>(std::floor((std::atan2(o.y(), o.x()) - (phi_i - std::numbers::pi)) / phi_w + 0.5));
  p %= phi_bins;
  if (p < 0) p += phi_bins;
  ++hist_by_k[index(row, t, p)];
}

void HeightfieldTally::merge(const HeightfieldTally& o) {
  rays += o.rays;
  escaped += o.escaped;
  bounce_limit += o.bounce_limit;
  lost += o.lost;
  bounces += o.bounces;
  edge_hits += o.edge_hits;
  vertex_hits += o.vertex_hits;
  max_k_seen = std::max(max_k_seen, o.max_k_seen);
  for (std::size_t q = 0; q < by_k.size(); ++q) {
    by_k[q] += o.by_k[q];
    energy_by_k[q] += o.energy_by_k[q];
  }
  for (std::size_t q = 0; q < hist_by_k.size(); ++q) hist_by_k[q] += o.hist_by_k[q];
}

double HeightfieldTally::energy() const {
  double e = 0.0;
  for (double x : energy_by_k) e += x;
  return e;
}

std::int64_t heightfield_chunk_count(const HeightfieldTraceOptions& opt) {
  return (opt.rays + kHeightfieldRaysPerChunk - 1) / kHeightfieldRaysPerChunk;
}

HeightfieldTally trace_heightfield_chunk(const HeightfieldSurface& s, const HeightfieldTraceOptions& opt,
                                         std::int64_t chunk) {
  HeightfieldTally tally(opt.theta_bins, opt.phi_bins, opt.max_k, opt.phi_i);
  const std::int64_t first = chunk * kHeightfieldRaysPerChunk;
  const std::int64_t count = std::min(kHeightfieldRaysPerChunk, opt.rays - first);
  Rng rng(opt.seed, kHeightfieldRayStream, static_cast<std::uint64_t>(chunk));
  const Vec3 i(std::sin(opt.theta_i) * std::cos(opt.phi_i), std::sin(opt.theta_i) * std::sin(opt.phi_i),
               std::cos(opt.theta_i));
  const double z0 = s.hierarchy.root().hi + 1.0;
  const double nd = static_cast<double>(s.field.n);
  for (std::int64_t r = 0; r < count; ++r) {
    const double x = nd * rng.uniform(), y = nd * rng.uniform();
    tally.add(trace_heightfield_ray(s, Vec3(x, y, z0), -i, opt.ray));
  }
  return tally;
}

HeightfieldTally trace_heightfield(const HeightfieldSurface& s, const HeightfieldTraceOptions& opt) {
  HeightfieldTally tally(opt.theta_bins, opt.phi_bins, opt.max_k, opt.phi_i);
  for (std::int64_t c = 0; c < heightfield_chunk_count(opt); ++c) tally.merge(trace_heightfield_chunk(s, opt, c));
  return tally;
}

}  // namespace vgroove::sim
