#include "vgroove/app/commands.h"
#include "vgroove/support/printable.h"

#include <iostream>
#include "vgroove/app/options.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/model_table.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/suite_run.h"
#include "vgroove/validation/table2_suite.h"

namespace vgroove::app {

using namespace validation;

namespace {
// Suites of procedural microsurfaces: "kind" brdf (Fig. 11), furnace, table2.
bool is_microsurface_suite(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("kind") || !j["kind"].is_string()) return false;
  const std::string k = j["kind"].get<std::string>();
  return k == "brdf" || k == "furnace" || k == "table2";
}

int validate_microsurface(const ValidateArgs& a, const nlohmann::json& j) {
  const std::string kind = j["kind"].get<std::string>();
  if (!a.sampling.empty())
    throw support::UserError("--sampling applies to single-groove suites; " + a.suite + " (kind " + kind +
                             ") lands its rays at random points of the surface");
  if (!a.eq6_form.empty())
    throw support::UserError("--eq6-form applies to single-groove suites; " + a.suite + " (kind " + kind +
                             ") uses the corrected Eq. 6 throughout");
  if (a.rays != kUnset) check_rays(a.rays, "--rays");
  if (a.seed != kUnsetSeed) check_seed(a.seed, "--seed");
  const long rays = a.rays != kUnset ? a.rays : 0;
  auto with_seed = [&](auto suite) {
    if (a.seed != kUnsetSeed) suite.seed = static_cast<std::uint64_t>(a.seed);
    return suite;
  };
  std::string report;
  bool pass = false;
  if (kind == "table2") {
    const Table2Suite suite = with_seed(parse_table2_suite(j, a.suite));
    support::check_memory(table2_run_memory_bytes(suite, a.threads), a.suite + ": the run",
                          std::to_string(suite.grooves) + " grooves per surface on each thread");
    if (!a.out.empty()) support::check_writable_target(a.out, a.force, {a.suite});
    if (a.dry_run) return 0;
    const Table2Run run = run_table2_suite(suite, rays, a.threads, a.cancel);
    if (run.interrupted) return interrupted_no_report();
    print_table2(std::cout, suite, run);
    report = table2_report_json(suite, run).dump(1) + "\n";
    pass = run.pass;
  } else if (!a.model_table.empty()) {
    const BrdfSuite suite = with_seed(parse_brdf_suite(j, a.suite));
    if (suite.kind != "brdf")
      throw support::UserError("--model-table applies to suites of kind \"brdf\"; " + a.suite + " is of kind " + kind);
    const ModelTable table = parse_model_table(support::read_json_file(a.model_table), a.model_table, suite);
    support::check_memory(brdf_run_memory_bytes(suite, a.threads, !a.out.empty()), a.suite + ": the run",
                          std::to_string(suite.cases()) + " cases, " + std::to_string(suite.grooves) +
                              " grooves per surface on each thread");
    if (!a.out.empty()) support::check_writable_target(a.out, a.force, {a.suite, a.model_table});
    if (a.dry_run) return 0;
    const ModelTableRun run = run_model_table(suite, table, rays, a.threads, a.cancel);
    if (run.interrupted) return interrupted_no_report();
    print_model_table(std::cout, suite, table, run);
    report = model_table_report_json(suite, table, run).dump(1) + "\n";
    pass = run.pass;
  } else {
    const BrdfSuite suite = with_seed(parse_brdf_suite(j, a.suite));
    support::check_memory(brdf_run_memory_bytes(suite, a.threads, !a.out.empty()), a.suite + ": the run",
                          std::to_string(suite.cases()) + " cases, " + std::to_string(suite.grooves) +
                              " grooves per surface on each thread");
    if (!a.out.empty()) support::check_writable_target(a.out, a.force, {a.suite});
    if (a.dry_run) return 0;
    const BrdfRun run = run_brdf_suite(suite, rays, a.threads, terminal_progress("validate " + suite.name), a.cancel);
    if (run.interrupted) return interrupted_no_report();
    print_brdf_table(std::cout, suite, run);
    report = brdf_report_json(suite, run).dump(1) + "\n";
    pass = run.pass;
  }
  if (!a.out.empty()) {
    support::write_file_atomically(a.out, report, a.force);
    std::cout << "report: " << support::printable(a.out) << "\n";
  }
  return pass ? 0 : 1;
}
}  // namespace

int cmd_validate(const ValidateArgs& a) {
  check_threads(a.threads);
  // Read once: the suite may come from a pipe.
  const nlohmann::json j = support::read_json_file(a.suite);
  if (is_microsurface_suite(j)) return validate_microsurface(a, j);
  if (!a.model_table.empty())
    throw support::UserError("--model-table applies to suites of kind \"brdf\" (e.g. data/suites/fig11.json); " +
                             a.suite + " is a single-groove suite");
  const SuiteSet set = parse_suite_set(j, a.suite);
  std::vector<CaseOptions> opts;
  for (const Suite& suite : set.suites)
    opts.push_back(options_with_overrides(suite, a.rays, a.sampling, a.eq6_form, a.seed));
  double memory = 0.0;
  std::size_t cases = 0;
  for (std::size_t n = 0; n < set.suites.size(); ++n) {
    memory += run_memory_bytes(set.suites[n], opts[n], a.threads, !a.out.empty());
    cases += set.suites[n].cases();
  }
  support::check_memory(memory, a.suite + ": the run",
                        std::to_string(cases) + " cases" + (a.out.empty() ? "" : ", with the report"));
  std::vector<std::string> inputs{a.suite};
  for (const Suite& suite : set.suites) inputs.push_back(suite.file);
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, inputs);  // fail before the work, not after
  if (a.dry_run) return 0;
  std::vector<SuiteRun> runs;
  bool pass = true;
  for (std::size_t n = 0; n < set.suites.size(); ++n) {
    runs.push_back(
        run_suite(set.suites[n], opts[n], a.threads, terminal_progress("validate " + set.suites[n].name), a.cancel));
    if (runs.back().interrupted) return interrupted_no_report();
    pass = pass && runs.back().summary.pass();
  }
  print_set_table(std::cout, set, runs);
  if (!a.out.empty()) {
    support::write_file_atomically(a.out, report_json(set, runs).dump(1) + "\n", a.force);
    std::cout << "report: " << support::printable(a.out) << "\n";
  }
  return pass ? 0 : 1;
}

int cmd_bins(const BinsArgs& a) {
  const nlohmann::json j = support::read_json_file(a.suite);
  if (!j.is_object() || !j.contains("kind") || j["kind"] != "brdf")
    throw support::UserError(a.suite + ": `vgroove bins` takes a suite of kind \"brdf\" (e.g. data/suites/fig11.json)");
  const BrdfSuite suite = parse_brdf_suite(j, a.suite);
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, {a.suite});
  if (a.dry_run) return 0;
  const std::string text = bin_layout_json(suite).dump(1) + "\n";
  if (a.out.empty()) {
    std::cout << text;
    return 0;
  }
  support::write_file_atomically(a.out, text, a.force);
  std::cout << "layout: " << support::printable(a.out) << " (" << suite.cases() << " cases)\n";
  return 0;
}

}  // namespace vgroove::app
