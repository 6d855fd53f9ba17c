#include "vgroove/validation/groove_suite_run.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/support/format.h"
#include "vgroove/validation/detail/part_fields.h"

#include "vgroove/validation/partial_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::validation {

double groove_suite_memory_bytes(const GrooveSuite& suite, const CaseOptions& options, int threads, bool report) {
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
void summarize(const GrooveSuite& suite, GrooveSuiteRun& run);
}  // namespace

GrooveCaseTally GrooveCaseWork::run_chunks(const Context&, std::size_t unit, std::int64_t, std::int64_t) const {
  const auto t0 = std::chrono::steady_clock::now();
  const std::size_t n =
      static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), unit) - first.begin()) - 1;
  const std::size_t c = unit - first[n];
  const GrooveSuiteCase sc = suites[n].case_at(c);
  GrooveCaseTally t{run_case(sc.groove, sc.theta_i, options[n], c, cancel)};
  t.thread_s = support::seconds_since(t0);
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

namespace {

// A figure that is >= 0 where finite (NaN and infinities are what non_finite reports).
double read_error(support::JsonObject& j, const std::string& key, double hi) {
  const double x = read_exact_double(j, key);
  if (std::isfinite(x) && !(x >= 0.0 && x <= hi))
    j.fail(key, "= " + support::value_text(j.raw(key)) + " is out of range [0, " + support::format("%g", hi) + "]");
  return x;
}

FacetOutcome read_facet(support::JsonObject& f, const CaseOptions& opt) {
  constexpr long long kCountMax = std::numeric_limits<long long>::max();
  FacetOutcome o;
  if (!f.raw("compared").is_boolean()) f.fail("compared", "must be true or false");
  o.compared = f.raw("compared").get<bool>();
  o.rays = f.integer("rays", 0, std::numeric_limits<long long>::max() / 4);
  o.vertex_hits = f.integer("vertex_hits", 0, o.rays);
  o.bounce_limit = f.integer("bounce_limit", 0, o.rays - o.vertex_hits);
  o.wrong_first = f.integer("wrong_first", 0, o.rays - o.vertex_hits - o.bounce_limit);
  const long double most = static_cast<long double>(o.rays) * opt.max_bounces;
  o.bounces = f.integer("bounces", 0, most > kCountMax ? kCountMax : static_cast<long long>(most));
  o.k = static_cast<int>(f.integer("k", 0, std::numeric_limits<int>::max()));
  o.l1 = read_error(f, "l1", 2.0);
  o.theta_o_error = read_error(f, "theta_o_error", std::numbers::pi);
  o.probe_rays = f.integer("probe_rays", 0, opt.probe_vertices ? 4 : 0);
  o.probe_escaped = f.integer("probe_escaped", 0, o.probe_rays);
  o.probe_vertex_hits = f.integer("probe_vertex_hits", 0, o.probe_rays);
  o.probe_blocked = f.integer("probe_blocked", 0, o.probe_rays);
  o.probe_bounce_limit = f.integer("probe_bounce_limit", 0, o.probe_rays);
  if (o.probe_escaped + o.probe_vertex_hits + o.probe_blocked + o.probe_bounce_limit != o.probe_rays)
    f.fail("probe_rays", "= " + std::to_string(o.probe_rays) + " is not the sum of the probes' fates");
  if (!f.raw("non_finite").is_boolean()) f.fail("non_finite", "must be true or false");
  o.non_finite = f.raw("non_finite").get<bool>();
  o.zones = f.integer("zones", 0, kCountMax);
  o.grid = f.integer("grid", 0, kCountMax);
  o.uncertified_cells = f.integer("uncertified_cells", 0, kCountMax);
  o.missed_bound = read_error(f, "missed_bound", 1.0);
  o.narrowest_zone = read_error(f, "narrowest_zone", 1.0);
  return o;
}

bool same_figure(double a, double b) { return a == b || (std::isnan(a) && std::isnan(b)); }

}  // namespace

GrooveCaseTally GrooveCaseWork::read_tally(support::JsonObject& j, std::size_t unit,
                                           const std::vector<ChunkRun>&) const {
  std::size_t n = 0;
  while (n + 1 < first.size() && first[n + 1] <= unit) ++n;
  const CaseOptions& opt = options[n];
  GrooveCaseTally tally;
  tally.thread_s = j.number("thread_s", 0.0, true, std::numeric_limits<double>::max(), true);
  CaseOutcome& t = tally.outcome;
  const nlohmann::json& facets = j.raw("facets");
  if (!facets.is_array() || facets.size() != 2) j.fail("facets", "must be an array of two facets (left, right)");
  // The case's figures as run_case forms them from its facets.
  CaseOutcome sum;
  for (std::size_t s = 0; s < 2; ++s) {
    support::JsonObject f(facets[s], j.file(), j.path("facets") + "/" + std::to_string(s));
    t.facet[s] = read_facet(f, opt);
    f.finish();
    const FacetOutcome& o = t.facet[s];
    // An unlit facet is not traced: its outcome stays the empty one. A lit facet gets the suite's
    // rays (with breakpoints, the zone search's).
    if (!o.compared) {
      if (o.rays || o.bounces || o.vertex_hits || o.bounce_limit || o.wrong_first || o.k || o.probe_rays || o.zones ||
          o.grid || o.uncertified_cells || o.l1 != 0.0 || o.theta_o_error != 0.0 || o.missed_bound != 0.0 ||
          o.narrowest_zone != 0.0 || o.non_finite)
        f.fail("compared", "= false, but the facet holds figures (an unlit facet is not traced)");
      continue;
    }
    if (opt.sampling != sim::Sampling::breakpoints && o.rays != opt.rays)
      f.fail("rays", "= " + std::to_string(o.rays) + ", not the " + std::to_string(opt.rays) + " rays of a lit facet");
    sum.l1 = std::max(sum.l1, o.l1);
    sum.rays += o.rays;
    sum.bounces += o.bounces;
    sum.theta_o_error = std::max(sum.theta_o_error, o.theta_o_error);
    sum.non_finite = sum.non_finite || o.non_finite;
  }
  t.rays = j.integer("rays", sum.rays, sum.rays);
  t.bounces = j.integer("bounces", sum.bounces, sum.bounces);
  t.l1 = read_exact_double(j, "l1");
  if (!same_figure(t.l1, sum.l1))
    j.fail("l1", "= " + support::value_text(j.raw("l1")) + " is not the largest of its facets'");
  t.theta_o_error = read_exact_double(j, "theta_o_error");
  if (!same_figure(t.theta_o_error, sum.theta_o_error))
    j.fail("theta_o_error", "= " + support::value_text(j.raw("theta_o_error")) + " is not the largest of its facets'");
  if (!j.raw("non_finite").is_boolean() || j.raw("non_finite").get<bool>() != sum.non_finite)
    j.fail("non_finite", "= " + support::value_text(j.raw("non_finite")) + " does not follow from its facets");
  t.non_finite = sum.non_finite;
  return tally;
}

Job<GrooveCaseWork> groove_cases_job(const std::vector<GrooveSuite>& suites, const std::vector<CaseOptions>& options,
                                     nlohmann::json descriptor) {
  GrooveCaseWork w{suites, options, {}};
  std::vector<support::WorkUnit> units;
  for (std::size_t n = 0; n < suites.size(); ++n) {
    w.first.push_back(units.size());
    for (std::size_t c = 0; c < suites[n].cases(); ++c) {
      // Cost: per lit facet, the rays' reflections (about pi / theta_v each) at a few ns, and the model.
      const GrooveSuiteCase sc = suites[n].case_at(c);
      const double bounces = sc.groove.degenerate() ? 0.0 : std::min(1e5, std::numbers::pi / sc.groove.theta_v + 1.0);
      support::WorkUnit u;
      u.chunk_cost =
          1000 + static_cast<std::int64_t>(2.0 * static_cast<double>(options[n].rays) * (5.0 + 2.0 * bounces));
      units.push_back(u);
    }
  }
  return make_job(std::move(w), std::move(units), std::move(descriptor));
}

std::vector<GrooveSuiteRun> groove_suite_runs_from(const GrooveCaseWork& work,
                                                   const std::vector<UnitResult<GrooveCaseWork>>& results, int threads,
                                                   double wall_s) {
  std::vector<GrooveSuiteRun> runs;
  for (std::size_t n = 0; n < work.suites.size(); ++n) {
    GrooveSuiteRun run;
    run.options = work.options[n];
    run.threads = threads;
    double thread_s = 0.0;
    for (std::size_t c = 0; c < work.suites[n].cases(); ++c) {
      thread_s += results[work.first[n] + c].tally.thread_s;
      CaseOutcome o = results[work.first[n] + c].tally.outcome;
      const GrooveSuiteCase sc = work.suites[n].case_at(c);
      o.groove = sc.groove, o.theta_i = sc.theta_i;
      run.cases.push_back(std::move(o));
    }
    run.summary.wall_s = wall_s >= 0.0 ? wall_s : thread_s;
    summarize(work.suites[n], run);
    runs.push_back(std::move(run));
  }
  return runs;
}

GrooveSuiteRun run_groove_suite(const GrooveSuite& suite, const CaseOptions& options, int threads,
                                const support::ProgressFn& progress, const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  Job<GrooveCaseWork> job = groove_cases_job({suite}, {options}, {});
  job.work.cancel = cancel;
  const auto results = run_job(job, threads, progress, cancel);
  const double wall_s = support::seconds_since(t0);
  if (!results) {
    GrooveSuiteRun run;
    run.options = options;
    run.threads = support::resolve_threads(threads);
    run.interrupted = true;
    return run;
  }
  return groove_suite_runs_from(job.work, *results, support::resolve_threads(threads), wall_s).front();
}

namespace {
void summarize(const GrooveSuite& suite, GrooveSuiteRun& run) {
  GrooveSuiteSummary& s = run.summary;
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
