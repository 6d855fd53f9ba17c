// vgroove validation: run every case of a suite and sum up against its thresholds.
#pragma once

#include "vgroove/support/parallel.h"
#include "vgroove/validation/groove_case.h"
#include "vgroove/validation/suite.h"

#include <vector>

namespace vgroove::validation {

struct Summary {
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
  double rays_per_case = 0.0;
  double wall_s = 0.0;
  double bounces_per_s = 0.0;
  bool pass_max_l1 = false, pass_mean_l1 = false, pass_theta_o = false;
  bool pass() const { return pass_max_l1 && pass_mean_l1 && pass_theta_o && non_finite_cases == 0; }
};

struct SuiteRun {
  CaseOptions options;  // as run (after command-line overrides)
  int threads = 1;
  std::vector<CaseOutcome> cases;  // in suite order: groove outer, theta_i inner
  Summary summary;
  bool interrupted = false;  // cancelled before every case ran: the summary is not meaningful
};

// An upper bound of the memory run_suite needs (support/memory.h): every case's outcome, each
// worker's tables, and with `report` the report's JSON (document and text, ~4 kB per case).
double run_memory_bytes(const Suite& suite, const CaseOptions& options, int threads, bool report);

// `cancel` (may be null) is polled between chunks of cases: set it from a signal handler to stop.
SuiteRun run_suite(const Suite& suite, const CaseOptions& options, int threads,
                   const support::ProgressFn& progress = {}, const std::atomic<bool>* cancel = nullptr);

}  // namespace vgroove::validation
