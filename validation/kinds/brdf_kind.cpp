// The suite kind "brdf" (validation/brdf_suite.h: Lee et al. 2018, Fig. 11), and the same suite
// with a model table (validation/model_table.h: a foreign model's lobes against the traced ones).
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/kinds/job_of.h"
#include "vgroove/validation/kinds/kinds.h"
#include "vgroove/validation/model_table.h"

namespace vgroove::validation {

namespace {

class BrdfPlan final : public SuitePlan<BrdfSuite> {
 public:
  BrdfPlan(const nlohmann::json& j, const std::string& file, const SuiteOverrides& o) {
    check_rough_surface_overrides(o, file, "brdf");
    suite_ = parse_brdf_suite(j, file);
    apply_rays_and_seed(o);
    check_suite_surface(suite_, rays_);  // --rays may leave fewer rays than fields
    if (suite_.surface == CheckSurface::heightfield && !o.model_table)
      throw support::UserError(file +
                               ": surface heightfield is held against a model table: give --model-table FILE "
                               "(`vgroove bins " +
                               file + "` writes its layout)");
    if (o.model_table) {
      table_file_ = *o.model_table;
      table_ = std::make_shared<const ModelTable>(
          parse_model_table(support::read_json_file(table_file_), table_file_, suite_));
    }
  }
  std::string kind() const override { return table_ ? "brdf with --model-table" : "brdf"; }
  std::vector<std::string> extra_inputs() const override {
    return table_ ? std::vector<std::string>{table_file_} : std::vector<std::string>{};
  }
  double memory_bytes(int threads, bool report) const override {
    return brdf_run_memory_bytes(suite_, threads, report);
  }
  std::string memory_what(int) const override {
    if (suite_.surface == CheckSurface::heightfield)
      return std::to_string(suite_.cases()) + " cases, a " + std::to_string(suite_.field_size) +
             "^2 heightfield on each thread";
    return std::to_string(suite_.cases()) + " cases, " + std::to_string(suite_.grooves) +
           " grooves per surface on each thread";
  }
  std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const override;

 private:
  std::string table_file_;
  std::shared_ptr<const ModelTable> table_;
};

std::unique_ptr<SuiteJob> BrdfPlan::job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const {
  if (table_)
    return suite_job(
        model_table_job(suite_, rays_, std::move(descriptor), cancel), suite_,
        [t = table_, rays = rays_](const BrdfSuite& s, const auto& r) { return model_table_run_from(s, *t, rays, r); },
        [t = table_](std::ostream& os, const BrdfSuite& s, const ModelTableRun& run) {
          print_model_table(os, s, *t, run);
        },
        [t = table_](const BrdfSuite& s, const ModelTableRun& run) { return model_table_report_json(s, *t, run); });
  auto job = brdf_job(suite_, rays_, std::move(descriptor));
  job.work.cancel = cancel;
  return suite_job(
      std::move(job), suite_, [rays = rays_](const BrdfSuite& s, const auto& r) { return brdf_run_from(s, rays, r); },
      print_brdf_table, brdf_report_json);
}

}  // namespace

const SuiteKind& brdf_kind() {
  static const KindOf<BrdfPlan> kind("brdf");
  return kind;
}

}  // namespace vgroove::validation
