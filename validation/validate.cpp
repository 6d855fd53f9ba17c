#include "vgroove/validation/validate.h"

#include "vgroove/support/json_reader.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/suite_run.h"

#include <algorithm>
#include <sstream>

namespace vgroove::validation {

namespace {
// Suites of rough surfaces: "kind" brdf (Fig. 11), furnace, sampling, table2, profiles,
// nonsymmetric_brdf.
bool is_microsurface_suite(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("kind") || !j["kind"].is_string()) return false;
  const std::string k = j["kind"].get<std::string>();
  return k == "brdf" || k == "furnace" || k == "table2" || k == "profiles" || k == "nonsymmetric_brdf" ||
         k == "sampling";
}

support::ProgressFn progress_for(const ProgressFactory& f, const std::string& name) {
  return f ? f("validate " + name) : support::ProgressFn{};
}
}  // namespace

ValidationPlan plan_validation(const ValidateOptions& a) {
  check_threads(a.threads, a.names.threads);
  ValidationPlan plan;
  plan.threads = a.threads;
  plan.inputs = {a.suite};
  // Read once: the suite may come from a pipe.
  const nlohmann::json j = support::read_json_file(a.suite);
  if (is_microsurface_suite(j)) {
    const std::string kind = j["kind"].get<std::string>();
    if (a.sampling)
      throw support::UserError(a.names.sampling + " applies to single-groove suites; " + a.suite + " (kind " + kind +
                               ") lands its rays at random points of the surface");
    if (a.eq6_form)
      throw support::UserError(a.names.eq6_form + " applies to single-groove suites; " + a.suite + " (kind " + kind +
                               ") uses the corrected Eq. 6 throughout");
    if (a.rays) check_rays(*a.rays, a.names.rays);
    if (a.seed) check_seed(*a.seed, a.names.seed);
    plan.rays = a.rays.value_or(0);
    if (a.model_table && kind != "brdf")
      throw support::UserError(a.names.model_table + " applies to suites of kind \"brdf\"; " + a.suite +
                               " is of kind " + kind);
    if (kind == "sampling") {
      if (a.rays)
        throw support::UserError(a.names.rays + " applies to suites that trace rays; " + a.suite +
                                 " (kind sampling) sets its samples in the file");
      if (a.seed)
        throw support::UserError(a.names.seed + ": " + a.suite + " (kind sampling) sets its seed in the file");
      plan.kind = ValidationPlan::Kind::sampling;
      plan.sampling = parse_sampling_suite(j, a.suite);
    } else if (kind == "furnace") {
      if (a.rays)
        throw support::UserError(a.names.rays + " applies to suites that trace rays; " + a.suite +
                                 " (kind furnace) sets its samples and sanity rays in the file");
      plan.kind = ValidationPlan::Kind::furnace;
      plan.furnace = parse_furnace_suite(j, a.suite);
      if (a.seed) plan.furnace.seed = static_cast<std::uint64_t>(*a.seed);
    } else if (kind == "nonsymmetric_brdf") {
      plan.kind = ValidationPlan::Kind::nonsymmetric;
      plan.nonsymmetric = parse_nonsymmetric_suite(j, a.suite);
      if (a.seed) plan.nonsymmetric.seed = static_cast<std::uint64_t>(*a.seed);
    } else if (kind == "profiles") {
      plan.kind = ValidationPlan::Kind::profiles;
      plan.profiles = parse_profiles_suite(j, a.suite);
      if (a.seed) plan.profiles.seed = static_cast<std::uint64_t>(*a.seed);
      support::check_memory(
          profiles_run_memory_bytes(plan.profiles, a.threads), a.suite + ": the run",
          std::to_string(plan.profiles.segments) + " segments per profile on each of " +
              std::to_string(std::min<std::size_t>(support::resolve_threads(a.threads), plan.profiles.cases())) +
              " workers");
    } else if (kind == "table2") {
      plan.kind = ValidationPlan::Kind::table2;
      plan.table2 = parse_table2_suite(j, a.suite);
      if (a.seed) plan.table2.seed = static_cast<std::uint64_t>(*a.seed);
      support::check_memory(table2_run_memory_bytes(plan.table2, a.threads), a.suite + ": the run",
                            std::to_string(plan.table2.grooves) + " grooves per surface on each thread");
    } else if (a.model_table) {
      plan.kind = ValidationPlan::Kind::model_table;
      plan.brdf = parse_brdf_suite(j, a.suite);
      if (a.seed) plan.brdf.seed = static_cast<std::uint64_t>(*a.seed);
      if (plan.brdf.kind != "brdf")
        throw support::UserError(a.names.model_table + " applies to suites of kind \"brdf\"; " + a.suite +
                                 " is of kind " + kind);
      plan.table = std::make_shared<const ModelTable>(
          parse_model_table(support::read_json_file(*a.model_table), *a.model_table, plan.brdf));
      plan.inputs.push_back(*a.model_table);
    } else {
      plan.kind = ValidationPlan::Kind::brdf;
      plan.brdf = parse_brdf_suite(j, a.suite);
      if (a.seed) plan.brdf.seed = static_cast<std::uint64_t>(*a.seed);
    }
    if (plan.kind == ValidationPlan::Kind::brdf || plan.kind == ValidationPlan::Kind::model_table)
      support::check_memory(brdf_run_memory_bytes(plan.brdf, a.threads, true), a.suite + ": the run",
                            std::to_string(plan.brdf.cases()) + " cases, " + std::to_string(plan.brdf.grooves) +
                                " grooves per surface on each thread");
    return plan;
  }
  if (a.model_table)
    throw support::UserError(a.names.model_table +
                             " applies to suites of kind \"brdf\" (e.g. data/suites/fig11.json); " + a.suite +
                             " is a single-groove suite");
  plan.set = parse_suite_set(j, a.suite);
  for (const Suite& suite : plan.set.suites) {
    plan.opts.push_back(options_with_overrides(suite, a.rays, a.sampling, a.eq6_form, a.seed, a.names));
    plan.inputs.push_back(suite.file);
  }
  double memory = 0.0;
  std::size_t cases = 0;
  for (std::size_t n = 0; n < plan.set.suites.size(); ++n) {
    memory += run_memory_bytes(plan.set.suites[n], plan.opts[n], a.threads, true);
    cases += plan.set.suites[n].cases();
  }
  support::check_memory(memory, a.suite + ": the run", std::to_string(cases) + " cases");
  return plan;
}

ValidationResult run_validation(const ValidationPlan& plan, const ProgressFactory& progress,
                                const std::atomic<bool>* cancel) {
  ValidationResult res;
  std::ostringstream table;
  switch (plan.kind) {
    case ValidationPlan::Kind::table2: {
      const Table2Run run = run_table2_suite(plan.table2, plan.rays, plan.threads, cancel);
      if (run.interrupted) return res.interrupted = true, res;
      print_table2(table, plan.table2, run);
      if (plan.report) res.report = table2_report_json(plan.table2, run);
      res.pass = run.pass;
      break;
    }
    case ValidationPlan::Kind::profiles: {
      const ProfilesRun run = run_profiles_suite(plan.profiles, plan.rays, plan.threads,
                                                 progress_for(progress, plan.profiles.name), cancel);
      if (run.interrupted) return res.interrupted = true, res;
      print_profiles_table(table, plan.profiles, run);
      if (plan.report) res.report = profiles_report_json(plan.profiles, run);
      res.pass = run.pass;
      break;
    }
    case ValidationPlan::Kind::sampling: {
      const SamplingRun run =
          run_sampling_suite(plan.sampling, plan.threads, progress_for(progress, plan.sampling.name), cancel);
      if (run.interrupted) return res.interrupted = true, res;
      print_sampling_table(table, plan.sampling, run);
      if (plan.report) res.report = sampling_report_json(plan.sampling, run);
      res.pass = run.pass;
      break;
    }
    case ValidationPlan::Kind::furnace: {
      const FurnaceRun run =
          run_furnace_suite(plan.furnace, 0, plan.threads, progress_for(progress, plan.furnace.name), cancel);
      if (run.interrupted) return res.interrupted = true, res;
      print_furnace_table(table, plan.furnace, run);
      if (plan.report) res.report = furnace_report_json(plan.furnace, run);
      res.pass = run.pass;
      break;
    }
    case ValidationPlan::Kind::nonsymmetric: {
      const NonsymmetricRun run = run_nonsymmetric_suite(plan.nonsymmetric, plan.rays, plan.threads,
                                                         progress_for(progress, plan.nonsymmetric.name), cancel);
      if (run.interrupted) return res.interrupted = true, res;
      print_nonsymmetric_table(table, plan.nonsymmetric, run);
      if (plan.report) res.report = nonsymmetric_report_json(plan.nonsymmetric, run);
      res.pass = run.pass;
      break;
    }
    case ValidationPlan::Kind::model_table: {
      const ModelTableRun run = run_model_table(plan.brdf, *plan.table, plan.rays, plan.threads, cancel);
      if (run.interrupted) return res.interrupted = true, res;
      print_model_table(table, plan.brdf, *plan.table, run);
      if (plan.report) res.report = model_table_report_json(plan.brdf, *plan.table, run);
      res.pass = run.pass;
      break;
    }
    case ValidationPlan::Kind::brdf: {
      const BrdfRun run =
          run_brdf_suite(plan.brdf, plan.rays, plan.threads, progress_for(progress, plan.brdf.name), cancel);
      if (run.interrupted) return res.interrupted = true, res;
      print_brdf_table(table, plan.brdf, run);
      if (plan.report) res.report = brdf_report_json(plan.brdf, run);
      res.pass = run.pass;
      break;
    }
    case ValidationPlan::Kind::single_grooves: {
      std::vector<SuiteRun> runs;
      bool pass = true;
      for (std::size_t n = 0; n < plan.set.suites.size(); ++n) {
        const Suite& suite = plan.set.suites[n];
        runs.push_back(run_suite(suite, plan.opts[n], plan.threads, progress_for(progress, suite.name), cancel));
        if (runs.back().interrupted) return res.interrupted = true, res;
        pass = pass && runs.back().summary.pass();
      }
      print_set_table(table, plan.set, runs);
      if (plan.report) res.report = report_json(plan.set, runs);
      res.pass = pass;
      break;
    }
  }
  res.table = table.str();
  return res;
}

}  // namespace vgroove::validation
