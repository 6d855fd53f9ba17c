// Tests of sim/dielectric_lifted.h: 3D tracing across extruded dielectric V-grooves by lifting the
// flatland tracers (issue 32, item 2). The lifted tracer against a direct 3D tracer of one extruded
// groove as a finite triangle mesh (Woop-Benthin-Wald hits, 3D Snell and Fresnel at each hit, no
// cross-section anywhere) path by path to rounding, on random grooves, frames, rays and both sides,
// grazing to 89.99 deg and through total internal reflection; a flat interface against 3D Fresnel
// and Snell by hand; eta = 1; the conductor limit against trace_groove3d and the 3D microsurface
// tally bit for bit; d.u = 0 against the flatland tracers bit for bit; conservation; splitting
// against random branching in distribution; bad input.
#include "vgroove/sim/dielectric_lifted.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/optics/snell.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/triangle_watertight.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace vgroove::sim {
namespace {

// Degrees to radians as Python's math.radians (the hand values below come from it).
double deg(double d) { return d * (std::numbers::pi / 180.0); }

// The unit travel direction of light at polar angle theta from the normal of its own side and
// azimuth phi: from above it travels down, from below up.
Vec3 travel(double theta, double phi, Medium from) {
  const double s = std::sin(theta), c = std::cos(theta);
  return Vec3(s * std::cos(phi), s * std::sin(phi), from == Medium::above ? -c : c);
}

// ---------------------------------------------------------------------------------------------
// The direct 3D tracer: the groove and its flat rims extruded along u as four planar quads of two
// triangles each, [-L, L] along u and [-W, W] across; a ray is followed in 3D with the watertight
// test (either winding), the face just left excluded, and split at each hit by 3D Fresnel and
// Snell with the normal taken from the mesh's own vertices. Nothing here uses a cross-section.
// A hit exactly on an edge (a zero barycentric weight) is counted, not resolved: random rays meet
// none.
struct MeshExit {
  Vec3 dir;
  double w;
  std::uint64_t path;
  int k;
  Medium side;
};
struct MeshResult {
  std::vector<MeshExit> exits;
  double left[2] = {0.0, 0.0};
  double cut = 0.0, bounce_limit = 0.0;
  int edge_hits = 0;  // hits with an exactly zero barycentric weight (none expected)
};

// The mesh's half length and half width, in facet lengths. The watertight test's t is a weighted
// mean of the vertices' coordinates along the ray, each ~size, with weights good to ~eps size /
// width: t carries ~eps size^2, 1e-8 here (at 1e7 it would be 0.01, hits landing above the rim plane).
// 1e4 is far beyond any path of the tests (a ray at 89.99 deg runs 5.7e3 units per unit height).
constexpr double kMeshSize = 1e4;
// The paths' agreement in direction and weight (run_mesh_comparison says why).
constexpr double kTolerance = 1e-12;

class ExtrudedGrooveMesh {
 public:
  ExtrudedGrooveMesh(const Groove& g, const GrooveFrame3d& frame, double half_width, double half_length)
      : a_(frame.a()), u_(frame.u()) {
    const Vec2 apex(0.0, 0.0), rim_l = g[Side::left].rim(), rim_r = g[Side::right].rim();
    const double W = half_width;
    // By Part: left facet, right facet, left flat, right flat; each from its left end to its right
    // end in the cross-section.
    add_face(rim_l, apex, half_length);
    add_face(apex, rim_r, half_length);
    add_face(Vec2(-W, g.rim_height), rim_l, half_length);
    add_face(rim_r, Vec2(W, g.rim_height), half_length);
  }

  Vec3 point(double x, double y, double z) const { return x * a_ + y * Vec3(0.0, 0.0, 1.0) + z * u_; }

  MeshResult trace(const Vec3& d, double x, double rim_height, Medium from, double eta, double min_weight,
                   int max_interactions) const {
    // Start on the ray's line outside the interface's slab: above the rims, or below the apex.
    const Vec3 cross_rim = point(x, rim_height, 0.0);
    const double t0 = from == Medium::above ? 1.0 / -d.z() : (rim_height + 1.0) / d.z();
    struct Pending {
      Vec3 o, d;
      double w;
      std::uint64_t path;
      int k;
      Medium in;
      int exclude;
    };
    MeshResult out;
    std::vector<Pending> stack{{cross_rim - t0 * d, d, 1.0, 0, 0, from, -1}};
    while (!stack.empty()) {
      const Pending h = stack.back();
      stack.pop_back();
      int face = -1;
      double t = 0.0;
      if (!nearest(h.o, h.d, h.exclude, face, t, out.edge_hits)) {
        out.exits.push_back(MeshExit{h.d, h.w, h.path, h.k, h.in});
        out.left[static_cast<int>(h.in)] += h.w;
        continue;
      }
      if (h.k == max_interactions) {
        out.bounce_limit += h.w;
        continue;
      }
      const Vec3 p = h.o + t * h.d;
      const Vec3& m = normal_[static_cast<std::size_t>(face)];  // towards medium 1
      const double eta_rel = h.in == Medium::above ? eta : 1.0 / eta;
      const Vec3 m_in = h.in == Medium::above ? m : Vec3(-m);
      Vec3 tr = Vec3::Zero();
      const bool crosses = optics::refract(h.d, m_in, eta_rel, tr);
      const double F = crosses ? optics::fresnel_dielectric(std::abs(h.d.dot(m)), eta_rel) : 1.0;
      const double w[2] = {h.w * F, h.w * (1.0 - F)};
      for (int b = 0; b < 2; ++b) {
        if (!(w[b] > 0.0)) continue;
        if (w[b] < min_weight) {
          out.cut += w[b];
          continue;
        }
        const Vec3 dn = b == 0 ? Vec3(h.d - 2.0 * h.d.dot(m) * m) : tr;
        const Medium med = b == 0 ? h.in : (h.in == Medium::above ? Medium::below : Medium::above);
        const std::uint64_t path = h.path | (b == 1 && h.k < 64 ? std::uint64_t{1} << h.k : 0);
        stack.push_back(Pending{p, dn, w[b], path, h.k + 1, med, face});
      }
    }
    return out;
  }

 private:
  void add_face(const Vec2& p, const Vec2& q, double L) {
    const Vec3 v0 = point(p.x(), p.y(), -L), v1 = point(q.x(), q.y(), -L);
    const Vec3 v2 = point(q.x(), q.y(), L), v3 = point(p.x(), p.y(), L);
    tris_.push_back({v0, v1, v2});
    tris_.push_back({v0, v2, v3});
    // The normal from the face's vertices on the line z = 0 and one unit along the axis (the far
    // vertices, at kMeshSize, carry their cross-section coordinates only to ~eps kMeshSize).
    const Vec3 p0 = point(p.x(), p.y(), 0.0);
    Vec3 m = (point(q.x(), q.y(), 0.0) - p0).cross(point(p.x(), p.y(), 1.0) - p0).normalized();
    if (m.z() < 0.0) m = -m;  // medium 1 lies above every face
    normal_.push_back(m);
  }

  bool nearest(const Vec3& o, const Vec3& d, int exclude, int& face, double& t, int& edge_hits) const {
    const WatertightRay ray = make_watertight_ray(o, d);
    double best = std::numeric_limits<double>::infinity();
    bool zero_weight = false;
    for (int f = 0; f < static_cast<int>(normal_.size()); ++f) {
      if (f == exclude) continue;
      for (int tri = 0; tri < 2; ++tri) {
        const auto& v = tris_[static_cast<std::size_t>(2 * f + tri)];
        WatertightHit hit;
        if (intersect_watertight(ray, v[0], v[1], v[2], best, hit) ||
            intersect_watertight(ray, v[0], v[2], v[1], best, hit)) {
          best = hit.t();
          face = f;
          zero_weight = hit.zeros() > 0;
        }
      }
    }
    if (face < 0) return false;
    edge_hits += zero_weight;
    t = best;
    return true;
  }

  Vec3 a_, u_;
  std::vector<std::array<Vec3, 3>> tris_;
  std::vector<Vec3> normal_;
};

// ---------------------------------------------------------------------------------------------

struct Worst {
  double dir = 0.0, weight = 0.0, total = 0.0;
  long paths = 0, rays = 0, tir_rays = 0, up_from_below = 0, down_from_above = 0, never_above = 0;
};

// One ray through both tracers: every exit matched by its signature (k, R/T bits), the same side,
// weight and 3D direction; the energy accounts. Returns false (with a message) on a mismatch.
::testing::AssertionResult same_paths(const LiftedResult& lifted, const MeshResult& mesh, double tol_dir,
                                      double tol_weight, Worst& worst) {
  if (mesh.edge_hits != 0) return ::testing::AssertionFailure() << "the mesh tracer met an edge";
  std::map<std::pair<int, std::uint64_t>, std::size_t> by_key;
  for (std::size_t i = 0; i < mesh.exits.size(); ++i) by_key[{mesh.exits[i].k, mesh.exits[i].path}] = i;
  if (by_key.size() != mesh.exits.size()) return ::testing::AssertionFailure() << "two mesh paths share a signature";
  if (lifted.flat.exits.size() != mesh.exits.size())
    return ::testing::AssertionFailure() << "lifted " << lifted.flat.exits.size() << " exits, mesh "
                                         << mesh.exits.size();
  for (std::size_t i = 0; i < lifted.flat.exits.size(); ++i) {
    const DielectricExit& e = lifted.flat.exits[i];
    const auto it = by_key.find({e.k, e.path});
    if (it == by_key.end())
      return ::testing::AssertionFailure() << "lifted path k = " << e.k << " bits " << e.path << " not in the mesh";
    const MeshExit& m = mesh.exits[it->second];
    if (m.side != e.side) return ::testing::AssertionFailure() << "path k = " << e.k << ": sides differ";
    const double dd = (lifted.dirs[i] - m.dir).norm(), dw = std::abs(e.weight - m.w);
    worst.dir = std::max(worst.dir, dd);
    worst.weight = std::max(worst.weight, dw);
    ++worst.paths;
    if (!(dd <= tol_dir) || !(dw <= tol_weight))
      return ::testing::AssertionFailure()
             << "path k = " << e.k << " bits " << e.path << ": |d - d_mesh| = " << dd << ", |w - w_mesh| = " << dw;
  }
  for (int s = 0; s < 2; ++s) {
    const double dl = std::abs(lifted.flat.left[s] - mesh.left[s]);
    worst.total = std::max(worst.total, dl);
    if (!(dl <= tol_weight)) return ::testing::AssertionFailure() << "left[" << s << "] differs by " << dl;
  }
  return ::testing::AssertionSuccess();
}

// Random grooves (symmetric and not), frames, rays from both sides at polar angles uniform in
// [theta_min, theta_max], eta and 1/eta: path by path against the mesh. Splitting; cut at 1e-12 as
// the default.
void run_mesh_comparison(double theta_min_deg, double theta_max_deg, int rays_per_case, std::uint64_t seed,
                         Worst& worst) {
  // Rounding: each hit adds a few ulp to a direction (refract and reflect are a handful of
  // operations); the mesh's normals (a normalized cross product) and the cross-section's (cos and
  // sin of the facet angle) differ by a few ulp, an error each reflection doubles and every hit on
  // the same face repeats; a refraction multiplies an angle error by cos_i / (eta_rel cos_t), large
  // near the critical angle, and F's slope is unbounded there. Over these paths (k up to ~20)
  // 1e-12 (4500 ulp of 1) bounds it: measured 6.1e-14 (0-80 deg) and 4.0e-14 (80-89.99 deg) on
  // these rays, 1.0e-13 on a k = 11 path of another draw (42 ulp per hit). A wrong law misses by
  // 1e-7 to 1e-1 in the variants tried (TheFlatlandTracerAtEitherIndexMissesTheMesh).
  const double tol = kTolerance;
  const double etas[] = {1.5, 1.0 / 1.5, 2.4, 1.0 / 2.4, 1.33};
  for (int ie = 0; ie < 5; ++ie) {
    const double eta = etas[ie];
    for (int c = 0; c < rays_per_case; ++c) {
      Rng rng(seed, static_cast<std::uint64_t>(ie), static_cast<std::uint64_t>(c));
      const bool sym = rng.uniform() < 0.5;
      const Groove g =
          sym ? make_symmetric_groove(deg(3.0 + 170.0 * rng.uniform()))
              : make_nonsymmetric_groove(-deg(3.0 + 84.0 * rng.uniform()), deg(3.0 + 84.0 * rng.uniform()));
      const double phi_a = std::numbers::pi * rng.uniform();
      const GrooveFrame3d frame{std::cos(phi_a), std::sin(phi_a)};
      const Medium from = rng.uniform() < 0.5 ? Medium::above : Medium::below;
      const double theta = deg(theta_min_deg + (theta_max_deg - theta_min_deg) * rng.uniform());
      const Vec3 d = travel(theta, 2.0 * std::numbers::pi * rng.uniform(), from);
      const double xl = g.rim_x(Side::left), xr = g.rim_x(Side::right);
      const double x = xl - 1.0 + (xr - xl + 2.0) * rng.uniform();
      DielectricOptions opt;
      opt.eta = eta;
      const LiftedGrooveTracer lifted(g, frame, opt);
      LiftedResult lr;
      lifted.trace(d, x, from, rng, lr);
      const ExtrudedGrooveMesh mesh(g, frame, kMeshSize, kMeshSize);
      const MeshResult mr = mesh.trace(d, x, g.rim_height, from, eta, opt.min_weight, opt.max_interactions);
      ASSERT_TRUE(same_paths(lr, mr, tol, tol, worst))
          << "eta " << eta << " case " << c << " from " << medium_name(from) << " d = " << d.transpose() << " x " << x;
      ++worst.rays;
      worst.tir_rays += from == Medium::below && lr.flat.left[0] == 0.0;
      // n2 |d.u| >= n1: medium 1 holds no direction with this axis component (TIR at every hit).
      const double du = -d.x() * frame.sin_phi_a + d.y() * frame.cos_phi_a;
      if (from == Medium::below && std::abs(du) * eta >= 1.0) {
        ++worst.never_above;
        EXPECT_EQ(lr.flat.left[0], 0.0);
      }
      worst.up_from_below += from == Medium::below && lr.flat.left[0] > 0.0;
      worst.down_from_above += from == Medium::above && lr.flat.left[1] > 0.0;
    }
  }
}

TEST(DielectricLifted, AgreesWithTheExtrudedMeshTracer) {
  Worst w;
  run_mesh_comparison(0.0, 80.0, 1000, 1, w);
  std::printf(
      "mesh vs lifted: %ld rays, %ld paths, max |d - d_mesh| %.3g, max |w - w_mesh| %.3g; "
      "from below: %ld out above, %ld none out (TIR; %ld with n2 |d.u| >= n1); from above: %ld into "
      "medium 2\n",
      w.rays, w.paths, w.dir, w.weight, w.up_from_below, w.tir_rays, w.never_above, w.down_from_above);
  EXPECT_EQ(w.rays, 5 * 1000);
  EXPECT_GT(w.tir_rays, 500);
  EXPECT_GT(w.never_above, 100);
  EXPECT_GT(w.up_from_below, 500);
}

TEST(DielectricLifted, AgreesWithTheExtrudedMeshTracerAtGrazingAngles) {
  Worst w;
  // Polar angles over [80, 89.99 deg].
  run_mesh_comparison(80.0, 89.99, 1000, 2, w);
  std::printf("grazing: %ld rays, %ld paths, max |d - d_mesh| %.3g, max |w - w_mesh| %.3g\n", w.rays, w.paths, w.dir,
              w.weight);
  // Fixed grazing rays along and across the axis, both sides.
  const Groove g = make_symmetric_groove(deg(100.0));
  for (double phi_a : {0.0, 0.3, 1.2}) {
    const GrooveFrame3d frame{std::cos(phi_a), std::sin(phi_a)};
    for (Medium from : {Medium::above, Medium::below}) {
      for (double az : {0.0, 0.5 * std::numbers::pi, 1.0, 2.5, 4.0}) {
        for (double x : {-0.3, 0.2, 0.9, -1.7}) {
          DielectricOptions opt;
          const Vec3 d = travel(deg(89.99), az, from);
          LiftedResult lr;
          Rng rng(0, 0, 0);
          LiftedGrooveTracer(g, frame, opt).trace(d, x, from, rng, lr);
          const MeshResult mr = ExtrudedGrooveMesh(g, frame, kMeshSize, kMeshSize)
                                    .trace(d, x, g.rim_height, from, opt.eta, opt.min_weight, opt.max_interactions);
          ASSERT_TRUE(same_paths(lr, mr, kTolerance, kTolerance, w)) << "phi_a " << phi_a << " az " << az << " x " << x;
          EXPECT_NEAR(lr.flat.total(), 1.0, 1e-14);
        }
      }
    }
  }
}

// The broken variants the mesh must tell apart, kept: the flatland tracer run on the lifted ray's
// cross-section (a) at the real eta (no effective index: wrong directions) and (b) at eta_eff
// (the right directions, Fresnel at the cross-section's angle: wrong weights), exits lifted as the
// lifted tracer's. Each misses the mesh on every ray with |d.u| > 0.2 that refracts somewhere.
TEST(DielectricLifted, TheFlatlandTracerAtEitherIndexMissesTheMesh) {
  Rng draw(9, 0, 0);
  int missed[2] = {0, 0}, rays = 0;
  for (int c = 0; c < 200; ++c) {
    const Groove g = make_symmetric_groove(deg(20.0 + 140.0 * draw.uniform()));
    const double phi_a = std::numbers::pi * draw.uniform();
    const GrooveFrame3d frame{std::cos(phi_a), std::sin(phi_a)};
    const Medium from = c % 2 ? Medium::above : Medium::below;
    const Vec3 d = travel(deg(20.0 + 50.0 * draw.uniform()), 2.0 * std::numbers::pi * draw.uniform(), from);
    const double x = -0.5 + draw.uniform();
    DielectricOptions opt;
    opt.eta = 1.5;
    const LiftedRay ray = lift_ray(d, frame, from, opt);
    if (!(ray.law.r[0] > 0.0) || std::abs(ray.q[static_cast<int>(from)]) < 0.2) continue;
    LiftedResult right;
    LiftedGrooveTracer(g, frame, opt).trace(d, x, from, draw, right);
    bool refracts = false;
    for (const DielectricExit& e : right.flat.exits) refracts |= e.path != 0;
    if (!refracts) continue;
    ++rays;
    const MeshResult mr = ExtrudedGrooveMesh(g, frame, kMeshSize, kMeshSize)
                              .trace(d, x, g.rim_height, from, opt.eta, opt.min_weight, opt.max_interactions);
    // N2 / N1 = eta r_2 / r_1.
    const double eta_eff = opt.eta * ray.law.r[1] / ray.law.r[0];
    for (int variant = 0; variant < 2; ++variant) {
      DielectricOptions flat = opt;
      flat.eta = variant == 0 ? opt.eta : eta_eff;
      LiftedResult lr;
      DielectricGrooveTracer(g, flat).trace(beam_ray(g, ray.e, x), from, draw, lr.flat);
      for (const DielectricExit& e : lr.flat.exits) lr.dirs.push_back(lift_exit(ray, frame, e.dir, e.side));
      Worst w;
      missed[variant] += !same_paths(lr, mr, kTolerance, kTolerance, w);
    }
  }
  std::printf("broken variants: %d rays, missed at eta %d, at eta_eff %d\n", rays, missed[0], missed[1]);
  EXPECT_GT(rays, 50);
  EXPECT_EQ(missed[0], rays);
  EXPECT_EQ(missed[1], rays);
}

// A flat interface (the flat rim far from the groove) lit in 3D: reflected F(theta_i) and
// transmitted 1 - F along the 3D Snell direction, by hand (Born & Wolf; the values from an
// independent evaluation). Light along the axis u is at normal incidence in the cross-section:
// the 3D angle, not the cross-section's, sets F (0.0892, not 0.04).
TEST(DielectricLifted, AFlatInterfaceIsFresnelAndSnellIn3d) {
  const Groove g = make_symmetric_groove(deg(90.0));
  struct Case {
    double theta_deg, eta, F, cos_t;
    Medium from;
  };
  // F(theta, eta_rel) and cos theta_t, eta_rel = eta from above, 1 / eta from below.
  const Case cases[] = {
      {60.0, 1.5, 0.08918671280221274, 0.816496580927726, Medium::above},
      {30.0, 1.5, 0.055190167295375916, 0.6614378277661478, Medium::below},
      {40.0, 1.5, 0.24529120428691048, 0.26524366132915705, Medium::below},
      {0.0, 1.5, 0.04000000000000001, 1.0, Medium::above},
      {89.99, 1.5, 0.9989858952314441, 0.7453560015818665, Medium::above},
      {50.0, 1.5, 1.0, -1.0, Medium::below},  // beyond the critical angle, 41.8 deg: TIR
  };
  for (double phi_a : {0.0, 0.7, 2.0}) {
    const GrooveFrame3d frame{std::cos(phi_a), std::sin(phi_a)};
    for (const Case& c : cases) {
      for (double az : {0.0, 0.5 * std::numbers::pi + phi_a, 1.3, 3.0}) {  // the second: along u
        DielectricOptions opt;
        opt.eta = c.eta;
        const Vec3 d = travel(deg(c.theta_deg), az, c.from);
        const double eta_rel = c.from == Medium::above ? c.eta : 1.0 / c.eta;
        for (double x : {-50.0, 50.0}) {
          LiftedResult lr;
          Rng rng(0, 0, 0);
          LiftedGrooveTracer(g, frame, opt).trace(d, x, c.from, rng, lr);
          const Medium other = c.from == Medium::above ? Medium::below : Medium::above;
          const std::string where = "theta " + std::to_string(c.theta_deg) + " az " + std::to_string(az);
          EXPECT_NEAR(lr.flat.left[static_cast<int>(c.from)], c.F, 1e-15) << where;
          EXPECT_NEAR(lr.flat.left[static_cast<int>(other)], 1.0 - c.F, 1e-15) << where;
          for (std::size_t i = 0; i < lr.dirs.size(); ++i) {
            const Vec3& o = lr.dirs[i];
            ASSERT_EQ(lr.flat.exits[i].k, 1);
            if (lr.flat.exits[i].side == c.from) {  // mirror: z flipped
              EXPECT_NEAR((o - Vec3(d.x(), d.y(), -d.z())).norm(), 0.0, 4e-16) << where;
            } else {  // Snell: tangential part / eta_rel, normal part cos_t onward
              const double sign = c.from == Medium::above ? -1.0 : 1.0;
              const Vec3 t(d.x() / eta_rel, d.y() / eta_rel, sign * c.cos_t);
              EXPECT_NEAR((o - t).norm(), 0.0, 4e-16) << where;
            }
          }
        }
      }
    }
  }
}

// The law against the derivation (docs/derivations/dielectric_lifting.md), without a tracer: for
// random hits, the refracted e is the 2D Snell direction with eta_eff = sqrt(n_k^2 - p^2) /
// sqrt(n_j^2 - p^2); total internal reflection in 3D is the cross-section's at eta_eff (away from
// the boundary's rounding); R_s at the 3D angle is the cross-section's R_s at eta_eff, R_p is not.
TEST(DielectricLifted, TheLawIsSnellWithTheEffectiveIndexAndFresnelAtThe3dAngle) {
  Rng draw(8, 0, 0);
  int refracted = 0, tir = 0, rp_differs = 0;
  for (int c = 0; c < 20000; ++c) {
    const double eta = c % 2 ? 1.5 : 1.0 / 2.4;
    const Medium in = c % 4 < 2 ? Medium::above : Medium::below;
    const double nj = in == Medium::above ? 1.0 : eta, nk = in == Medium::above ? eta : 1.0;
    const double q = (2.0 * draw.uniform() - 1.0) * 0.999;  // d.u in medium j
    const double p = nj * q;
    // A hit of e (unit) on a part of normal n at cross-section angle theta' from -m_in.
    const double phi = 2.0 * std::numbers::pi * draw.uniform(), th = 0.5 * std::numbers::pi * draw.uniform();
    const Vec2 n(std::sin(phi), std::cos(phi));
    const Vec2 m_in = in == Medium::above ? n : Vec2(-n);
    const Vec2 tang(m_in.y(), -m_in.x());
    const Vec2 e = -std::cos(th) * m_in + std::sin(th) * tang;
    detail::LiftedLaw law;
    law.eta = eta;
    law.inv_eta = 1.0 / eta;
    const double rk2 = 1.0 - (p / nk) * (p / nk);
    law.r[static_cast<int>(in)] = std::sqrt(1.0 - q * q);
    law.r[1 - static_cast<int>(in)] = rk2 > 0.0 ? std::sqrt(rk2) : 0.0;
    Vec2 t = Vec2::Zero();
    const double F = law(e, n, in, t);
    const double Nj = std::sqrt(nj * nj - p * p), Nk2 = nk * nk - p * p;
    // The cross-section's critical condition: N_j^2 sin^2 theta' >= N_k^2.
    const double margin = Nj * Nj * std::sin(th) * std::sin(th) - Nk2;
    if (std::abs(margin) < 1e-9) continue;
    if (margin > 0.0) {
      ++tir;
      EXPECT_EQ(F, 1.0) << "3D refracts where the cross-section reflects totally";
      continue;
    }
    ++refracted;
    ASSERT_LT(F, 1.0) << "3D reflects totally where the cross-section refracts";
    const double eta_eff = std::sqrt(Nk2) / Nj;
    Vec2 t2 = Vec2::Zero();
    ASSERT_TRUE(optics::refract(e, m_in, eta_eff, t2));
    EXPECT_LE((t - t2).norm(), 1e-13) << "q " << q << " theta' " << th;
    // R_s at the 3D angle = R_s of the cross-section at eta_eff; R_p differs once p != 0.
    const double rj = law.r[static_cast<int>(in)];
    const double eta_rel = nk / nj;
    const auto f3 = optics::fresnel_dielectric_polarized(rj * std::cos(th), eta_rel);
    const auto f2 = optics::fresnel_dielectric_polarized(std::cos(th), eta_eff);
    EXPECT_NEAR(f3.s, f2.s, 1e-13);
    EXPECT_NEAR(F, f3.unpolarized(), 1e-13);
    rp_differs += std::abs(f3.p - f2.p) > 1e-6;
  }
  std::printf("law: %d refracted, %d totally reflected, R_p differs in %d\n", refracted, tir, rp_differs);
  EXPECT_GT(tir, 2000);
  EXPECT_GT(refracted, 5000);
  EXPECT_GT(rp_differs, refracted / 2);
}

// eta = 1: no interface; every ray passes straight, weight 1, at every hit F = 0.
TEST(DielectricLifted, EtaOnePassesStraightThrough) {
  Rng draw(3, 0, 0);
  for (int c = 0; c < 500; ++c) {
    const Groove g = make_nonsymmetric_groove(-deg(5.0 + 80.0 * draw.uniform()), deg(5.0 + 80.0 * draw.uniform()));
    const double phi_a = std::numbers::pi * draw.uniform();
    const GrooveFrame3d frame{std::cos(phi_a), std::sin(phi_a)};
    const Medium from = c % 2 ? Medium::above : Medium::below;
    const Vec3 d = travel(deg(89.0 * draw.uniform()), 2.0 * std::numbers::pi * draw.uniform(), from);
    DielectricOptions opt;
    opt.eta = 1.0;
    LiftedResult lr;
    LiftedGrooveTracer(g, frame, opt).trace(d, -2.0 + 4.0 * draw.uniform(), from, draw, lr);
    ASSERT_EQ(lr.flat.exits.size(), 1u);
    EXPECT_EQ(lr.flat.exits[0].weight, 1.0);
    EXPECT_NE(lr.flat.exits[0].side, from);
    EXPECT_EQ(lr.flat.exits[0].path, (std::uint64_t{1} << lr.flat.exits[0].k) - 1);  // all T
    // d's components through e = (d.a, d.n) / r, the lift's r and the rotation back: a few ulp each.
    EXPECT_LE((lr.dirs[0] - d).norm(), 1e-15);
  }
}

// With F = 1 the lifted tracer is trace_groove3d bit for bit (same cross-section, same lift), and
// the 3D microsurface tally of trace_microsurface3d_chunk_reference is reproduced exactly.
TEST(DielectricLifted, ConductorLimitIsTheLiftedConductorTallyBitForBit) {
  Microsurface3dOptions mo;
  mo.alpha = 0.6;
  mo.grooves = 300;
  mo.seed = 5;
  const Microsurface3d surface = make_microsurface3d(mo);
  Microsurface3dTraceOptions to;
  to.rays = 20000;
  to.seed = 9;
  to.theta_bins = 30;
  to.phi_bins = 24;
  to.max_k = 6;
  DielectricOptions opt;
  opt.conductor_limit = true;
  for (double theta_i : {0.0, deg(45.0), deg(85.0)}) {
    to.theta_i = theta_i;
    const Microsurface3dTally ref = trace_microsurface3d_chunk_reference(surface, to, 0);
    Microsurface3dTally mine(to.theta_bins, to.phi_bins, to.max_k);
    // trace_microsurface3d_chunk_reference's draws, ray by ray.
    Rng rng(to.seed, kRay3dStream, 0);
    const Vec3 i(-std::sin(theta_i), 0.0, std::cos(theta_i));
    const double g_count = static_cast<double>(surface.grooves.size());
    const int last = static_cast<int>(surface.grooves.size()) - 1;
    std::int64_t bitwise = 0;
    for (std::int64_t j = 0; j < std::min<std::int64_t>(to.rays, kRaysPerChunk); ++j) {
      const int gi = std::min(last, static_cast<int>(uniform_open(rng) * g_count));
      const double f = uniform_open(rng);
      const Groove& g = surface.grooves[static_cast<std::size_t>(gi)];
      const GrooveFrame3d& frame = surface.frames[static_cast<std::size_t>(gi)];
      const double x = g.rim_x(Side::left) + f * (g.rim_x(Side::right) - g.rim_x(Side::left));
      LiftedResult lr;
      Rng unused(0, 0, 0);
      LiftedGrooveTracer(g, frame, opt).trace(-i, x, Medium::above, unused, lr);
      const Trace3dResult t3 = trace_groove3d(g, frame, i, f, to.trace);
      Trace3dResult as3d;
      if (lr.flat.exits.size() == 1) {
        as3d.trace.how = Termination::escaped;
        as3d.trace.bounces = lr.flat.exits[0].k;
        as3d.o = lr.dirs[0];
        ASSERT_EQ(t3.trace.how, Termination::escaped);
        ASSERT_EQ(t3.trace.bounces, as3d.trace.bounces);
        ASSERT_EQ(std::memcmp(t3.o.data(), as3d.o.data(), sizeof(double) * 3), 0)
            << "ray " << j << ": " << t3.o.transpose() << " vs " << as3d.o.transpose();
        ++bitwise;
      } else {
        ASSERT_EQ(lr.flat.vertex, 1.0);
        ASSERT_EQ(t3.trace.how, Termination::vertex_hit);
        as3d.trace.how = Termination::vertex_hit;
      }
      mine.add(as3d);
    }
    EXPECT_GT(bitwise, to.rays - 10);
    EXPECT_EQ(mine.by_k, ref.by_k);
    EXPECT_EQ(mine.hist_by_k, ref.hist_by_k);
    EXPECT_EQ(mine.hist, ref.hist);
  }
}

// d.u = 0: the cross-section is the whole ray; where r = 1 exactly, the lifted tracers are the
// flatland tracers bit for bit (weights, signatures, directions with z for y).
TEST(DielectricLifted, NoAxisComponentIsTheFlatlandTracer) {
  Rng draw(4, 0, 0);
  int exact = 0;
  MicrosurfaceOptions so;
  so.grooves = 50;
  so.alpha = 0.7;
  const Microsurface surface = make_microsurface(so);
  for (int c = 0; c < 400; ++c) {
    const Groove g = make_nonsymmetric_groove(-deg(5.0 + 80.0 * draw.uniform()), deg(5.0 + 80.0 * draw.uniform()));
    const Medium from = c % 2 ? Medium::above : Medium::below;
    const double th = deg(89.0 * (2.0 * draw.uniform() - 1.0));
    const Vec2 e2(std::sin(th), from == Medium::above ? -std::cos(th) : std::cos(th));
    if (std::sqrt(e2.x() * e2.x() + e2.y() * e2.y()) != 1.0) continue;
    ++exact;
    const GrooveFrame3d frame{1.0, 0.0};  // a = x, u = y
    const Vec3 d(e2.x(), 0.0, e2.y());
    DielectricOptions opt;
    opt.eta = c % 3 ? 1.5 : 1.0 / 2.4;
    const double x = -2.0 + 4.0 * draw.uniform();
    LiftedResult lr;
    DielectricResult fr;
    Rng r1(0, 0, 0), r2(0, 0, 0);
    LiftedGrooveTracer(g, frame, opt).trace(d, x, from, r1, lr);
    DielectricGrooveTracer(g, opt).trace(beam_ray(g, e2, x), from, r2, fr);
    auto same = [&](const LiftedResult& a, const DielectricResult& b) {
      ASSERT_EQ(a.flat.exits.size(), b.exits.size());
      for (std::size_t i = 0; i < b.exits.size(); ++i) {
        EXPECT_EQ(a.flat.exits[i].weight, b.exits[i].weight);
        EXPECT_EQ(a.flat.exits[i].path, b.exits[i].path);
        EXPECT_EQ(a.dirs[i].x(), b.exits[i].dir.x());
        EXPECT_EQ(a.dirs[i].y(), 0.0);
        EXPECT_EQ(a.dirs[i].z(), b.exits[i].dir.y());
      }
    };
    same(lr, fr);
    // The procedural surface, both sides.
    const LiftedSurfaceTracer ls(surface, frame, opt);
    if (from == Medium::above) {
      const Groove& gs = surface.grooves[static_cast<std::size_t>(c % so.grooves)];
      const double xs = gs.rim_x(Side::left) + draw.uniform() * (gs.rim_x(Side::right) - gs.rim_x(Side::left));
      ls.trace_from_above(c % so.grooves, xs, d, r1, lr);
      ls.flatland().trace_from_above(c % so.grooves, beam_ray(gs, e2, xs), r2, fr);
    } else {
      const double xs = 50.0 * draw.uniform();
      ls.trace_from_below(xs, d, r1, lr);
      ls.flatland().trace_from_below(xs, e2, r2, fr);
    }
    same(lr, fr);
  }
  EXPECT_GT(exact, 100);
}

// Energy: left (both sides) + cut + bounce limit + vertex = 1 to rounding, for splitting with
// cuts and a bounce limit that bite, on the single groove and the surface; random branching: 1
// exactly, and in distribution the splitting's energies (5 sigma of the sample count).
TEST(DielectricLifted, EnergyIsConservedToRounding) {
  MicrosurfaceOptions so;
  so.grooves = 64;
  so.alpha = 1.0;
  const Microsurface surface = make_microsurface(so);
  Rng draw(6, 0, 0);
  double worst = 0.0, cut = 0.0, limit = 0.0;
  for (int c = 0; c < 600; ++c) {
    const Groove g = make_symmetric_groove(deg(10.0 + 160.0 * draw.uniform()));
    const double phi_a = std::numbers::pi * draw.uniform();
    const GrooveFrame3d frame{std::cos(phi_a), std::sin(phi_a)};
    const Medium from = c % 2 ? Medium::above : Medium::below;
    const Vec3 d = travel(deg(89.99 * draw.uniform()), 2.0 * std::numbers::pi * draw.uniform(), from);
    DielectricOptions opt;
    opt.eta = c % 4 < 2 ? 1.5 : 1.0 / 1.5;
    opt.min_weight = c % 3 == 0 ? 1e-3 : 1e-12;
    opt.max_interactions = c % 5 == 0 ? 3 : 100000;
    LiftedResult lr;
    LiftedGrooveTracer(g, frame, opt).trace(d, -1.5 + 3.0 * draw.uniform(), from, draw, lr);
    worst = std::max(worst, std::abs(lr.flat.total() - 1.0));
    cut += lr.flat.cut, limit += lr.flat.bounce_limit;
    const LiftedSurfaceTracer ls(surface, frame, opt);
    if (from == Medium::above) {
      const int gi = c % so.grooves;
      const Groove& gs = surface.grooves[static_cast<std::size_t>(gi)];
      ls.trace_from_above(gi, gs.rim_x(Side::left) * (1.0 - 2.0 * draw.uniform()), d, draw, lr);
    } else {
      ls.trace_from_below(64.0 * draw.uniform(), d, draw, lr);
    }
    worst = std::max(worst, std::abs(lr.flat.total() - 1.0));
    cut += lr.flat.cut, limit += lr.flat.bounce_limit;
  }
  EXPECT_LE(worst, 1e-14);
  EXPECT_GT(cut, 0.0);
  EXPECT_GT(limit, 0.0);

  // Random branching against splitting, on one 3D beam over the surface: the energy that goes
  // down, per ray a 0/1 outcome; the split mean is the exact expectation.
  DielectricOptions split, random;
  split.eta = random.eta = 1.5;
  random.branching = Branching::random;
  const GrooveFrame3d frame{std::cos(0.4), std::sin(0.4)};
  const LiftedSurfaceTracer ts(surface, frame, split), tr(surface, frame, random);
  const Vec3 d = travel(deg(70.0), 1.0, Medium::above);
  const int n = 20000;
  double mean_split = 0.0, hits_random = 0.0;
  LiftedResult lr;
  for (int j = 0; j < n; ++j) {
    Rng rng(7, 1, static_cast<std::uint64_t>(j));
    const int gi = static_cast<int>(rng.uniform() * so.grooves);
    const Groove& gs = surface.grooves[static_cast<std::size_t>(gi)];
    const double x = gs.rim_x(Side::left) * (1.0 - 2.0 * rng.uniform());
    ts.trace_from_above(gi, x, d, rng, lr);
    mean_split += lr.flat.left[1];
    tr.trace_from_above(gi, x, d, rng, lr);
    EXPECT_EQ(lr.flat.total(), 1.0);
    hits_random += lr.flat.left[1];
  }
  mean_split /= n;
  const double p = hits_random / n, sigma = std::sqrt(mean_split * (1.0 - mean_split) / n);
  std::printf("down: split %.5f, random %.5f (sigma %.2g)\n", mean_split, p, sigma);
  EXPECT_LE(std::abs(p - mean_split), 5.0 * sigma);
}

TEST(DielectricLifted, BadInputIsRefused) {
  const Groove g = make_symmetric_groove(deg(90.0));
  const GrooveFrame3d frame{1.0, 0.0};
  DielectricOptions opt;
  opt.polarization = Polarization::s;
  try {
    LiftedGrooveTracer(g, frame, opt);
    ADD_FAILURE() << "accepted polarization s";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("polarization = s is out of range"), std::string::npos) << e.what();
  }
  opt.polarization = Polarization::unpolarized;
  opt.eta = -1.0;
  EXPECT_THROW(LiftedGrooveTracer(g, frame, opt), std::invalid_argument);
  opt.eta = 1.5;
  const LiftedGrooveTracer tr(g, frame, opt);
  LiftedResult lr;
  Rng rng(0, 0, 0);
  try {
    tr.trace(Vec3(0.0, 0.6, 0.8), 0.0, Medium::above, rng, lr);
    ADD_FAILURE() << "accepted an upward ray from above";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("d.z = 0.80000000000000004 is out of range [-1, 0)"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(tr.trace(Vec3(0.0, 0.6, -0.8), 0.0, Medium::below, rng, lr), std::invalid_argument);
  EXPECT_THROW(tr.trace(Vec3(0.0, 0.0, std::nan("")), 0.0, Medium::below, rng, lr), std::invalid_argument);
}

}  // namespace
}  // namespace vgroove::sim
