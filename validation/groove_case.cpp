#include "validation/groove_case.h"

#include "sim/tally.h"

#include <algorithm>
#include <cmath>

namespace vgroove::validation {

namespace {

// A facet whose projected width is below this fraction of its length receives a beam too thin
// to place rays in (positions round at 1e-16): it is treated as not lit, by model and tracer alike.
constexpr double kMinProjectedWidth = 1e-12;

analytic::FacetSide to_analytic(sim::Side s) {
  return s == sim::Side::left ? analytic::FacetSide::left : analytic::FacetSide::right;
}

FacetOutcome run_facet(const sim::Groove& g, double theta_i, sim::Side side, const CaseOptions& opt,
                       std::uint64_t stream) {
  FacetOutcome out;
  const analytic::FacetPrediction pred =
      analytic::G_kaleidoscopic(theta_i, g.theta_v, to_analytic(side), opt.form);
  if (!pred.lit || pred.f_a < kMinProjectedWidth) return out;
  out.compared = true;
  out.k = pred.k;

  const sim::Interval aim = sim::aimed_at(g, theta_i, side);
  const sim::Vec2 dir = sim::beam_direction(theta_i);
  sim::Rng rng(opt.seed, stream, static_cast<std::uint64_t>(side));
  const sim::TraceOptions topt{opt.max_bounces};
  sim::Tally tally;
  for (long j = 0; j < opt.rays; ++j) {
    const double x = sim::sample_position(opt.sampling, aim, j, opt.rays, rng);
    tally.add(sim::trace(g, sim::beam_ray(g, dir, x), topt));
  }

  const double n = static_cast<double>(opt.rays);
  out.rays = tally.rays;
  out.bounces = tally.bounces;
  out.vertex_hits = tally.vertex_hits;
  out.bounce_limit = tally.bounce_limit;
  for (const auto& b : tally.bins[1 - static_cast<int>(side)]) out.wrong_first += b.count;

  // L1 over every bin either side has.
  double l1 = std::abs(static_cast<double>(tally.blocked) / n - pred.shadow);
  l1 += static_cast<double>(tally.vertex_hits + tally.bounce_limit + out.wrong_first) / n;
  const auto& bins = tally.bins[static_cast<int>(side)];
  const int kmax = std::max(static_cast<int>(bins.size()) - 1, pred.more.n);
  for (int k = 0; k <= kmax; ++k) {
    const double traced = k < static_cast<int>(bins.size()) ? static_cast<double>(bins[k].count) / n : 0.0;
    double model = 0.0;
    if (k == pred.fewer.n) model += pred.fewer.G;
    if (k == pred.more.n) model += pred.more.G;
    l1 += std::abs(traced - model);
    if (traced > 0.0) {
      // Eq. (5) holds for any bounce count, so every traced bin is checked, predicted or not.
      const double theta_o = analytic::exit_angle(theta_i, g.theta_v, k, to_analytic(side));
      const double err = std::abs(sim::angle_between(sim::direction_at(theta_o), bins[k].exit_dir)) + bins[k].spread();
      out.theta_o_error = std::max(out.theta_o_error, err);
    }
  }
  out.l1 = l1;
  return out;
}

}  // namespace

CaseOutcome run_case(double theta_v, double theta_i, const CaseOptions& opt, std::uint64_t stream) {
  CaseOutcome c;
  c.theta_v = theta_v;
  c.theta_i = theta_i;
  const sim::Groove g = sim::make_symmetric_groove(theta_v);
  for (sim::Side s : {sim::Side::left, sim::Side::right}) {
    FacetOutcome& f = c.facet[static_cast<int>(s)];
    f = run_facet(g, theta_i, s, opt, stream);
    if (!f.compared) continue;
    c.l1 = std::max(c.l1, f.l1);
    c.rays += f.rays;
    c.bounces += f.bounces;
    c.theta_o_error = std::max(c.theta_o_error, f.theta_o_error);
  }
  return c;
}

}  // namespace vgroove::validation
