#include "vgroove/validation/suite_run.h"

#include <algorithm>
#include <chrono>

namespace vgroove::validation {

SuiteRun run_suite(const Suite& suite, const CaseOptions& options, int threads, const support::ProgressFn& progress,
                   const std::atomic<bool>* cancel) {
  SuiteRun run;
  run.options = options;
  run.threads = support::resolve_threads(threads);
  run.cases.resize(suite.cases());
  const auto t0 = std::chrono::steady_clock::now();
  run.interrupted = !support::parallel_for(
      run.cases.size(), run.threads,
      [&](std::size_t c) {
        const SuiteCase sc = suite.case_at(c);
        run.cases[c] = run_case(sc.groove, sc.theta_i, options, c);
      },
      progress, cancel);
  Summary& s = run.summary;
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Sums in suite order: the same figures for any thread count.
  double sum_l1 = 0.0;
  bool first = true;
  for (std::size_t c = 0; c < run.cases.size(); ++c) {
    const CaseOutcome& o = run.cases[c];
    if (o.groove.degenerate()) {
      ++s.degenerate_cases;
      continue;
    }
    ++s.cases;
    sum_l1 += o.l1;
    if (o.l1 > s.max_l1 || first) s.max_l1 = o.l1, s.worst_case = c, first = false;
    s.max_theta_o_error = std::max(s.max_theta_o_error, o.theta_o_error);
    s.rays += o.rays;
    s.bounces += o.bounces;
    if (o.non_finite) ++s.non_finite_cases;
    for (const FacetOutcome& f : o.facet) {
      if (!f.compared) continue;
      s.probe_rays += f.probe_rays;
      s.probe_escaped += f.probe_escaped;
      s.probe_vertex_hits += f.probe_vertex_hits;
      s.probe_blocked += f.probe_blocked;
      s.probe_bounce_limit += f.probe_bounce_limit;
      ++s.facets_compared;
      s.vertex_hits += f.vertex_hits;
      s.bounce_limit += f.bounce_limit;
      s.wrong_first += f.wrong_first;
      s.zones += f.zones;
      s.max_zones = std::max(s.max_zones, f.zones);
      s.uncertified_cells += f.uncertified_cells;
      s.max_missed_bound = std::max(s.max_missed_bound, f.missed_bound);
      if (f.zones > 0 && (s.narrowest_zone == 0.0 || f.narrowest_zone < s.narrowest_zone))
        s.narrowest_zone = f.narrowest_zone;
    }
  }
  s.mean_l1 = s.cases ? sum_l1 / static_cast<double>(s.cases) : 0.0;
  s.rays_per_case = s.cases ? static_cast<double>(s.rays) / static_cast<double>(s.cases) : 0.0;
  s.bounces_per_s = s.wall_s > 0 ? static_cast<double>(s.bounces) / s.wall_s : 0.0;
  // NaN compares false, so a NaN error fails the thresholds as well as non_finite_cases.
  s.pass_max_l1 = s.max_l1 <= suite.thresholds.max_l1;
  s.pass_mean_l1 = s.mean_l1 <= suite.thresholds.mean_l1;
  s.pass_theta_o = s.max_theta_o_error <= suite.thresholds.max_theta_o_error_rad;
  return run;
}

}  // namespace vgroove::validation
