#include "vgroove/validation/suite_run.h"

#include "vgroove/validation/partial_report.h"

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
  // Every case's outcome is held twice while the parts are merged, then once in the run.
  return cases * (3.0 * sizeof(CaseOutcome) + (report ? kReportBytesPerCase : 0.0)) + workers * tables;
}

namespace {
void summarize(const Suite& suite, SuiteRun& run);
}  // namespace

GrooveCaseTally GrooveCaseWork::run_chunks(const Context&, std::size_t unit, std::int64_t, std::int64_t) const {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n =
      static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), unit) - first.begin()) - 1;
  const std::size_t c = unit - first[n];
  const SuiteCase sc = suites[n].case_at(c);
  GrooveCaseTally t{run_case(sc.groove, sc.theta_i, options[n], c, cancel)};
  t.thread_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

nlohmann::json GrooveCaseWork::tally_json(const Tally& tally) {
  const CaseOutcome& t = tally.outcome;
  nlohmann::json facets = nlohmann::json::array();
  for (const FacetOutcome& f : t.facet)
    facets.push_back({{"compared", f.compared},
                      {"l1", exact_json(f.l1)},
                      {"rays", f.rays},
                      {"bounces", f.bounces},
                      {"vertex_hits", f.vertex_hits},
                      {"bounce_limit", f.bounce_limit},
                      {"wrong_first", f.wrong_first},
                      {"k", f.k},
                      {"theta_o_error", exact_json(f.theta_o_error)},
                      {"probe_rays", f.probe_rays},
                      {"probe_escaped", f.probe_escaped},
                      {"probe_vertex_hits", f.probe_vertex_hits},
                      {"probe_blocked", f.probe_blocked},
                      {"probe_bounce_limit", f.probe_bounce_limit},
                      {"non_finite", f.non_finite},
                      {"zones", f.zones},
                      {"grid", f.grid},
                      {"uncertified_cells", f.uncertified_cells},
                      {"missed_bound", exact_json(f.missed_bound)},
                      {"narrowest_zone", exact_json(f.narrowest_zone)}});
  return {{"facets", facets},
          {"l1", exact_json(t.l1)},
          {"rays", t.rays},
          {"bounces", t.bounces},
          {"theta_o_error", exact_json(t.theta_o_error)},
          {"non_finite", t.non_finite},
          {"thread_s", tally.thread_s}};
}

GrooveCaseTally GrooveCaseWork::tally_from_json(const nlohmann::json& j) {
  GrooveCaseTally tally;
  tally.thread_s = j.at("thread_s").get<double>();
  CaseOutcome& t = tally.outcome;
  for (int n = 0; n < 2; ++n) {
    const nlohmann::json& f = j.at("facets").at(static_cast<std::size_t>(n));
    FacetOutcome& o = t.facet[n];
    o.compared = f.at("compared"), o.l1 = exact_double(f.at("l1")), o.rays = f.at("rays"), o.bounces = f.at("bounces");
    o.vertex_hits = f.at("vertex_hits"), o.bounce_limit = f.at("bounce_limit"), o.wrong_first = f.at("wrong_first");
    o.k = f.at("k"), o.theta_o_error = exact_double(f.at("theta_o_error")), o.probe_rays = f.at("probe_rays");
    o.probe_escaped = f.at("probe_escaped"), o.probe_vertex_hits = f.at("probe_vertex_hits");
    o.probe_blocked = f.at("probe_blocked"), o.probe_bounce_limit = f.at("probe_bounce_limit");
    o.non_finite = f.at("non_finite");
    o.zones = f.at("zones"), o.grid = f.at("grid"), o.uncertified_cells = f.at("uncertified_cells");
    o.missed_bound = exact_double(f.at("missed_bound")), o.narrowest_zone = exact_double(f.at("narrowest_zone"));
  }
  t.l1 = exact_double(j.at("l1")), t.rays = j.at("rays"), t.bounces = j.at("bounces");
  t.theta_o_error = exact_double(j.at("theta_o_error")), t.non_finite = j.at("non_finite");
  return tally;
}

Job<GrooveCaseWork> groove_cases_job(const std::vector<Suite>& suites, const std::vector<CaseOptions>& options,
                                     nlohmann::json descriptor) {
  GrooveCaseWork w{suites, options, {}};
  std::vector<support::WorkUnit> units;
  for (std::size_t n = 0; n < suites.size(); ++n) {
    w.first.push_back(units.size());
    for (std::size_t c = 0; c < suites[n].cases(); ++c) {
      // Cost: per lit facet, the rays' reflections (about pi / theta_v each) at a few ns, and the model.
      const SuiteCase sc = suites[n].case_at(c);
      const double bounces = sc.groove.degenerate() ? 0.0 : std::min(1e5, std::numbers::pi / sc.groove.theta_v + 1.0);
      support::WorkUnit u;
      u.chunk_cost =
          1000 + static_cast<std::int64_t>(2.0 * static_cast<double>(options[n].rays) * (5.0 + 2.0 * bounces));
      units.push_back(u);
    }
  }
  return make_job(std::move(w), std::move(units), std::move(descriptor));
}

std::vector<SuiteRun> suite_runs_from(const GrooveCaseWork& work,
                                      const std::vector<UnitResult<GrooveCaseWork>>& results, int threads,
                                      double wall_s) {
  std::vector<SuiteRun> runs;
  for (std::size_t n = 0; n < work.suites.size(); ++n) {
    SuiteRun run;
    run.options = work.options[n];
    run.threads = threads;
    double thread_s = 0.0;
    for (std::size_t c = 0; c < work.suites[n].cases(); ++c) {
      thread_s += results[work.first[n] + c].tally.thread_s;
      CaseOutcome o = results[work.first[n] + c].tally.outcome;
      const SuiteCase sc = work.suites[n].case_at(c);
      o.groove = sc.groove, o.theta_i = sc.theta_i;
      run.cases.push_back(std::move(o));
    }
    run.summary.wall_s = wall_s >= 0.0 ? wall_s : thread_s;
    summarize(work.suites[n], run);
    runs.push_back(std::move(run));
  }
  return runs;
}

SuiteRun run_suite(const Suite& suite, const CaseOptions& options, int threads, const support::ProgressFn& progress,
                   const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  Job<GrooveCaseWork> job = groove_cases_job({suite}, {options}, {});
  job.work.cancel = cancel;
  const auto results = run_job(job, threads, progress, cancel);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!results) {
    SuiteRun run;
    run.options = options;
    run.threads = support::resolve_threads(threads);
    run.interrupted = true;
    return run;
  }
  return suite_runs_from(job.work, *results, support::resolve_threads(threads), wall_s).front();
}

namespace {
void summarize(const Suite& suite, SuiteRun& run) {
  Summary& s = run.summary;
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
}
}  // namespace

}  // namespace vgroove::validation
