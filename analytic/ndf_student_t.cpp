#include "vgroove/analytic/ndf_student_t.h"

#include "vgroove/common/log_gamma_ratio.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vgroove::analytic {

namespace {

// The continued fraction of I_x(a, b) (Abramowitz & Stegun 26.5.8: its terms d_2m and d_2m+1) by
// the modified Lentz method; it converges fast for x < (a + 1) / (a + b + 2), in about
// sqrt(max(a, b)) terms near that point.
double beta_fraction(double a, double b, double x) {
  constexpr double tiny = 1e-300;  // keeps Lentz's C and D off zero
  const double ab = a + b, a1 = a + 1.0, am = a - 1.0;
  double C = 1.0, Dn = 1.0 - ab * x / a1;
  if (std::abs(Dn) < tiny) Dn = tiny;
  Dn = 1.0 / Dn;
  double f = Dn;
  auto step = [&](double d) {
    Dn = 1.0 + d * Dn;
    if (std::abs(Dn) < tiny) Dn = tiny;
    C = 1.0 + d / C;
    if (std::abs(C) < tiny) C = tiny;
    Dn = 1.0 / Dn;
    f *= Dn * C;
    return Dn * C;
  };
  for (int m = 1; m <= 100000; ++m) {
    const double m2 = 2.0 * m;
    step(m * (b - m) * x / ((am + m2) * (a + m2)));
    if (std::abs(step(-(a + m) * (ab + m) * x / ((a + m2) * (a1 + m2))) - 1.0) < 1e-16) break;
  }
  return f;
}

}  // namespace

double incomplete_beta(double a, double b, double x, double one_minus_x) {
  assert(a > 0.0 && b > 0.0);
  if (!(x > 0.0)) return 0.0;
  if (!(one_minus_x > 0.0)) return 1.0;
  // I_x(a, b) = x^a (1 - x)^b / (a B(a, b)) times the fraction, or 1 - I_(1-x)(b, a) on the side
  // where the fraction converges slowly (Abramowitz & Stegun 26.5.8, 26.5.2).
  // log(Gamma(a + b) / (Gamma(a) Gamma(b))): the larger one's ratio without lgamma's cancellation
  // where the smaller is at most 1 (the t laws' b = 1/2).
  const double lo = std::min(a, b), hi = std::max(a, b);
  const double log_beta =
      lo <= 1.0 ? log_gamma_ratio(hi, lo) - std::lgamma(lo) : std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b);
  // x^a (1 - x)^b by pow (exp(a log x) would scale log x's last-bit error by a log x: 1e-14 at a =
  // 40, x = 1e-3).
  const double front = std::exp(log_beta) * std::pow(x, a) * std::pow(one_minus_x, b);
  if (x < (a + 1.0) / (a + b + 2.0)) return front * beta_fraction(a, b, x) / a;
  return 1.0 - front * beta_fraction(b, a, one_minus_x) / b;
}

}  // namespace vgroove::analytic
