// The suite kind "table2" (validation/table2_suite.h: Lee et al. 2018, Table 2).
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/table2_suite.h"

namespace vgroove::validation {

namespace {

class Table2Plan final : public SuitePlan<Table2Suite> {
 public:
  Table2Plan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "table2");
    suite_ = parse_table2_suite(j, file);
    apply_rays_and_seed(o);
  }
  std::string kind() const override { return "table2"; }
  double memory_bytes(int threads, bool) const override { return table2_run_memory_bytes(suite_, threads); }
  std::string memory_what(int) const override {
    return std::to_string(suite_.grooves) + " grooves per surface on each thread";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override {
    auto job = table2_job(suite_, rays_, std::move(descriptor));
    job.work.cancel = cancel;
    return suite_job(
        std::move(job), suite_,
        [cancel](const Table2Suite& s, const auto& results) { return table2_run_from(s, results, cancel); },
        print_table2, table2_report_json);
  }
};

}  // namespace

const SuiteKind& table2_kind() {
  static const KindOf<Table2Plan> kind("table2");
  return kind;
}

}  // namespace vgroove::validation
