// vgroove validation: run every case of a single-groove suite and sum up against its thresholds.
#pragma once

#include "vgroove/support/parallel.h"
#include "vgroove/validation/groove_case.h"
#include "vgroove/validation/groove_suite.h"
#include "vgroove/validation/work_run.h"

#include <memory>

#include <vector>

namespace vgroove::validation {

struct GrooveSuiteSummary {
  std::size_t cases = 0;             // compared: all but the degenerate ones
  std::size_t degenerate_cases = 0;  // zero-aperture grooves: listed, not compared
  std::size_t facets_compared = 0;
  double max_l1 = 0.0;
  double mean_l1 = 0.0;
  std::size_t worst_case = 0;  // index of the case with max_l1
  double max_theta_o_error = 0.0;
  std::int64_t rays = 0;
  std::int64_t bounces = 0;
  std::int64_t vertex_hits = 0;
  std::int64_t bounce_limit = 0;
  std::int64_t wrong_first = 0;
  std::int64_t probe_rays = 0, probe_escaped = 0, probe_vertex_hits = 0, probe_blocked = 0, probe_bounce_limit = 0;
  std::size_t non_finite_cases = 0;  // cases with a NaN or infinity anywhere: always a failure
  // Breakpoint placement (sim/zones.h): zones found over all facets and per facet at most, grid
  // cells with equal ends no certificate covers, the largest fraction of a beam they may hide,
  // and the narrowest zone found (a fraction of its beam).
  std::int64_t zones = 0;
  long max_zones = 0;
  std::int64_t uncertified_cells = 0;
  double max_missed_bound = 0.0;
  double narrowest_zone = 0.0;
  double rays_per_case = 0.0;
  double wall_s = 0.0;
  double bounces_per_s = 0.0;
  bool pass_max_l1 = false, pass_mean_l1 = false, pass_theta_o = false;
  bool pass() const { return pass_max_l1 && pass_mean_l1 && pass_theta_o && non_finite_cases == 0; }
};

struct GrooveSuiteRun {
  CaseOptions options;  // as run (after command-line overrides)
  int threads = 1;
  std::vector<CaseOutcome> cases;  // in suite order: groove outer, theta_i inner
  GrooveSuiteSummary summary;
  bool interrupted = false;  // cancelled before every case ran: the summary is not meaningful
};

// An upper bound of the memory run_groove_suite needs (support/memory.h): every case's outcome, each
// worker's tables, and with `report` the report's JSON (document and text, ~4 kB per case).
double groove_suite_memory_bytes(const GrooveSuite& suite, const CaseOptions& options, int threads, bool report);

// `cancel` (may be null) is polled between chunks of cases: set it from a signal handler to stop.
GrooveSuiteRun run_groove_suite(const GrooveSuite& suite, const CaseOptions& options, int threads,
                                const support::ProgressFn& progress = {}, const std::atomic<bool>* cancel = nullptr);

// Single-groove suites as work items (work_run.h): one unit per case of every suite of a set
// (suite-major), one chunk each (a case's rays come from its own streams Rng(seed, case, facet):
// it is not cut), no fixed part.
struct GrooveCaseTally {
  CaseOutcome outcome;
  double thread_s = 0.0;  // time spent on the case (a timing: never compared)
};
struct GrooveCaseWork {
  struct Context {};
  struct Fixed {};
  using Tally = GrooveCaseTally;
  std::vector<GrooveSuite> suites;
  std::vector<CaseOptions> options;           // per suite
  std::vector<std::size_t> first;             // the first unit of each suite
  const std::atomic<bool>* cancel = nullptr;  // polled between a case's rays
  std::shared_ptr<const Context> prepare(std::size_t) const { return std::make_shared<Context>(); }
  Tally run_chunks(const Context&, std::size_t unit, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t) const { return {}; }
  static void merge(Tally&, const Tally&) {}  // one chunk per unit: never two tallies to merge
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed&) { return nlohmann::json::object(); }
  Tally read_tally(support::JsonObject& j, std::size_t unit, const std::vector<ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject&, std::size_t) const { return {}; }
};
Job<GrooveCaseWork> groove_cases_job(const std::vector<GrooveSuite>& suites, const std::vector<CaseOptions>& options,
                                     nlohmann::json descriptor);
// Each suite's run (cases and summary) from every unit's results; wall_s and threads are the caller's.
std::vector<GrooveSuiteRun> groove_suite_runs_from(const GrooveCaseWork& work,
                                                   const std::vector<UnitResult<GrooveCaseWork>>& results, int threads,
                                                   double wall_s);

}  // namespace vgroove::validation
