// Tests of analytic/ndf_student_t.h, the Student-T NDF (Ribardiere et al. 2017), each form against
// what it was derived from: normalization by quadrature (3D and flatland), the flatland form as
// the marginal of the 3D slope law, Lambda against its defining integral and against Smith's
// projected-area constraint (Heitz 2014, Eq. (5)) in 2D and 3D, the CDF against the integral of
// D and its inverse against the CDF; and the limits: gamma = 2 is GGX to rounding, gamma =
// 1 + 1/alpha^2 is Phong, and gamma -> infinity tends to Beckmann at the rate 1/gamma with the
// coefficient of the expansion (x^2/2 - x in 3D, x = tan^2 / alpha^2). The vector forms (four
// lanes) against the double ones. incomplete_beta against Boost.Math.
#include "vgroove/analytic/ndf_student_t.h"

#include "tests/stats.h"
#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf.h"

#include <gtest/gtest.h>
#include <boost/math/special_functions/beta.hpp>

#include <cmath>
#include <numbers>

namespace vgroove::analytic {
namespace {

using vgroove::test_stats::tanh_sinh;
constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

const double kAlphas[] = {0.05, 0.3, 1.0, 2.0};
const double kGammas[] = {1.6, 2.0, 3.0, 10.0, 1e3};

// The slope law P22(|s|^2) (the header), written from its definition.
double P22(double r2, double alpha, double gamma) {
  const double c = (gamma - 1.0) * alpha * alpha;
  return (gamma - 1.0) * std::exp((gamma - 1.0) * std::log(c) - gamma * std::log(c + r2)) / kPi;
}

TEST(StudentT, NormalizedIn3DAndFlatland) {
  for (double alpha : kAlphas)
    for (double gamma : kGammas) {
      const NdfKind st = student_t_ndf(gamma);
      // 3D: 2 pi int D cos sin = 1, in u = tan^2 theta / (1 + tan^2) to follow the heavy tail.
      const double i3 =
          2.0 * kPi * tanh_sinh([&](double t) { return D(st, t, alpha) * std::cos(t) * std::sin(t); }, 0.0, 0.5 * kPi);
      EXPECT_NEAR(i3, 1.0, 2e-9) << "alpha=" << alpha << " gamma=" << gamma;
      auto f2 = [&](double t) { return D2(st, t, alpha) * std::cos(t); };
      const double i2 = tanh_sinh(f2, -0.5 * kPi, 0.0) + tanh_sinh(f2, 0.0, 0.5 * kPi);
      EXPECT_NEAR(i2, 1.0, 2e-9) << "alpha=" << alpha << " gamma=" << gamma;
    }
}

// The flatland form is the marginal of P22 along one axis: D2(theta) cos^3 theta = int P22(x^2 + t^2) dt,
// x = tan theta (ndf.h's definition of the flatland forms).
TEST(StudentT, FlatlandIsTheMarginalOfTheSlopes) {
  for (double alpha : {0.3, 1.0})
    for (double gamma : {1.6, 2.5, 10.0})
      for (double theta_deg : {0.0, 20.0, 50.0, 80.0}) {
        const double th = deg(theta_deg), x = std::tan(th);
        // t = tan(v), dt = dv / cos^2 v over (-pi/2, pi/2).
        auto f = [&](double v) {
          const double t = std::tan(v), c = std::cos(v);
          return P22(x * x + t * t, alpha, gamma) / (c * c);
        };
        const double marginal = 2.0 * tanh_sinh(f, 0.0, 0.5 * kPi);
        const double c = std::cos(th);
        EXPECT_NEAR(D2(student_t_ndf(gamma), th, alpha) * c * c * c / marginal, 1.0, 1e-11)
            << "alpha=" << alpha << " gamma=" << gamma << " theta=" << theta_deg;
      }
}

// Lambda = (1/mu) int_mu^inf (x - mu) P(x) dx, mu = cot theta_o, P the flatland slope law (Heitz
// 2014, App. A), by quadrature in x = mu + tan(v).
TEST(StudentT, LambdaIsItsSlopeIntegral) {
  for (double alpha : {0.05, 0.3, 1.0, 2.0})
    for (double gamma : {1.6, 2.0, 4.0, 50.0})
      for (double theta_deg : {10.0, 45.0, 70.0, 88.0}) {
        const double th = deg(theta_deg), mu = 1.0 / std::tan(th);
        const NdfKind st = student_t_ndf(gamma);
        auto P = [&](double x) {
          const double a = std::atan(x);
          const double c = std::cos(a);
          return D2(st, a, alpha) * c * c * c;
        };
        auto f = [&](double v) {
          const double t = std::tan(v), c = std::cos(v);
          return t * P(mu + t) / (c * c);
        };
        const double ref = tanh_sinh(f, 0.0, 0.5 * kPi) / mu;
        const double lam = Lambda(st, th, alpha);
        EXPECT_NEAR(lam, ref, 1e-10 * std::max(1.0, ref) + 1e-14)
            << "alpha=" << alpha << " gamma=" << gamma << " theta=" << theta_deg;
      }
}

// Smith's projected-area constraint with G1 = 1 / (1 + Lambda): in flatland int G1 <o, m>+ D2 =
// cos theta_o, and in 3D int G1 <o, m>+ D dm = cos theta_o (Heitz 2014, Eq. (5)).
TEST(StudentT, SmithProjectedAreaIsConserved) {
  for (double alpha : {0.3, 1.0})
    for (double gamma : {1.6, 3.0, 20.0})
      for (double to_deg : {0.0, 30.0, 75.0, 89.0}) {
        const NdfKind st = student_t_ndf(gamma);
        const double to = deg(to_deg), g1 = 1.0 / (1.0 + Lambda(st, to, alpha));
        const double lo = std::max(-0.5 * kPi, to - 0.5 * kPi), hi = std::min(0.5 * kPi, to + 0.5 * kPi);
        auto f2 = [&](double tm) { return g1 * std::cos(to - tm) * D2(st, tm, alpha); };
        EXPECT_NEAR(tanh_sinh(f2, lo, 0.0) + tanh_sinh(f2, 0.0, hi), std::cos(to), 1e-9)
            << "2D alpha=" << alpha << " gamma=" << gamma << " theta_o=" << to_deg;
        // 3D: int_0^{2 pi} <o.m>+ dphi = 2 (cc phi* + ss sin phi*) (ndf_test.cpp, SmithG1).
        auto over_phi = [&](double tm) {
          const double cc = std::cos(to) * std::cos(tm), ss = std::sin(to) * std::sin(tm);
          const double phi_max = cc >= ss ? kPi : std::acos(-cc / ss);
          return 2.0 * (cc * phi_max + ss * std::sin(phi_max)) * D(st, tm, alpha) * std::sin(tm);
        };
        const double kink = 0.5 * kPi - to;
        const double area = g1 * (kink > 0.0 ? tanh_sinh(over_phi, 0.0, kink) + tanh_sinh(over_phi, kink, 0.5 * kPi)
                                             : tanh_sinh(over_phi, 0.0, 0.5 * kPi));
        EXPECT_NEAR(area, std::cos(to), 1e-9) << "3D alpha=" << alpha << " gamma=" << gamma << " theta_o=" << to_deg;
      }
}

// The CDF over the grooves' area is the integral of 2 pi D cos sin, and the inverse inverts it.
TEST(StudentT, CdfIsTheIntegralOfDAndTheInverseInvertsIt) {
  for (double alpha : {0.05, 0.5, 2.0})
    for (double gamma : {1.6, 2.0, 7.0, 1e3}) {
      const NdfKind st = student_t_ndf(gamma);
      for (double th_deg : {1.0, 10.0, 40.0, 80.0, 89.5}) {
        const double th = deg(th_deg);
        const double ref =
            2.0 * kPi * tanh_sinh([&](double t) { return D(st, t, alpha) * std::cos(t) * std::sin(t); }, 0.0, th);
        EXPECT_NEAR(groove_cdf(st, alpha, th), ref, 1e-11) << alpha << " " << gamma << " " << th_deg;
      }
      for (double u : {1e-12, 1e-3, 0.3, 0.5, 0.9, 1.0 - 1e-9}) {
        double c = 0.0, s = 0.0;
        const double th = groove_cdf_inverse(st, alpha, u, c, s);
        EXPECT_NEAR(groove_cdf(st, alpha, th) / u, 1.0, 1e-12) << alpha << " " << gamma << " u=" << u;
        EXPECT_NEAR(c, std::cos(th), 1e-15);
        EXPECT_NEAR(s, std::sin(th), 1e-15);
        EXPECT_EQ(groove_cdf_inverse(st, alpha, u), th);
      }
    }
}

// gamma = 2 is GGX: every form to rounding (a few ulp).
TEST(StudentT, GammaTwoIsGgx) {
  const NdfKind st = student_t_ndf(2.0);
  for (double alpha : kAlphas)
    for (double th_deg : {0.0, 5.0, 30.0, 60.0, 85.0, 89.9}) {
      const double th = deg(th_deg);
      const std::string at = "alpha=" + std::to_string(alpha) + " theta=" + std::to_string(th_deg);
      EXPECT_NEAR(D(st, th, alpha) / D(NdfKind::ggx, th, alpha), 1.0, 2e-15) << at;
      EXPECT_NEAR(D2(st, th, alpha) / D2(NdfKind::ggx, th, alpha), 1.0, 2e-15) << at;
      if (th_deg > 0.0) {
        EXPECT_NEAR(groove_cdf(st, alpha, th) / groove_cdf(NdfKind::ggx, alpha, th), 1.0, 1e-14) << at;
        EXPECT_NEAR(Lambda(st, th, alpha) / Lambda(NdfKind::ggx, th, alpha), 1.0, 1e-13) << at;
      }
    }
  for (double u : {1e-9, 0.1, 0.5, 0.99})
    EXPECT_NEAR(groove_cdf_inverse(st, 0.7, u) / groove_cdf_inverse(NdfKind::ggx, 0.7, u), 1.0, 1e-14) << u;
}

// gamma = 1 + 1/alpha^2 is Phong (the header): D, D2 and the CDF.
TEST(StudentT, GammaOnePlusInverseAlphaSquaredIsPhong) {
  for (double alpha : {0.2, 0.5, 0.9, 1.2}) {
    const NdfKind st = student_t_ndf(1.0 + 1.0 / (alpha * alpha));
    for (double th_deg : {0.0, 10.0, 45.0, 80.0}) {
      const double th = deg(th_deg);
      EXPECT_NEAR(D(st, th, alpha) / D(NdfKind::phong, th, alpha), 1.0, 1e-13) << alpha << " " << th_deg;
      EXPECT_NEAR(D2(st, th, alpha) / D2(NdfKind::phong, th, alpha), 1.0, 1e-13) << alpha << " " << th_deg;
      if (th_deg > 0.0)
        EXPECT_NEAR(groove_cdf(st, alpha, th) / groove_cdf(NdfKind::phong, alpha, th), 1.0, 1e-13) << alpha;
    }
  }
}

// gamma -> infinity: D_gamma / D_Beckmann = exp(-gamma log1p(x / (gamma - 1)) + x), x = tan^2 /
// alpha^2, = 1 + (x^2/2 - x) / gamma + O(1/gamma^2) (the factor in front is 1/(pi alpha^2 cos^4)
// for every gamma). Flatland: the t law over the Gaussian, 1 + (4 x^2 - 4 x - 1) / (8 (gamma - 1))
// + O(1/gamma^2). Checked at gamma = 10^3 and 10^4: gamma (ratio - 1) within 10/gamma of the
// coefficient, and the distance shrinking tenfold.
TEST(StudentT, LargeGammaTendsToBeckmannAtRateOneOverGamma) {
  for (double alpha : {0.3, 1.0})
    for (double th_deg : {10.0, 30.0, 50.0}) {
      const double th = deg(th_deg), t = std::tan(th), x = t * t / (alpha * alpha);
      double prev = 0.0;
      for (double gamma : {1e3, 1e4}) {
        const NdfKind st = student_t_ndf(gamma);
        const double r3 = D(st, th, alpha) / D(NdfKind::beckmann, th, alpha) - 1.0;
        EXPECT_NEAR(gamma * r3, 0.5 * x * x - x, 10.0 / gamma * (1.0 + x * x * x))
            << "3D alpha=" << alpha << " theta=" << th_deg << " gamma=" << gamma;
        const double r2 = D2(st, th, alpha) / D2(NdfKind::beckmann, th, alpha) - 1.0;
        EXPECT_NEAR((gamma - 1.0) * r2, (4.0 * x * x - 4.0 * x - 1.0) / 8.0, 10.0 / gamma * (1.0 + x * x * x))
            << "2D alpha=" << alpha << " theta=" << th_deg << " gamma=" << gamma;
        const double rl = Lambda(st, th, alpha) - Lambda(NdfKind::beckmann, th, alpha);
        if (prev != 0.0) EXPECT_NEAR(rl / prev, 0.1, 0.01) << "Lambda alpha=" << alpha << " theta=" << th_deg;
        prev = rl;
      }
    }
}

// The four-lane forms (the lobe's kernels) against the double ones: D within a few ulp times the
// exponent gamma (exp and log by polynomials), the inverse CDF's tan within a few ulp.
TEST(StudentT, VectorFormsAgreeWithTheDoubleOnes) {
  for (double alpha : {0.05, 0.5, 2.0})
    for (double gamma : {1.6, 2.0, 30.0}) {
      const StudentT n{alpha, gamma};
      for (double th : {0.01, 0.3, 0.9, 1.3, 1.55}) {
        const simd::V4 c = simd::splat(std::cos(th)), s = simd::splat(std::sin(th));
        const double d = n.D_cs(std::cos(th), std::sin(th));
        EXPECT_NEAR(n.D_cs(c, s)[2] / d, 1.0, 4e-16 * (2.0 + gamma)) << alpha << " " << gamma << " " << th;
      }
      for (double w : {0.01, 0.3, 0.7}) {
        const double u = w * w;
        const double t = n.inverse_cdf(u, [u] { return std::log1p(-u); });
        const simd::V4 x = simd::splat(w);
        const simd::V4 tv = n.inverse_cdf(x * x, [&] { return batch::log_batch((1.0 - x) * (1.0 + x)); });
        EXPECT_NEAR(tv[1] / t, 1.0, 2e-15) << alpha << " " << gamma << " w=" << w;
      }
    }
}

TEST(IncompleteBeta, AgreesWithBoostMath) {
  for (double a : {0.5, 0.6, 1.0, 2.5, 40.0, 1e4})
    for (double x : {1e-12, 1e-3, 0.2, 0.5, 0.9, 0.999999}) {
      const double ref = boost::math::ibeta(a, 0.5, x);
      EXPECT_NEAR(incomplete_beta(a, 0.5, x, 1.0 - x), ref, 1e-14 * std::max(ref, 1e-300) + 1e-300)
          << "a=" << a << " x=" << x;
    }
}

}  // namespace
}  // namespace vgroove::analytic
