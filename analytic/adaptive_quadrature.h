// vgroove analytic: adaptive Gauss-Kronrod quadrature (7-point Gauss, 15-point Kronrod), for the
// integrals over a groove family whose integrands are smooth between kinks at unknown places.
//
// The 15-point Kronrod extension of the 7-point Gauss rule (Piessens et al., QUADPACK, 1983: the
// nodes and weights of its QK15); the difference of the two estimates bounds the error of the 7-
// point one, and the 15-point estimate is kept.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace vgroove::analytic {

struct GaussKronrod {
  double kronrod = 0.0, gauss = 0.0;
};

template <class F>
GaussKronrod gauss_kronrod_15(F&& f, double a, double b) {
  static constexpr double xgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                    0.207784955007898467600689403773245, 0.0};
  static constexpr double wgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
  static constexpr double wg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                   0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double k = wgk[7] * fc, g = wg[3] * fc;
  for (int j = 0; j < 7; ++j) {
    const double f1 = f(c - h * xgk[j]), f2 = f(c + h * xgk[j]);
    k += wgk[j] * (f1 + f2);
    if (j % 2 == 1) g += wg[j / 2] * (f1 + f2);
  }
  return {k * h, g * h};
}

// int_a^b f by global adaptive subdivision (QUADPACK's QAG strategy): start from `initial` equal
// parts, then halve the part with the largest error estimate until the summed estimate is below
// max(rel_tol |integral|, abs_tol) or `max_parts` parts are in use (which bounds the cost when
// the integrand's rounding noise exceeds the tolerance, e.g. next to a singular direction).
template <class F>
double integrate_adaptive(F&& f, double a, double b, double rel_tol, double abs_tol = 0.0, int initial = 4,
                          int max_parts = 256) {
  if (!(b > a)) return 0.0;
  struct Part {
    double lo, hi, value, error;
  };
  std::vector<Part> parts;
  parts.reserve(static_cast<std::size_t>(max_parts) + 2);
  const double h = (b - a) / initial;
  double total = 0.0, error = 0.0;
  for (int j = 0; j < initial; ++j) {
    const double lo = a + j * h, hi = j + 1 == initial ? b : a + (j + 1) * h;
    const GaussKronrod r = gauss_kronrod_15(f, lo, hi);
    parts.push_back({lo, hi, r.kronrod, std::abs(r.kronrod - r.gauss)});
    total += r.kronrod;
    error += parts.back().error;
  }
  while (error > std::max(rel_tol * std::abs(total), abs_tol) && static_cast<int>(parts.size()) < max_parts) {
    std::size_t worst = 0;
    for (std::size_t n = 1; n < parts.size(); ++n)
      if (parts[n].error > parts[worst].error) worst = n;
    const Part p = parts[worst];
    const double m = 0.5 * (p.lo + p.hi);
    if (!(m > p.lo && m < p.hi)) break;  // the part is one ulp wide
    const GaussKronrod r1 = gauss_kronrod_15(f, p.lo, m), r2 = gauss_kronrod_15(f, m, p.hi);
    parts[worst] = {p.lo, m, r1.kronrod, std::abs(r1.kronrod - r1.gauss)};
    parts.push_back({m, p.hi, r2.kronrod, std::abs(r2.kronrod - r2.gauss)});
    total += r1.kronrod + r2.kronrod - p.value;
    error += parts[worst].error + parts.back().error - p.error;
  }
  // The sum afresh (the running total collects rounding).
  double s = 0.0;
  for (const Part& p : parts) s += p.value;
  return s;
}

}  // namespace vgroove::analytic
