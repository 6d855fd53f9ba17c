#include "vgroove/validation/chi_square.h"

#include <cmath>
#include <limits>

namespace vgroove::validation {

double gamma_q(double a, double x) {
  if (!(x > 0.0)) return 1.0;
  if (std::isinf(x)) return 0.0;
  const double ln_front = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    // P(a, x) = e^-x x^a / Gamma(a + 1) sum_n x^n / ((a + 1) ... (a + n)).
    double ap = a, del = 1.0 / a, sum = del;
    for (int n = 0; n < 100000 && std::abs(del) > 1e-17 * std::abs(sum); ++n) {
      ap += 1.0;
      del *= x / ap;
      sum += del;
    }
    return 1.0 - sum * std::exp(ln_front);
  }
  constexpr double tiny = 1e-300;  // keeps Lentz's c and d off zero
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-16) break;
  }
  return std::exp(ln_front) * h;
}

ChiSquareResult chi_square(const std::vector<double>& expected, const std::vector<double>& observed) {
  std::vector<double> e_cells, o_cells;
  double e = 0.0, o = 0.0;
  for (std::size_t j = 0; j < expected.size(); ++j) {
    e += expected[j];
    o += observed[j];
    if (e >= 5.0) e_cells.push_back(e), o_cells.push_back(o), e = o = 0.0;
  }
  if (e > 0.0 || o > 0.0) {
    if (e_cells.empty())
      e_cells.push_back(e), o_cells.push_back(o);
    else
      e_cells.back() += e, o_cells.back() += o;
  }
  ChiSquareResult r;
  for (std::size_t c = 0; c < e_cells.size(); ++c) {
    const double diff = o_cells[c] - e_cells[c];
    if (e_cells[c] > 0.0)
      r.stat += diff * diff / e_cells[c];
    else if (o_cells[c] > 0.0)
      r.stat = std::numeric_limits<double>::infinity();
  }
  r.dof = static_cast<int>(e_cells.size()) - 1;
  r.p = r.dof > 0 ? gamma_q(0.5 * r.dof, 0.5 * r.stat) : (r.stat > 0.0 ? 0.0 : 1.0);
  return r;
}

}  // namespace vgroove::validation
