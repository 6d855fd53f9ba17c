// vgroove validation: a Job of work items (work_run.h) as a SuiteJob (suite_kind.h): one process,
// a shard, or the merge of parts, all through the same items and the same `finish`, so that a
// kind writes only how its units' results become the table, the report and the verdict.
//
//   finish(const std::vector<UnitResult<Work>>& results, int threads, double wall_s, bool report)
//     -> SuiteResult, or std::optional<SuiteResult> (nothing: cancelled while finishing)
#pragma once

#include "vgroove/support/seconds_since.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/suite_kind.h"
#include "vgroove/validation/work_run.h"

#include <chrono>
#include <memory>
#include <utility>

namespace vgroove::validation {

template <class Work, class Finish>
class JobOf final : public SuiteJob {
 public:
  JobOf(Job<Work> job, Finish finish) : job_(std::move(job)), finish_(std::move(finish)) {}
  const nlohmann::json& descriptor() const override { return job_.descriptor; }

  std::optional<SuiteResult> run(int threads, const support::ProgressFn& progress, const std::atomic<bool>* cancel,
                                 bool report) const override {
    const auto t0 = std::chrono::steady_clock::now();
    auto results = run_job(job_, threads, progress, cancel);
    if (!results) return std::nullopt;
    const double wall = support::seconds_since(t0);
    return finish_(*results, support::resolve_threads(threads), wall, report);
  }

  std::optional<nlohmann::json> run_part(const support::Shard& shard, int threads, const support::ProgressFn& progress,
                                         const std::atomic<bool>* cancel) const override {
    return run_job_part(job_, shard, threads, progress, cancel);
  }

  SuiteResult merge(const std::vector<Part>& parts, int threads, double wall_s, bool report) const override {
    std::optional<SuiteResult> r = finish_(merge_job_parts(job_, parts), threads, wall_s, report);
    if (!r) throw support::UserError("merge: interrupted");
    return std::move(*r);
  }

 private:
  Job<Work> job_;
  Finish finish_;
};

template <class Work, class Finish>
std::unique_ptr<SuiteJob> job_of(Job<Work> job, Finish finish) {
  return std::make_unique<JobOf<Work, Finish>>(std::move(job), std::move(finish));
}

// The job of a kind that turns its units' results into a run the way every kind does:
//   run_from(suite, results) -> Run {pass, threads, wall_s[, interrupted]},
//   print(std::ostream&, suite, run), report(suite, run) -> nlohmann::json.
template <class Work, class Suite, class RunFrom, class Print, class Report>
std::unique_ptr<SuiteJob> suite_job(Job<Work> job, Suite suite, RunFrom run_from, Print print, Report report) {
  return job_of(std::move(job),
                [suite = std::move(suite), run_from, print, report](const auto& results, int threads, double wall_s,
                                                                    bool want_report) -> std::optional<SuiteResult> {
                  auto run = run_from(suite, results);
                  if constexpr (requires { run.interrupted; })
                    if (run.interrupted) return std::nullopt;
                  run.threads = threads, run.wall_s = wall_s;
                  return suite_result(
                      run.pass, want_report, [&](std::ostream& os) { print(os, suite, run); },
                      [&] { return report(suite, run); });
                });
}

}  // namespace vgroove::validation
