// vgroove validation: Pearson's chi-square goodness-of-fit test of observed counts against
// expected ones, as Mitsuba 3 (mitsuba/python/chi2.py with the core chi2()) and nori
// (src/chi2test.cpp with hypothesis::chi2_test) run it for BSDF samplers:
//   - the cells are sorted by expected count; cells expecting fewer than `min_expected` (5) are
//     pooled, in that order, until the pool expects at least min_expected, and each full pool is
//     one cell (a last, incomplete pool joins the next cell, or the last cell formed);
//   - a cell that expects nothing but received samples rejects outright;
//   - dof = cells after pooling - 1 (the total is fixed); p = Q(dof/2, stat/2), the regularized
//     upper incomplete gamma function;
//   - the significance level is corrected for the number of tests run together by Sidak's rule,
//     level_1 = 1 - (1 - level)^(1 / tests), so that all of them together reject a correct
//     sampler with probability `level`.
#pragma once

#include <string>
#include <vector>

namespace vgroove::validation {

// Q(a, x), the regularized upper incomplete gamma function (series below a + 1, Lentz's continued
// fraction above), within 1e-12 relative of Boost.Math's down to Q = 1e-30 for 2a in [1, 10^4]
// (tests/validation/chi_square_test.cpp).
double gamma_q(double a, double x);
// The chi-square survival function: P(X >= x) for X with dof degrees of freedom.
double chi_square_sf(double x, int dof);
// Sidak's correction: the level of one of `tests` tests for the family level `level`.
double sidak_level(double level, int tests);

struct ChiSquareResult {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 1.0;
  double level = 0.0;  // the corrected level the p-value is held to
  int cells = 0;       // cells given (with expected > 0 or observed > 0)
  int pooled_in = 0, pooled_out = 0;
  bool samples_where_none_expected = false;
  bool reject = false;
};
// Its members for a shard part (outcome_fields.h).
template <class F>
void fields(ChiSquareResult& r, F&& f) {
  f("statistic", r.statistic), f("dof", r.dof), f("p_value", r.p_value), f("level", r.level), f("cells", r.cells);
  f("pooled_in", r.pooled_in), f("pooled_out", r.pooled_out);
  f("samples_where_none_expected", r.samples_where_none_expected), f("reject", r.reject);
}

// The test of the header; observed and expected of equal length (counts, not fractions).
ChiSquareResult chi_square_test(const std::vector<double>& observed, const std::vector<double>& expected, double level,
                                int tests, double min_expected = 5.0);

// Pearson's statistic over cells kept in their order (a histogram of an ordered variable):
// adjacent cells pooled until the pool expects at least 5 (a leftover joins the last cell);
// samples in a cell the model gives nothing make the statistic infinite (p = 0).
struct OrderedChiSquare {
  double stat = 0.0;
  int dof = 0;     // pooled cells - 1 (the total is fixed)
  double p = 1.0;  // probability of a statistic this large under the model
};
template <class F>
void fields(OrderedChiSquare& c, F&& f) {
  f("stat", c.stat), f("dof", c.dof), f("p", c.p);
}
OrderedChiSquare chi_square(const std::vector<double>& expected, const std::vector<double>& observed);

}  // namespace vgroove::validation
