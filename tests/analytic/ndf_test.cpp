// Tests of analytic/ndf.h: normalization of the 3D and flatland NDFs by quadrature, values at
// hand-derived points, Phong against Beckmann for small alpha (Walter et al. 2007's exponent
// map), and the masking functions against Heitz 2014's projected-area constraint (his Eq. (5)):
// for every view direction o the visible projected area of the facets is the macrosurface's,
//   int G1(o, m) <o, m> D(m) dm = cos(theta_o).
//
// Conventions (ndf.h): angles from the normal, counter-clockwise positive; D is normalized so that
// int D cos = 1 over the hemisphere, D2 so that int D2 cos = 1 over (-pi/2, pi/2).
#include "vgroove/analytic/ndf.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace vgroove::analytic {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

using vgroove::test_stats::tanh_sinh;

// 3D: 2 pi int_0^{pi/2} D cos sin dtheta.
double integral_3d(NdfKind kind, double alpha) {
  return 2.0 * std::numbers::pi *
         tanh_sinh([&](double t) { return D(kind, t, alpha) * std::cos(t) * std::sin(t); }, 0.0,
                   0.5 * std::numbers::pi);
}

// 2D: int_{-pi/2}^{pi/2} D2 cos dtheta, split at the peak.
double integral_2d(NdfKind kind, double alpha) {
  auto f = [&](double t) { return D2(kind, t, alpha) * std::cos(t); };
  return tanh_sinh(f, -0.5 * std::numbers::pi, 0.0) + tanh_sinh(f, 0.0, 0.5 * std::numbers::pi);
}

const NdfKind kKinds[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};
const double kAlphas[] = {0.05, 0.3, 0.5, 1.0, 2.0};

using KindAlpha = std::tuple<NdfKind, double>;
std::string kind_alpha_name(const testing::TestParamInfo<KindAlpha>& info) {
  std::ostringstream os;
  os << ndf_name(std::get<0>(info.param)) << "_a" << std::get<1>(info.param);
  std::string s = os.str();
  std::replace(s.begin(), s.end(), '.', 'p');
  return s;
}

// ---------------------------------------------------------------------------------------------
// Normalization. The quadrature is exact to ~1e-13 for these smooth integrands. Phong with
// alpha > 1 (alpha_p < -1) has an integrable singularity cos^(alpha_p + 1) at pi/2 (3D: D cos sin)
// and at +-pi/2 (2D: D2 cos); there
// theta cannot come closer to pi/2 than the rounding of std::numbers::pi/2, eps = 6.1e-17, where cos(theta)
// stops shrinking, so the last sliver int_0^eps x^-1/2 dx = 2 sqrt(eps) = 1.6e-8 per end is
// misjudged: the tolerance for those cases is 4e-8 (alpha = 2: alpha_p + 1 = -0.5).
double normalization_tolerance(NdfKind kind, double alpha) {
  return kind == NdfKind::phong && phong_exponent(alpha) + 1.0 < 0.0 ? 4e-8 : 1e-11;
}

class NdfNormalization : public testing::TestWithParam<KindAlpha> {};

TEST_P(NdfNormalization, ProjectedAreaIsOne3D) {
  const auto [kind, alpha] = GetParam();
  EXPECT_NEAR(integral_3d(kind, alpha), 1.0, normalization_tolerance(kind, alpha))
      << ndf_name(kind) << " alpha=" << alpha;
}

TEST_P(NdfNormalization, ProjectedLengthIsOne2D) {
  const auto [kind, alpha] = GetParam();
  EXPECT_NEAR(integral_2d(kind, alpha), 1.0, normalization_tolerance(kind, alpha))
      << ndf_name(kind) << " alpha=" << alpha;
}

INSTANTIATE_TEST_SUITE_P(Grid, NdfNormalization,
                         testing::Combine(testing::ValuesIn(kKinds), testing::ValuesIn(kAlphas)), kind_alpha_name);

TEST(NdfNormalization, QuadratureIsExactOnAKnownIntegral) {
  // The quadrature on its own, on the singular case the Phong test meets:
  // int_0^{pi/2} cos^-1/2 = B(1/2, 1/4) / 2 = Gamma(1/2) Gamma(1/4) / (2 Gamma(3/4)).
  const double exact = 0.5 * std::exp(std::lgamma(0.5) + std::lgamma(0.25) - std::lgamma(0.75));
  // The singular end costs up to 2 sqrt(6.1e-17) = 1.6e-8 (see below).
  EXPECT_NEAR(tanh_sinh([](double t) { return 1.0 / std::sqrt(std::cos(t)); }, 0.0, 0.5 * std::numbers::pi), exact,
              2e-8);
  // The same integral written in the distance to the singular end, which the nodes carry exactly.
  EXPECT_NEAR(tanh_sinh([](double x) { return 1.0 / std::sqrt(std::sin(x)); }, 0.0, 0.5 * std::numbers::pi), exact,
              1e-13);
  EXPECT_NEAR(tanh_sinh([](double t) { return std::cos(t); }, 0.0, 0.5 * std::numbers::pi), 1.0, 1e-14);
}

// ---------------------------------------------------------------------------------------------
// Hand values.
TEST(NdfHandValues, PeakOfEach3DNdfIsOneOverPiAlphaSquared) {
  // Beckmann and GGX: 1/(pi a^2) at theta = 0 by their formulas; Phong: (p + 2)/(2 pi) with
  // p + 2 = 2/a^2 -- the reason for Walter et al.'s exponent map.
  for (double a : kAlphas)
    for (NdfKind k : kKinds)
      EXPECT_NEAR(D(k, 0.0, a), 1.0 / (std::numbers::pi * a * a), 1e-14 / (a * a)) << ndf_name(k) << " alpha=" << a;
}

TEST(NdfHandValues, PeakOf2DNdfs) {
  for (double a : kAlphas) {
    EXPECT_NEAR(D2_beckmann(0.0, a), 1.0 / (std::sqrt(std::numbers::pi) * a), 1e-14 / a) << "alpha=" << a;
    EXPECT_NEAR(D2_ggx(0.0, a), 1.0 / (2.0 * a), 1e-14 / a) << "alpha=" << a;
  }
  // Phong with alpha_p = 0, 1, 2 (alpha = 1, sqrt(2/3), sqrt(1/2)): D2 = K cos^p with
  // K = 1 / int cos^(p+1) = 1/2, 2/pi, 3/4.
  EXPECT_NEAR(D2_phong(0.3, 1.0), 0.5, 1e-15);
  EXPECT_NEAR(D2_phong(0.3, std::sqrt(2.0 / 3.0)), 2.0 / std::numbers::pi * std::cos(0.3), 1e-14);
  EXPECT_NEAR(D2_phong(0.3, std::sqrt(0.5)), 0.75 * std::cos(0.3) * std::cos(0.3), 1e-14);
}

TEST(NdfHandValues, AtSlopeEqualToAlpha) {
  // tan(theta) = a: cos^2 = 1/(1 + a^2).
  for (double a : {0.1, 0.5, 1.0, 2.0}) {
    const double t = std::atan(a), q = 1.0 + a * a;
    // Beckmann: e^-1 / (pi a^2 cos^4); GGX: a^2 / (pi cos^4 (2 a^2)^2) = q^2 / (4 pi a^2).
    EXPECT_NEAR(D_beckmann(t, a), std::exp(-1.0) * q * q / (std::numbers::pi * a * a), 1e-13 * q * q / (a * a))
        << "alpha=" << a;
    EXPECT_NEAR(D_ggx(t, a), q * q / (4.0 * std::numbers::pi * a * a), 1e-13 * q * q / (a * a)) << "alpha=" << a;
    // 2D: P(a) / cos^3 with P = e^-1/(sqrt(pi) a) and P = 2^-3/2 / (2 a).
    EXPECT_NEAR(D2_beckmann(t, a), std::exp(-1.0) * std::pow(q, 1.5) / (std::sqrt(std::numbers::pi) * a),
                1e-13 * q * q / a)
        << "alpha=" << a;
    EXPECT_NEAR(D2_ggx(t, a), std::pow(q, 1.5) / (2.0 * a * std::pow(2.0, 1.5)), 1e-13 * q * q / a) << "alpha=" << a;
  }
  // Phong, alpha_p = 2 at 60 deg: (4 / 2 pi) cos^2 = 1 / (2 pi).
  EXPECT_NEAR(D_phong(deg(60), std::sqrt(0.5)), 1.0 / (2.0 * std::numbers::pi), 1e-14);
}

TEST(NdfHandValues, PhongEqualsGgxAtAlphaOne) {
  // alpha = 1: alpha_p = 0, so Phong is uniform, D = 1/pi and D2 = 1/2; GGX at alpha = 1 is
  // 1/(pi (cos^2 + sin^2)^2) = 1/pi and 1/(2 (cos^2 + sin^2)^(3/2)) = 1/2.
  for (double t = -1.5; t <= 1.5; t += 0.25) {
    EXPECT_NEAR(D_phong(t, 1.0), 1.0 / std::numbers::pi, 1e-15) << "theta=" << t;
    EXPECT_NEAR(D_ggx(t, 1.0), 1.0 / std::numbers::pi, 1e-15) << "theta=" << t;
    EXPECT_NEAR(D2_phong(t, 1.0), 0.5, 1e-15) << "theta=" << t;
    EXPECT_NEAR(D2_ggx(t, 1.0), 0.5, 1e-15) << "theta=" << t;
  }
}

TEST(NdfHandValues, EvenAndZeroBelowTheHorizon) {
  for (NdfKind k : kKinds)
    for (double a : kAlphas) {
      for (double t : {0.1, 0.7, 1.2, 1.5}) {
        EXPECT_EQ(D(k, t, a), D(k, -t, a)) << ndf_name(k) << " alpha=" << a << " theta=" << t;
        EXPECT_EQ(D2(k, t, a), D2(k, -t, a)) << ndf_name(k) << " alpha=" << a << " theta=" << t;
        // Zero only by underflow (Beckmann at alpha = 0.05, theta = 1.2: exp(-2600)).
        EXPECT_GE(D2(k, t, a), 0.0) << ndf_name(k) << " alpha=" << a << " theta=" << t;
      }
      for (double t : {0.5 * std::numbers::pi + 1e-9, 2.0, -2.0, std::numbers::pi}) {
        EXPECT_EQ(D(k, t, a), 0.0) << ndf_name(k) << " alpha=" << a << " theta=" << t;
        EXPECT_EQ(D2(k, t, a), 0.0) << ndf_name(k) << " alpha=" << a << " theta=" << t;
      }
    }
}

TEST(NdfHandValues, PhongExponent) {
  EXPECT_DOUBLE_EQ(phong_exponent(1.0), 0.0);
  EXPECT_DOUBLE_EQ(phong_exponent(0.5), 6.0);
  EXPECT_DOUBLE_EQ(phong_exponent(0.1), 198.0);
  EXPECT_DOUBLE_EQ(phong_exponent(2.0), -1.5);
}

// ---------------------------------------------------------------------------------------------
// Phong against Beckmann for small alpha. With t = tan(theta) = x a and p = 2/a^2 - 2,
//   ln(D_phong / D_beckmann) = (p + 4) ln cos + t^2/a^2 = (t^2 - ln(1 + t^2)) / a^2 - ln(1 + t^2),
// and 0 <= t^2 - ln(1+t^2) <= t^4/2, 0 <= ln(1+t^2) <= t^2, so |ln ratio| <= a^2 max(x^4/2, x^2).
// In the projected measure, with u = x^2 ~ Exp(1) under Beckmann, the L1 distance is
//   int |D_p - D_b| cos dm = a^2 E|u^2/2 - u| + O(a^4) = 2 a^2 int_0^2 (u - u^2/2) e^-u du + O(a^4)
//                          = 4 e^-2 a^2 + O(a^4) = 0.5413 a^2 + O(a^4)
// (E[u^2/2 - u] = 0, so E|.| is twice the integral over the part where it is negative).
TEST(PhongBeckmann, PointwiseRatioWithinTheExpansionBound) {
  for (double a : {0.2, 0.1, 0.05, 0.02})
    for (double x = 0.0; x <= 3.0; x += 0.125) {
      const double t = std::atan(x * a);
      const double lr = std::log(D_phong(t, a) / D_beckmann(t, a));
      EXPECT_LE(std::abs(lr), a * a * std::max(0.5 * x * x * x * x, x * x) + 1e-12) << "alpha=" << a << " x=" << x;
    }
}

TEST(PhongBeckmann, L1DistanceShrinksAsAlphaSquared) {
  // 2 int_0^2 (u - u^2/2) e^-u du = 2 [(1 - 3 e^-2) - (2 - 10 e^-2)/2] = 4 e^-2.
  const double c = 4.0 * std::exp(-2.0);  // 0.5413
  for (double a : {0.1, 0.05, 0.02}) {
    const double l1 =
        2.0 * std::numbers::pi *
        tanh_sinh([&](double t) { return std::abs(D_phong(t, a) - D_beckmann(t, a)) * std::cos(t) * std::sin(t); }, 0.0,
                  0.5 * std::numbers::pi, 1.0 / 256.0);
    // The O(a^4) remainder: within 10% of the leading term for a <= 0.1.
    EXPECT_NEAR(l1 / (a * a), c, 0.1 * c) << "alpha=" << a << " L1=" << l1;
  }
}

// ---------------------------------------------------------------------------------------------
// Masking.
TEST(G1VCavity, HandValues) {
  // Normal view: nothing masked.
  EXPECT_DOUBLE_EQ(G1_vcavity_inplane(0.0, deg(45)), 1.0);
  // theta_h = 45, theta_o = 60: the other facet (-45) faces away (60 + 45 > 90), so
  // G1 = 2 cos45 cos60 / cos15 = sqrt(3) - 1.
  EXPECT_NEAR(G1_vcavity_inplane(deg(60), deg(45)), std::sqrt(3.0) - 1.0, 1e-15);
  // The facet facing away from o: zero (Heaviside).
  EXPECT_EQ(G1_vcavity_inplane(deg(60), deg(-45)), 0.0);
  EXPECT_EQ(G1_vcavity(-0.1, 0.5, 0.9), 0.0);
  // Both facets visible: theta_o = 30, theta_h = +-30: 2 cos30 cos30 / cos0 = 1.5 -> 1.
  EXPECT_EQ(G1_vcavity_inplane(deg(30), deg(30)), 1.0);
  EXPECT_EQ(G1_vcavity_inplane(deg(30), deg(-30)), 1.0);
}

TEST(G1VCavity, ProjectedAreaIsConserved) {
  // Heitz 2014, Sec. 6.1: a V-cavity has the normals +-theta_m, D = (delta_m + delta_m') / (2 cos theta_m);
  // Eq. (5) reads cos theta_o = sum over both of G1 <o, m> / (2 cos theta_m).
  for (double tm = 1.0; tm < 90.0; tm += 7.0)
    for (double to = -89.0; to < 90.0; to += 4.0) {
      const double m = deg(tm), o = deg(to);
      double area = 0.0;
      for (double n : {m, -m}) area += G1_vcavity_inplane(o, n) * std::max(0.0, std::cos(o - n)) / (2.0 * std::cos(n));
      EXPECT_NEAR(area, std::cos(o), 1e-14) << "theta_m=" << tm << " deg, theta_o=" << to << " deg";
    }
}

TEST(SmithLambda, HandValues) {
  // a = 1/(alpha tan theta_o) = 1.
  const double a = 0.5, t = std::atan(1.0 / a);
  EXPECT_NEAR(Lambda_ggx(t, a), 0.5 * (std::sqrt(2.0) - 1.0), 1e-15);
  EXPECT_NEAR(Lambda_beckmann(t, a), 0.5 * (std::erf(1.0) - 1.0) + std::exp(-1.0) / (2.0 * std::sqrt(std::numbers::pi)),
              1e-15);
  EXPECT_EQ(Lambda_ggx(0.0, a), 0.0);
  EXPECT_EQ(Lambda_beckmann(0.0, a), 0.0);
  EXPECT_EQ(G1_smith_ggx(0.0, a), 1.0);
  // Even in theta_o, and G1 decreasing towards grazing.
  EXPECT_EQ(Lambda_ggx(-0.7, a), Lambda_ggx(0.7, a));
  EXPECT_EQ(Lambda_beckmann(-0.7, a), Lambda_beckmann(0.7, a));
  EXPECT_GT(G1_smith_beckmann(0.5, a), G1_smith_beckmann(1.0, a));
  EXPECT_GT(G1_smith_ggx(0.5, a), G1_smith_ggx(1.0, a));
}

// The projected-area constraint with Smith's G1 = chi+(o.m) / (1 + Lambda(o)) in flatland: with
// D2 the marginal slope law (ndf.h), int <o, m>+ D2(m) dtheta_m / cos theta_o = 1 + Lambda(o)
// with Heitz's closed-form Lambda. The integrand has a kink where o.m = 0, at theta_m =
// theta_o -+ pi/2: integrate only where o.m > 0, split at 0 (the peak).
double projected_area_2d(NdfKind kind, double alpha, double to, double g1) {
  const double lo = std::max(-0.5 * std::numbers::pi, to - 0.5 * std::numbers::pi),
               hi = std::min(0.5 * std::numbers::pi, to + 0.5 * std::numbers::pi);
  auto f = [&](double tm) { return g1 * std::cos(to - tm) * D2(kind, tm, alpha); };
  return tanh_sinh(f, lo, 0.0) + tanh_sinh(f, 0.0, hi);
}

TEST(SmithG1, ProjectedAreaIsConservedIn2D) {
  for (double a : {0.05, 0.3, 0.5, 1.0, 2.0})
    for (double to_deg : {0.0, 20.0, 45.0, 70.0, 85.0, 89.0, -60.0}) {
      const double to = deg(to_deg);
      EXPECT_NEAR(projected_area_2d(NdfKind::beckmann, a, to, G1_smith_beckmann(to, a)), std::cos(to), 1e-9)
          << "beckmann alpha=" << a << " theta_o=" << to_deg << " deg";
      EXPECT_NEAR(projected_area_2d(NdfKind::ggx, a, to, G1_smith_ggx(to, a)), std::cos(to), 1e-9)
          << "ggx alpha=" << a << " theta_o=" << to_deg << " deg";
    }
}

TEST(SmithG1, ProjectedAreaIsConservedIn3D) {
  // The same in 3D (Heitz 2014, Eq. (5)): o = (sin to, 0, cos to), m at (tm, phi):
  // o.m = cc + ss cos phi (cc = cos to cos tm, ss = sin to sin tm), positive for
  // phi < phi* = acos(-cc/ss) (all phi when cc >= ss, i.e. tm <= pi/2 - to). Symmetric in phi:
  // int_0^{2 pi} <o.m>+ dphi = 2 (cc phi* + ss sin phi*). The outer integrand has a kink at
  // tm = pi/2 - to, where the range is split.
  for (NdfKind kind : {NdfKind::beckmann, NdfKind::ggx})
    for (double a : {0.3, 1.0})
      for (double to_deg : {30.0, 75.0}) {
        const double to = deg(to_deg);
        const double g1 = kind == NdfKind::beckmann ? G1_smith_beckmann(to, a) : G1_smith_ggx(to, a);
        auto over_phi = [&](double tm) {
          const double cc = std::cos(to) * std::cos(tm), ss = std::sin(to) * std::sin(tm);
          const double phi_max = cc >= ss ? std::numbers::pi : std::acos(-cc / ss);
          return 2.0 * (cc * phi_max + ss * std::sin(phi_max)) * D(kind, tm, a) * std::sin(tm);
        };
        const double kink = 0.5 * std::numbers::pi - to;
        const double area = g1 * (tanh_sinh(over_phi, 0.0, kink) + tanh_sinh(over_phi, kink, 0.5 * std::numbers::pi));
        EXPECT_NEAR(area, std::cos(to), 1e-11) << ndf_name(kind) << " alpha=" << a << " theta_o=" << to_deg << " deg";
      }
}

// D_vanishing_aperture is a lower bound of where D_cs is exactly 0, and close to it: D is 0 just
// below it and at every smaller aperture tried, and positive a tenth above it. GGX never vanishes.
TEST(NdfVanishing, DIsZeroBelowTheVanishingApertureAndPositiveAbove) {
  auto D_at = [](NdfKind ndf, double v, double alpha) {
    return D_cs(ndf, std::sin(0.5 * v), std::cos(0.5 * v), alpha);  // cos, sin of theta_m = (pi - v) / 2
  };
  EXPECT_EQ(D_vanishing_aperture(NdfKind::ggx, 0.5), 0.0);
  EXPECT_EQ(D_vanishing_aperture(NdfKind::phong, 1.5), 0.0);  // p < 0: D grows towards vertical facets
  int checked = 0;
  for (const NdfKind ndf : {NdfKind::beckmann, NdfKind::phong})
    for (const double alpha : {0.01, 0.05, 0.2, 0.5, 1.0, 2.0}) {
      const double v0 = D_vanishing_aperture(ndf, alpha);
      if (!(v0 > 0.0)) continue;
      ++checked;
      for (const double f : {1.0 - 1e-12, 0.9, 0.5, 1e-3, 1e-9})
        EXPECT_EQ(D_at(ndf, f * v0, alpha), 0.0) << ndf_name(ndf) << " alpha " << alpha << " at " << f << " v0";
      // Positive where the exponent is 20 above the bound's: tan / alpha smaller by sqrt(740 / 760)
      // (Beckmann), cos larger by exp(20 / p) (Phong).
      const double v1 =
          ndf == NdfKind::beckmann
              ? 2.0 * std::atan(1.0 / (alpha * std::sqrt(740.0)))
              : 2.0 * std::asin(std::min(1.0, std::sin(0.5 * v0) * std::exp(20.0 / phong_exponent(alpha))));
      EXPECT_GT(D_at(ndf, v1, alpha), 0.0) << ndf_name(ndf) << " alpha " << alpha;
    }
  EXPECT_GE(checked, 9);
}

}  // namespace
}  // namespace vgroove::analytic
