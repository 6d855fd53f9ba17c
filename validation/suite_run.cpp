#include "vgroove/validation/suite_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

namespace vgroove::validation {

double run_memory_bytes(const Suite& suite, const CaseOptions& options, int threads, bool report) {
  constexpr double kReportBytesPerCase = 4096;  // measured: 2.5 kB (Table 1's nonsymmetric report)
  constexpr double kTableEntryBytes = 64;       // a BeamTracer reflection, rounded up
  const double cases = static_cast<double>(suite.cases());
  const double workers = std::min(static_cast<double>(support::resolve_threads(threads)), std::ceil(cases / 16.0));
  // A BeamTracer tabulates the reflections a ray can make, at most ceil(pi / theta_v) + 1.
  double narrowest = std::numbers::pi;
  for (std::size_t c = 0; c < suite.grooves.size() + suite.listed.size(); ++c) {
    const GrooveParams& g = c < suite.grooves.size() ? suite.grooves[c] : suite.listed[c - suite.grooves.size()].groove;
    if (!g.degenerate()) narrowest = std::min(narrowest, g.theta_v);
  }
  const double entries = std::min({std::ceil(std::numbers::pi / narrowest) + 1.0, double{sim::BeamTracer::kMaxTable},
                                   static_cast<double>(options.max_bounces)});
  const double tables = 2.0 * entries * kTableEntryBytes;
  return cases * (sizeof(CaseOutcome) + (report ? kReportBytesPerCase : 0.0)) + workers * tables;
}

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
                          run.cases[c] = run_case(sc.groove, sc.theta_i, options, c, cancel);
                        },
                        progress, cancel) ||
                    support::cancelled(cancel);
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
