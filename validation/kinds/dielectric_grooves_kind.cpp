// The suite kind "dielectric_grooves" (validation/dielectric_grooves_suite.h: the kaleidoscopic
// dielectric model of single grooves against exact split tracing).
#include "vgroove/support/user_error.h"
#include "vgroove/validation/dielectric_grooves_suite.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/ranges.h"

namespace vgroove::validation {

namespace {

class DielectricGroovesPlan final : public PlannedSuite {
 public:
  DielectricGroovesPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    if (o.sampling)
      throw support::UserError(o.names.sampling + " applies to single-groove conductor suites; " + file +
                               " (kind dielectric_grooves) places its rays by breakpoint search");
    check_rough_surface_overrides(o, file, "dielectric_grooves");
    if (o.rays && *o.rays > kMaxDielectricGrid)
      throw support::UserError(o.names.rays + " = " + std::to_string(*o.rays) + " is out of range [1, " +
                               std::to_string(kMaxDielectricGrid) +
                               "] for kind dielectric_grooves (the breakpoint grid per lit facet)");
    if (o.seed)
      throw support::UserError(o.names.seed + " applies to suites with random placement; " + file +
                               " (kind dielectric_grooves) traces by breakpoint search and stratified rays");
    suite_ = parse_dielectric_grooves_suite(j, file);
    if (o.rays) suite_.options.grid = *o.rays;  // the breakpoint search's grid per lit facet
  }
  std::string name() const override { return suite_.name; }
  std::string kind() const override { return "dielectric_grooves"; }
  // Per thread: the split work lists and one facet's lobes (a few hundred kB at most).
  double memory_bytes(int threads, bool) const override { return 1e6 * threads; }
  std::string memory_what(int threads) const override {
    return std::to_string(suite_.cases()) + " cases on " + std::to_string(threads) + " threads";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>*) const override {
    return suite_job(dielectric_grooves_job(suite_, std::move(descriptor)), suite_, dielectric_grooves_run_from,
                     print_dielectric_grooves_table, dielectric_grooves_report_json);
  }

 private:
  DielectricGroovesSuite suite_;
};

}  // namespace

const SuiteKind& dielectric_grooves_kind() {
  static const KindOf<DielectricGroovesPlan> kind("dielectric_grooves");
  return kind;
}

}  // namespace vgroove::validation
