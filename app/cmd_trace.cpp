#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"
#include "vgroove/common/angles.h"
#include "vgroove/validation/ranges.h"

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

void add_trace_command(CLI::App& app, Commands& commands) {
  using validation::kDefaultMaxBounces;
  using validation::kMaxBounces;
  using validation::theta_i_range_text;
  auto* trace = app.add_subcommand("trace",
                                   "Trace a beam through one V-groove (symmetric or not) exactly; print the fraction "
                                   "of the beam and the exit angle per (facet hit first, bounce count k).");
  TraceArgs& ta = commands.add(trace, cmd_trace);
  ta.cancel = commands.context().cancel;
  add_groove_options(trace, ta.groove);
  add_real(trace, "--theta-i-deg", ta.theta_i_deg, "incident angle theta_i in degrees, " + theta_i_range_text())
      ->capture_default_str();
  add_integer(trace, "--rays", ta.rays, "rays across the groove's opening", 1, kMaxRays)->capture_default_str();
  add_text(trace, "--sampling", ta.sampling, "ray placement: stratified (midpoints of equal strata) or random")
      ->capture_default_str();
  add_seed(trace, ta.seed, "seed of the random placement")->capture_default_str();
  add_integer(trace, "--max-bounces", ta.max_bounces,
              "bounce limit; rays past it are counted, not dropped (default: " + std::to_string(kDefaultMaxBounces) +
                  ", raised to the groove's bound ceil(180 / theta_v) + 1 for apertures narrow enough to need it)",
              1, kMaxBounces);
  trace->add_flag("--json", ta.json, "print JSON (the same shape as `analytic --json`)");
}

}  // namespace vgroove::app
