// The suite kind "nonsymmetric_brdf" (validation/nonsymmetric_suite.h: Lee et al. 2018, Sec. 5.2-5.3).
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/nonsymmetric_suite.h"

namespace vgroove::validation {

namespace {

class NonsymmetricPlan final : public PlannedSuite {
 public:
  NonsymmetricPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "nonsymmetric_brdf");
    suite_ = parse_nonsymmetric_suite(j, file);
    rays_ = o.rays.value_or(0);
    if (o.seed) suite_.seed = static_cast<std::uint64_t>(*o.seed);
  }
  std::string name() const override { return suite_.name; }
  std::string kind() const override { return "nonsymmetric_brdf"; }
  double memory_bytes(int threads, bool report) const override {
    return nonsymmetric_run_memory_bytes(suite_, threads, report);
  }
  std::string memory_what(int) const override {
    return std::to_string(suite_.cases().size()) + " cases, " + std::to_string(suite_.grooves) +
           " grooves per surface on each thread";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override {
    return suite_job(nonsymmetric_job(suite_, rays_, std::move(descriptor), cancel), suite_, nonsymmetric_run_from,
                     print_nonsymmetric_table, nonsymmetric_report_json);
  }

 private:
  NonsymmetricSuite suite_;
  long rays_ = 0;
};

}  // namespace

const SuiteKind& nonsymmetric_kind() {
  static const KindOf<NonsymmetricPlan> kind("nonsymmetric_brdf");
  return kind;
}

}  // namespace vgroove::validation
