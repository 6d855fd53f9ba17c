// The suite kind "dielectric_brdf" (validation/dielectric_brdf_suite.h: rough dielectric surfaces
// traced exactly against Walter et al. 2007 and the dielectric Smith walk).
#include "vgroove/validation/dielectric_brdf_suite.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"

#include <algorithm>

namespace vgroove::validation {

namespace {

class DielectricBrdfPlan final : public SuitePlan<DielectricBrdfSuite> {
 public:
  DielectricBrdfPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "dielectric_brdf");
    suite_ = parse_dielectric_brdf_suite(j, file);
    apply_rays_and_seed(o);
  }
  std::string kind() const override { return "dielectric_brdf"; }
  double memory_bytes(int threads, bool) const override { return dielectric_brdf_memory_bytes(suite_, threads); }
  std::string memory_what(int threads) const override {
    return std::to_string(suite_.cases()) + " cases, one surface on each of " +
           std::to_string(std::min<std::size_t>(support::resolve_threads(threads), suite_.cases())) + " workers";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override {
    return suite_job(dielectric_brdf_job(suite_, rays_, std::move(descriptor), cancel), suite_,
                     dielectric_brdf_run_from, print_dielectric_brdf_table, dielectric_brdf_report_json);
  }
};

}  // namespace

const SuiteKind& dielectric_brdf_kind() {
  static const KindOf<DielectricBrdfPlan> kind("dielectric_brdf");
  return kind;
}

}  // namespace vgroove::validation
