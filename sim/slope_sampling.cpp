#include "vgroove/sim/slope_sampling.h"

#include "vgroove/common/log_gamma_ratio.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

// Degrees of freedom of Phong's slope law: nu = alpha_p + 2 with Walter et al.'s
// alpha_p = 2/alpha^2 - 2 (slope_sampling.h).
double phong_nu(double alpha) { return 2.0 / (alpha * alpha); }

// Student-T's slope law (slope_sampling.h): nu = 2 gamma - 2 degrees of freedom, nu sigma^2 =
// (gamma - 1) alpha^2.
double student_t_scale2(NdfKind kind, double alpha) { return (kind.gamma - 1.0) * alpha * alpha; }

// Continued fraction of the incomplete beta function (the even/odd terms d_2m, d_2m+1 of
// Abramowitz & Stegun 26.5.8), evaluated by the modified Lentz method. Converges quickly for
// x < (a + 1) / (a + b + 2), in about sqrt(max(a, b)) terms near that point.
double beta_continued_fraction(double a, double b, double x) {
  constexpr double tiny = 1e-300;  // keeps Lentz's c and d off zero
  constexpr double eps = 1e-16;
  constexpr int max_terms = 100000;
  const double qab = a + b, qap = a + 1.0, qam = a - 1.0;
  double c = 1.0, d = 1.0 - qab * x / qap;
  if (std::abs(d) < tiny) d = tiny;
  d = 1.0 / d;
  double h = d;
  for (int m = 1; m <= max_terms; ++m) {
    const double m2 = 2.0 * m;
    double aa = m * (b - m) * x / ((qam + m2) * (a + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    h *= d * c;
    aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2));
    d = 1.0 + aa * d;
    if (std::abs(d) < tiny) d = tiny;
    c = 1.0 + aa / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < eps) break;
  }
  return h;
}

// The lower tail T(w) = P(theta_m <= -w) for w in [0, pi/2] (slope_sampling.h).
double lower_tail(NdfKind kind, double alpha, double w) {
  if (!(w < kHalfPi)) return 0.0;
  const double c = std::cos(w), s = std::sin(w);
  switch (kind) {
    case NdfKind::beckmann:
      return 0.5 * std::erfc(s / (c * alpha));
    case NdfKind::ggx: {
      // (1 - x/sqrt(1+x^2)) / 2 with x = tan w / alpha, without cancelling: x/sqrt(1+x^2) = s/q,
      // q = sqrt(alpha^2 c^2 + s^2), and (1 - s/q) = (q^2 - s^2) / (q (q + s)) = alpha^2 c^2 / (q (q + s)).
      const double q = std::sqrt(alpha * alpha * c * c + s * s);
      return 0.5 * alpha * alpha * c * c / (q * (q + s));
    }
    case NdfKind::phong:
      return 0.5 * incomplete_beta(0.5 * phong_nu(alpha), 0.5, c * c, s * s);
    case NdfKind::student_t: {
      // x = nu sigma^2 / (nu sigma^2 + tan^2) = k2 c^2 / (k2 c^2 + s^2), k2 = nu sigma^2.
      const double k2c2 = student_t_scale2(kind, alpha) * c * c, d = k2c2 + s * s;
      return 0.5 * incomplete_beta(kind.gamma - 1.0, 0.5, k2c2 / d, s * s / d);
    }
  }
  return 0.0;
}

}  // namespace

double incomplete_beta(double a, double b, double x, double one_minus_x) {
  assert(a > 0.0 && b > 0.0);
  if (!(x > 0.0)) return 0.0;
  if (!(one_minus_x > 0.0)) return 1.0;
  // I_x(a, b) = x^a (1-x)^b / (a B(a, b)) * cf(a, b, x), or by I_x(a, b) = 1 - I_{1-x}(b, a) on
  // the side where the fraction converges slowly (Abramowitz & Stegun 26.5.8, 26.5.2).
  // 1 / B(a, b) through the larger one's Gamma ratio (no lgamma cancellation) where the smaller is
  // at most 1; x^a (1 - x)^b by pow (exp(a log x) scales log x's last-bit error by a log x).
  const double ln_inverse_beta = std::min(a, b) <= 1.0
                                     ? log_gamma_ratio(std::max(a, b), std::min(a, b)) - std::lgamma(std::min(a, b))
                                     : std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b);
  const double front = std::exp(ln_inverse_beta) * std::pow(x, a) * std::pow(one_minus_x, b);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_continued_fraction(a, b, x) / a;
  return 1.0 - front * beta_continued_fraction(b, a, one_minus_x) / b;
}

double theta_m_pdf(NdfKind kind, double alpha, double theta_m) {
  assert(alpha > 0.0);
  if (!(std::abs(theta_m) < kHalfPi)) return 0.0;
  // p(theta) = P(tan theta) / cos^2 theta: ds = dtheta / cos^2 theta.
  const double c = std::cos(theta_m);
  const double s = std::tan(theta_m);
  double P = 0.0;
  switch (kind) {
    case NdfKind::beckmann:
      P = std::exp(-(s * s) / (alpha * alpha)) / (alpha * std::sqrt(std::numbers::pi));
      break;
    case NdfKind::ggx: {
      const double r = 1.0 + (s * s) / (alpha * alpha);
      P = 1.0 / (2.0 * alpha * r * std::sqrt(r));
      break;
    }
    case NdfKind::phong: {
      const double nu = phong_nu(alpha);
      // The Gammas through their ratio: Gamma(nu/2) overflows for alpha below about 0.08.
      const double front = std::exp(log_gamma_ratio(0.5 * nu, 0.5)) / std::sqrt(std::numbers::pi);
      P = front * std::exp(-0.5 * (nu + 1.0) * std::log1p(s * s));
      break;
    }
    case NdfKind::student_t: {
      // f(t) = Gamma((nu+1)/2) / (sqrt(nu pi) Gamma(nu/2)) (1 + t^2/nu)^(-(nu+1)/2), s = sigma t:
      // P(s) = Gamma(gamma - 1/2) / (sqrt(pi k2) Gamma(gamma - 1)) (1 + s^2/k2)^(1/2 - gamma).
      const double k2 = student_t_scale2(kind, alpha);
      const double front = std::exp(log_gamma_ratio(kind.gamma - 1.0, 0.5)) / std::sqrt(std::numbers::pi * k2);
      P = front * std::exp((0.5 - kind.gamma) * std::log1p(s * s / k2));
      break;
    }
  }
  return P / (c * c);
}

double theta_m_cdf(NdfKind kind, double alpha, double theta_m) {
  assert(alpha > 0.0);
  if (!(theta_m > -kHalfPi)) return 0.0;
  if (!(theta_m < kHalfPi)) return 1.0;
  // Symmetric law: P(theta_m' <= theta) = T(-theta) below 0, 1 - T(theta) above.
  return theta_m <= 0.0 ? lower_tail(kind, alpha, -theta_m) : 1.0 - lower_tail(kind, alpha, theta_m);
}

namespace {

// w in [0, pi/2] with lower_tail(w) = u, for u in (0, 1/2). T decreases from 1/2 to 0. Newton's
// method on g(w) = ln T(w) - ln u (g' = -p/T), which is nearly linear in the tails where T itself
// is exponential, kept inside a bracket [lo, hi] with T(lo) > u >= T(hi) and replaced by bisection
// whenever it would leave it.
double solve_tail(NdfKind kind, double alpha, double u) {
  double lo = 0.0, hi = kHalfPi;
  // Start from the Gaussian tail's rough inverse erfc(y) ~ exp(-y^2), exact in shape for Beckmann;
  // the bracket takes care of the heavier Phong tails.
  double w = std::atan(alpha * std::sqrt(-std::log(2.0 * u)));
  if (!(w > lo && w < hi)) w = 0.5 * (lo + hi);
  for (int it = 0; it < 300; ++it) {
    const double T = lower_tail(kind, alpha, w);
    if (T == u) return w;
    (T > u ? lo : hi) = w;
    const double p = theta_m_pdf(kind, alpha, -w);
    const bool newton = T > 0.0 && p > 0.0;
    double next = newton ? w + std::log(T / u) * T / p : 0.5 * (lo + hi);
    // Converged when Newton's step is below the rounding of w. Tested before the bracket: at the
    // root the step rounds to w itself, an end of the bracket, which the bisection below would
    // take as a step outside it (and bisect some 50 more times, to within 2 ulps of the root).
    if (newton && std::abs(next - w) <= 4e-16 * w) return next >= lo && next <= hi ? next : w;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // Or the bracket is one or two ulps wide.
    if (hi - lo <= 4e-16 * hi) return next;
    w = next;
  }
  return w;
}

}  // namespace

double sample_theta_m(NdfKind kind, double alpha, double u) {
  assert(alpha > 0.0);
  if (!(u > 0.0)) return -kHalfPi;
  if (!(u < 1.0)) return kHalfPi;
  if (kind == NdfKind::ggx) {
    // Inverting (1 + x/sqrt(1+x^2))/2 = u: x/sqrt(1+x^2) = v = 2u - 1, x = v / sqrt(1 - v^2), with
    // 1 - v^2 = 4 u (1 - u) (no cancellation near u = 0 or 1); theta = atan(alpha x).
    return std::atan2(alpha * (2.0 * u - 1.0), 2.0 * std::sqrt(u * (1.0 - u)));
  }
  if (u == 0.5) return 0.0;
  // Symmetric: solve in the lower tail; 1 - u is exact for u >= 1/2 (Sterbenz).
  return u < 0.5 ? -solve_tail(kind, alpha, u) : solve_tail(kind, alpha, 1.0 - u);
}

}  // namespace vgroove::sim
