// vgroove analytic: Gauss-Legendre quadrature, the one rule every integral of analytic/ uses.
//
// The n-point rule integrates polynomials of degree 2n - 1 exactly on [-1, 1]. Nodes and weights
// come from Newton's method on the Legendre polynomial P_n (three-term recurrence), started at
// cos(pi (i + 3/4) / (n + 1/2)); converged to |dz| < 1e-16, i.e. to the last bit for n <= 64.
#pragma once

#include <cstddef>
#include <vector>

namespace vgroove::analytic {

struct GaussLegendre {
  std::vector<double> x;  // nodes on [-1, 1], ascending; the rule is symmetric, x[n-1-i] = -x[i]
  std::vector<double> w;  // weights, summing to 2
  std::size_t size() const { return x.size(); }
};

// The n-point rule, n >= 1.
GaussLegendre gauss_legendre(int n);

// The rule of order 2, 4 or 8, computed once (the lobes pick one per piece by its mass).
const GaussLegendre& gauss_legendre_cached(int n);

// int_a^b f by the rule mapped onto [a, b].
template <class F>
double integrate(const GaussLegendre& g, F&& f, double a, double b) {
  const double c = 0.5 * (a + b), d = 0.5 * (b - a);
  double s = 0.0;
  for (std::size_t i = 0; i < g.size(); ++i) s += g.w[i] * f(c + d * g.x[i]);
  return d * s;
}

// The same sum with the nodes taken from the right end, x -> -x (the rule is symmetric, so the
// value differs only by the rounding of the sum's order; the flatland lobes sum this way).
template <class F>
double integrate_mirrored(const GaussLegendre& g, F&& f, double a, double b) {
  const double c = 0.5 * (a + b), d = 0.5 * (b - a);
  double s = 0.0;
  for (std::size_t i = 0; i < g.size(); ++i) s += g.w[i] * f(c - d * g.x[i]);
  return d * s;
}

}  // namespace vgroove::analytic
