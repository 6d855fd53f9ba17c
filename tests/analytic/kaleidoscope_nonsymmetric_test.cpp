// Tests of the nonsymmetric kaleidoscope (Lee et al. 2018, Eq. 7-9) on its own: the symmetric
// special case, conservation, mirror symmetry and hand values.
#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/common/angles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

namespace vgroove::analytic {
namespace {

// Shares summed per bounce count (Eq. 9's zones may share a count when k_b = 2).
std::map<int, double> by_count(const NonsymmetricPrediction& p) {
  std::map<int, double> m;
  for (const BounceShare& s : p.share)
    if (s.G != 0.0) m[s.n] += s.G;
  return m;
}
std::map<int, double> by_count(const FacetPrediction& p) {
  std::map<int, double> m;
  for (const BounceShare& s : {p.fewer, p.more})
    if (s.G != 0.0) m[s.n] += s.G;
  return m;
}

TEST(KaleidoscopeNonsymmetric, SymmetricGroovesReduceToEq4To6) {
  for (double theta_s_deg : {2.5, 10.0, 30.0, 44.0, 45.0, 60.0, 77.0, 87.5})
    for (double theta_i_deg = -89.0; theta_i_deg <= 89.0; theta_i_deg += 3.7)
      for (FacetSide side : {FacetSide::left, FacetSide::right}) {
        const double ts = theta_s_deg * kRadPerDeg, ti = theta_i_deg * kRadPerDeg;
        const NonsymmetricPrediction ns = G_nonsymmetric(ti, -ts, ts, side);
        const FacetPrediction sy = G_kaleidoscopic(ti, std::numbers::pi - 2.0 * ts, side);
        ASSERT_EQ(ns.lit, sy.lit) << "theta_s=" << theta_s_deg << " theta_i=" << theta_i_deg;
        if (!ns.lit) continue;
        EXPECT_NEAR(ns.shadow, sy.shadow, 1e-12) << "theta_s=" << theta_s_deg << " theta_i=" << theta_i_deg;
        const auto a = by_count(ns), b = by_count(sy);
        for (const auto& [n, g] : a)
          EXPECT_NEAR(g, b.count(n) ? b.at(n) : 0.0, 1e-12)
              << "n=" << n << " theta_s=" << theta_s_deg << " theta_i=" << theta_i_deg;
        for (const auto& [n, g] : b)
          EXPECT_NEAR(g, a.count(n) ? a.at(n) : 0.0, 1e-12)
              << "n=" << n << " theta_s=" << theta_s_deg << " theta_i=" << theta_i_deg;
        for (int n = 1; n < 6; ++n)
          EXPECT_NEAR(exit_angle_nonsymmetric(ti, -ts, ts, n, side),
                      exit_angle(ti, std::numbers::pi - 2.0 * ts, n, side), 1e-12)
              << "n=" << n << " theta_s=" << theta_s_deg << " theta_i=" << theta_i_deg;
      }
}

TEST(KaleidoscopeNonsymmetric, SharesAreFractionsThatSumToOne) {
  for (double l = -90.0; l < 0.0; l += 7.3)
    for (double r = 1.0; r <= 90.0; r += 6.1)
      for (double ti = -89.5; ti < 90.0; ti += 4.9)
        for (FacetSide side : {FacetSide::left, FacetSide::right}) {
          if (aperture(l * kRadPerDeg, r * kRadPerDeg) <= 0.0) continue;
          const NonsymmetricPrediction p = G_nonsymmetric(ti * kRadPerDeg, l * kRadPerDeg, r * kRadPerDeg, side);
          if (!p.lit) continue;
          double sum = p.shadow;
          for (const BounceShare& s : p.share) {
            EXPECT_GE(s.G, 0.0) << "theta_l=" << l << " theta_r=" << r << " theta_i=" << ti;
            EXPECT_LE(s.G, 1.0) << "theta_l=" << l << " theta_r=" << r << " theta_i=" << ti;
            sum += s.G;
          }
          EXPECT_NEAR(sum, 1.0, 1e-12) << "theta_l=" << l << " theta_r=" << r << " theta_i=" << ti;
        }
}

TEST(KaleidoscopeNonsymmetric, MirrorImageSwapsTheFacets) {
  // The groove (theta_l, theta_r) lit from theta_i is the mirror image of (-theta_r, -theta_l) lit
  // from -theta_i, with left and right exchanged and exit angles negated.
  for (double l : {-80.0, -45.0, -12.0})
    for (double r : {7.0, 33.0, 71.0})
      for (double ti : {-70.0, -20.0, 0.0, 15.0, 64.0}) {
        const auto a = G_nonsymmetric(ti * kRadPerDeg, l * kRadPerDeg, r * kRadPerDeg, FacetSide::left);
        const auto b = G_nonsymmetric(-ti * kRadPerDeg, -r * kRadPerDeg, -l * kRadPerDeg, FacetSide::right);
        ASSERT_EQ(a.lit, b.lit);
        if (!a.lit) continue;
        for (int z = 0; z < 4; ++z) {
          EXPECT_EQ(a.share[z].n, b.share[z].n);
          EXPECT_NEAR(a.share[z].G, b.share[z].G, 1e-12) << "theta_l=" << l << " theta_r=" << r << " theta_i=" << ti;
          EXPECT_NEAR(a.share[z].theta_o, -b.share[z].theta_o, 1e-12);
        }
      }
}

TEST(KaleidoscopeNonsymmetric, RightAngleCornerHandValues) {
  // theta_l = -30, theta_r = 60: a right-angle corner (theta_v = 90) tilted by 15 deg. Light from
  // theta_i = 20 deg: one reflection on the left facet mirrors it about that facet's normal,
  // theta_o = 2 theta_l - theta_i = -80 deg; two reflections in a right angle retroreflect: 20 deg.
  EXPECT_NEAR(aperture(-30 * kRadPerDeg, 60 * kRadPerDeg), 90 * kRadPerDeg, 1e-15);
  EXPECT_NEAR(exit_angle_nonsymmetric(20 * kRadPerDeg, -30 * kRadPerDeg, 60 * kRadPerDeg, 1), -80 * kRadPerDeg, 1e-12);
  EXPECT_NEAR(exit_angle_nonsymmetric(20 * kRadPerDeg, -30 * kRadPerDeg, 60 * kRadPerDeg, 2), 20 * kRadPerDeg, 1e-12);
  // Eq. (7): (pi + 40 - 30 deg) / 180 deg + 0.5 = 1.555..., k_b = 2.
  EXPECT_EQ(bounce_count_kb(20 * kRadPerDeg, -30 * kRadPerDeg, 60 * kRadPerDeg), 2);
}

TEST(KaleidoscopeNonsymmetric, JacobianAngularFactorIsTheDerivativeOfEq8) {
  // Central differences of Eq. (8) in theta_l (theta_o is linear in theta_l at fixed k).
  for (int k = 1; k <= 9; ++k) {
    const double ti = 0.3, l = -0.6, r = 0.4, h = 1e-6;
    const double d = (exit_angle_nonsymmetric(ti, l + h, r, k) - exit_angle_nonsymmetric(ti, l - h, r, k)) / (2 * h);
    EXPECT_NEAR(0.5 * d, dtheta_h_dtheta_l(k), 1e-8) << "k=" << k;
  }
  // The printed factor 0.5 |0.5 - (-1)^k (k + 0.5)| is (k + 1)/2 for odd k and k/2 for even k.
  EXPECT_DOUBLE_EQ(std::abs(dtheta_h_dtheta_l(1)), 1.0);
  EXPECT_DOUBLE_EQ(std::abs(dtheta_h_dtheta_l(2)), 1.0);
  EXPECT_DOUBLE_EQ(std::abs(dtheta_h_dtheta_l(3)), 2.0);
  EXPECT_DOUBLE_EQ(std::abs(dtheta_h_dtheta_l(4)), 2.0);
}

}  // namespace
}  // namespace vgroove::analytic
