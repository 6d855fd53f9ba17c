// vgroove analytic: Gauss-Legendre quadrature, the one rule every integral of analytic/ uses.
//
// The n-point rule integrates polynomials of degree 2n - 1 exactly on [-1, 1]. Nodes and weights
// come from Newton's method on the Legendre polynomial P_n (three-term recurrence), started at
// cos(pi (i + 3/4) / (n + 1/2)); converged to |dz| < 1e-16, i.e. to the last bit for n <= 64.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <queue>
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

// A map s -> g(s) of [0, 1] onto itself and its slope g'(s), flat (g' = 0) at each end marked: s^2,
// 1 - (1 - s)^2, or the smoothstep s^2 (3 - 2 s) for both. A panel whose integrand has a
// square-root point at a marked end is smooth in s (the lobes' phi_a panels next to where a bin
// edge starts to cut the arcs of exits).
inline void flat_end_map(bool flat_0, bool flat_1, double s, double& g, double& dg) {
  if (flat_0 && flat_1) {
    g = s * s * (3.0 - 2.0 * s);
    dg = 6.0 * s * (1.0 - s);
  } else if (flat_0) {
    g = s * s;
    dg = 2.0 * s;
  } else if (flat_1) {
    g = 1.0 - (1.0 - s) * (1.0 - s);
    dg = 2.0 * (1.0 - s);
  } else {
    g = s;
    dg = 1.0;
  }
}

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

// ---- Adaptive Gauss-Kronrod ---------------------------------------------------------------------
//
// One rule: the 15-point Kronrod extension of the 7-point Gauss rule (Piessens et al., QUADPACK,
// 1983: the nodes and weights of its QK15); |K15 - G7| estimates the error of the 7-point
// estimate and the 15-point one is kept. Two globally adaptive drivers over it (QUADPACK's QAG
// strategy: bisect the piece with the largest estimate until the summed estimates fall below the
// tolerance or a piece budget is spent). The estimate is used as is (QUADPACK's (200 e / r)^1.5
// rescaling is not applied: it is not an upper bound where the integrand has jumps, which every
// integrand here has). Integrable end singularities and jumps converge by bisection; pass the
// known jumps and peaks as breakpoints.
//   - integrate_adaptive: from breakpoints, with the error, the evaluations and whether it
//     converged (AdaptiveResult); the pieces summed from the largest estimate down.
//   - integrate_adaptive_parts: from equal parts of [a, b], the value alone; the parts summed in
//     their order along [a, b] (the nonsymmetric BRDF's and sampler's integrals over a groove
//     family, smooth between kinks at unknown places).
// The two sum in different orders and round their error estimates differently, so their values
// differ in the last bits: each keeps its callers' reports as they are.

struct AdaptiveResult {
  double value = 0.0;
  double error = 0.0;  // the summed |K15 - G7| of the final pieces
  long evaluations = 0;
  bool converged = false;  // error <= tolerance before max_pieces
};

struct AdaptiveOptions {
  double abs_tol = 1e-10;
  double rel_tol = 0.0;
  int max_pieces = 2000;
};

namespace detail {
// Kronrod nodes on [0, 1] (x_k[1], x_k[3], x_k[5] are the Gauss nodes) and weights.
inline constexpr double kXk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                  0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                  0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                  0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
inline constexpr double kWk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                  0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                  0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                  0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                  0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

// The rule on [a, b]: the Kronrod and Gauss sums k and g on [-1, 1] and the half-width h (the
// estimates are k h and g h).
struct KronrodGauss {
  double k, g, h;
};
template <class F>
KronrodGauss gauss_kronrod_15(F& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double k = kWk[7] * fc, g = kWg[3] * fc;
  for (int j = 0; j < 7; ++j) {
    const double x = h * kXk[j];
    const double f1 = f(c - x), f2 = f(c + x);
    k += kWk[j] * (f1 + f2);
    if (j % 2 == 1) g += kWg[j / 2] * (f1 + f2);
  }
  return {k, g, h};
}

struct Piece {
  double a, b, value, error;
  bool operator<(const Piece& o) const { return error < o.error; }
};
template <class F>
Piece kronrod_piece(F& f, double a, double b) {
  const KronrodGauss r = gauss_kronrod_15(f, a, b);
  return {a, b, r.k * r.h, std::abs((r.k - r.g) * r.h)};
}
}  // namespace detail

// int f over [points[0], points.back()], the points (ascending) the initial pieces.
template <class F>
AdaptiveResult integrate_adaptive(F&& f, const std::vector<double>& points, const AdaptiveOptions& opt = {}) {
  AdaptiveResult r;
  std::priority_queue<detail::Piece> pieces;
  for (std::size_t j = 0; j + 1 < points.size(); ++j) {
    if (!(points[j + 1] > points[j])) continue;
    pieces.push(detail::kronrod_piece(f, points[j], points[j + 1]));
    r.evaluations += 15;
  }
  auto totals = [&]() {
    // Summed in a copy, so the running sums never accumulate the rounding of many updates.
    auto q = pieces;
    double v = 0.0, e = 0.0;
    while (!q.empty()) v += q.top().value, e += q.top().error, q.pop();
    return std::pair<double, double>{v, e};
  };
  double value = 0.0, error = 0.0;
  {
    auto [v, e] = totals();
    value = v, error = e;
  }
  while (!pieces.empty() && error > std::max(opt.abs_tol, opt.rel_tol * std::abs(value)) &&
         static_cast<int>(pieces.size()) < opt.max_pieces) {
    const detail::Piece p = pieces.top();
    const double m = 0.5 * (p.a + p.b);
    if (!(m > p.a && m < p.b)) break;  // no room left in double
    pieces.pop();
    const detail::Piece l = detail::kronrod_piece(f, p.a, m), u = detail::kronrod_piece(f, m, p.b);
    r.evaluations += 30;
    value += l.value + u.value - p.value;
    error += l.error + u.error - p.error;
    pieces.push(l);
    pieces.push(u);
  }
  auto [v, e] = totals();
  r.value = v;
  r.error = e;
  r.converged = e <= std::max(opt.abs_tol, opt.rel_tol * std::abs(v));
  return r;
}

template <class F>
AdaptiveResult integrate_adaptive(F&& f, double a, double b, const AdaptiveOptions& opt = {}) {
  return integrate_adaptive(f, std::vector<double>{a, b}, opt);
}

// int_a^b f from `initial` equal parts, halving the part with the largest estimate until the
// summed estimate is below max(rel_tol |integral|, abs_tol) or `max_parts` parts are in use (which
// bounds the cost when the integrand's rounding noise exceeds the tolerance, e.g. next to a
// singular direction).
template <class F>
double integrate_adaptive_parts(F&& f, double a, double b, double rel_tol, double abs_tol = 0.0, int initial = 4,
                                int max_parts = 256) {
  if (!(b > a)) return 0.0;
  struct Part {
    double lo, hi, value, error;
  };
  auto part = [&f](double lo, double hi) {
    const detail::KronrodGauss r = detail::gauss_kronrod_15(f, lo, hi);
    const double k = r.k * r.h, g = r.g * r.h;
    return Part{lo, hi, k, std::abs(k - g)};
  };
  std::vector<Part> parts;
  parts.reserve(static_cast<std::size_t>(max_parts) + 2);
  const double h = (b - a) / initial;
  double total = 0.0, error = 0.0;
  for (int j = 0; j < initial; ++j) {
    parts.push_back(part(a + j * h, j + 1 == initial ? b : a + (j + 1) * h));
    total += parts.back().value;
    error += parts.back().error;
  }
  while (error > std::max(rel_tol * std::abs(total), abs_tol) && static_cast<int>(parts.size()) < max_parts) {
    std::size_t worst = 0;
    for (std::size_t n = 1; n < parts.size(); ++n)
      if (parts[n].error > parts[worst].error) worst = n;
    const Part p = parts[worst];
    const double m = 0.5 * (p.lo + p.hi);
    if (!(m > p.lo && m < p.hi)) break;  // the part is one ulp wide
    parts[worst] = part(p.lo, m);
    parts.push_back(part(m, p.hi));
    total += parts[worst].value + parts.back().value - p.value;
    error += parts[worst].error + parts.back().error - p.error;
  }
  // The sum afresh (the running total collects rounding).
  double s = 0.0;
  for (const Part& p : parts) s += p.value;
  return s;
}

}  // namespace vgroove::analytic
