// vgroove validation: Pearson's chi-square of counts against a model's expected counts, with
// cells pooled until each expects at least 5, and its p-value (the chi-square survival function
// Q(dof / 2, stat / 2), the regularized upper incomplete gamma function).
#pragma once

#include <vector>

namespace vgroove::validation {

struct ChiSquareResult {
  double stat = 0.0;
  int dof = 0;     // pooled cells - 1 (the total is fixed)
  double p = 1.0;  // probability of a statistic this large under the model
};

// Cells in the given order; adjacent cells pooled until the expected count reaches 5 (a leftover
// joins the last cell). Observed counts in a cell the model gives nothing make the statistic
// infinite (p = 0).
ChiSquareResult chi_square(const std::vector<double>& expected, const std::vector<double>& observed);

// Q(a, x), the regularized upper incomplete gamma function (series below a + 1, Lentz's
// continued fraction above).
double gamma_q(double a, double x);

}  // namespace vgroove::validation
