#include "vgroove/validation/validate.h"

#include "vgroove/support/json_reader.h"
#include "vgroove/support/memory.h"

namespace vgroove::validation {

SuiteOverrides overrides_of(const ValidateOptions& a) {
  SuiteOverrides o;
  o.rays = a.rays;
  o.seed = a.seed;
  o.sampling = a.sampling;
  o.eq6_form = a.eq6_form;
  o.model_table = a.model_table;
  o.names = a.names;
  return o;
}

ValidationPlan plan_validation(const ValidateOptions& a) {
  check_threads(a.threads, a.names.threads);
  ValidationPlan plan;
  plan.threads = a.threads;
  // Read once: the suite may come from a pipe.
  const nlohmann::json j = a.suite_json ? *a.suite_json : support::read_json_file(a.suite);
  plan.suite = find_kind(j).plan(j, a.suite, overrides_of(a));
  if (!a.suite_json) plan.inputs = {a.suite};
  for (std::string& f : plan.suite->extra_inputs()) plan.inputs.push_back(std::move(f));
  support::check_memory(plan.suite->memory_bytes(a.threads, true), a.suite + ": the run",
                        plan.suite->memory_what(a.threads));
  return plan;
}

ValidationResult run_validation(const ValidationPlan& plan, const ProgressFactory& progress,
                                const std::atomic<bool>* cancel) {
  ValidationResult res;
  const auto job = plan.suite->job(nlohmann::json::object(), cancel);
  std::optional<SuiteResult> r = job->run(
      plan.threads, progress ? progress("validate " + plan.suite->name()) : support::ProgressFn{}, cancel, plan.report);
  if (!r) return res.interrupted = true, res;
  res.report = std::move(r->report);
  res.table = std::move(r->table);
  res.pass = r->pass;
  return res;
}

}  // namespace vgroove::validation
