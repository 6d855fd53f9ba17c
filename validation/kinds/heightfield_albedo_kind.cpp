// The suite kind "heightfield_albedo" (validation/heightfield_albedo.h: the albedo E(mu, alpha) of
// random heightfields per k against the Smith walk, Smith's E_ss and the V-groove model).
#include "vgroove/validation/heightfield_albedo.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"

#include <algorithm>

namespace vgroove::validation {

namespace {

class HeightfieldAlbedoPlan final : public SuitePlan<HeightfieldAlbedoSuite> {
 public:
  HeightfieldAlbedoPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "heightfield_albedo");
    suite_ = parse_heightfield_albedo_suite(j, file);
    apply_rays_and_seed(o);
  }
  std::string kind() const override { return "heightfield_albedo"; }
  double memory_bytes(int threads, bool) const override { return heightfield_albedo_memory_bytes(suite_, threads); }
  std::string memory_what(int threads) const override {
    return "one " + std::to_string(suite_.field_size) + "^2 field with its hierarchy on each of " +
           std::to_string(std::min<std::size_t>(support::resolve_threads(threads), suite_.items())) + " workers";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override {
    return suite_job(heightfield_albedo_job(suite_, rays_, std::move(descriptor), cancel), suite_,
                     heightfield_albedo_run_from, print_heightfield_albedo_table, heightfield_albedo_report_json);
  }
};

}  // namespace

const SuiteKind& heightfield_albedo_kind() {
  static const KindOf<HeightfieldAlbedoPlan> kind("heightfield_albedo");
  return kind;
}

}  // namespace vgroove::validation
