// `vgroove validate --shard I/N --out P` and `mpirun -n K vgroove validate SUITE`: the suite's work
// items (validation/work_run.h) split over shards or MPI ranks; and `vgroove merge` of its parts.
// The kinds that trace case by case: single grooves (Table 1, stress; sets of suites), "brdf"
// (Fig. 11), "table2"; the others (read by validation/validate.h) run in one process. The report written from the parts
// is the single-process report (timings aside).
#include "vgroove/app/commands.h"

#include "vgroove/app/distributed.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/app/options.h"
#include "vgroove/app/outputs.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/suite_run.h"
#include "vgroove/validation/table2_suite.h"
#include "vgroove/validation/validate.h"

#include <chrono>
#include <iostream>

namespace vgroove::app {

using namespace validation;

namespace {

// What the run's options are in its descriptor (null: the suite's), and back.
nlohmann::json options_json(const ValidateArgs& a) {
  return {{"rays", a.rays != kUnset ? nlohmann::json(a.rays) : nlohmann::json(nullptr)},
          {"seed", a.seed != kUnsetSeed ? nlohmann::json(a.seed) : nlohmann::json(nullptr)},
          {"sampling", a.sampling.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.sampling)},
          {"eq6_form", a.eq6_form.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.eq6_form)}};
}
ValidateArgs args_from(const Part& part) {
  ValidateArgs a;
  const nlohmann::json& o = part.header.job.at("options");
  a.suite = input_file_of(part);
  if (!o.at("rays").is_null()) a.rays = o["rays"].get<long>();
  if (!o.at("seed").is_null()) a.seed = o["seed"].get<long long>();
  if (!o.at("sampling").is_null()) a.sampling = o["sampling"].get<std::string>();
  if (!o.at("eq6_form").is_null()) a.eq6_form = o["eq6_form"].get<std::string>();
  return a;
}

// The kinds whose work items split over shards and ranks: those that trace rays case by case.
const char* split_kind_name(ValidationPlan::Kind k) {
  switch (k) {
    case ValidationPlan::Kind::single_grooves:
      return "single-groove";
    case ValidationPlan::Kind::brdf:
      return "brdf";
    case ValidationPlan::Kind::table2:
      return "table2";
    default:
      return nullptr;
  }
}
const char* kind_name(ValidationPlan::Kind k) {
  switch (k) {
    case ValidationPlan::Kind::furnace:
      return "furnace";
    case ValidationPlan::Kind::sampling:
      return "sampling";
    case ValidationPlan::Kind::profiles:
      return "profiles";
    case ValidationPlan::Kind::nonsymmetric:
      return "nonsymmetric_brdf";
    case ValidationPlan::Kind::model_table:
      return "brdf with --model-table";
    default:
      return split_kind_name(k);
  }
}

// The suite file read (validation/validate.h) with the command line's overrides, refused where it
// cannot be split.
ValidationPlan plan_of(const ValidateArgs& a, const std::optional<support::Shard>& shard) {
  ValidationPlan p = plan_validation(validate_options(a));
  if (!split_kind_name(p.kind))
    throw support::UserError((shard ? "--shard" : "mpirun") + std::string(": ") + a.suite + " (kind " +
                             kind_name(p.kind) +
                             ") runs in one process; single-groove, brdf and table2 suites split over shards and "
                             "ranks");
  return p;
}

std::vector<std::string> input_files(const ValidateArgs& a, const ValidationPlan& p) {
  std::vector<std::string> files = {a.suite};
  for (const Suite& s : p.set.suites)
    if (s.file != a.suite) files.push_back(s.file);
  return files;
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Shard, ranks or merge: where a job's results come from.
struct Source {
  std::optional<support::Shard> shard;       // a shard: write its part
  const std::vector<Part>* parts = nullptr;  // merge: these parts
  const ValidateArgs* args = nullptr;
};

// Runs (or merges) the plan's job; prints and writes on the process that has the results.
template <class Work, class Finish>
int run_plan_job(const Job<Work>& job, const Source& src, const std::string& out, bool force, Finish&& finish) {
  const auto t0 = Clock::now();
  int threads = 0;
  std::optional<std::vector<UnitResult<Work>>> results;
  if (src.parts) {
    results = merge_job_parts(job, *src.parts);
    double wall = 0.0;
    for (const Part& p : *src.parts) threads += p.header.threads, wall = std::max(wall, p.header.wall_s);
    return finish(*results, threads, wall, out, force);
  }
  const ValidateArgs& a = *src.args;
  if (src.shard) {
    const auto part =
        run_job_part(job, *src.shard, a.threads, terminal_progress("validate " + src.shard->text()), a.cancel);
    if (!part) return interrupted_no_report();
    write_partial(out, *part, force);
    return 0;
  }
  results = run_distributed(job, a.threads, terminal_progress("validate"), a.cancel, &threads);
  if (!results) return 0;  // not rank 0: its results went there
  return finish(*results, threads, seconds_since(t0), out, force);
}

void write_report(const std::string& out, const nlohmann::json& report, bool force) {
  if (out.empty()) return;
  support::write_file_atomically(out, report.dump(1) + "\n", force);
  std::cout << "report: " << out << "\n";
}

int run_plan(const ValidationPlan& p, const nlohmann::json& descriptor, const Source& src, const std::string& out,
             bool force) {
  if (p.kind == ValidationPlan::Kind::brdf)
    return run_plan_job(brdf_job(p.brdf, p.rays, descriptor), src, out, force,
                        [&](const auto& results, int threads, double wall, const std::string& o, bool f) {
                          BrdfRun run = brdf_run_from(p.brdf, p.rays, results);
                          run.threads = threads, run.wall_s = wall;
                          print_brdf_table(std::cout, p.brdf, run);
                          write_report(o, brdf_report_json(p.brdf, run), f);
                          return run.pass ? 0 : 1;
                        });
  if (p.kind == ValidationPlan::Kind::table2)
    return run_plan_job(table2_job(p.table2, p.rays, descriptor), src, out, force,
                        [&](const auto& results, int threads, double wall, const std::string& o, bool f) {
                          Table2Run run = table2_run_from(p.table2, results);
                          run.threads = threads, run.wall_s = wall;
                          print_table2(std::cout, p.table2, run);
                          write_report(o, table2_report_json(p.table2, run), f);
                          return run.pass ? 0 : 1;
                        });
  const auto job = groove_cases_job(p.set.suites, p.opts, descriptor);
  return run_plan_job(job, src, out, force,
                      [&](const auto& results, int threads, double wall, const std::string& o, bool f) {
                        const std::vector<SuiteRun> runs = suite_runs_from(job.work, results, threads, wall);
                        bool pass = true;
                        for (const SuiteRun& r : runs) pass = pass && r.summary.pass();
                        print_set_table(std::cout, p.set, runs);
                        write_report(o, report_json(p.set, runs), f);
                        return pass ? 0 : 1;
                      });
}

}  // namespace

int validate_split(const ValidateArgs& a) {
  check_threads(a.threads, "--threads");
  const std::optional<support::Shard> shard = shard_from(a.shard, a.out);
  if (shard && world().distributed())
    throw support::UserError("--shard cannot be combined with mpirun (the ranks split the work among themselves)");
  const ValidationPlan p = plan_of(a, shard);
  if (!a.out.empty()) support::check_writable_target(a.out, a.force);  // fail before the work, not after
  if (a.dry_run) return 0;
  Source src;
  src.shard = shard;
  src.args = &a;
  return run_plan(p, job_descriptor("validate", split_kind_name(p.kind), input_files(a, p), options_json(a)), src,
                  a.out, a.force);
}

int merge_validate(const std::vector<Part>& parts, const MergeArgs& m) {
  const nlohmann::json& job = parts.front().header.job;
  const ValidateArgs a = args_from(parts.front());
  const ValidationPlan p = plan_of(a, support::Shard{});
  check_input_unchanged(job, input_files(a, p), parts.front().file);
  if (m.dry_run) return 0;
  Source src;
  src.parts = &parts;
  return run_plan(p, job, src, m.out, m.force);
}

}  // namespace vgroove::app
