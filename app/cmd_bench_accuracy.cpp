#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/printable.h"

#include <cstdio>
#include <numbers>
#include "vgroove/app/distributed.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/app/options.h"
#include "vgroove/app/outputs.h"
#include "vgroove/app/progress.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/cost_curve.h"
#include "vgroove/validation/groove_suite_run.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"

namespace vgroove::app {

using namespace validation;

namespace {
// The runs of `bench accuracy` as one job: the suite once per (sampling, rays), sampling outer.
struct AccuracyPlan {
  std::vector<GrooveSuite> suites;
  std::vector<CaseOptions> options;
};
AccuracyPlan accuracy_plan(const GrooveSuite& suite, const std::vector<sim::Sampling>& samplings,
                           const std::vector<long>& rays) {
  AccuracyPlan p;
  for (sim::Sampling smp : samplings)
    for (long r : rays) {
      CaseOptions o = suite.options;
      o.rays = r;
      o.sampling = smp;
      p.suites.push_back(suite);
      p.options.push_back(o);
    }
  return p;
}
nlohmann::json accuracy_descriptor(const AccuracyArgs& a) {
  return job_descriptor("bench accuracy", "single-groove", {a.suite}, {{"rays", a.rays}, {"sampling", a.samplings}});
}
}  // namespace

int cmd_bench_accuracy(const AccuracyArgs& a) {
  check_threads(a.threads, "--threads");
  const GrooveSuiteSet set = load_groove_suite_set(a.suite);
  if (set.suites.size() != 1)
    throw support::UserError(a.suite + ": is a set of " + std::to_string(set.suites.size()) +
                             " suites; `bench accuracy` takes one suite file (e.g. data/suites/table1_symmetric.json)");
  const GrooveSuite& suite = set.suites.front();
  for (long r : a.rays) check_rays(r, "--rays");
  std::vector<sim::Sampling> samplings;
  for (const auto& s : a.samplings) samplings.push_back(parse_sampling(s, "--sampling", true));
  for (long r : a.rays) {
    CaseOptions o = suite.options;
    o.rays = r;
    support::check_memory(groove_suite_memory_bytes(suite, o, a.threads, false), a.suite + ": the run",
                          std::to_string(suite.cases()) + " cases");
  }
  const std::optional<support::Shard> shard = shard_from(a.shard, a.out);
  if (shard && world().distributed())
    throw support::UserError("--shard cannot be combined with mpirun (the ranks split the work among themselves)");
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, {a.suite});
  if (a.dry_run) return 0;
  const AccuracyPlan plan = accuracy_plan(suite, samplings, a.rays);
  if (shard) {
    const auto part = run_job_part(groove_cases_job(plan.suites, plan.options, accuracy_descriptor(a)), *shard,
                                   a.threads, terminal_progress("accuracy " + shard->text()), a.cancel);
    if (!part) return interrupted_no_report();
    write_partial(a.out, *part, a.force);
    return 0;
  }
  std::vector<GrooveSuiteRun> runs;
  if (world().distributed()) {
    const auto job = groove_cases_job(plan.suites, plan.options, accuracy_descriptor(a));
    int threads = 0;
    const auto results = run_distributed(job, a.threads, terminal_progress("accuracy"), a.cancel, &threads);
    if (!results) return 0;  // not rank 0: its results went there
    runs = groove_suite_runs_from(job.work, *results, threads, -1.0);
  } else {
    for (std::size_t n = 0; n < plan.suites.size(); ++n) {
      const CaseOptions& o = plan.options[n];
      runs.push_back(run_groove_suite(
          suite, o, a.threads,
          terminal_progress(std::string(sim::sampling_name(o.sampling)) + " " + std::to_string(o.rays)), a.cancel));
      if (runs.back().interrupted) return interrupted_no_report();
    }
  }
  write_accuracy_report(suite, runs, a.out, a.force);
  return 0;
}

void write_accuracy_report(const GrooveSuite& suite, const std::vector<GrooveSuiteRun>& all_runs,
                           const std::string& out, bool force) {
  nlohmann::json runs = nlohmann::json::array();
  std::printf("accuracy against rays: suite %s (%zu cases), vgroove %s (git %s)\n",
              support::printable(suite.name).c_str(), suite.cases(), version_string(), git_revision());
  std::printf("  %-10s %10s %12s %12s %12s %10s %8s\n", "sampling", "rays/facet", "max L1", "mean L1", "rays", "wall s",
              "pass");
  const int threads_used = all_runs.empty() ? 0 : all_runs.front().threads;
  for (const GrooveSuiteRun& run : all_runs) {
    const sim::Sampling smp = run.options.sampling;
    const long rays = run.options.rays;
    const GrooveSuiteSummary& s = run.summary;
    std::printf("  %-10s %10ld %12.4g %12.4g %12lld %10.3f %8s\n", sim::sampling_name(smp), rays, s.max_l1, s.mean_l1,
                static_cast<long long>(s.rays), s.wall_s, s.pass() ? "yes" : "no");
    std::fflush(stdout);
    runs.push_back({{"sampling", sim::sampling_name(smp)},
                    {"rays_per_facet", rays},
                    {"max_l1", s.max_l1},
                    {"mean_l1", s.mean_l1},
                    {"max_theta_o_error_rad", s.max_theta_o_error},
                    {"rays", s.rays},
                    {"bounces", s.bounces},
                    {"wall_s", s.wall_s},
                    {"bounces_per_s", s.bounces_per_s},
                    {"pass", s.pass()}});
    if (smp == sim::Sampling::breakpoints) {
      // rays_per_facet is the grid's size M; rays counts every ray traced (grid and bisection).
      runs.back()["zones"] = s.zones;
      runs.back()["uncertified_cells"] = s.uncertified_cells;
      runs.back()["max_missed_bound"] = s.max_missed_bound;
    }
  }
  // Which placement reaches the suite's thresholds first, in wall time.
  std::string fastest = "none";
  double fastest_s = 0.0;
  for (const auto& r : runs)
    if (r["pass"].get<bool>() && (fastest == "none" || r["wall_s"].get<double>() < fastest_s))
      fastest = r["sampling"].get<std::string>() + " at " + std::to_string(r["rays_per_facet"].get<long>()) +
                " rays per facet",
      fastest_s = r["wall_s"].get<double>();
  std::printf("  reaches the thresholds (max L1 <= %g, mean L1 <= %g) soonest: %s\n", suite.thresholds.max_l1,
              suite.thresholds.mean_l1, fastest.c_str());
  // The tracer's cost grows like pi / theta_v; the model's does not (one thread, theta_i = 30 deg).
  const double kTheta_i = 30.0 * kRadPerDeg;
  const std::vector<double> apertures_deg = {1, 2, 5, 10, 20, 45, 90, 135, 180};
  std::vector<double> apertures;
  for (double d : apertures_deg) apertures.push_back(d * kRadPerDeg);
  const std::vector<CostPoint> cost = cost_vs_theta_v(apertures, kTheta_i, 20000);
  nlohmann::json cost_json = nlohmann::json::array();
  std::printf("  cost against theta_v (one thread, theta_i = 30 deg, 20000 stratified rays):\n");
  std::printf("  %10s %12s %14s %16s %13s\n", "theta_v", "bounces/ray", "tracer ns/ray", "model ns/eval",
              "tracer/model");
  for (const CostPoint& c : cost) {
    std::printf("  %10.0f %12.2f %14.1f %16.1f %13.3f\n", output_deg(c.theta_v), c.bounces_per_ray, c.tracer_ns_per_ray,
                c.model_ns_per_eval, c.tracer_ns_per_ray / c.model_ns_per_eval);
    cost_json.push_back({{"theta_v_deg", output_deg(c.theta_v)},
                         {"bounces_per_ray", c.bounces_per_ray},
                         {"tracer_ns_per_ray", c.tracer_ns_per_ray},
                         {"model_ns_per_eval", c.model_ns_per_eval}});
  }
  if (!out.empty()) {
    nlohmann::json j = provenance();
    j["suite"] = suite.name;
    j["suite_file"] = suite.file;
    j["seed"] = suite.options.seed;
    j["threads"] = threads_used;
    j["runs"] = runs;
    j["thresholds"] = {{"max_l1", suite.thresholds.max_l1}, {"mean_l1", suite.thresholds.mean_l1}};
    j["soonest_to_thresholds"] = fastest;
    j["cost_vs_theta_v"] = {{"theta_i_deg", 30.0}, {"rays", 20000}, {"threads", 1}, {"points", cost_json}};
    support::write_file_atomically(out, support::json_text(j, 1) + "\n", force);
    std::printf("report: %s\n", support::printable(out).c_str());
  }
}

int merge_accuracy(const std::vector<Part>& parts, const MergeArgs& a) {
  const nlohmann::json& job = parts.front().header.job;
  const std::string file = input_file_of(parts.front());
  const GrooveSuiteSet set = load_groove_suite_set(file);
  check_input_unchanged(job, {file}, parts.front().file);
  std::vector<sim::Sampling> samplings;
  for (const auto& smp : job.at("options").at("sampling")) samplings.push_back(parse_sampling(smp, "sampling", true));
  const AccuracyPlan plan =
      accuracy_plan(set.suites.front(), samplings, job.at("options").at("rays").get<std::vector<long>>());
  if (!a.out.empty()) support::check_writable_target(a.out, a.force);
  if (a.dry_run) return 0;
  const auto j = groove_cases_job(plan.suites, plan.options, job);
  int threads = 0;
  for (const Part& p : parts) threads += p.header.threads;
  write_accuracy_report(set.suites.front(), groove_suite_runs_from(j.work, merge_job_parts(j, parts), threads, -1.0),
                        a.out, a.force);
  return 0;
}

void add_bench_accuracy_command(CLI::App& bench, Commands& commands) {
  auto* acc = bench.add_subcommand("accuracy",
                                   "Run a suite at several ray counts and placements; report max/mean "
                                   "L1 against rays and wall time.");
  AccuracyArgs& ac = commands.add(acc, cmd_bench_accuracy);
  ac.cancel = commands.context().cancel;
  add_text(acc, "suite", ac.suite, "suite spec")->required();
  add_integer(acc, "--rays", ac.rays, "rays per lit facet, comma-separated", 1, kMaxRays)
      ->delimiter(',')
      ->capture_default_str();
  add_text(acc, "--sampling", ac.samplings,
           "placements, comma-separated: stratified, random, breakpoints (--rays is then the grid's size)")
      ->delimiter(',')
      ->capture_default_str();
  add_threads(acc, ac.threads);
  add_text(acc, "--out", ac.out, "report JSON to write");
  acc->add_flag("--force", ac.force, "overwrite an existing report");
  add_shard(acc, ac.shard, "`vgroove merge` joins them; each run's wall_s is then its summed case time");
}

}  // namespace vgroove::app
