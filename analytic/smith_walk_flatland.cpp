#include "vgroove/analytic/smith_walk_flatland.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::analytic {

namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;
constexpr double kSqrtPi = 1.7724538509055160273;

// The view in slope space with b = |sin theta_view| >= 0 (the mirror image when sin < 0).
struct View {
  double a, b;
  bool mirrored;
};
View view_of(double theta_view) {
  const double s = std::sin(theta_view);
  return {std::cos(theta_view), std::abs(s), s < 0.0};
}

// Beckmann's upper tail U(x) = (a/2) erfc(x) + b alpha e^{-x^2} / (2 sqrt pi), x = s / alpha.
double beckmann_tail(double a, double b_alpha, double x) {
  return 0.5 * a * std::erfc(x) + b_alpha * std::exp(-x * x) / (2.0 * kSqrtPi);
}

// GGX: (R + a) / R, R = sqrt(a^2 + (b alpha)^2), without cancelling when a < 0.
double ggx_w(double a, double b_alpha, double R) { return a >= 0.0 ? (R + a) / R : b_alpha * b_alpha / ((R - a) * R); }

// Beckmann: x >= x0 with U(x) = target, U decreasing; safeguarded Newton, U' = -(a + b alpha x)
// e^{-x^2} / sqrt pi.
double solve_beckmann(double a, double b_alpha, double x0, double target) {
  // Below -27 erfc is 2 and e^{-x^2} 0 to double precision; above 27 U is 0.
  double lo = std::max(x0, -27.0), hi = std::max(lo, 0.0) + 27.0;
  double x = std::max(lo, 0.0);
  for (int it = 0; it < 300; ++it) {
    const double f = beckmann_tail(a, b_alpha, x) - target;
    if (f == 0.0) return x;
    (f > 0.0 ? lo : hi) = x;
    const double d = -(a + b_alpha * x) * std::exp(-x * x) / kSqrtPi;
    double next = d < 0.0 ? x - f / d : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-15 * (1.0 + std::abs(x)) || hi - lo <= 1e-15 * (1.0 + std::abs(hi))) return next;
    x = next;
  }
  return x;
}

}  // namespace

double visible_projected_length(NdfKind ndf, double alpha, double theta_view) {
  assert(ndf == NdfKind::beckmann || ndf == NdfKind::ggx);
  const View v = view_of(theta_view);
  const double b_alpha = v.b * alpha;
  if (ndf == NdfKind::ggx) {
    // (a + R) / 2: Heitz 2014's cos theta (1 + Lambda) for an upward view.
    const double R = std::hypot(v.a, b_alpha);
    return v.a >= 0.0 ? 0.5 * (v.a + R) : 0.5 * b_alpha * b_alpha / (R - v.a);
  }
  if (v.b == 0.0) return std::max(v.a, 0.0);
  return beckmann_tail(v.a, b_alpha, -v.a / b_alpha);
}

double visible_normal_pdf(NdfKind ndf, double alpha, double theta_view, double m) {
  if (!(std::abs(m) < kHalfPi)) return 0.0;
  const double c = std::cos(theta_view - m);
  if (!(c > 0.0)) return 0.0;
  return c * D2(ndf, m, alpha) / visible_projected_length(ndf, alpha, theta_view);
}

double sample_visible_normal(NdfKind ndf, double alpha, double theta_view, double u) {
  assert(ndf == NdfKind::beckmann || ndf == NdfKind::ggx);
  const View v = view_of(theta_view);
  const double b_alpha = v.b * alpha;
  // The mirror image reverses the order of the normals: its sample is taken at 1 - u, so that m
  // grows with u either way.
  const double u_own = v.mirrored ? 1.0 - u : u;
  double m;
  if (ndf == NdfKind::ggx) {
    // phi from psi - pi/2 (at s0) to pi/2; s = alpha tan phi, m = atan(s).
    const double R = std::hypot(v.a, b_alpha);
    const double psi = std::atan2(b_alpha, v.a);
    const double phi = psi - kHalfPi + 2.0 * std::asin(std::sqrt(0.5 * u_own * ggx_w(v.a, b_alpha, R)));
    m = std::atan2(alpha * std::sin(phi), std::cos(phi));
  } else {
    const double x0 = v.b > 0.0 ? -v.a / b_alpha : -std::numeric_limits<double>::infinity();
    const double A = visible_projected_length(ndf, alpha, theta_view);
    // A facet turned exactly to the edge of visibility when A underflows (a view within e^-700
    // of grazing every facet): the boundary normal.
    // The upper tail U(s) = (1 - u_own) A, without rounding 1 - (1 - u) when mirrored.
    const double x = A > 0.0 ? solve_beckmann(v.a, b_alpha, x0, (v.mirrored ? u : 1.0 - u) * A) : x0;
    m = std::atan(alpha * x);
  }
  return v.mirrored ? -m : m;
}

double walk_free_path(NdfKind ndf, double alpha, double lc, double theta_travel, double xi) {
  const double lambda = Lambda(ndf, theta_travel, alpha);
  const double log_xi = std::log(xi);
  if (std::cos(theta_travel) > 0.0) {
    // Up: leaves with probability C1(h)^Lambda.
    if (lambda == 0.0 || log_xi < lambda * lc) return std::numeric_limits<double>::infinity();
    return lc - log_xi / lambda;
  }
  // Down (or level): always meets the surface; Lambda of the reversed direction is the same.
  return lc + log_xi / (1.0 + lambda);
}

}  // namespace vgroove::analytic
