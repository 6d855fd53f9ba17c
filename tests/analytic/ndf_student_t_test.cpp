// Tests of analytic/detail/ndf_student_t.h, the Student-T NDF (Ribardiere et al. 2017), each form against
// what it was derived from: normalization by quadrature (3D and flatland), the flatland form as
// the marginal of the 3D slope law, Lambda against its defining integral and against Smith's
// projected-area constraint (Heitz 2014, Eq. (5)) in 2D and 3D, the CDF against the integral of
// D and its inverse against the CDF; and the limits: gamma = 2 is GGX to rounding, gamma =
// 1 + 1/alpha^2 is Phong, and gamma -> infinity tends to Beckmann at the rate 1/gamma with the
// coefficient of the expansion (x^2/2 - x in 3D, x = tan^2 / alpha^2). The vector forms (four
// lanes) against the double ones. incomplete_beta against Boost.Math.
#include "vgroove/analytic/detail/ndf_student_t.h"

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

// The slope laws at a slope x, from D and D2 through cos and sin of atan(x) formed from x itself:
// an angle cannot carry the tail, which for gamma = 1.6 holds 2 % of Lambda's integral beyond x = 1e8
// (within 1e-8 rad of the horizon).
double slope_cos(double x) { return 1.0 / std::hypot(1.0, x); }
double P2(const NdfKind& st, double alpha, double x) {
  const double c = slope_cos(x);
  return D2_cs(st, c, x * c, alpha) * c * c * c;
}
double P3(const NdfKind& st, double alpha, double r) {
  const double c = slope_cos(r);
  return D_cs(st, c, r * c, alpha) * c * c * c * c;
}

// int_a^b f(x) dx over pieces growing geometrically from a ([a, a + w], [a + w, a + 4 w], ...;
// w the slopes' scale), so the quadrature follows a peak at a and its tail alike.
template <class F>
double geometric_pieces(F&& f, double a, double b, double w) {
  double sum = 0.0, lo = a;
  for (double step = w; lo < b; step *= 4.0) {
    const double hi = std::min(b, a + step);
    sum += tanh_sinh(f, lo, hi);
    lo = hi;
  }
  return sum;
}

// int_a^inf f(x) dx for f decaying as x^(2 - 2 gamma) (a > 0): geometric pieces to a + 4^10 w, then
// x = X s^(-p), p = 1 / (2 gamma - 3), where f dx tends to a constant times ds as s -> 0, up to x =
// 1e50, and beyond it f's power law integrated in closed form (f(1e50) 1e50 / (2 gamma - 3); the
// slope laws' forms under- and overflow much further out).
template <class F>
double heavy_tail_integral(F&& f, double a, double w, double gamma) {
  const double X = a + std::pow(4.0, 10.0) * w, cap = 1e50, p = 1.0 / (2.0 * gamma - 3.0);
  const double s_cap = std::pow(X / cap, 1.0 / p);
  const double tail = tanh_sinh(
      [&](double s) {
        const double x = X * std::pow(s, -p);
        return f(x) * p * x / s;
      },
      s_cap, 1.0);
  return geometric_pieces(f, a, X, w) + tail + f(cap) * cap / (2.0 * gamma - 3.0);
}

// Lambda = (1/mu) int_mu^inf (x - mu) P(x) dx, mu = cot theta_o, P the flatland slope law (Heitz
// 2014, App. A), in heavy_tail_integral. Seen failing at gamma = 1.6 (0.05 % low, the tail cut at
// x ~ 1e16) with the tail integrated in x = mu + tan(v).
TEST(StudentT, LambdaIsItsSlopeIntegral) {
  for (double alpha : {0.05, 0.3, 1.0, 2.0})
    for (double gamma : {1.6, 2.0, 4.0, 50.0})
      for (double theta_deg : {10.0, 45.0, 70.0, 88.0}) {
        const double th = deg(theta_deg), mu = 1.0 / std::tan(th);
        const NdfKind st = student_t_ndf(gamma);
        auto f = [&](double x) { return (x - mu) * P2(st, alpha, x); };
        const double ref = heavy_tail_integral(f, mu, alpha, gamma) / mu;
        const double lam = Lambda(st, th, alpha);
        EXPECT_NEAR(lam, ref, 1e-10 * std::max(1.0, ref) + 1e-14)
            << "alpha=" << alpha << " gamma=" << gamma << " theta=" << theta_deg;
      }
}

// Smith's projected-area constraint with G1 = 1 / (1 + Lambda): in flatland int G1 <o, m>+ D2 =
// cos theta_o, and in 3D int G1 <o, m>+ D dm = cos theta_o (Heitz 2014, Eq. (5)); in slopes, as
// Lambda's test, with the kinks (where <o, m> = 0) as ends of the pieces. Flatland: with x = tan
// theta_m, <o, m> D2 dtheta_m = (cos t_o + x sin t_o) P(x) dx, and P even folds x < 0 onto x > 0.
// 3D: <o, m>+ over phi_m is 2 cos theta_m (cos t_o phi* + r sin t_o sin phi*) (ndf_test.cpp,
// SmithG1), and D sin theta_m dtheta_m = P22(r) r / cos theta_m dr.
TEST(StudentT, SmithProjectedAreaIsConserved) {
  for (double alpha : {0.3, 1.0})
    for (double gamma : {1.6, 3.0, 20.0})
      for (double to_deg : {0.0, 30.0, 75.0, 89.0}) {
        const NdfKind st = student_t_ndf(gamma);
        const double to = deg(to_deg), g1 = 1.0 / (1.0 + Lambda(st, to, alpha));
        const double ct = std::cos(to), st_o = std::sin(to);
        // Where <o, m> changes form: x = cot t_o (none at normal view).
        const double kink = to_deg > 0.0 ? ct / st_o : 0.0;
        auto pieces = [&](auto&& f) {
          return geometric_pieces(f, 0.0, kink, alpha) + heavy_tail_integral(f, kink, alpha, gamma);
        };
        auto f2 = [&](double x) { return (ct + x * st_o + std::max(0.0, ct - x * st_o)) * P2(st, alpha, x); };
        EXPECT_NEAR(g1 * pieces(f2), ct, 1e-9) << "2D alpha=" << alpha << " gamma=" << gamma << " theta_o=" << to_deg;
        auto f3 = [&](double r) {
          const double phi_max = ct >= r * st_o ? kPi : std::acos(-ct / (r * st_o));
          return 2.0 * (ct * phi_max + r * st_o * std::sin(phi_max)) * P3(st, alpha, r) * r;
        };
        EXPECT_NEAR(g1 * pieces(f3), ct, 1e-9) << "3D alpha=" << alpha << " gamma=" << gamma << " theta_o=" << to_deg;
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
      if (th_deg > 0.0) {
        EXPECT_NEAR(groove_cdf(st, alpha, th) / groove_cdf(NdfKind::phong, alpha, th), 1.0, 1e-13) << alpha;
      }
    }
  }
}

// gamma -> infinity: D_gamma / D_Beckmann = exp(-gamma log1p(x / (gamma - 1)) + x), x = tan^2 /
// alpha^2, = 1 + (x^2/2 - x) / gamma + O(1/gamma^2) (the factor in front is 1/(pi alpha^2 cos^4)
// for every gamma). Flatland: the t law over the Gaussian, 1 + (4 x^2 - 4 x - 1) / (8 (gamma - 1))
// + O(1/gamma^2). Checked at gamma = 10^3 and 10^4: gamma (ratio - 1) within 10/gamma of the
// coefficient, and the distance shrinking tenfold.
TEST(StudentT, LargeGammaTendsToBeckmannAtRateOneOverGamma) {
  int lambda_checked = 0;
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
        // Lambda where it is far above its rounding (Student-T's loses log2(4 gamma) bits of terms of
        // order 1: at alpha 0.3 and 30 deg, Lambda ~ 1e-16 and the difference is rounding).
        if (Lambda(NdfKind::beckmann, th, alpha) > 1e-6) {
          const double rl = Lambda(st, th, alpha) - Lambda(NdfKind::beckmann, th, alpha);
          if (prev != 0.0) {
            EXPECT_NEAR(rl / prev, 0.1, 0.01) << "Lambda alpha=" << alpha << " theta=" << th_deg;
            ++lambda_checked;
          }
          prev = rl;
        }
      }
    }
  EXPECT_EQ(lambda_checked, 3);  // alpha 0.3 at 50 deg, alpha 1 at 30 and 50 deg
}

// The four-lane forms (the lobe's kernels) against the double ones: D = y^gamma / ... within 2 ulp
// times 2 + gamma |log y| (y^gamma is exp(gamma log y) by polynomials: log y's last-bit error
// scaled by gamma |log y|), the inverse CDF's tan within a few ulp given the same log(1 - u) (the
// lobe's kernels form log(1 - u) as log((1 - w)(1 + w)), whose rounding lobe_3d.h states for every
// NDF). The bound 4e-16 (2 + gamma), without |log y|, failed: 2.4e-14 at theta 1.55, gamma 30.
TEST(StudentT, VectorFormsAgreeWithTheDoubleOnes) {
  for (double alpha : {0.05, 0.5, 2.0})
    for (double gamma : {1.6, 2.0, 30.0}) {
      const StudentT n{alpha, gamma};
      for (double th : {0.01, 0.3, 0.9, 1.3, 1.55}) {
        const simd::V4 c = simd::splat(std::cos(th)), s = simd::splat(std::sin(th));
        const double d = n.D_cs(std::cos(th), std::sin(th));
        const double log_y = std::abs(std::log(n.y(std::cos(th), std::sin(th))));
        EXPECT_NEAR(n.D_cs(c, s)[2] / d, 1.0, 4.5e-16 * (2.0 + gamma * log_y)) << alpha << " " << gamma << " " << th;
      }
      for (double w : {0.01, 0.3, 0.7}) {
        const double u = w * w;
        const double t = n.inverse_cdf(u, [u] { return std::log1p(-u); });
        const simd::V4 x = simd::splat(w);
        const simd::V4 tv = n.inverse_cdf(x * x, [u] { return simd::splat(std::log1p(-u)); });
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
