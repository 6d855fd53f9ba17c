#include "vgroove/sim/partner_sampling.h"

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/slope_sampling.h"

#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

// Phong's exponent alpha_p = 2/alpha^2 - 2 (sim/slope_sampling.h).
double phong_p(double alpha) { return 2.0 / (alpha * alpha) - 2.0; }

double standard_normal(Rng& rng) {
  // Box-Muller, one of the pair.
  return std::sqrt(-2.0 * std::log(uniform_open(rng))) * std::cos(2.0 * std::numbers::pi * uniform_open(rng));
}

// Gamma(3/2) = Exp(1) + Z^2 / 2 (a sum of Gamma(1) and Gamma(1/2)).
double sample_gamma_three_halves(Rng& rng) {
  const double z = standard_normal(rng);
  return -std::log(uniform_open(rng)) + 0.5 * z * z;
}

// beta - sin(beta) without cancellation for small beta (series to beta^9: relative 1e-17 below 0.1).
double beta_minus_sin(double b) {
  if (b < 0.1) {
    const double b2 = b * b;
    return b * b2 / 6.0 * (1.0 - b2 / 20.0 * (1.0 - b2 / 42.0 * (1.0 - b2 / 72.0)));
  }
  return b - std::sin(b);
}

// beta in [0, pi] with beta - sin(beta) = pi u: Newton kept inside the bracket.
double solve_kepler(double u) {
  const double target = std::numbers::pi * u;
  double lo = 0.0, hi = std::numbers::pi;
  double b = u < 0.5 ? std::cbrt(6.0 * target) : std::numbers::pi * (1.0 - 0.5 * (1.0 - u));
  if (!(b > lo && b < hi)) b = 0.5 * (lo + hi);
  for (int it = 0; it < 200; ++it) {
    const double g = beta_minus_sin(b) - target;
    if (g == 0.0) return b;
    (g < 0.0 ? lo : hi) = b;
    const double s = std::sin(0.5 * b);
    const double dg = 2.0 * s * s;  // 1 - cos(beta)
    double next = dg > 0.0 ? b - g / dg : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - b) <= 4e-16 * next || hi - lo <= 4e-16 * hi) return next;
    b = next;
  }
  return b;
}

}  // namespace

bool theta_r_law_exists(NdfKind kind, double alpha) {
  if (!(alpha > 0.0)) return false;
  if (kind == NdfKind::student_t) return false;  // not written for Student-T
  return kind != NdfKind::phong || phong_p(alpha) > -1.0;
}

double sample_gamma(double shape, Rng& rng) {
  assert(shape > 0.0);
  if (shape < 1.0) {
    // Gamma(a) = Gamma(a + 1) U^(1/a) (Marsaglia and Tsang 2000, Sec. 6).
    const double g = sample_gamma(shape + 1.0, rng);
    return g * std::exp(std::log(uniform_open(rng)) / shape);
  }
  // Marsaglia and Tsang, "A Simple Method for Generating Gamma Variables", ACM TOMS 26(3), 2000.
  const double d = shape - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
  for (;;) {
    const double x = standard_normal(rng);
    double v = 1.0 + c * x;
    if (v <= 0.0) continue;
    v = v * v * v;
    const double u = uniform_open(rng);
    if (std::log(u) < 0.5 * x * x + d - d * v + d * std::log(v)) return d * v;
  }
}

double theta_r_pdf_3d(NdfKind kind, double alpha, double theta_r) {
  assert(theta_r_law_exists(kind, alpha));
  if (!(theta_r >= 0.0 && theta_r < kHalfPi)) return 0.0;
  const double c = std::cos(theta_r), s = std::sin(theta_r), a2 = alpha * alpha;
  switch (kind) {
    case NdfKind::beckmann: {
      // Density of x: 4 x^2 exp(-x^2/a^2) / (sqrt(pi) a^3); dx/dtheta = 1/cos^2.
      if (c == 0.0) return 0.0;
      const double x = s / c;
      return 4.0 * x * x * std::exp(-x * x / a2) / (std::sqrt(std::numbers::pi) * a2 * alpha * c * c);
    }
    case NdfKind::ggx: {
      // Density of x: (4 a / pi) x^2 / (a^2 + x^2)^2; times 1/cos^2: s^2 / (a^2 c^2 + s^2)^2.
      const double q = a2 * c * c + s * s;
      return 4.0 * alpha / std::numbers::pi * s * s / (q * q);
    }
    case NdfKind::phong: {
      // 2 cos^p sin^2 / B(3/2, (p+1)/2).
      const double p = phong_p(alpha);
      const double ln_beta = std::lgamma(1.5) + std::lgamma(0.5 * (p + 1.0)) - std::lgamma(0.5 * (p + 4.0));
      return 2.0 * std::exp(p * std::log(c) - ln_beta) * s * s;
    }
    case NdfKind::student_t:
      break;  // no partner law for Student-T (theta_r_law_exists)
  }
  return 0.0;
}

double theta_r_cdf_3d(NdfKind kind, double alpha, double theta_r) {
  assert(theta_r_law_exists(kind, alpha));
  if (!(theta_r > 0.0)) return 0.0;
  if (!(theta_r < kHalfPi)) return 1.0;
  const double c = std::cos(theta_r), s = std::sin(theta_r);
  switch (kind) {
    case NdfKind::beckmann: {
      const double r = s / (c * alpha);  // sqrt(y)
      return std::erf(r) - 2.0 * r / std::sqrt(std::numbers::pi) * std::exp(-r * r);
    }
    case NdfKind::ggx: {
      const double psi = std::atan2(s, alpha * c);
      return (2.0 * psi - std::sin(2.0 * psi)) / std::numbers::pi;
    }
    case NdfKind::phong:
      return incomplete_beta(1.5, 0.5 * (phong_p(alpha) + 1.0), s * s, c * c);
    case NdfKind::student_t:
      break;  // no partner law for Student-T (theta_r_law_exists)
  }
  return 0.0;
}

double sample_theta_r_3d(NdfKind kind, double alpha, Rng& rng) {
  assert(theta_r_law_exists(kind, alpha));
  switch (kind) {
    case NdfKind::beckmann:
      // x = alpha sqrt(y), y ~ Gamma(3/2).
      return std::atan(alpha * std::sqrt(sample_gamma_three_halves(rng)));
    case NdfKind::ggx: {
      // psi = beta / 2, x = alpha tan(psi).
      const double half = 0.5 * solve_kepler(uniform_open(rng));
      return std::atan2(alpha * std::sin(half), std::cos(half));
    }
    case NdfKind::phong: {
      // sin^2 = X / (X + Y), cos^2 = Y / (X + Y).
      const double X = sample_gamma_three_halves(rng), Y = sample_gamma(0.5 * (phong_p(alpha) + 1.0), rng);
      return std::atan2(std::sqrt(X), std::sqrt(Y));
    }
    case NdfKind::student_t:
      break;  // no partner law for Student-T (theta_r_law_exists)
  }
  return 0.0;
}

double theta_r_pdf(NdfKind kind, double alpha, double theta_r) {
  assert(theta_r_law_exists(kind, alpha));
  if (!(theta_r >= 0.0 && theta_r < kHalfPi)) return 0.0;
  const double c = std::cos(theta_r), s = std::sin(theta_r), a2 = alpha * alpha;
  switch (kind) {
    case NdfKind::beckmann: {
      if (c == 0.0) return 0.0;
      const double x = s / c;
      return 2.0 * x / a2 * std::exp(-x * x / a2) / (c * c);
    }
    case NdfKind::ggx: {
      const double q = a2 * c * c + s * s;
      return alpha * s / (q * std::sqrt(q));
    }
    case NdfKind::phong: {
      const double p = phong_p(alpha);
      return (p + 1.0) * std::pow(c, p) * s;
    }
    case NdfKind::student_t:
      break;  // no partner law for Student-T (theta_r_law_exists)
  }
  return 0.0;
}

double theta_r_cdf(NdfKind kind, double alpha, double theta_r) {
  assert(theta_r_law_exists(kind, alpha));
  if (!(theta_r > 0.0)) return 0.0;
  if (!(theta_r < kHalfPi)) return 1.0;
  const double c = std::cos(theta_r), s = std::sin(theta_r);
  switch (kind) {
    case NdfKind::beckmann: {
      const double x = s / c;
      return -std::expm1(-x * x / (alpha * alpha));
    }
    case NdfKind::ggx:
      return 1.0 - alpha * c / std::sqrt(alpha * alpha * c * c + s * s);
    case NdfKind::phong:
      return -std::expm1((phong_p(alpha) + 1.0) * std::log(c));
    case NdfKind::student_t:
      break;  // no partner law for Student-T (theta_r_law_exists)
  }
  return 0.0;
}

double sample_theta_r(NdfKind kind, double alpha, double u) {
  assert(theta_r_law_exists(kind, alpha));
  if (!(u > 0.0)) return 0.0;
  if (!(u < 1.0)) return kHalfPi;
  switch (kind) {
    case NdfKind::beckmann:
      return std::atan(alpha * std::sqrt(-std::log1p(-u)));
    case NdfKind::ggx:
      // x / alpha = sqrt((1 - u)^-2 - 1) = sqrt(u (2 - u)) / (1 - u).
      return std::atan2(alpha * std::sqrt(u * (2.0 - u)), 1.0 - u);
    case NdfKind::phong: {
      // cos = (1 - u)^(1/(p+1)); 1 - cos = 2 sin^2(theta/2) keeps small angles exact.
      const double one_minus_cos = -std::expm1(std::log1p(-u) / (phong_p(alpha) + 1.0));
      return 2.0 * std::asin(std::sqrt(0.5 * one_minus_cos));
    }
    case NdfKind::student_t:
      break;  // no partner law for Student-T (theta_r_law_exists)
  }
  return 0.0;
}

}  // namespace vgroove::sim
