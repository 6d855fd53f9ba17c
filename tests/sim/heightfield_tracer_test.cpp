// Tests of sim/heightfield_tracer.h: the exact 3D tracer of periodic heightfields.
//
// Known answers:
// - A flat field is a mirror: one bounce, the exit direction (d_x, d_y, -d_z) bit for bit, for
//   any origin and any incidence to 89.9 deg (the grazing rays cross dozens of periods), on the
//   triangles' interiors, edges and vertices alike.
// - A field of one V-groove family of slope 1 (90 deg grooves) lit along the groove axis (in the
//   cross-section: normal incidence) returns every ray after exactly two bounces into the mirror
//   direction (0, -sin, cos) bit for bit (the reflections' arithmetic is exact there).
// - A V-groove family of slope 0.75 at (50 deg, phi 2.5) against the lifted tracer
//   (sim/microsurface3d.h, one groove at phi_a = pi - phi_i): every ray of bounce count k leaves
//   along the lifted tracer's direction for k (to 1e-12), and the fractions per k agree with a
//   stratified integration of the lifted tracer over the opening (5 sigma of the binomial).
// - Energy with F = 1 is exactly the number of escaped rays and every ray escapes (lost = 0,
//   bounce_limit = 0) on Gaussian fields, alpha 0.2..1, theta_i 0..89.9 deg: no NaN (a NaN
//   direction would be counted lost). A conductor's energy on a flat field is F(cos theta_i) per ray.
// - Edges and vertices: vertical rays through every vertex and every edge (cell sides and
//   diagonals) of a Gaussian field hit them exactly (counted), and none is lost; on the V-groove
//   field an apex edge or apex vertex gives exactly 2 bounces and the exit (0, 0, 1), a ridge
//   edge 1 bounce, a vertex inside a facet the facet's reflection.
// - Periodic wrap: the same ray moved by whole periods gives the same result bit for bit.
// - Bounce cosines (HeightfieldRayOptions::cosines): recording them leaves the path bit for bit;
//   one cosine per bounce; the product of F(cos_j) in bounce order is, bit for bit, the
//   throughput of the trace with that reflectance (a conductor, a dielectric, Schlick); a field
//   taken at the macro normal instead (F(cos theta_i)^k, the deliberately broken variant) is far off.
// - Determinism: chunks traced on two threads and merged in chunk order give the one-thread tally
//   bit for bit (energies included, with a conductor).
#include "vgroove/sim/heightfield_tracer.h"

#include "vgroove/optics/fresnel.h"
#include "vgroove/sim/effects.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/sim/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <thread>
#include <utility>
#include <vector>

namespace vgroove::sim {
namespace {

using V3 = Eigen::Vector3d;
constexpr double kPi = std::numbers::pi;

double deg(double d) { return d * kPi / 180.0; }

V3 dir_of(double theta, double phi) {
  return V3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

TEST(HeightfieldTracer, FlatFieldIsAMirrorToTheBit) {
  const HeightfieldSurface s = make_heightfield_surface(make_flat_heightfield(16, 0.3));
  Rng rng(11, 0, 0);
  for (double theta_deg : {0.0, 10.0, 45.0, 80.0, 89.0, 89.9}) {
    for (int q = 0; q < 200; ++q) {
      const V3 d = -dir_of(deg(theta_deg), 2.0 * kPi * rng.uniform());
      const V3 org(16.0 * rng.uniform(), 16.0 * rng.uniform(), 1.3);
      const HeightfieldRayResult r = trace_heightfield_ray(s, org, d);
      ASSERT_EQ(r.how, HeightfieldFate::escaped) << theta_deg;
      EXPECT_EQ(r.bounces, 1) << theta_deg;
      EXPECT_EQ(r.o.x(), d.x());
      EXPECT_EQ(r.o.y(), d.y());
      EXPECT_EQ(r.o.z(), -d.z());
    }
  }
  // Straight down onto a vertex, a cell side, a diagonal: counted, one bounce, straight up.
  for (const V3& at : {V3(3.0, 5.0, 1.0), V3(3.5, 5.0, 1.0), V3(3.0, 5.5, 1.0), V3(3.25, 5.25, 1.0)}) {
    const HeightfieldRayResult r = trace_heightfield_ray(s, at, V3(0, 0, -1));
    EXPECT_EQ(r.how, HeightfieldFate::escaped);
    EXPECT_EQ(r.bounces, 1);
    EXPECT_EQ(r.o, V3(0, 0, 1));
    EXPECT_EQ(r.edge_hits + r.vertex_hits, 1) << at.transpose();
    EXPECT_EQ(r.vertex_hits, at.x() == 3.0 && at.y() == 5.0 ? 1 : 0);
  }
}

TEST(HeightfieldTracer, FlatFieldTallyAndFresnelEnergy) {
  const HeightfieldSurface s = make_heightfield_surface(make_flat_heightfield(8));
  HeightfieldTraceOptions opt;
  opt.theta_i = deg(30.0);
  opt.phi_i = 1.0;
  opt.rays = 10000;
  HeightfieldTally t = trace_heightfield(s, opt);
  EXPECT_EQ(t.escaped, opt.rays);
  EXPECT_EQ(t.by_k[1], opt.rays);
  EXPECT_EQ(t.energy(), static_cast<double>(opt.rays));
  // Every ray in the mirror bin: theta bin 30 (of 90 one-degree bins: 30 deg is its lower edge,
  // rounding may put it in 29) and phi bin 0.
  const std::int64_t mirror = t.hist_by_k[t.index(1, 30, 0)] + t.hist_by_k[t.index(1, 29, 0)];
  EXPECT_EQ(mirror, opt.rays);
  opt.ray.fresnel = HeightfieldFresnel{HeightfieldReflectance::conductor, 0.2, 3.0};
  t = trace_heightfield(s, opt);
  const double F = optics::fresnel_conductor(std::cos(opt.theta_i), 0.2, 3.0);
  EXPECT_NEAR(t.energy_by_k[1], F * static_cast<double>(opt.rays), 1e-9 * opt.rays);
  opt.ray.fresnel = HeightfieldFresnel{HeightfieldReflectance::dielectric, 1.5};
  t = trace_heightfield(s, opt);
  EXPECT_NEAR(t.energy_by_k[1], optics::fresnel_dielectric(std::cos(opt.theta_i), 1.5) * opt.rays, 1e-9 * opt.rays);
  opt.ray.fresnel = HeightfieldFresnel{HeightfieldReflectance::schlick, 1.0, 0.0, 0.04};
  t = trace_heightfield(s, opt);
  EXPECT_NEAR(t.energy_by_k[1], optics::fresnel_schlick(std::cos(opt.theta_i), 0.04) * opt.rays, 1e-9 * opt.rays);
}

TEST(HeightfieldTracer, RightAngleGroovesLitAlongTheAxisReturnTwoBouncesToTheMirror) {
  const HeightfieldSurface s = make_heightfield_surface(make_vgroove_heightfield(16, 4, 1.0));
  Rng rng(12, 0, 0);
  for (double theta_deg : {0.0, 30.0, 70.0, 89.9}) {
    const double th = deg(theta_deg);
    const V3 d(0.0, -std::sin(th), -std::cos(th));
    for (int q = 0; q < 500; ++q) {
      const V3 org(16.0 * rng.uniform(), 16.0 * rng.uniform(), 5.0);
      const HeightfieldRayResult r = trace_heightfield_ray(s, org, d);
      ASSERT_EQ(r.how, HeightfieldFate::escaped);
      EXPECT_EQ(r.bounces, 2) << theta_deg << " at " << org.transpose();
      EXPECT_EQ(r.o, V3(0.0, -std::sin(th), std::cos(th))) << theta_deg;
    }
  }
}

TEST(HeightfieldTracer, VGrooveEdgesAndVerticesTakeTheirLimits) {
  const HeightfieldSurface s = make_heightfield_surface(make_vgroove_heightfield(16, 4, 0.75));
  const V3 down(0, 0, -1);
  // Apex (valley) edge x = 4 and an apex vertex: the wedge's two reflections (off one facet at
  // the apex, then the other), the limit of the rays beside the apex on one side. By hand: off
  // the normal (0.75, 0, 1) to (0.96, 0, 0.28), then off (-0.75, 0, 1) to (0.5376, 0, 0.8432).
  for (const V3& at : {V3(4.0, 2.3, 9.0), V3(4.0, 7.0, 9.0), V3(12.0, 0.5, 9.0)}) {
    const HeightfieldRayResult r = trace_heightfield_ray(s, at, down);
    EXPECT_EQ(r.how, HeightfieldFate::escaped);
    EXPECT_EQ(r.bounces, 2) << at.transpose();
    EXPECT_NEAR(std::abs(r.o.x()), 0.5376, 1e-15);
    EXPECT_EQ(r.o.y(), 0.0);
    EXPECT_NEAR(r.o.z(), 0.8432, 1e-15);
    EXPECT_EQ(r.edge_hits + r.vertex_hits, 1);
    const HeightfieldRayResult left = trace_heightfield_ray(s, at - V3(1e-9, 0, 0), down);
    const HeightfieldRayResult right = trace_heightfield_ray(s, at + V3(1e-9, 0, 0), down);
    EXPECT_EQ(left.bounces, 2);
    EXPECT_EQ(right.bounces, 2);
    EXPECT_LT(std::min((r.o - left.o).norm(), (r.o - right.o).norm()), 1e-15);
  }
  // Ridge edge x = 8: one reflection off one facet (the first found), leaving up.
  for (const V3& at : {V3(8.0, 2.3, 9.0), V3(0.0, 11.7, 9.0)}) {
    const HeightfieldRayResult r = trace_heightfield_ray(s, at, down);
    EXPECT_EQ(r.how, HeightfieldFate::escaped);
    EXPECT_EQ(r.bounces, 1) << at.transpose();
    EXPECT_NEAR(std::abs(r.o.x()), 0.96, 1e-15);
    EXPECT_NEAR(r.o.z(), 0.28, 1e-15);
    EXPECT_EQ(r.edge_hits, 1);
  }
  // Inside a facet: a vertex, a cell side and a diagonal reflect as the interior next to them
  // (a ray moved by 1e-9 cells).
  for (const V3& at : {V3(2.0, 3.0, 9.0), V3(2.5, 3.0, 9.0), V3(2.0, 3.5, 9.0), V3(2.5, 3.5, 9.0), V3(6.0, 1.0, 9.0)}) {
    const HeightfieldRayResult r = trace_heightfield_ray(s, at, down);
    const HeightfieldRayResult near = trace_heightfield_ray(s, at + V3(1e-9, 2e-9, 0.0), down);
    EXPECT_EQ(r.how, HeightfieldFate::escaped);
    EXPECT_EQ(r.bounces, near.bounces) << at.transpose();
    EXPECT_NEAR((r.o - near.o).norm(), 0.0, 1e-15) << at.transpose();
    // (>= 1: a ray reflected along a grid line meets edges again.)
    EXPECT_GE(r.edge_hits + r.vertex_hits, 1) << at.transpose();
    EXPECT_EQ(near.edge_hits + near.vertex_hits, 0) << at.transpose();
  }
}

TEST(HeightfieldTracer, VGrooveFamilyMatchesTheLiftedTracer) {
  const double slope = 0.75, theta_i = deg(50.0), phi_i = 2.5;
  const HeightfieldSurface s = make_heightfield_surface(make_vgroove_heightfield(32, 4, slope));
  // The lifted tracer's groove: facets at theta_m = atan(slope) across a = (cos phi_a, sin phi_a),
  // with the light at azimuth pi: the field's light at phi_i is at pi - phi_a from the x axis.
  Microsurface3d m;
  add_groove3d(m, std::atan(slope), kPi - phi_i);
  const V3 i_ms = direction3(theta_i, kPi);
  const int M = 200000;
  std::map<int, double> ref_frac;
  std::map<int, V3> ref_o;
  for (int q = 0; q < M; ++q) {
    const Trace3dResult r = trace_groove3d(m.grooves[0], m.frames[0], i_ms, (q + 0.5) / M);
    ASSERT_EQ(r.trace.how, Termination::escaped);
    ref_frac[r.trace.bounces] += 1.0 / M;
    ref_o[r.trace.bounces] = r.o;
  }
  // The field's exit directions, turned so that the light is at azimuth pi.
  const double rot = kPi - phi_i;
  const V3 d = -dir_of(theta_i, phi_i);
  Rng rng(13, 0, 0);
  const int n = 20000;
  std::map<int, int> count;
  for (int q = 0; q < n; ++q) {
    const HeightfieldRayResult r = trace_heightfield_ray(s, V3(32.0 * rng.uniform(), 32.0 * rng.uniform(), 4.0), d);
    ASSERT_EQ(r.how, HeightfieldFate::escaped);
    ++count[r.bounces];
    ASSERT_TRUE(ref_o.count(r.bounces)) << "k = " << r.bounces << " never seen by the lifted tracer";
    const V3 o(std::cos(rot) * r.o.x() - std::sin(rot) * r.o.y(), std::sin(rot) * r.o.x() + std::cos(rot) * r.o.y(),
               r.o.z());
    EXPECT_NEAR((o - ref_o[r.bounces]).norm(), 0.0, 1e-12) << "k = " << r.bounces;
  }
  ASSERT_GE(ref_frac.size(), 2u);  // a real multiple-scattering case
  for (const auto& [k, p] : ref_frac) {
    const double got = static_cast<double>(count[k]) / n;
    const double tol = 5.0 * std::sqrt(p * (1.0 - p) / n) + 4.0 / M;
    EXPECT_NEAR(got, p, tol) << "k = " << k;
  }
}

class HeightfieldEnergy : public testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(HeightfieldEnergy, EveryRayLeavesAndEnergyIsExactlyOne) {
  const auto [alpha, theta_deg] = GetParam();
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({64, alpha, alpha, 4.0, 21}));
  HeightfieldTraceOptions opt;
  opt.theta_i = deg(theta_deg);
  opt.phi_i = 0.7;
  opt.rays = 3000;
  opt.seed = 5;
  const HeightfieldTally t = trace_heightfield(s, opt);
  EXPECT_EQ(t.lost, 0);
  EXPECT_EQ(t.bounce_limit, 0);
  EXPECT_EQ(t.escaped, opt.rays);
  EXPECT_EQ(t.energy(), static_cast<double>(t.escaped));
  std::int64_t binned = 0;
  for (std::int64_t c : t.hist_by_k) binned += c;
  EXPECT_EQ(binned, t.escaped);
}

INSTANTIATE_TEST_SUITE_P(Grid, HeightfieldEnergy,
                         testing::Combine(testing::Values(0.2, 0.5, 1.0), testing::Values(0.0, 45.0, 80.0, 89.9)));

TEST(HeightfieldTracer, VerticalRaysThroughEveryVertexAndEdgeAreCountedNotLost) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({32, 0.8, 0.8, 4.0, 3}));
  const V3 down(0, 0, -1);
  const double z = s.hierarchy.root().hi + 1.0;
  int vertex = 0, edge = 0;
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      const HeightfieldRayResult v = trace_heightfield_ray(s, V3(i, j, z), down);
      ASSERT_EQ(v.how, HeightfieldFate::escaped) << i << " " << j;
      EXPECT_GE(v.vertex_hits, 1);
      vertex += v.vertex_hits;
      for (const V3& at : {V3(i + 0.5, j, z), V3(i, j + 0.5, z), V3(i + 0.5, j + 0.5, z)}) {
        const HeightfieldRayResult e = trace_heightfield_ray(s, at, down);
        ASSERT_EQ(e.how, HeightfieldFate::escaped) << at.transpose();
        EXPECT_GE(e.edge_hits, 1) << at.transpose();
        edge += e.edge_hits;
      }
    }
  EXPECT_GE(vertex, 1024);
  EXPECT_GE(edge, 3 * 1024);
}

// A ray exactly through an edge or a vertex takes the limit of the rays beside it on one side:
// its bounce count and exit direction are those of a ray moved by 1e-9 cells into one of the
// triangles touching the feature (a second, zero-distance hit of a neighbour would add a bounce).
TEST(HeightfieldTracer, EdgeAndVertexRaysTakeTheLimitOfOneSide) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({32, 0.8, 0.8, 4.0, 5}));
  const double z = s.hierarchy.root().hi + 1.0;
  const V3 down(0, 0, -1);
  // Offsets towards the interiors of the triangles around a vertex, and to both sides of each kind
  // of edge (horizontal, vertical, diagonal).
  const std::vector<V3> around_vertex = {V3(2, 1, 0),   V3(1, 2, 0),   V3(-1, 1, 0),
                                         V3(-2, -1, 0), V3(-1, -2, 0), V3(1, -1, 0)};
  int checked = 0;
  for (int j = 0; j < 32; j += 3)
    for (int i = 0; i < 32; i += 3) {
      const std::vector<std::pair<V3, std::vector<V3>>> cases = {
          {V3(i, j, z), around_vertex},
          {V3(i + 0.5, j, z), {V3(0, 1, 0), V3(0, -1, 0)}},
          {V3(i, j + 0.5, z), {V3(1, 0, 0), V3(-1, 0, 0)}},
          {V3(i + 0.5, j + 0.5, z), {V3(1, -1, 0), V3(-1, 1, 0)}}};
      for (const auto& [at, sides] : cases) {
        const HeightfieldRayResult r = trace_heightfield_ray(s, at, down);
        ASSERT_EQ(r.how, HeightfieldFate::escaped);
        bool matched = false;
        for (const V3& side : sides) {
          const HeightfieldRayResult b = trace_heightfield_ray(s, at + 1e-9 * side, down);
          matched = matched || (b.bounces == r.bounces && (b.o - r.o).norm() < 1e-12);
        }
        EXPECT_TRUE(matched) << "at " << at.transpose() << ": k = " << r.bounces << ", o = " << r.o.transpose();
        ++checked;
      }
    }
  EXPECT_EQ(checked, 4 * 11 * 11);
}

// The same limit over every edge of 40 rough fields (alpha 1, l = 2 cells): 122880 rays exactly
// on edges. Without the rule that the next segment skips the triangles touching the edge just
// hit, 3 of them met the neighbour across the edge again at t ~ 1e-16 (an extra bounce).
TEST(HeightfieldTracer, ExactEdgeRaysNeverHitTheirEdgeTwice) {
  const V3 down(0, 0, -1);
  int mismatches = 0, rays = 0;
  for (int seed = 0; seed < 40; ++seed) {
    const HeightfieldSurface s =
        make_heightfield_surface(make_gaussian_heightfield({32, 1.0, 1.0, 2.0, static_cast<std::uint64_t>(seed)}));
    const double z = s.hierarchy.root().hi + 1.0;
    for (int j = 0; j < 32; ++j)
      for (int i = 0; i < 32; ++i) {
        const std::pair<V3, V3> cases[] = {{V3(i + 0.5, j, z), V3(0, 1, 0)},
                                           {V3(i, j + 0.5, z), V3(1, 0, 0)},
                                           {V3(i + 0.5, j + 0.5, z), V3(1, -1, 0)}};
        for (const auto& [at, side] : cases) {
          const HeightfieldRayResult r = trace_heightfield_ray(s, at, down);
          const HeightfieldRayResult a = trace_heightfield_ray(s, at + 1e-9 * side, down);
          const HeightfieldRayResult b = trace_heightfield_ray(s, at - 1e-9 * side, down);
          const bool ok =
              r.how == HeightfieldFate::escaped && ((a.bounces == r.bounces && (a.o - r.o).norm() < 1e-12) ||
                                                    (b.bounces == r.bounces && (b.o - r.o).norm() < 1e-12));
          if (!ok) {
            ++mismatches;
            ADD_FAILURE() << "seed " << seed << " at " << at.transpose() << ": k = " << r.bounces << " (sides "
                          << a.bounces << ", " << b.bounces << ")";
          }
          ++rays;
        }
      }
  }
  EXPECT_EQ(rays, 40 * 3 * 1024);
  EXPECT_EQ(mismatches, 0);
}

// The hierarchy only chooses which triangles are tested: with every level below the root replaced
// by the root's bounds (nothing pruned inside a period), every ray gives the same bits.
TEST(HeightfieldTracer, HierarchyPrunesWithoutChangingAnyAnswer) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({64, 1.0, 0.6, 4.0, 17}));
  HeightfieldSurface flat_bounds = s;
  for (int k = 0; k + 1 < flat_bounds.hierarchy.levels; ++k)
    for (HeightBounds& b : flat_bounds.hierarchy.level[static_cast<std::size_t>(k)]) b = s.hierarchy.root();
  Rng rng(15, 0, 0);
  int multiple = 0;
  for (int q = 0; q < 4000; ++q) {
    const double theta = q % 4 == 3 ? deg(89.9) : deg(88.0 * rng.uniform());
    // Every fourth ray along a diagonal (d_x = d_y exactly): through period corners.
    const double phi = q % 4 == 2 ? 1.25 * kPi : 2.0 * kPi * rng.uniform();
    V3 d = -dir_of(theta, phi);
    if (q % 4 == 2) d.y() = d.x();
    const V3 org(64.0 * rng.uniform(), 64.0 * rng.uniform(), s.hierarchy.root().hi + 0.25);
    const HeightfieldRayResult a = trace_heightfield_ray(s, org, d);
    const HeightfieldRayResult b = trace_heightfield_ray(flat_bounds, org, d);
    ASSERT_EQ(a.how, HeightfieldFate::escaped);
    EXPECT_EQ(a.bounces, b.bounces) << q;
    EXPECT_EQ(a.o, b.o) << q;
    EXPECT_EQ(a.edge_hits, b.edge_hits) << q;
    multiple += a.bounces > 1;
  }
  EXPECT_GT(multiple, 40);  // 60 of the 1000 rays reflect more than once
}

TEST(HeightfieldTracer, BounceLimitIsItsOwnBucket) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({64, 1.0, 1.0, 4.0, 2}));
  HeightfieldTraceOptions opt;
  opt.rays = 4000;
  opt.ray.max_bounces = 1;
  const HeightfieldTally t = trace_heightfield(s, opt);
  EXPECT_EQ(t.lost, 0);
  EXPECT_GT(t.bounce_limit, 0);
  EXPECT_EQ(t.escaped + t.bounce_limit, t.rays);
  EXPECT_EQ(t.by_k[1], t.escaped);
  EXPECT_EQ(t.energy(), static_cast<double>(t.escaped));
}

TEST(HeightfieldTracer, WholePeriodsApartGiveTheSameRay) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({32, 0.6, 0.6, 4.0, 9}));
  Rng rng(14, 0, 0);
  for (int q = 0; q < 300; ++q) {
    const V3 d = -dir_of(deg(85.0 * rng.uniform()), 2.0 * kPi * rng.uniform());
    const V3 org(32.0 * rng.uniform(), 32.0 * rng.uniform(), s.hierarchy.root().hi + 0.5);
    const HeightfieldRayResult a = trace_heightfield_ray(s, org, d);
    const HeightfieldRayResult b = trace_heightfield_ray(s, org + V3(32.0, -64.0, 0.0), d);
    ASSERT_EQ(a.how, HeightfieldFate::escaped);
    EXPECT_EQ(a.bounces, b.bounces);
    EXPECT_EQ(a.o, b.o);
  }
}

TEST(HeightfieldTracer, TwoThreadsMergedInChunkOrderGiveTheSameBits) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({32, 0.7, 0.4, 2.0, 4}));
  HeightfieldTraceOptions opt;
  opt.theta_i = deg(60.0);
  opt.rays = 5 * kHeightfieldRaysPerChunk / 2;
  opt.ray.fresnel = HeightfieldFresnel{HeightfieldReflectance::conductor, 0.2, 3.0};
  const HeightfieldTally one = trace_heightfield(s, opt);
  const std::int64_t chunks = heightfield_chunk_count(opt);
  std::vector<HeightfieldTally> parts(static_cast<std::size_t>(chunks));
  std::thread other([&] {
    for (std::int64_t c = 1; c < chunks; c += 2)
      parts[static_cast<std::size_t>(c)] = trace_heightfield_chunk(s, opt, c);
  });
  for (std::int64_t c = 0; c < chunks; c += 2) parts[static_cast<std::size_t>(c)] = trace_heightfield_chunk(s, opt, c);
  other.join();
  HeightfieldTally two(opt.theta_bins, opt.phi_bins, opt.max_k, opt.phi_i);
  for (const HeightfieldTally& p : parts) two.merge(p);
  EXPECT_EQ(one.rays, opt.rays);
  EXPECT_EQ(two.by_k, one.by_k);
  EXPECT_EQ(two.hist_by_k, one.hist_by_k);
  EXPECT_EQ(two.energy_by_k, one.energy_by_k);
  EXPECT_EQ(two.edge_hits, one.edge_hits);
  EXPECT_LT(one.energy(), static_cast<double>(one.escaped));  // the conductor absorbs
}

TEST(HeightfieldTracer, BounceCosinesGiveEveryReflectanceOfOneTrace) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({64, 0.9, 0.9, 4.0, 12}));
  const double theta_i = deg(80.0);
  const Eigen::Vector3d dir(-std::sin(theta_i), 0.0, -std::cos(theta_i));
  const std::vector<HeightfieldFresnel> fresnels = {{HeightfieldReflectance::conductor, 0.27, 2.78},
                                                    {HeightfieldReflectance::dielectric, 1.5},
                                                    {HeightfieldReflectance::schlick, 1.0, 0.0, 0.04}};
  auto F = [](const HeightfieldFresnel& f, double c) {
    return f.kind == HeightfieldReflectance::conductor    ? ConductorReflectance{f.eta, f.kappa}(c)
           : f.kind == HeightfieldReflectance::dielectric ? DielectricReflectance{f.eta}(c)
                                                          : SchlickReflectance{f.F0}(c);
  };
  Rng rng(3, 0, 0);
  std::vector<double> cosines;
  int multiple = 0;
  double broken = 0.0;
  for (int r = 0; r < 1000; ++r) {
    const Eigen::Vector3d org(64.0 * rng.uniform(), 64.0 * rng.uniform(), s.hierarchy.root().hi + 1.0);
    const HeightfieldRayResult plain = trace_heightfield_ray(s, org, dir);
    HeightfieldRayOptions rec;
    rec.cosines = &cosines;
    const HeightfieldRayResult a = trace_heightfield_ray(s, org, dir, rec);
    ASSERT_EQ(a.how, HeightfieldFate::escaped);
    ASSERT_EQ(a.bounces, plain.bounces);
    ASSERT_EQ(a.o, plain.o);
    ASSERT_EQ(static_cast<int>(cosines.size()), a.bounces);
    multiple += a.bounces >= 2;
    for (const HeightfieldFresnel& f : fresnels) {
      HeightfieldRayOptions with;
      with.fresnel = f;
      const HeightfieldRayResult b = trace_heightfield_ray(s, org, dir, with);
      double prod = 1.0, macro = 1.0;
      for (double c : cosines) prod *= F(f, c), macro *= F(f, std::cos(theta_i));
      ASSERT_EQ(prod, b.throughput) << "ray " << r;
      broken = std::max(broken, std::abs(macro - b.throughput));
    }
  }
  EXPECT_GT(multiple, 40);            // 60 of the 1000 rays reflect more than once
  EXPECT_GT(broken, 0.05) << broken;  // the macro normal's cosine is not the facets'
}

}  // namespace
}  // namespace vgroove::sim
