// The suite kind "energy_audit" (validation/energy_audit.h: compensation formulas against exact
// multiple scattering).
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_audit.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"

namespace vgroove::validation {

namespace {

class EnergyAuditPlan final : public PlannedSuite {
 public:
  EnergyAuditPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "energy_audit");
    suite_ = parse_energy_audit(j, file);
    if (o.rays) suite_.walk_paths = *o.rays;  // the walk's paths per cell
    if (o.seed) suite_.seed = static_cast<std::uint64_t>(*o.seed);
  }
  std::string name() const override { return suite_.name; }
  std::string kind() const override { return "energy_audit"; }
  double memory_bytes(int threads, bool) const override { return energy_audit_memory_bytes(suite_, threads); }
  std::string memory_what(int threads) const override {
    std::string what = std::to_string(suite_.cells()) + " cells' tallies and arrays";
    if (suite_.heightfield)
      what += " and " + std::to_string(2 * suite_.hf_fields) + " " + std::to_string(suite_.hf_field_size) +
              "^2 fields on each of " + std::to_string(support::resolve_threads(threads)) + " workers";
    return what;
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>*) const override {
    return suite_job(energy_audit_job(suite_, std::move(descriptor)), suite_, energy_audit_run_from, print_energy_audit,
                     energy_audit_report_json);
  }

 private:
  EnergyAuditSuite suite_;
};

}  // namespace

const SuiteKind& energy_audit_kind() {
  static const KindOf<EnergyAuditPlan> kind("energy_audit");
  return kind;
}

}  // namespace vgroove::validation
