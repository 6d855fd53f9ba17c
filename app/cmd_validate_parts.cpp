// `vgroove validate --shard I/N --out P` and `mpirun -n K vgroove validate SUITE`: the suite's job
// (validation/suite_kind.h: the work items of every kind) split over shards or MPI ranks; and
// `vgroove merge` of its parts. The report written from the parts is the single-process report
// (timings aside).
#include "vgroove/app/commands.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/app/distributed.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/app/options.h"
#include "vgroove/app/outputs.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/validate.h"

#include <chrono>
#include <filesystem>
#include <iostream>

namespace vgroove::app {

using namespace validation;

namespace {

// What the run's options are in its descriptor (null: the suite's), and back.
nlohmann::json options_json(const ValidateArgs& a) {
  const auto text = [](const std::string& v) { return v.empty() ? nlohmann::json(nullptr) : nlohmann::json(v); };
  return {{"rays", a.rays != kUnset ? nlohmann::json(a.rays) : nlohmann::json(nullptr)},
          {"seed", a.seed != kUnsetSeed ? nlohmann::json(a.seed) : nlohmann::json(nullptr)},
          {"sampling", text(a.sampling)},
          {"eq6_form", text(a.eq6_form)},
          {"model_table", a.model_table.empty() ? nlohmann::json(nullptr)
                                                : nlohmann::json(std::filesystem::absolute(a.model_table).string())}};
}
ValidateArgs args_from(const Part& part) {
  ValidateArgs a;
  const nlohmann::json& o = part.header.job.at("options");
  a.suite = input_file_of(part);
  if (!o.at("rays").is_null()) a.rays = o["rays"].get<long>();
  if (!o.at("seed").is_null()) a.seed = o["seed"].get<long long>();
  if (!o.at("sampling").is_null()) a.sampling = o["sampling"].get<std::string>();
  if (!o.at("eq6_form").is_null()) a.eq6_form = o["eq6_form"].get<std::string>();
  if (!o.at("model_table").is_null()) a.model_table = o["model_table"].get<std::string>();
  return a;
}

using support::Clock;
using support::seconds_since;

void write_report(const std::string& out, const SuiteResult& r, bool force) {
  std::cout << r.table;
  if (out.empty()) return;
  support::write_file_atomically(out, support::json_text(r.report, 1) + "\n", force);
  std::cout << "report: " << support::printable(out) << "\n";
}

}  // namespace

int validate_split(const ValidateArgs& a) {
  check_threads(a.threads, "--threads");
  const std::optional<support::Shard> shard = shard_from(a.shard, a.out);
  if (shard && world().distributed())
    throw support::UserError("--shard cannot be combined with mpirun (the ranks split the work among themselves)");
  const ValidationPlan p = plan_validation(validate_options(a));
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, p.inputs);  // fail before the work, not after
  if (a.dry_run) return 0;
  const auto job = p.suite->job(job_descriptor("validate", p.suite->kind(), p.inputs, options_json(a)), a.cancel);
  if (shard) {
    const auto part = job->run_part(*shard, a.threads, terminal_progress("validate " + shard->text()), a.cancel);
    if (!part) return interrupted_no_report();
    write_partial(a.out, *part, a.force);
    return 0;
  }
  const auto t0 = Clock::now();
  const auto parts = gather_parts([&](const support::Shard& s) {
    return job->run_part(s, a.threads, world().root() ? terminal_progress("validate") : support::ProgressFn{},
                         a.cancel);
  });
  if (!parts) return 0;  // not rank 0: its results went there
  const SuiteResult r = job->merge(*parts, threads_of(*parts), seconds_since(t0), !a.out.empty());
  write_report(a.out, r, a.force);
  return r.pass ? 0 : 1;
}

int merge_validate(const std::vector<Part>& parts, const MergeArgs& m) {
  const nlohmann::json& descriptor = parts.front().header.job;
  const ValidateArgs a = args_from(parts.front());
  const ValidationPlan p = plan_validation(validate_options(a));
  check_input_unchanged(descriptor, p.inputs, parts.front().file);
  if (m.dry_run) return 0;
  double wall = 0.0;
  for (const Part& part : parts) wall = std::max(wall, part.header.wall_s);
  const SuiteResult r = p.suite->job(descriptor, nullptr)->merge(parts, threads_of(parts), wall, !m.out.empty());
  write_report(m.out, r, m.force);
  return r.pass ? 0 : 1;
}

}  // namespace vgroove::app
