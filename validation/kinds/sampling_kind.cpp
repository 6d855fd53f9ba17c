// The suite kind "sampling" (validation/sampling_suite.h: the importance sampling held to account).
#include "vgroove/support/user_error.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/sampling_suite.h"

namespace vgroove::validation {

namespace {

class SamplingPlan final : public PlannedSuite {
 public:
  SamplingPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "sampling");
    if (o.rays)
      throw support::UserError(o.names.rays + " applies to suites that trace rays; " + file +
                               " (kind sampling) sets its samples in the file");
    if (o.seed) throw support::UserError(o.names.seed + ": " + file + " (kind sampling) sets its seed in the file");
    suite_ = parse_sampling_suite(j, file);
  }
  std::string name() const override { return suite_.name; }
  std::string kind() const override { return "sampling"; }
  double memory_bytes(int, bool) const override { return 0.0; }
  std::string memory_what(int threads) const override {
    (void)threads;
    return std::string();
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override {
    return suite_job(sampling_job(suite_, std::move(descriptor), cancel), suite_, sampling_run_from,
                     print_sampling_table, sampling_report_json);
  }

 private:
  SamplingSuite suite_;
};

}  // namespace

const SuiteKind& sampling_kind() {
  static const KindOf<SamplingPlan> kind("sampling");
  return kind;
}

}  // namespace vgroove::validation
