#include "vgroove/analytic/partner_table.h"

#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace vgroove::analytic {

namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

double exact_p(NdfKind ndf, double alpha, bool flatland, double B) {
  return flatland ? P2_theta_r(ndf, B, alpha) : P_theta_r(ndf, B, alpha);
}

// P's mass on [a, b]: adaptive Gauss-Kronrod (no node at the ends, where Phong may be singular).
double exact_mass(NdfKind ndf, double alpha, bool flatland, double a, double b) {
  return integrate_adaptive_parts([&](double B) { return exact_p(ndf, alpha, flatland, B); }, a, b, 1e-12, 1e-16, 2,
                                  64);
}

}  // namespace

PartnerTable make_partner_table(NdfKind ndf, double alpha, bool flatland, int cells) {
  if (!partner_law_exists(ndf, alpha))
    throw std::domain_error("no partner law P(theta_r) for this NDF and alpha (Phong needs alpha < sqrt(2))");
  if (cells < 2) throw std::invalid_argument("make_partner_table: cells must be >= 2");
  PartnerTable t;
  if (ndf == NdfKind::phong && phong_exponent(alpha) < 0.0)
    throw std::domain_error("the tabulated partner law needs a bounded P(theta_r): Phong alpha <= 1");
  // The nodes: `cells` mapped ones (dense where D lives) and `cells` uniform ones (the tails of
  // the heavy NDFs at small alpha, where the mapped cells grow to ~ alpha^-1 pi / (2 cells)).
  for (int j = 0; j < cells; ++j) {
    t.B.push_back(std::atan(alpha * std::tan(kHalfPi * j / cells)));
    t.B.push_back(kHalfPi * j / cells);
  }
  t.B.push_back(kHalfPi);
  std::sort(t.B.begin(), t.B.end());
  t.B.erase(std::unique(t.B.begin(), t.B.end()), t.B.end());
  const int N = static_cast<int>(t.B.size()) - 1;
  t.p.resize(t.B.size());
  t.cdf.resize(t.B.size());
  for (int j = 0; j < N; ++j) t.p[j] = exact_p(ndf, alpha, flatland, t.B[j]);
  t.p[N] = exact_p(ndf, alpha, flatland, std::nextafter(kHalfPi, 0.0));
  t.cdf[0] = 0.0;
  for (int j = 0; j < N; ++j) t.cdf[j + 1] = t.cdf[j] + 0.5 * (t.p[j] + t.p[j + 1]) * (t.B[j + 1] - t.B[j]);
  const double total = t.cdf[N];
  for (int j = 0; j <= N; ++j) {
    t.p[j] /= total;
    t.cdf[j] /= total;
  }
  t.cdf[N] = 1.0;
  return t;
}

double sample_partner(const PartnerTable& t, double u) {
  const int N = static_cast<int>(t.B.size()) - 1;
  // The cell j with cdf[j] <= u < cdf[j + 1] (binary search), skipping empty cells.
  const auto it = std::upper_bound(t.cdf.begin(), t.cdf.end(), u);
  const int j = std::clamp(static_cast<int>(it - t.cdf.begin()) - 1, 0, N - 1);
  const double h = t.B[j + 1] - t.B[j], p0 = t.p[j], slope = (t.p[j + 1] - p0) / h;
  const double r = std::max(0.0, u - t.cdf[j]);
  // p0 x + slope x^2 / 2 = r, the root in [0, h] in its stable form.
  const double disc = std::max(0.0, p0 * p0 + 2.0 * slope * r);
  const double den = p0 + std::sqrt(disc);
  const double x = den > 0.0 ? 2.0 * r / den : 0.0;
  return std::clamp(t.B[j] + std::min(x, h), t.B[j], t.B[j + 1]);
}

double partner_table_pdf(const PartnerTable& t, double B) {
  if (!(B >= 0.0 && B <= kHalfPi)) return 0.0;
  const int N = static_cast<int>(t.B.size()) - 1;
  const auto it = std::upper_bound(t.B.begin(), t.B.end(), B);
  const int j = std::clamp(static_cast<int>(it - t.B.begin()) - 1, 0, N - 1);
  const double h = t.B[j + 1] - t.B[j];
  const double w = h > 0.0 ? (B - t.B[j]) / h : 0.0;
  return (1.0 - w) * t.p[j] + w * t.p[j + 1];
}

double partner_table_l1_error(const PartnerTable& t, NdfKind ndf, double alpha, bool flatland) {
  double sum = 0.0;
  for (std::size_t j = 0; j + 1 < t.B.size(); ++j)
    sum += integrate_adaptive_parts(
        [&](double B) { return std::abs(partner_table_pdf(t, B) - exact_p(ndf, alpha, flatland, B)); }, t.B[j],
        t.B[j + 1], 1e-6, 1e-15, 1, 32);
  return sum;
}

double partner_table_cdf_error(const PartnerTable& t, NdfKind ndf, double alpha, bool flatland) {
  double exact = 0.0, worst = 0.0;
  for (std::size_t j = 0; j + 1 < t.B.size(); ++j) {
    exact += exact_mass(ndf, alpha, flatland, t.B[j], t.B[j + 1]);
    worst = std::max(worst, std::abs(t.cdf[j + 1] - exact));
  }
  return worst;
}

}  // namespace vgroove::analytic
