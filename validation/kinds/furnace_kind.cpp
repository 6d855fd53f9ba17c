// The suite kind "furnace" (validation/furnace_suite.h: the white furnace of the BRDF).
#include "vgroove/support/user_error.h"
#include "vgroove/validation/furnace_suite.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"

namespace vgroove::validation {

namespace {

class FurnacePlan final : public PlannedSuite {
 public:
  FurnacePlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "furnace");
    if (o.rays)
      throw support::UserError(o.names.rays + " applies to suites that trace rays; " + file +
                               " (kind furnace) sets its samples and sanity rays in the file");
    suite_ = parse_furnace_suite(j, file);
    if (o.seed) suite_.seed = static_cast<std::uint64_t>(*o.seed);
  }
  std::string name() const override { return suite_.name; }
  std::string kind() const override { return "furnace"; }
  double memory_bytes(int, bool) const override { return 0.0; }
  std::string memory_what(int threads) const override {
    (void)threads;
    return std::string();
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>*) const override {
    return suite_job(furnace_job(suite_, 0, std::move(descriptor)), suite_, furnace_run_from, print_furnace_table,
                     furnace_report_json);
  }

 private:
  FurnaceSuite suite_;
};

}  // namespace

const SuiteKind& furnace_kind() {
  static const KindOf<FurnacePlan> kind("furnace");
  return kind;
}

}  // namespace vgroove::validation
