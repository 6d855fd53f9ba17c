#include "vgroove/analytic/kaleidoscope.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::analytic {

int saturate_to_int(double k) {
  // Apertures below pi / INT_MAX (8e-8 deg) would overflow int: such k mean "more than any ray
  // can be traced", and saturate rather than wrap.
  if (!(k < static_cast<double>(std::numeric_limits<int>::max()))) return std::numeric_limits<int>::max();
  if (!(k > static_cast<double>(std::numeric_limits<int>::min()))) return std::numeric_limits<int>::min();
  return static_cast<int>(k);
}

int bounce_count(double theta_i, double theta_v) {
  // Lee et al. 2018, Eq. (4): k = floor((pi + 2 theta_i) / (pi - 2|theta_s|)) + 1.
  return saturate_to_int(std::floor((std::numbers::pi + 2.0 * theta_i) / theta_v) + 1.0);
}

double exit_angle(double theta_i, double theta_v, int n) {
  // Lee et al. 2018, Eq. (5).
  const double sign = (n % 2 == 0) ? 1.0 : -1.0;
  return std::remainder(sign * (theta_i + std::numbers::pi - n * theta_v), 2.0 * std::numbers::pi);
}

double exit_angle(double theta_i, double theta_v, int n, FacetSide first) {
  return first == FacetSide::left ? exit_angle(theta_i, theta_v, n) : -exit_angle(-theta_i, theta_v, n);
}

double opening_width(double theta_i, double theta_v) { return 2.0 * std::sin(0.5 * theta_v) * std::cos(theta_i); }

namespace {
FacetPrediction left_first(double theta_i, double theta_v, Eq6Form form) {
  FacetPrediction p;
  // f of the left rim a (angle theta_v/2) and of the right rim b (angle -theta_v/2).
  p.f_a = std::sin(0.5 * theta_v - theta_i);
  p.lit = p.f_a > 0.0;
  if (!p.lit) return p;
  // "if f_b < 0 then light is arriving to the opposite facet ... we set f_b = max(f(b), 0)".
  p.f_b = std::max(0.0, -std::sin(0.5 * theta_v + theta_i));
  p.k = bounce_count(theta_i, theta_v);
  // Transition point k on the circle at theta_k = k theta_v - theta_v/2 (Sec. 4.1, App. B).
  const double f_k = std::sin(p.k * theta_v - 0.5 * theta_v - theta_i);
  // The corrected form: k lies on the arc a'b' (App. B), so f_k in [f_b, f_a] exactly; when
  // f(k) < 0 the k-reflection zone lies beyond the apex and is empty (ERRATA E1). The clamp to
  // f_a only absorbs rounding at Eq. (4)'s integer boundaries.
  p.f_k = form == Eq6Form::corrected ? std::clamp(f_k, p.f_b, p.f_a) : f_k;
  // Lee et al. 2018, Eq. (6).
  p.fewer = {p.k - 1, (p.f_a - p.f_k) / p.f_a, exit_angle(theta_i, theta_v, p.k - 1)};
  p.more = {p.k, (p.f_k - p.f_b) / p.f_a, exit_angle(theta_i, theta_v, p.k)};
  p.shadow = p.f_b / p.f_a;
  return p;
}
}  // namespace

FacetPrediction G_kaleidoscopic(double theta_i, double theta_v, FacetSide first, Eq6Form form) {
  if (first == FacetSide::left) return left_first(theta_i, theta_v, form);
  // The right facet is the mirror image: theta_i -> -theta_i, and theta_o back with a sign.
  FacetPrediction p = left_first(-theta_i, theta_v, form);
  if (p.lit) {
    p.fewer.theta_o = exit_angle(theta_i, theta_v, p.fewer.n, FacetSide::right);
    p.more.theta_o = exit_angle(theta_i, theta_v, p.more.n, FacetSide::right);
  }
  return p;
}

}  // namespace vgroove::analytic
