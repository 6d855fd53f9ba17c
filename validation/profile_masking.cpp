#include "vgroove/validation/profile_masking.h"

#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int bin_of(double theta_m, int bins) {
  const int b = static_cast<int>(std::floor((theta_m + 0.5 * std::numbers::pi) / (std::numbers::pi / bins)));
  return std::clamp(b, 0, bins - 1);
}

double ratio(double num, double den) { return den > 0.0 ? num / den : kNaN; }

}  // namespace

MaskingMeasure measure_masking(const sim::Polyline& p, const MaskingCase& c, const sim::VisibilityTally& from_o,
                               const sim::VisibilityTally& from_i) {
  const int nb = c.bins;
  const std::size_t B = static_cast<std::size_t>(nb);
  MaskingMeasure m;
  m.bins = nb;
  m.rays = from_o.rays;
  m.lost = from_o.vertex_hits + from_o.back_face;
  const double N = static_cast<double>(from_o.rays);
  const double beam_o = p.period * std::cos(c.theta_o), beam_i = p.period * std::cos(c.theta_i);
  const sim::Vec2 o = sim::direction_at(c.theta_o), i = sim::direction_at(c.theta_i);
  const double lambda_o = analytic::Lambda(c.ndf, c.theta_o, c.alpha),
               lambda_i = analytic::Lambda(c.ndf, c.theta_i, c.alpha);
  m.g1_smith = 1.0 / (1.0 + lambda_o);
  m.g2_smith_separable = m.g1_smith / (1.0 + lambda_i);
  m.g2_smith_correlated = 1.0 / (1.0 + lambda_o + lambda_i);

  // Per bin: weights, the V-cavity's visible share, the traced counts.
  std::vector<double> w1(B, 0.0), v1(B, 0.0), seen(B, 0.0), w2(B, 0.0), v2(B, 0.0), seen_lit(B, 0.0);
  double front = 0.0, length = 0.0, lit_v = 0.0, lit_s = 0.0;
  double lit_sum = 0.0, lit_sq = 0.0;  // sum c f and sum c^2 f over the beam from i, c per ray
  // The same with the projected length dx = ds (m.n) per segment (the macro fraction).
  double width = 0.0, mlit_v = 0.0, mlit_s = 0.0, mlit_sum = 0.0, mlit_sq = 0.0;
  const double Ni = static_cast<double>(from_i.rays);
  for (int s = 0; s < p.segments(); ++s) {
    const std::size_t ss = static_cast<std::size_t>(s);
    const sim::Vec2& n = p.normal[ss];
    const double theta_m = p.normal_angle(s), len = p.length(s);
    const double on = o.dot(n), in = i.dot(n);
    const std::size_t b = static_cast<std::size_t>(bin_of(theta_m, nb));
    length += len;
    const double dx = len * n.y();  // a heightfield: n.y > 0 (sim/polyline.h)
    width += dx;
    if (on > 0.0) {
      const double share = len * on / beam_o;
      const double g_o = analytic::G1_vcavity_inplane(c.theta_o, theta_m);
      w1[b] += share;
      v1[b] += g_o * share;
      front += len * on;
      seen[b] += static_cast<double>(from_o.seen[ss]);
      if (in > 0.0) {
        w2[b] += share;
        v2[b] += std::min(g_o, analytic::G1_vcavity_inplane(c.theta_i, theta_m)) * share;
        seen_lit[b] += static_cast<double>(from_o.seen_lit[ss]);
      }
    }
    if (in > 0.0) {
      lit_v += analytic::G1_vcavity_inplane(c.theta_i, theta_m) * len;
      lit_s += len / (1.0 + lambda_i);
      // A ray of the beam from i that sees this segment stands for the length beam_i / (N in).
      const double per_ray = beam_i / in;
      const double f = static_cast<double>(from_i.seen[ss]) / Ni;
      lit_sum += per_ray * f;
      lit_sq += per_ray * per_ray * f;
      const double g_i = analytic::G1_vcavity_inplane(c.theta_i, theta_m);
      mlit_v += g_i * dx;
      mlit_s += dx / (1.0 + lambda_i);
      const double per_ray_dx = per_ray * n.y();  // its projected length
      mlit_sum += per_ray_dx * f;
      mlit_sq += per_ray_dx * per_ray_dx * f;
    }
  }
  m.g1_weight = w1;
  m.g2_weight = w2;
  for (std::size_t b = 0; b < B; ++b) {
    m.g1_traced.push_back(ratio(seen[b] / N, w1[b]));
    m.g1_vcavity.push_back(ratio(v1[b], w1[b]));
    m.g2_traced.push_back(ratio(seen_lit[b] / N, w2[b]));
    m.g2_vcavity.push_back(ratio(v2[b], w2[b]));
  }
  double seen_all = 0.0, v_all = 0.0;
  for (std::size_t b = 0; b < B; ++b) seen_all += seen[b], v_all += v1[b];
  m.g1_identity = beam_o / front;
  m.g1_average_traced = (seen_all / N) * beam_o / front;
  m.g1_average_vcavity = v_all * beam_o / front;
  // Each ray from i adds c (its segment's length per ray) with probability f: the mean over the
  // N rays has the variance (sum c^2 f - (sum c f)^2) / N.
  m.lit_arc_traced = lit_sum / length;
  m.lit_arc_traced_sd = std::sqrt(std::max(0.0, lit_sq - lit_sum * lit_sum) / Ni) / length;
  m.lit_arc_vcavity = lit_v / length;
  m.lit_arc_smith = lit_s / length;
  m.lit_traced = mlit_sum / width;
  m.lit_traced_sd = std::sqrt(std::max(0.0, mlit_sq - mlit_sum * mlit_sum) / Ni) / width;
  m.lit_vcavity = mlit_v / width;
  m.lit_smith = mlit_s / width;

  // Counts against V-cavity: G1 over the bins; G2 over the bins and the seen-but-unlit rest.
  std::vector<double> e1, e2, o2;
  for (std::size_t b = 0; b < B; ++b) e1.push_back(N * v1[b]);
  m.g1_chi2 = chi_square(e1, seen);
  double e_lit = 0.0, o_lit = 0.0;
  for (std::size_t b = 0; b < B; ++b)
    e2.push_back(N * v2[b]), o2.push_back(seen_lit[b]), e_lit += e2.back(), o_lit += seen_lit[b];
  e2.push_back(N - e_lit);
  o2.push_back(seen_all - o_lit);
  m.g2_chi2 = chi_square(e2, o2);
  return m;
}

}  // namespace vgroove::validation
