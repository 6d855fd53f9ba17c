// Tests of the flatland V-groove BRDF (analytic/brdf_flatland.h): the white furnace, reciprocity,
// the flatland Eq. (25) (Cook-Torrance == the k = 1 term), pointwise against binned, hand values
// and hard angles.
#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/common/angles.h"

#include "tests/stats.h"
#include "vgroove/analytic/ndf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace vgroove::analytic {
namespace {

constexpr NdfKind kNdfs[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};

// White furnace: F = 1 and every groove's peaks on one line, so every ray that enters leaves
// (header, step b). The sum of all rows, the k > max_k one included, is 1 up to quadrature
// error; the pieces are smooth and Gauss-Legendre converges exponentially, so 1e-9 is a
// quadrature bound, far above rounding (~1e-15 per bin times 90 bins). Phong with alpha = 0.01
// (exponent 19998) reaches 1.3e-11: the normalization constant of D2_phong itself, a ratio of
// Gamma functions of ~1e4, carries that error.
TEST(FlatlandLobe, WhiteFurnace) {
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.01, 0.1, 0.3, 0.5, 0.7, 1.0, 2.0})
      for (double deg : {0.0, 20.0, 40.0, 60.0, 80.0, 89.9}) {
        const FlatlandLobe lobe = flatland_lobe(ndf, alpha, deg * kRadPerDeg, 90, 16);
        EXPECT_NEAR(lobe.albedo, 1.0, 1e-9) << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg;
        EXPECT_EQ(lobe.by_k[0], 0.0);  // peaks on a line: every ray meets a facet
        EXPECT_LT(lobe.below, 1e-15) << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg;
        double bins = 0.0;
        for (double v : lobe.theta_o) bins += v;
        EXPECT_NEAR(bins, lobe.albedo, 1e-13);
      }
}

// The single lobe loses what Cook-Torrance ignores: albedo < 1 (strictly, where the NDF has mass
// beyond 30 deg, as all three have at alpha >= 0.3). At normal incidence there is no shadowing but
// there is masking (header, step e): the albedo is int D2 cos(h) min(1, 2 cos 2h)^+ dh, computed
// here by tanh-sinh on the pieces split at the kinks h = +-30 deg and +-45 deg (2 cos 2h = 1, 0).
TEST(FlatlandSingleLobe, AlbedoBelowOneAndNormalIncidenceByHand) {
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.3, 0.5, 1.0, 2.0}) {
      for (double deg : {0.0, 40.0, 80.0}) {
        const FlatlandLobe s = flatland_single_lobe(ndf, alpha, deg * kRadPerDeg, 90);
        EXPECT_LT(s.albedo, 1.0) << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg;
        EXPECT_GT(s.albedo, 0.0);
      }
      auto f = [&](double h) {
        return D2(ndf, h, alpha) * std::cos(h) * std::min(1.0, std::max(0.0, 2.0 * std::cos(2.0 * h)));
      };
      const double a30 = std::numbers::pi / 6.0, a45 = std::numbers::pi / 4.0;
      const double by_hand = 2.0 * (test_stats::tanh_sinh(f, 0.0, a30) + test_stats::tanh_sinh(f, a30, a45));
      const FlatlandLobe s0 = flatland_single_lobe(ndf, alpha, 0.0, 90);
      EXPECT_NEAR(s0.albedo, by_hand, 1e-10) << ndf_name(ndf) << " alpha=" << alpha;
    }
}

// Reciprocity (header): rho2(i, o; k) cos cos is the same both ways per k. Rounding: w_k is a
// difference of offsets f of size <= 1 (3 roundings each ~eps), so each solution carries an
// absolute error of at most 16 eps D2(theta_s) / (2k cos theta_i cos theta_o); the bound sums
// that over the candidate solutions of both directions (the header's inversion of Eq. 5).
double rounding_scale(NdfKind ndf, double alpha, double ti, double to, int k) {
  double s = 0.0;
  for (double sgn_side : {1.0, -1.0})
    for (int m = -k - 2; m <= k + 2; ++m) {
      const double a = sgn_side * ti, b = sgn_side * to;
      const double theta_v = (a + std::numbers::pi - (k % 2 == 0 ? 1.0 : -1.0) * b + 2.0 * std::numbers::pi * m) / k;
      if (theta_v > 0.0 && theta_v <= std::numbers::pi) s += D2(ndf, 0.5 * theta_v - 0.5 * std::numbers::pi, alpha);
    }
  return 16.0 * std::numeric_limits<double>::epsilon() * s / (2.0 * k * std::cos(ti) * std::cos(to));
}

TEST(FlatlandBrdf, Reciprocity) {
  std::mt19937_64 rng(20180611);
  std::uniform_real_distribution<double> angle(-1.55, 1.55);
  int nonzero = 0;
  for (int t = 0; t < 600; ++t) {
    const NdfKind ndf = kNdfs[t % 3];
    const double alpha = 0.1 + 0.3 * (t % 7);
    const double ti = angle(rng), to = angle(rng);
    const double x = flatland_brdf(ndf, alpha, ti, to, 16), y = flatland_brdf(ndf, alpha, to, ti, 16);
    EXPECT_LE(std::abs(x - y), 1e-12 * std::max(x, y))
        << ndf_name(ndf) << " alpha=" << alpha << " ti=" << ti << " to=" << to;
    if (x > 0.0) ++nonzero;
    for (int k = 1; k <= 8; ++k) {
      const double xk = flatland_brdf_k(ndf, alpha, ti, to, k), yk = flatland_brdf_k(ndf, alpha, to, ti, k);
      const double tol =
          1e-12 * std::max(xk, yk) + rounding_scale(ndf, alpha, ti, to, k) + rounding_scale(ndf, alpha, to, ti, k);
      EXPECT_LE(std::abs(xk - yk), tol) << ndf_name(ndf) << " alpha=" << alpha << " k=" << k << " ti=" << ti
                                        << " to=" << to;
    }
  }
  EXPECT_GT(nonzero, 500);
}

// The flatland Eq. (25): Cook-Torrance with the V-cavity G equals the k = 1 term, pointwise
// (the same formula up to rounding) and per bin (two quadratures: over theta_h from Eq. 1-3 and
// over theta_v from the kaleidoscope, both converged to ~1e-13).
TEST(FlatlandBrdf, CookTorranceIsTheSingleBounceTerm) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-1.5, 1.5);
  for (int t = 0; t < 300; ++t) {
    const NdfKind ndf = kNdfs[t % 3];
    const double alpha = 0.05 + 0.25 * (t % 8);
    const double ti = angle(rng), to = angle(rng);
    const double ct = flatland_brdf_single(ndf, alpha, ti, to), k1 = flatland_brdf_k(ndf, alpha, ti, to, 1);
    EXPECT_NEAR(ct, k1, 1e-12 * std::max(1.0, ct) + rounding_scale(ndf, alpha, ti, to, 1))
        << ndf_name(ndf) << " alpha=" << alpha << " ti=" << ti << " to=" << to;
  }
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.1, 0.5, 1.0})
      for (double deg : {0.0, 35.0, -70.0}) {
        const FlatlandLobe s = flatland_single_lobe(ndf, alpha, deg * kRadPerDeg, 90);
        const FlatlandLobe m = flatland_lobe(ndf, alpha, deg * kRadPerDeg, 90, 4);
        for (int b = 0; b < 90; ++b)
          EXPECT_NEAR(s.theta_o_by_k[90 + b], m.theta_o_by_k[90 + b], 1e-12)
              << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg << " bin=" << b;
      }
}

// Pointwise against binned: the composite midpoint rule of rho2_k cos(theta_o) over each bin
// (N = 1600 points per 6 deg bin, h = 6.5e-5 rad). Its error is (bin) h^2 max|f''| / 24 on smooth
// parts plus up to h^2 |J| / 8 per kink where the slope jumps by J (Eq. 3's min, Eq. 6's clamps):
// with |J| <~ 2 (measured slopes -0.7 and -2.3 on the two sides of the worst kink, GGX 0.5 at
// theta_i = -65 deg, theta_o = 1.425) that is <~ 1e-9. Measured: 1.5e-10 there; the midpoint
// sums converge to the binned value (N = 6400: 1.6e-12). The binned side is exact to ~1e-13
// (QuadratureConverged).
TEST(FlatlandLobe, PointwiseAgreesWithBinned) {
  constexpr int bins = 30, N = 1600;
  for (double deg : {0.0, 30.0, -65.0}) {
    const double ti = deg * kRadPerDeg;
    const FlatlandLobe lobe = flatland_lobe(NdfKind::ggx, 0.5, ti, bins, 8);
    const double w = std::numbers::pi / bins;
    for (int k = 1; k <= 3; ++k)
      for (int b = 0; b < bins; ++b) {
        double s = 0.0;
        for (int j = 0; j < N; ++j) {
          const double to = -0.5 * std::numbers::pi + b * w + (j + 0.5) * w / N;
          s += flatland_brdf_k(NdfKind::ggx, 0.5, ti, to, k) * std::cos(to);
        }
        s *= w / N;
        EXPECT_NEAR(s, lobe.theta_o_by_k[static_cast<std::size_t>(k) * bins + b], 1e-9)
            << "theta_i=" << deg << " k=" << k << " bin=" << b;
      }
  }
}

// The quadrature has converged: doubling the Gauss-Legendre order moves no bin by more than 1e-12.
TEST(FlatlandLobe, QuadratureConverged) {
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.01, 0.3, 2.0})
      for (double deg : {50.0, -89.9}) {
        FlatlandLobeOptions hi;
        hi.quadrature_order = 32;
        const FlatlandLobe a = flatland_lobe(ndf, alpha, deg * kRadPerDeg, 90, 16);
        const FlatlandLobe b = flatland_lobe(ndf, alpha, deg * kRadPerDeg, 90, 16, hi);
        for (std::size_t j = 0; j < a.theta_o_by_k.size(); ++j)
          ASSERT_NEAR(a.theta_o_by_k[j], b.theta_o_by_k[j], 1e-12)
              << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg << " cell=" << j;
      }
}

// The narrow-groove limit that bins the unresolved tail (header, Limits): resolving every n up
// to 64 and placing the rest by the limit agrees with resolving up to 4096, per bin, within the
// 64-tail's flux (the limit misplaces at most what it places).
TEST(FlatlandLobe, TailLimitAgreesWithResolvedBins) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::phong})
    for (double deg : {0.0, 30.0, -60.0}) {
      FlatlandLobeOptions lo;
      lo.resolve_cap = 64;
      const FlatlandLobe a = flatland_lobe(ndf, 1.5, deg * kRadPerDeg, 90, 16, lo);
      const FlatlandLobe b = flatland_lobe(ndf, 1.5, deg * kRadPerDeg, 90, 16);
      ASSERT_EQ(a.n_resolved, 64);
      ASSERT_GT(a.tail, 1e-5);
      for (std::size_t j = 0; j < a.theta_o_by_k.size(); ++j)
        EXPECT_NEAR(a.theta_o_by_k[j], b.theta_o_by_k[j], a.tail)
            << ndf_name(ndf) << " theta_i=" << deg << " cell=" << j;
      EXPECT_NEAR(a.albedo, b.albedo, 1e-12);
    }
}

// Hand values. alpha -> 0: a flat mirror, everything in the bin of -theta_i with k = 1.
// theta_i = 0: the lobe is symmetric, bin b against bins - 1 - b, per k.
TEST(FlatlandLobe, HandValues) {
  // Beckmann only: its Gaussian tail beyond 1 deg of the mirror direction (12 standard deviations
  // of theta_o = 2 theta_h - theta_i at alpha = 1e-3) is exp(-72); GGX's tail is algebraic (~alpha).
  {
    for (double deg : {1.0, 25.0, -61.0}) {  // -theta_i 1 deg from the edges of its 2 deg bin
      const FlatlandLobe lobe = flatland_lobe(NdfKind::beckmann, 1e-3, deg * kRadPerDeg, 90, 4);
      const int mirror = static_cast<int>(std::floor((-deg + 90.0) / 2.0));
      EXPECT_NEAR(lobe.theta_o_by_k[90 + static_cast<std::size_t>(mirror)], 1.0, 1e-9) << "theta_i=" << deg;
    }
  }
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.2, 0.8, 2.0}) {
      const FlatlandLobe lobe = flatland_lobe(ndf, alpha, 0.0, 90, 16);
      for (int r = 0; r < 18; ++r)
        for (int b = 0; b < 45; ++b)
          EXPECT_NEAR(lobe.theta_o_by_k[static_cast<std::size_t>(r) * 90 + b],
                      lobe.theta_o_by_k[static_cast<std::size_t>(r) * 90 + 89 - b], 1e-14)
              << ndf_name(ndf) << " alpha=" << alpha << " row=" << r << " bin=" << b;
    }
  // A 90 deg groove at normal incidence retroreflects after exactly 2 bounces (ERRATA E1's
  // example): rho2(0, theta_o; 2) is fed only by theta_s = +-45 deg, so rho2(0, 0; 2) =
  // 2 D2(45 deg) w / (2 * 2) with w = f_a - f_k = sin 45 deg (all of the facet's rays).
  for (NdfKind ndf : kNdfs) {
    const double expected = 2.0 * D2(ndf, std::numbers::pi / 4.0, 0.5) * std::sin(std::numbers::pi / 4.0) / 4.0;
    EXPECT_NEAR(flatland_brdf_k(ndf, 0.5, 0.0, 0.0, 2), expected, 1e-14) << ndf_name(ndf);
  }
}

// Hard cases: grazing incidence and exit, the mirror direction, the hemisphere's edge.
TEST(FlatlandBrdf, HardAnglesAreFinite) {
  const double edge = 0.5 * std::numbers::pi;
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.01, 0.1, 1.0, 2.0})
      for (double ti : {-89.9 * kRadPerDeg, -1e-9, 0.0, 60.0 * kRadPerDeg, 89.9 * kRadPerDeg})
        for (double to : {-ti, ti, -edge, edge, std::nextafter(edge, 0.0), 0.0, 89.99 * kRadPerDeg}) {
          const double v = flatland_brdf(ndf, alpha, ti, to, 16);
          const double s = flatland_brdf_single(ndf, alpha, ti, to);
          EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << ndf_name(ndf) << " a=" << alpha << " " << ti << " " << to;
          EXPECT_TRUE(std::isfinite(s) && s >= 0.0) << ndf_name(ndf) << " a=" << alpha << " " << ti << " " << to;
        }
  // Outside the open hemisphere: 0 by definition (header, Limits).
  EXPECT_EQ(flatland_brdf(NdfKind::ggx, 0.5, 0.1, edge + 1e-9, 4), 0.0);
  EXPECT_EQ(flatland_brdf_single(NdfKind::ggx, 0.5, -edge, 0.1), 0.0);
}

}  // namespace
}  // namespace vgroove::analytic

namespace vgroove::analytic {
namespace {

// The flatland BRDF at the horizon, down to the edge of the range the command line accepts
// (|theta| < 90 deg, the largest double below it): theta 90 deg - 10^-U(0, 14) deg on either side.
// Reciprocity per k bitwise (the widths' operands swap bitwise, beam_width) and the k = 1 term
// equal to the single-scattering BRDF to 1e-12 relative plus the inputs' own conditioning: an
// angle near +-pi/2 is known to eps absolute, and the factors that vanish there, cos(theta_i),
// cos(theta_o) and cos((theta_o - theta_i)/2) (the mirror direction at the edge), carry that
// absolutely, so two exact evaluations from rounded sums of angles may differ by 4 eps over the
// smallest of them (values under 1e-200 absolutely: the far tails' exp and pow amplify the angles'
// last bits). The evaluation by differences of sines (flatland_brdf_k_reference, which
// flatland_brdf_k was) is off by up to all of the value there (a k = 1 term 0 against a
// single-scattering value; 2.4e-4 from 1e-5 deg): seen failing with flatland_brdf_k returning
// flatland_brdf_k_reference.
TEST(FlatlandBrdf, GrazingPairsAreReciprocalAndK1IsSingleScatteringToTheEdgeOfTheRange) {
  std::mt19937_64 rng(90);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double edge_deg = std::nextafter(90.0, 0.0);
  auto grazing = [&]() {
    const double deg = std::min(edge_deg, 90.0 - std::pow(10.0, -14.0 * U(rng)));
    return (U(rng) < 0.5 ? -1.0 : 1.0) * deg_to_rad(deg);
  };
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.01, 0.1, 0.5, 1.0, 2.0}) {
      int nonzero = 0;
      for (int n = 0; n < 3000; ++n) {
        const double ti = grazing(), to = n % 3 == 2 ? (U(rng) - 0.5) * std::numbers::pi : grazing();
        for (int k = 1; k <= 8; ++k) {
          const double a = flatland_brdf_k(ndf, alpha, ti, to, k), b = flatland_brdf_k(ndf, alpha, to, ti, k);
          nonzero += a > 0.0;
          ASSERT_EQ(a, b) << ndf_name(ndf) << " alpha=" << alpha << " k=" << k << " ti=" << ti << " to=" << to;
        }
        const double ct = flatland_brdf_single(ndf, alpha, ti, to), k1 = flatland_brdf_k(ndf, alpha, ti, to, 1);
        const double eps = std::numeric_limits<double>::epsilon();
        const double smallest = std::min({std::cos(ti), std::cos(to), std::cos(0.5 * (to - ti))});
        ASSERT_NEAR(ct, k1, (1e-12 + 4.0 * eps / smallest) * std::max(ct, k1) + 1e-200)
            << ndf_name(ndf) << " alpha=" << alpha << " ti=" << ti << " to=" << to;
      }
      if (alpha >= 0.5 && (ndf != NdfKind::beckmann || alpha == 2.0)) {
        EXPECT_GT(nonzero, 500) << ndf_name(ndf) << " " << alpha;
      }
    }
}

// The single pass (flatland_brdf, flatland_brdf_k) against the straightforward sum over every k and
// m (flatland_brdf_k_reference): the same solutions, widths as products here and as differences of
// sines there, so within 1e-10 relative away from the horizon (|theta| <= 88.8 deg).
TEST(FlatlandBrdf, SinglePassEqualsEveryMReference) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(-1.55, 1.55);
  for (int t = 0; t < 2000; ++t) {
    const NdfKind ndf = kNdfs[t % 3];
    const double alpha = 0.05 + 0.25 * (t % 8);
    const double ti = angle(rng), to = angle(rng);
    for (int k = 1; k <= 6; ++k) {
      const double a = flatland_brdf_k(ndf, alpha, ti, to, k), b = flatland_brdf_k_reference(ndf, alpha, ti, to, k);
      ASSERT_NEAR(a, b, 1e-10 * std::max(a, b) + 1e-300) << ndf_name(ndf) << " k=" << k << " ti=" << ti << " to=" << to;
    }
    const double a = flatland_brdf(ndf, alpha, ti, to, 32), b = flatland_brdf_reference(ndf, alpha, ti, to, 32);
    ASSERT_NEAR(a, b, 1e-10 * std::max(a, b) + 1e-300) << ndf_name(ndf) << " ti=" << ti << " to=" << to;
  }
}

}  // namespace
}  // namespace vgroove::analytic
