// vgroove validation: a SuiteJob for a kind whose run is not yet cut into work items: it runs in
// one process, and a shard or a merge of it is refused.
#pragma once

#include "vgroove/support/user_error.h"
#include "vgroove/validation/suite_kind.h"

#include <memory>
#include <string>
#include <utility>

namespace vgroove::validation {

// run(threads, progress, cancel, report) -> std::optional<SuiteResult> (nothing when cancelled).
template <class Run>
class OneProcessJob final : public SuiteJob {
 public:
  OneProcessJob(nlohmann::json descriptor, std::string what, Run run)
      : descriptor_(std::move(descriptor)), what_(std::move(what)), run_(std::move(run)) {}
  const nlohmann::json& descriptor() const override { return descriptor_; }
  std::optional<SuiteResult> run(int threads, const support::ProgressFn& progress, const std::atomic<bool>* cancel,
                                 bool report) const override {
    return run_(threads, progress, cancel, report);
  }
  std::optional<nlohmann::json> run_part(const support::Shard&, int, const support::ProgressFn&,
                                         const std::atomic<bool>*) const override {
    throw support::UserError("--shard and mpirun: " + what_ + " runs in one process");
  }
  SuiteResult merge(const std::vector<Part>&, int, double, bool) const override {
    throw support::UserError("merge: " + what_ + " runs in one process");
  }

 private:
  nlohmann::json descriptor_;
  std::string what_;
  Run run_;
};

template <class Run>
std::unique_ptr<SuiteJob> one_process_job(nlohmann::json descriptor, std::string what, Run run) {
  return std::make_unique<OneProcessJob<Run>>(std::move(descriptor), std::move(what), std::move(run));
}

}  // namespace vgroove::validation
