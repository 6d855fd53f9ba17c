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
  double memory_bytes(int, bool) const override {
    // Per cell its tally and fixed part (rows x channels, ~50 channels) and the report's arrays.
    return static_cast<double>(suite_.cells()) * (suite_.max_k + 2) * 64.0 * 8.0 * 12.0;
  }
  std::string memory_what(int) const override { return std::to_string(suite_.cells()) + " cells' tallies and arrays"; }
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
