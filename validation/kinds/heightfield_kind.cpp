// The suite kind "heightfield" (validation/heightfield_suite.h: random heightfields traced in 3D
// against the Smith walk, Cook-Torrance with Smith's G and the V-groove model).
#include "vgroove/validation/heightfield_suite.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"

#include <algorithm>

namespace vgroove::validation {

namespace {

class HeightfieldPlan final : public SuitePlan<HeightfieldSuite> {
 public:
  HeightfieldPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "heightfield");
    suite_ = parse_heightfield_suite(j, file);
    apply_rays_and_seed(o);
  }
  std::string kind() const override { return "heightfield"; }
  // Refuses a field that does not fit (one per worker) before any work.
  double memory_bytes(int threads, bool) const override { return heightfield_run_memory_bytes(suite_, threads); }
  std::string memory_what(int threads) const override {
    return "one " + std::to_string(suite_.field_size) + "^2 field with its hierarchy on each of " +
           std::to_string(std::min<std::size_t>(support::resolve_threads(threads), suite_.cases())) + " workers";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override {
    return suite_job(heightfield_job(suite_, rays_, std::move(descriptor), cancel), suite_, heightfield_run_from,
                     print_heightfield_table, heightfield_report_json);
  }
};

}  // namespace

const SuiteKind& heightfield_kind() {
  static const KindOf<HeightfieldPlan> kind("heightfield");
  return kind;
}

}  // namespace vgroove::validation
