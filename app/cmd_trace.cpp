#include "vgroove/app/commands.h"
#include "vgroove/common/angles.h"

#include <cstdio>
#include <iostream>
#include "vgroove/app/bounce_rows.h"
#include "vgroove/app/options.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/single_groove.h"

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
  sim::Tally tally;
  if (!trace_beam_rays(
          params, a.theta_i_deg * kRadPerDeg, a.rays, sampling, static_cast<std::uint64_t>(a.seed), max_bounces,
          [&](long, int m, const double*, const sim::TraceResult* r) {
            for (int j = 0; j < m; ++j) tally.add(r[j]);
          },
          a.cancel))
    return interrupted_no_report();
  const nlohmann::json j = trace_json(params, a.theta_i_deg, a.rays, sampling, a.seed, max_bounces, tally);
  if (a.json) {
    std::cout << support::json_text(j, 2) << "\n";
  } else {
    std::printf("trace: %s, theta_i %g deg, %ld rays (%s, seed %lld); fractions of the beam entering the opening\n",
                groove_text(params).c_str(), a.theta_i_deg, a.rays, a.sampling.c_str(), a.seed);
    print_rows(j["bounces"]);
    std::printf("  escaped %lld, vertex hits %lld, bounce limit %lld; largest exit-angle spread in a bin %.3g rad\n",
                static_cast<long long>(tally.escaped), static_cast<long long>(tally.vertex_hits),
                static_cast<long long>(tally.bounce_limit), j["max_exit_spread_rad"].get<double>());
    if (tally.bounce_limit > 0)
      std::printf(
          "  %lld of %ld rays were still inside after --max-bounces = %d reflections; this groove needs up to "
          "%d (the default)\n",
          static_cast<long long>(tally.bounce_limit), a.rays, max_bounces, default_max_bounces(params.theta_v));
  }
  return 0;
}

}  // namespace vgroove::app
