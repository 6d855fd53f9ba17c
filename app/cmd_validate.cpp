#include "vgroove/app/commands.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/printable.h"

#include <iostream>
#include "vgroove/app/mpi_world.h"
#include "vgroove/app/outputs.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/model_table.h"
#include "vgroove/validation/validate.h"

namespace vgroove::app {

using namespace validation;

ValidateOptions validate_options(const ValidateArgs& a) {
  ValidateOptions o;
  o.suite = a.suite;
  if (a.rays != kUnset) o.rays = a.rays;
  o.threads = a.threads;
  if (!a.sampling.empty()) o.sampling = a.sampling;
  if (!a.eq6_form.empty()) o.eq6_form = a.eq6_form;
  if (a.seed != kUnsetSeed) o.seed = a.seed;
  if (!a.model_table.empty()) o.model_table = a.model_table;
  return o;
}

int cmd_validate(const ValidateArgs& a) {
  if (!a.shard.empty() || world().distributed()) return validate_split(a);
  ValidationPlan plan = plan_validation(validate_options(a));
  plan.report = !a.out.empty();  // the report is only written, never printed
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, plan.inputs);  // fail before the work, not after
  if (a.dry_run) return 0;
  const ValidationResult res = run_validation(plan, terminal_progress, a.cancel);
  if (res.interrupted) return interrupted_no_report();
  std::cout << res.table;
  if (!a.out.empty()) {
    support::write_file_atomically(a.out, support::json_text(res.report, 1) + "\n", a.force);
    std::cout << "report: " << support::printable(a.out) << "\n";
  }
  return res.pass ? 0 : 1;
}

int cmd_bins(const BinsArgs& a) {
  const nlohmann::json j = support::read_json_file(a.suite);
  if (!j.is_object() || !j.contains("kind") || j["kind"] != "brdf")
    throw support::UserError(a.suite + ": `vgroove bins` takes a suite of kind \"brdf\" (e.g. data/suites/fig11.json)");
  const BrdfSuite suite = parse_brdf_suite(j, a.suite);
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, {a.suite});
  if (a.dry_run) return 0;
  const std::string text = support::json_text(bin_layout_json(suite), 1) + "\n";
  if (a.out.empty()) {
    std::cout << text;
    return 0;
  }
  support::write_file_atomically(a.out, text, a.force);
  std::cout << "layout: " << support::printable(a.out) << " (" << suite.cases() << " cases)\n";
  return 0;
}

}  // namespace vgroove::app
