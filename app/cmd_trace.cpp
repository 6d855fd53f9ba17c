#include "vgroove/app/commands.h"
#include "vgroove/common/angles.h"

#include <cstdio>
#include <iostream>
#include <numbers>
#include "vgroove/app/bounce_rows.h"
#include "vgroove/app/options.h"
#include "vgroove/app/progress.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/tally.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/report.h"

namespace vgroove::app {

using namespace validation;

int cmd_trace(const TraceArgs& a) {
  const GrooveParams params = groove_from(a.groove);
  check_theta_i(a.theta_i_deg, "--theta-i-deg");
  check_rays(a.rays, "--rays");
  const sim::Sampling sampling = parse_sampling(a.sampling, "--sampling");
  check_seed(a.seed, "--seed");
  if (a.dry_run) return 0;
  const int max_bounces = a.max_bounces > 0 ? a.max_bounces : default_max_bounces(params.theta_v);
  const double theta_i = a.theta_i_deg * kRadPerDeg;
  const sim::Groove g = make_groove(params);
  const sim::Interval open = sim::opening(g);
  const sim::Vec2 dir = sim::beam_direction(theta_i);
  sim::Rng rng(static_cast<std::uint64_t>(a.seed), 0, 0);
  sim::Tally tally;
  // One ray makes at most ceil(pi / theta_v) reflections (a millisecond at the narrowest aperture): the
  // cancellation flag is read before each.
  for (long j = 0; j < a.rays; ++j) {
    if (support::cancelled(a.cancel)) return interrupted_no_report();
    tally.add(sim::trace(g, sim::beam_ray(g, dir, sim::sample_position(sampling, open, j, a.rays, rng)),
                         sim::TraceOptions{max_bounces}));
  }
  nlohmann::json rows = nlohmann::json::array();
  double max_spread = 0.0;
  for (int f = 0; f < 2; ++f)
    for (const auto& [k, b] : tally.bins[f]) {
      rows.push_back(bounce_row(f == 0 ? "left" : "right", k,
                                static_cast<double>(b.count) / static_cast<double>(a.rays), b.theta_o()));
      max_spread = std::max(max_spread, b.spread());
    }
  nlohmann::json j = provenance();
  j["inputs"] = groove_json(params);
  j["inputs"].update({{"theta_i_deg", a.theta_i_deg},
                      {"rays", a.rays},
                      {"sampling", a.sampling},
                      {"seed", a.seed},
                      {"max_bounces", max_bounces}});
  j["bounces"] = rows;
  j["rays"] = tally.rays;
  j["buckets"] = {{"escaped", tally.escaped},
                  {"blocked", tally.blocked},
                  {"vertex_hit", tally.vertex_hits},
                  {"bounce_limit", tally.bounce_limit}};
  j["max_exit_spread_rad"] = max_spread;
  if (a.json) {
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("trace: %s, theta_i %g deg, %ld rays (%s, seed %lld); fractions of the beam entering the opening\n",
                groove_text(params).c_str(), a.theta_i_deg, a.rays, a.sampling.c_str(), a.seed);
    print_rows(rows);
    std::printf("  escaped %lld, vertex hits %lld, bounce limit %lld; largest exit-angle spread in a bin %.3g rad\n",
                static_cast<long long>(tally.escaped), static_cast<long long>(tally.vertex_hits),
                static_cast<long long>(tally.bounce_limit), max_spread);
    if (tally.bounce_limit > 0)
      std::printf(
          "  %lld of %ld rays were still inside after --max-bounces = %d reflections; this groove needs up to "
          "%d (the default)\n",
          static_cast<long long>(tally.bounce_limit), a.rays, max_bounces, default_max_bounces(params.theta_v));
  }
  return 0;
}

}  // namespace vgroove::app
