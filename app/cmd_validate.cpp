#include "vgroove/app/cli_options.h"
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

void add_validate_command(CLI::App& app, Commands& commands) {
  auto* val = app.add_subcommand("validate",
                                 "Run a suite (sim against analytic), print the table beside the paper's "
                                 "figures, write the report JSON; exit 1 if a threshold is exceeded.");
  ValidateArgs& va = commands.add(val, cmd_validate);
  va.cancel = commands.context().cancel;
  add_text(val, "suite", va.suite, "suite spec, e.g. data/suites/table1_symmetric.json")->required();
  add_text(val, "--out", va.out, "report JSON to write (refuses to overwrite without --force)");
  add_integer(val, "--rays", va.rays, "rays per lit facet (default: the suite's)", 1, kMaxRays);
  add_threads(val, va.threads);
  add_text(val, "--sampling", va.sampling,
           "override the suite's placement: stratified, random, or breakpoints (a grid of --rays stratified "
           "rays, then bisection between neighbours of different outcome down to adjacent doubles: exact "
           "fractions)");
  add_seed(val, va.seed, "override the suite's seed");
  add_text(val, "--eq6-form", va.eq6_form, "override the suite's form of Eq. 6: corrected or printed");
  add_text(val, "--model-table", va.model_table,
           "\"brdf\" suites: hold this table of a foreign model's bin-integrated lobes (layout from "
           "`vgroove bins SUITE`) against the simulation instead of vgroove's model");
  val->add_flag("--force", va.force, "overwrite an existing report");
  add_shard(val, va.shard, "`vgroove merge` joins them into this report");
}

void add_bins_command(CLI::App& app, Commands& commands) {
  auto* bins = app.add_subcommand("bins",
                                  "Write a \"brdf\" suite's bin layout (cases, bin edges, frame) as JSON: fill in a "
                                  "model's flux per bin and run `vgroove validate SUITE --model-table FILE`.");
  BinsArgs& bi = commands.add(bins, cmd_bins);
  add_text(bins, "suite", bi.suite, "suite spec of kind \"brdf\", e.g. data/suites/fig11.json")->required();
  add_text(bins, "--out", bi.out, "layout JSON to write (default: stdout)");
  bins->add_flag("--force", bi.force, "overwrite an existing file");
}

}  // namespace vgroove::app
