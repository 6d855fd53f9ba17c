// Tests of sim/heightfield_masking.h: traced G1 on surfaces whose answer is known by hand.
//
// Flat: every point is visible from every direction (G1 = 1). One V-groove family of slope s
// (facets at theta_m = atan s, normals in the x-z plane), viewed across the grooves at theta_o
// (phi_o = 0): the facet tilted away from o is in view whole while it faces o (theta_o < pi/2 -
// theta_m); the one tilted towards o is hidden behind the near ridge from theta_o + theta_m >
// pi/2 on, where the visible part of its length is (by the law of sines in the groove's
// triangle) 2 cos theta_m cos theta_o / cos(theta_o - theta_m) - the V-cavity's G1 (Heitz 2014,
// Eq. 24), exact on V-grooves. Viewed along the grooves (phi_o = pi/2) nothing is hidden.
// Every surface: the visible projected area per unit macro area is cos theta_o (each line from o
// meets the surface once), within 5 standard errors of the points' mean.
#include "vgroove/sim/heightfield_masking.h"
#include "vgroove/sim/heightfield.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(HeightfieldMasking, FlatFieldIsVisibleWhole) {
  const HeightfieldSurface s = make_heightfield_surface(make_flat_heightfield(16, 0.25));
  for (double theta_o_deg : {0.0, 30.0, 60.0, 85.0, 89.9}) {
    HeightfieldMaskingOptions opt;
    opt.theta_o = theta_o_deg * kDeg;
    opt.phi_o = 0.3;
    opt.points = 5000;
    const HeightfieldMaskingTally t = heightfield_masking(s, opt);
    EXPECT_EQ(t.points, 5000);
    EXPECT_EQ(t.front, 5000) << theta_o_deg;
    EXPECT_EQ(t.visible, 5000) << theta_o_deg;
    EXPECT_EQ(t.lost, 0);
    EXPECT_EQ(t.g1(), 1.0) << theta_o_deg;
    // Every point carries w = cos theta_o: the visible area is that to the sum's rounding.
    EXPECT_NEAR(t.visible_area(), std::cos(opt.theta_o), 1e-12) << theta_o_deg;
  }
}

// The V-groove family (slope 1: theta_m = 45 deg) across and along the grooves.
TEST(HeightfieldMasking, VGrooveFamilyIsTheVCavityByHand) {
  const double slope = 1.0, theta_m = std::atan(slope);
  const HeightfieldSurface s = make_heightfield_surface(make_vgroove_heightfield(64, 8, slope));
  for (double theta_o_deg : {20.0, 40.0, 50.0, 60.0, 75.0, 85.0}) {
    HeightfieldMaskingOptions opt;
    opt.theta_o = theta_o_deg * kDeg;
    opt.phi_o = 0.0;
    opt.points = 40000;
    opt.theta_m_bins = 2;  // 0-45, 45-90: the facets (45 deg) fall in bin 1
    opt.phi_m_bins = 2;    // towards o (0), away from o (1)
    const HeightfieldMaskingTally t = heightfield_masking(s, opt);
    ASSERT_EQ(t.lost, 0);
    const int towards = 1 * 2 + 0, away = 1 * 2 + 1;
    const double c = std::cos(opt.theta_o);
    const double hidden_from = 0.5 * std::numbers::pi - theta_m;
    // Towards o: G1 by hand; its points are a binomial sample, so 5 sigma of the count.
    const double g_towards =
        opt.theta_o > hidden_from ? 2.0 * std::cos(theta_m) * c / std::cos(opt.theta_o - theta_m) : 1.0;
    const double k = static_cast<double>(t.count[towards]);
    const double sd = std::sqrt(std::max(g_towards * (1.0 - g_towards), 1.0 / k) / k);
    EXPECT_NEAR(t.g1(towards), g_towards, 5.0 * sd) << "theta_o = " << theta_o_deg;
    if (opt.theta_o < hidden_from) {
      EXPECT_EQ(t.g1(away), 1.0) << "theta_o = " << theta_o_deg;
    } else {
      EXPECT_EQ(t.count[away], 0) << "theta_o = " << theta_o_deg;  // back-facing
    }
    EXPECT_NEAR(t.visible_area(), c, 5.0 * t.visible_area_se()) << "theta_o = " << theta_o_deg;
  }
  // Along the grooves: every facing point visible.
  HeightfieldMaskingOptions along;
  along.theta_o = 80.0 * kDeg;
  along.phi_o = 0.5 * std::numbers::pi;
  along.points = 5000;
  const HeightfieldMaskingTally t = heightfield_masking(s, along);
  EXPECT_EQ(t.visible, t.front);
  EXPECT_EQ(t.front, t.points);
}

// The identity on rough Gaussian and GGX fields, to grazing view.
TEST(HeightfieldMasking, VisibleProjectedAreaIsTheMacroArea) {
  for (bool ggx : {false, true}) {
    const GaussianHeightfieldOptions f{64, 0.6, 0.4, 4.0, 5};
    const HeightfieldSurface s = make_heightfield_surface(ggx ? make_ggx_heightfield(f) : make_gaussian_heightfield(f));
    for (double theta_o_deg : {0.0, 45.0, 70.0, 85.0, 89.9}) {
      HeightfieldMaskingOptions opt;
      opt.theta_o = theta_o_deg * kDeg;
      opt.phi_o = 0.7;
      opt.points = 80000;
      const HeightfieldMaskingTally t = heightfield_masking(s, opt);
      EXPECT_EQ(t.lost, 0);
      EXPECT_NEAR(t.visible_area(), std::cos(opt.theta_o), 5.0 * t.visible_area_se())
          << (ggx ? "ggx" : "gaussian") << " theta_o = " << theta_o_deg << ": G1 = " << t.g1();
      // The check resolves 5% of the area up to 85 deg.
      if (theta_o_deg <= 85.0) {
        EXPECT_LT(5.0 * t.visible_area_se(), 0.05 * std::cos(opt.theta_o));
      }
    }
  }
}

// A small period viewed at grazing along the grid's axis or diagonal: the ray towards a point crosses
// many periods, and the periodic images of the point's own triangle can hide it (a point counted
// visible because the ray met "its" triangle in another period broke the identity by 23 to 65
// standard errors at 89 and 89.9 deg).
TEST(HeightfieldMasking, ImagesOfThePointsOwnTriangleCanHideIt) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({16, 0.8, 0.8, 2.0, 3}));
  for (double phi_o : {0.0, 0.25 * std::numbers::pi})
    for (double theta_o_deg : {89.0, 89.9}) {
      HeightfieldMaskingOptions opt;
      opt.theta_o = theta_o_deg * kDeg;
      opt.phi_o = phi_o;
      opt.points = 100000;
      const HeightfieldMaskingTally t = heightfield_masking(s, opt);
      EXPECT_EQ(t.lost, 0);
      EXPECT_NEAR(t.visible_area(), std::cos(opt.theta_o), 5.0 * t.visible_area_se())
          << "phi_o = " << phi_o << " theta_o = " << theta_o_deg;
    }
}

TEST(HeightfieldMasking, ChunksMergedInOrderGiveTheSameBits) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({64, 0.5, 0.5, 4.0, 2}));
  HeightfieldMaskingOptions opt;
  opt.theta_o = 1.0;
  opt.points = 3 * kHeightfieldPointsPerChunk + 17;
  opt.seed = 11;
  const HeightfieldMaskingTally a = heightfield_masking(s, opt);
  HeightfieldMaskingTally b(opt.theta_m_bins, opt.phi_m_bins);
  for (std::int64_t c = 0; c < heightfield_masking_chunk_count(opt); ++c) b.merge(heightfield_masking_chunk(s, opt, c));
  EXPECT_EQ(a.points, opt.points);
  EXPECT_EQ(a.visible, b.visible);
  EXPECT_EQ(a.sum_wv, b.sum_wv);
  EXPECT_EQ(a.visible_weight, b.visible_weight);
  opt.seed = 12;
  EXPECT_NE(heightfield_masking(s, opt).sum_wv, a.sum_wv);
}

TEST(HeightfieldMasking, OutOfRangeOptionsAreRefused) {
  const HeightfieldSurface s = make_heightfield_surface(make_flat_heightfield(4));
  HeightfieldMaskingOptions opt;
  opt.theta_o = 0.5 * std::numbers::pi;
  EXPECT_THROW(heightfield_masking(s, opt), std::invalid_argument);
  opt.theta_o = 0.1;
  opt.points = 0;
  EXPECT_THROW(heightfield_masking(s, opt), std::invalid_argument);
}

// G2(i, o) (heightfield_joint_masking): identities that hold exactly on every realization.
// i = o: every point is visible from both or from neither, so G2 = G1_i = G1_o to the bit, and
// the points (heightfield_masking's stream and layout) and their visible count are G1's.
TEST(HeightfieldJointMasking, SameDirectionIsG1OnTheSamePoints) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({64, 0.6, 0.6, 4.0, 7}));
  for (double theta_deg : {0.0, 60.0, 85.0}) {
    HeightfieldJointMaskingOptions opt;
    opt.theta_i = opt.theta_o = theta_deg * kDeg;
    opt.phi_i = opt.phi_o = 0.4;
    opt.points = 2 * kHeightfieldPointsPerChunk + 5;
    opt.seed = 3;
    const HeightfieldJointMaskingTally t = heightfield_joint_masking(s, opt);
    EXPECT_EQ(t.points, opt.points);
    EXPECT_EQ(t.lost, 0);
    EXPECT_EQ(t.visible_both, t.visible_i);
    EXPECT_EQ(t.visible_both, t.visible_o);
    EXPECT_EQ(t.g2(), t.g1_i());
    EXPECT_EQ(t.g2(), t.g1_o());
    for (int b = 0; b < opt.theta_m_bins * opt.phi_m_bins; ++b)
      if (t.count[static_cast<std::size_t>(b)] > 0) {
        EXPECT_EQ(t.g2(b), t.g1_o(b)) << "bin " << b;
      }
    HeightfieldMaskingOptions g1;
    g1.theta_o = opt.theta_o, g1.phi_o = opt.phi_o, g1.points = opt.points, g1.seed = opt.seed;
    const HeightfieldMaskingTally m = heightfield_masking(s, g1);
    EXPECT_EQ(t.front, m.front) << theta_deg;
    EXPECT_EQ(t.visible_both, m.visible) << theta_deg;
    if (theta_deg > 0.0) {
      EXPECT_LT(t.visible_both, t.front) << theta_deg;  // some masking to see
    }
  }
}

// Apart: G1_i + G1_o - 1 <= G2 <= min(G1_i, G1_o) bin by bin (a point visible from both is
// visible from each; one hidden from i or from o is not counted), and swapping i and o gives the
// same sums to the bit, bin by bin (4 azimuth bins from the pair's bisector: reciprocity,
// G2(i, o, m) = G2(o, i, m)); HeightfieldJointMasking.BinsAreSymmetricInIAndO: more pairs.
TEST(HeightfieldJointMasking, BoundedByEachG1AndSymmetric) {
  for (bool ggx : {false, true}) {
    const GaussianHeightfieldOptions f{64, 0.8, 0.8, 4.0, 9};
    const HeightfieldSurface s = make_heightfield_surface(ggx ? make_ggx_heightfield(f) : make_gaussian_heightfield(f));
    HeightfieldJointMaskingOptions opt;
    opt.theta_i = 70.0 * kDeg, opt.phi_i = 0.3;
    opt.theta_o = 50.0 * kDeg, opt.phi_o = 0.3 + 2.0;
    opt.points = 6000;
    opt.theta_m_bins = 4, opt.phi_m_bins = 4;
    const HeightfieldJointMaskingTally t = heightfield_joint_masking(s, opt);
    EXPECT_EQ(t.lost, 0);
    EXPECT_LT(t.visible_both, std::min(t.visible_i, t.visible_o));
    for (int b = -1; b < opt.theta_m_bins * opt.phi_m_bins; ++b) {
      const double g2 = b < 0 ? t.g2() : t.g2(b), gi = b < 0 ? t.g1_i() : t.g1_i(b), go = b < 0 ? t.g1_o() : t.g1_o(b);
      if (b >= 0 && t.count[static_cast<std::size_t>(b)] == 0) continue;
      EXPECT_LE(g2, std::min(gi, go)) << "bin " << b;
      EXPECT_GE(g2, gi + go - 1.0 - 1e-15) << "bin " << b;  // the sums' rounding
    }
    HeightfieldJointMaskingOptions swapped = opt;
    std::swap(swapped.theta_i, swapped.theta_o);
    std::swap(swapped.phi_i, swapped.phi_o);
    const HeightfieldJointMaskingTally u = heightfield_joint_masking(s, swapped);
    EXPECT_EQ(u.sum_wio, t.sum_wio);
    EXPECT_EQ(u.sum_wi, t.sum_wo);
    EXPECT_EQ(u.sum_wo, t.sum_wi);
    EXPECT_EQ(u.weight_io, t.weight_io);
    EXPECT_EQ(u.weight, t.weight);
    EXPECT_EQ(u.weight_i, t.weight_o);
    EXPECT_EQ(u.count, t.count);
    EXPECT_EQ(u.visible_both, t.visible_both);
  }
}

// The reference azimuth of G2's bins by hand: the bisector of the smaller angle, across azimuth
// 0 too; opposite azimuths: the bisector in [0, pi); a direction at the normal: the other's.
TEST(HeightfieldJointMasking, BinAzimuthIsTheBisectorOfThePair) {
  const double pi = std::numbers::pi;
  EXPECT_NEAR(heightfield_joint_bin_azimuth(0.5, 0.2, 1.0, 1.0), 0.6, 1e-15);
  EXPECT_NEAR(heightfield_joint_bin_azimuth(0.5, 6.0, 1.0, 0.2), 0.5 * (6.0 + 0.2 + 2.0 * pi), 1e-14);
  EXPECT_NEAR(heightfield_joint_bin_azimuth(0.5, -0.3, 1.0, 0.3), 0.0, 1e-15);
  EXPECT_EQ(heightfield_joint_bin_azimuth(1.0, 0.0, 1.0, pi), 0.5 * pi);
  EXPECT_NEAR(heightfield_joint_bin_azimuth(1.0, 1.5 * pi, 1.0, 0.5 * pi), 0.0, 1e-15);
  EXPECT_EQ(heightfield_joint_bin_azimuth(0.0, 0.0, 1.0, 2.5), 2.5);
  EXPECT_EQ(heightfield_joint_bin_azimuth(1.0, 2.5, 0.0, 0.0), 2.5);
  for (const auto& [a, b] : {std::pair{0.1, 3.0}, std::pair{0.0, pi}, std::pair{5.9, 0.4}, std::pair{-2.0, 2.0}})
    EXPECT_EQ(heightfield_joint_bin_azimuth(0.7, a, 0.4, b), heightfield_joint_bin_azimuth(0.4, b, 0.7, a)) << a;
}

// Reciprocity bin by bin on more pairs (8 azimuth bins): across, opposite (the mirror plane, the
// suite's dphi 180), the light at the normal (the bins are then G1's from phi_o: the same
// front-facing count per bin as heightfield_masking(o) on the same points).
TEST(HeightfieldJointMasking, BinsAreSymmetricInIAndO) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({64, 0.7, 0.7, 4.0, 4}));
  struct Pair {
    double theta_i, phi_i, theta_o, phi_o;
  };
  const double pi = std::numbers::pi;
  for (const Pair& c :
       {Pair{1.2, 0.0, 1.2, pi}, Pair{0.9, 0.0, 1.3, 0.5 * pi}, Pair{1.4, 5.5, 0.6, 1.0}, Pair{0.0, 0.0, 1.3, 2.0}}) {
    HeightfieldJointMaskingOptions opt;
    opt.theta_i = c.theta_i, opt.phi_i = c.phi_i, opt.theta_o = c.theta_o, opt.phi_o = c.phi_o;
    opt.points = 5000;
    opt.theta_m_bins = 3, opt.phi_m_bins = 8;
    opt.seed = 5;
    HeightfieldJointMaskingOptions swapped = opt;
    std::swap(swapped.theta_i, swapped.theta_o);
    std::swap(swapped.phi_i, swapped.phi_o);
    const HeightfieldJointMaskingTally t = heightfield_joint_masking(s, opt), u = heightfield_joint_masking(s, swapped);
    EXPECT_EQ(t.lost, 0);
    EXPECT_LT(t.visible_both, t.front);  // some shadowing or masking to compare
    EXPECT_EQ(u.count, t.count) << c.theta_i << " " << c.phi_o;
    EXPECT_EQ(u.weight, t.weight) << c.theta_i << " " << c.phi_o;
    EXPECT_EQ(u.weight_io, t.weight_io) << c.theta_i << " " << c.phi_o;
    EXPECT_EQ(u.weight_i, t.weight_o) << c.theta_i << " " << c.phi_o;
    EXPECT_EQ(u.weight_o, t.weight_i) << c.theta_i << " " << c.phi_o;
    if (c.theta_i == 0.0) {
      HeightfieldMaskingOptions g1;
      g1.theta_o = opt.theta_o, g1.phi_o = opt.phi_o, g1.points = opt.points, g1.seed = opt.seed;
      g1.theta_m_bins = opt.theta_m_bins, g1.phi_m_bins = opt.phi_m_bins;
      EXPECT_EQ(heightfield_masking(s, g1).count, t.count);
    }
  }
}

// One V-groove family (slope 1, facets at 45 deg) across the grooves: the part of a facet visible
// from any direction is a segment from its ridge (the opposite wall hides its foot), so a point
// visible from the more masked direction is visible from the other: visible_both = min(visible_i,
// visible_o) exactly, and G2 of the facet is min of the V-cavity G1s (2 cos theta_m cos theta /
// cos(theta - theta_m) from theta + theta_m > 90 deg, header of this file).
TEST(HeightfieldJointMasking, VGrooveFamilyIsTheMinimumOfTheTwoG1s) {
  const double theta_m = std::atan(1.0);
  const HeightfieldSurface s = make_heightfield_surface(make_vgroove_heightfield(64, 8, 1.0));
  const auto g1 = [&](double theta) {
    return theta + theta_m > 0.5 * std::numbers::pi
               ? 2.0 * std::cos(theta_m) * std::cos(theta) / std::cos(theta - theta_m)
               : 1.0;
  };
  struct Pair {
    double theta_i_deg, phi_i, theta_o_deg;
  };
  // Both on the side the +x facet faces; the light opposite at 30 deg (the +x facet turned away
  // from it, in view whole); both grazing on one side.
  for (const Pair& c : {Pair{70.0, 0.0, 55.0}, Pair{30.0, std::numbers::pi, 60.0}, Pair{85.0, 0.0, 80.0}}) {
    HeightfieldJointMaskingOptions opt;
    opt.theta_i = c.theta_i_deg * kDeg, opt.phi_i = c.phi_i;
    opt.theta_o = c.theta_o_deg * kDeg, opt.phi_o = 0.0;
    opt.points = 40000;
    opt.theta_m_bins = 2, opt.phi_m_bins = 2;
    const HeightfieldJointMaskingTally t = heightfield_joint_masking(s, opt);
    ASSERT_EQ(t.lost, 0);
    EXPECT_EQ(t.visible_both, std::min(t.visible_i, t.visible_o)) << c.theta_i_deg << " " << c.theta_o_deg;
    // The weight: one facet, N = (1, 0, 1), w = (i.N) (o.N) / |N| = |N| (i.m) (o.m) at every point.
    const double si = std::sin(opt.theta_i) * std::cos(opt.phi_i), so = std::sin(opt.theta_o);
    const double w = (si + std::cos(opt.theta_i)) * (so + std::cos(opt.theta_o)) / std::sqrt(2.0);
    EXPECT_NEAR(t.sum_w / static_cast<double>(t.front), w, 1e-12 * w);
    const int towards = 1 * 2 + 0;         // the +x facet: normal azimuth 0 = phi_o
    EXPECT_EQ(t.count[towards], t.front);  // the -x facet faces away from o (theta_o > 45 deg)
    const double expected = std::min(c.phi_i == 0.0 ? g1(opt.theta_i) : 1.0, g1(opt.theta_o));
    const double k = static_cast<double>(t.count[towards]);
    const double sd = std::sqrt(std::max(expected * (1.0 - expected), 1.0 / k) / k);
    EXPECT_NEAR(t.g2(towards), expected, 5.0 * sd) << c.theta_i_deg << " " << c.theta_o_deg;
  }
}

TEST(HeightfieldJointMasking, ChunksMergedInOrderAndOutOfRangeOptions) {
  const HeightfieldSurface s = make_heightfield_surface(make_gaussian_heightfield({64, 0.5, 0.5, 4.0, 2}));
  HeightfieldJointMaskingOptions opt;
  opt.theta_i = 1.1, opt.theta_o = 0.7, opt.phi_o = 2.5;
  opt.points = 2 * kHeightfieldPointsPerChunk + 17;
  opt.seed = 11;
  const HeightfieldJointMaskingTally a = heightfield_joint_masking(s, opt);
  HeightfieldJointMaskingTally b(opt.theta_m_bins, opt.phi_m_bins);
  for (std::int64_t c = 0; c < heightfield_joint_masking_chunk_count(opt); ++c)
    b.merge(heightfield_joint_masking_chunk(s, opt, c));
  EXPECT_EQ(a.sum_wio, b.sum_wio);
  EXPECT_EQ(a.weight_io, b.weight_io);
  EXPECT_EQ(a.visible_both, b.visible_both);
  opt.theta_i = 0.5 * std::numbers::pi;
  EXPECT_THROW(heightfield_joint_masking(s, opt), std::invalid_argument);
  opt.theta_i = 0.1, opt.theta_o = -0.1;
  EXPECT_THROW(heightfield_joint_masking(s, opt), std::invalid_argument);
  opt.theta_o = 0.1, opt.points = 0;
  EXPECT_THROW(heightfield_joint_masking(s, opt), std::invalid_argument);
}

}  // namespace
}  // namespace vgroove::sim
