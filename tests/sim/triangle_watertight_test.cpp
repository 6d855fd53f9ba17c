// Tests of sim/triangle_watertight.h: the Woop-Benthin-Wald test in double precision.
//
// Hand values: a vertical ray onto a unit right triangle at (0.25, 0.25) hits at t = 1 with the
// weights (1/2, 1/4, 1/4). Facing: det > 0 exactly when d . n < 0 (random directions, every
// dominant axis and sign). Watertightness: rays aimed at points of the shared edge of two
// non-coplanar triangles (random origins, so the rounded directions leave the edge by an ulp or
// so) hit at least one of the two, and a ray with an edge weight exactly 0 in one has it exactly
// 0 in the other. The same rays through a naive test that computes each triangle's edge functions
// from its own edge vectors (kept below as the broken variant) slip through the edge: seen here.
#include "vgroove/sim/triangle_watertight.h"

#include "vgroove/sim/rng.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <iostream>
#include <limits>

namespace vgroove::sim {
namespace {

using V3 = Eigen::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(TriangleWatertight, HandValuesOfAVerticalRay) {
  const WatertightRay r = make_watertight_ray(V3(0.25, 0.25, 1.0), V3(0.0, 0.0, -1.0));
  WatertightHit h;
  ASSERT_TRUE(intersect_watertight(r, V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), kInf, h));
  EXPECT_EQ(h.t(), 1.0);
  EXPECT_EQ(h.U / h.det, 0.5);
  EXPECT_EQ(h.V / h.det, 0.25);
  EXPECT_EQ(h.W / h.det, 0.25);
  EXPECT_EQ(h.zeros(), 0);
  // From below (back face) and beyond t_max: no hit.
  EXPECT_FALSE(intersect_watertight(make_watertight_ray(V3(0.25, 0.25, -1.0), V3(0, 0, 1)), V3(0, 0, 0), V3(1, 0, 0),
                                    V3(0, 1, 0), kInf, h));
  EXPECT_FALSE(intersect_watertight(r, V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0), 1.0, h));
  // Through the vertex (1, 0, 0) and the edge x = y: exactly two / one zero weights.
  ASSERT_TRUE(intersect_watertight(make_watertight_ray(V3(1.0, 0.0, 1.0), V3(0, 0, -1)), V3(0, 0, 0), V3(1, 0, 0),
                                   V3(0, 1, 0), kInf, h));
  EXPECT_EQ(h.zeros(), 2);
  ASSERT_TRUE(intersect_watertight(make_watertight_ray(V3(0.5, 0.5, 1.0), V3(0, 0, -1)), V3(0, 0, 0), V3(1, 0, 0),
                                   V3(0, 1, 0), kInf, h));
  EXPECT_EQ(h.zeros(), 1);
}

V3 random_unit(Rng& rng) {
  const double z = 2.0 * rng.uniform() - 1.0, a = 2.0 * std::acos(-1.0) * rng.uniform();
  const double s = std::sqrt(1.0 - z * z);
  return V3(s * std::cos(a), s * std::sin(a), z);
}

TEST(TriangleWatertight, FrontFacingIsDetPositive) {
  Rng rng(1, 2, 3);
  const V3 a(0.1, -0.2, 0.3), b(1.2, 0.1, -0.4), c(-0.3, 0.9, 0.5);
  const V3 n = (b - a).cross(c - a);
  int hits = 0;
  for (int q = 0; q < 20000; ++q) {
    const V3 d = random_unit(rng);
    const double u = rng.uniform(), v = rng.uniform() * (1.0 - u);
    const V3 target = a + u * (b - a) + v * (c - a);
    WatertightHit h;
    const bool hit = intersect_watertight(make_watertight_ray(target - 3.0 * d, d), a, b, c, kInf, h);
    if (d.dot(n) < -1e-9) {
      EXPECT_TRUE(hit) << "d = " << d.transpose();
      hits += hit;
      // t = T / det loses digits as the ray grazes the plane: a few ulps over the cosine.
      if (hit) {
        EXPECT_NEAR(h.t(), 3.0, 1e-14 / std::abs(d.dot(n.normalized())));
      }
    }
    if (d.dot(n) > 1e-9) {
      EXPECT_FALSE(hit) << "d = " << d.transpose();
    }
  }
  EXPECT_GT(hits, 9000);
}

// The broken variant: each triangle's barycentric test from its own edge vectors (Moller-Trumbore
// style), so the shared edge is evaluated by different operations in the two triangles.
bool naive_hit(const V3& o, const V3& d, const V3& a, const V3& b, const V3& c) {
  const V3 e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0) return false;
  const V3 s = o - a;
  const double u = s.dot(p) / det;
  const V3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  return u >= 0.0 && v >= 0.0 && u + v <= 1.0 && e2.dot(q) / det > 0.0;
}

TEST(TriangleWatertight, NoRaySlipsThroughASharedEdge) {
  // Two triangles of a non-planar quad sharing the edge p q, counter-clockwise seen from above.
  const V3 p(0.0, 0.0, 0.37), q(1.0, 1.0, -0.21), r(1.0, 0.0, 0.13), s(0.0, 1.0, 0.71);
  Rng rng(4, 5, 6);
  int slips = 0, naive_slips = 0, edge_zeros = 0;
  const int rays = 200000;
  for (int k = 0; k < rays; ++k) {
    const double f = rng.uniform();
    const V3 target = p + f * (q - p);
    V3 d = random_unit(rng);
    if (d.z() > 0.0) d.z() = -d.z();
    // Rays that meet both triangles' front faces (the two planes differ).
    if (d.dot((r - p).cross(q - p)) > -0.05 || d.dot((q - p).cross(s - p)) > -0.05) continue;
    const V3 o = target - (1.0 + 3.0 * rng.uniform()) * d;
    const WatertightRay w = make_watertight_ray(o, d);
    WatertightHit h1, h2;
    const bool a = intersect_watertight(w, p, r, q, kInf, h1);  // counter-clockwise from above
    const bool b = intersect_watertight(w, p, q, s, kInf, h2);
    if (!a && !b) ++slips;
    if (a && b) {
      // Both: the shared edge's weight is exactly 0 in each (weight of r in the first, of s in the second).
      EXPECT_EQ(h1.V, 0.0);
      EXPECT_EQ(h2.W, 0.0);
      ++edge_zeros;
    }
    if (!naive_hit(o, d, p, r, q) && !naive_hit(o, d, p, q, s)) ++naive_slips;
  }
  EXPECT_EQ(slips, 0);
  EXPECT_GT(edge_zeros, 0);  // rays exactly on the edge occur and are counted by both
  EXPECT_GT(naive_slips, 0) << "the naive test was expected to slip";
  std::cout << "rays on the edge (both hit): " << edge_zeros << ", naive slips: " << naive_slips << "\n";
}

}  // namespace
}  // namespace vgroove::sim
