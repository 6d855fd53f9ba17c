#include "vgroove/validation/chi_square.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

namespace vgroove::validation {

namespace {
// ln(x^a e^-x / Gamma(a)), the factor in front of both expansions. For large a, -x + a ln x and
// ln Gamma(a) are large and nearly cancel (at a = 5000 both are ~4e4: 4e-12 of the result lost to
// rounding), so there it is written with Stirling's series,
//   ln Gamma(a) = (a - 1/2) ln a - a + ln(2 pi) / 2 + 1/(12 a) - 1/(360 a^3) + 1/(1260 a^5) - 1/(1680 a^7),
// (truncation below 1/(1188 a^9) < 2e-15 from a = 20) as a (log1p(t) - t) + ln(a) / 2 - ln(2 pi) / 2
// - the series' tail, t = (x - a) / a: each term small where the result is not.
double ln_front(double a, double x) {
  if (a < 20.0) return -x + a * std::log(x) - std::lgamma(a);
  const double t = (x - a) / a, r = 1.0 / (a * a);
  const double tail = (1.0 / 12.0 - r * (1.0 / 360.0 - r * (1.0 / 1260.0 - r / 1680.0))) / a;
  return a * (std::log1p(t) - t) + 0.5 * std::log(a) - 0.5 * std::log(2.0 * std::numbers::pi) - tail;
}
}  // namespace

double gamma_q(double a, double x) {
  if (!(x > 0.0)) return 1.0;
  const double ln_front = validation::ln_front(a, x);
  if (x < a + 1.0) {
    // P(a, x) by its series, Q = 1 - P.
    double ap = a, del = 1.0 / a, sum = del;
    for (int n = 0; n < 100000 && std::abs(del) > 1e-17 * std::abs(sum); ++n) {
      ap += 1.0;
      del *= x / ap;
      sum += del;
    }
    return 1.0 - sum * std::exp(ln_front);
  }
  // Q(a, x) by Lentz's continued fraction.
  constexpr double tiny = 1e-300;
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

double chi_square_sf(double x, int dof) { return dof > 0 ? gamma_q(0.5 * dof, 0.5 * x) : 1.0; }

double sidak_level(double level, int tests) {
  // 1 - (1 - level)^(1/tests), written with expm1/log1p so that small levels keep their digits.
  return -std::expm1(std::log1p(-level) / std::max(1, tests));
}

ChiSquareResult chi_square_test(const std::vector<double>& observed, const std::vector<double>& expected, double level,
                                int tests, double min_expected) {
  ChiSquareResult r;
  r.level = sidak_level(level, tests);
  std::vector<std::size_t> order(expected.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  struct Cell {
    double o = 0.0, e = 0.0;
  };
  std::vector<Cell> cells;
  Cell pool;
  bool pool_open = false;
  for (std::size_t idx : order) {
    const double o = observed[idx], e = expected[idx];
    if (!(e > 0.0)) {
      if (o > 0.0) r.samples_where_none_expected = true;
      continue;
    }
    ++r.cells;
    if (e < min_expected) {
      pool.o += o, pool.e += e;
      pool_open = true;
      ++r.pooled_in;
      if (pool.e >= min_expected) {
        cells.push_back(pool);
        ++r.pooled_out;
        pool = Cell{};
        pool_open = false;
      }
      continue;
    }
    Cell c{o, e};
    if (pool_open) {  // an incomplete pool joins the next cell
      c.o += pool.o, c.e += pool.e;
      pool = Cell{};
      pool_open = false;
    }
    cells.push_back(c);
  }
  if (pool_open) {
    if (cells.empty()) {
      cells.push_back(pool);
    } else {
      cells.back().o += pool.o;
      cells.back().e += pool.e;
    }
  }
  for (const Cell& c : cells) r.statistic += (c.o - c.e) * (c.o - c.e) / c.e;
  r.dof = static_cast<int>(cells.size()) - 1;
  r.p_value = chi_square_sf(r.statistic, r.dof);
  r.reject = r.samples_where_none_expected || r.dof < 1 || !(r.p_value >= r.level);
  return r;
}

OrderedChiSquare chi_square(const std::vector<double>& expected, const std::vector<double>& observed) {
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
  OrderedChiSquare r;
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
