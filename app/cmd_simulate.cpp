#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/app/distributed.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/app/options.h"
#include "vgroove/app/outputs.h"
#include "vgroove/app/progress.h"
#include "vgroove/scene/simulate.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/memory.h"
#include "vgroove/validation/partial_report.h"

#include <chrono>
#include <iostream>

namespace vgroove::app {

using namespace scene;

nlohmann::json simulate_descriptor(const Scene& scene) {
  return validation::job_descriptor("simulate", "scene", {scene.file}, nlohmann::json::object());
}

int write_simulation(const Scene& scene, const SimulationResult& r, const std::string& out, bool force) {
  if (const std::string problem = lost_rays_problem(r); !problem.empty()) {
    std::cerr << "vgroove: error: " << support::printable(scene.file) << ": " << problem << "\n";
    return 1;
  }
  print_result_table(std::cout, scene, r);
  if (!out.empty()) {
    support::write_file_atomically(out, support::json_text(result_json(scene, r), 1) + "\n", force);
    std::cout << "result: " << support::printable(out) << "\n";
  }
  return 0;
}

int cmd_simulate(const SimulateArgs& a) {
  check_threads(a.threads, "--threads");
  const Scene scene = load_scene(a.scene);
  support::check_memory(simulate_memory_bytes(scene, a.threads, !a.out.empty()), a.scene + ": the run",
                        std::to_string(scene.light.theta_i.size()) + " incident angles x " +
                            std::to_string(scene.channels.size()) + " channels, " +
                            std::to_string(scene.record.theta_o_bins * (scene.record.histogram_max_k + 2)) +
                            " histogram cells" +
                            (scene.geometry.kind == GeometryKind::microsurface
                                 ? ", " + std::to_string(scene.geometry.grooves) + " grooves"
                                 : std::string()));
  const std::optional<support::Shard> shard = shard_from(a.shard, a.out);
  if (shard && world().distributed())
    throw support::UserError("--shard cannot be combined with mpirun (the ranks split the work among themselves)");
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, {a.scene});  // fail before the work, not after
  if (a.dry_run) return 0;
  auto job = simulate_job(scene, simulate_descriptor(scene));
  job.work.cancel = a.cancel;
  if (shard) {
    const auto part = validation::run_job_part(job, *shard, a.threads, {}, a.cancel);
    if (!part) return interrupted_no_report();
    write_partial(a.out, *part, a.force);
    return 0;
  }
  if (world().distributed()) {
    const auto t0 = std::chrono::steady_clock::now();
    int threads = 0;
    const auto results = run_distributed(job, a.threads, {}, a.cancel, &threads);
    if (!results) return 0;  // not rank 0: its results went there
    SimulationResult r = simulation_from(scene, *results);
    r.threads = threads;
    r.wall_s = support::seconds_since(t0);
    return write_simulation(scene, r, a.out, a.force);
  }
  const SimulationResult r = simulate(scene, a.threads, a.cancel);
  if (r.interrupted) {
    std::cerr << "vgroove: interrupted; no result written\n";
    return kExitInterrupted;
  }
  return write_simulation(scene, r, a.out, a.force);
}

void add_simulate_command(CLI::App& app, Commands& commands) {
  auto* simu = app.add_subcommand("simulate",
                                  "Run a scene (data/scenes/*.json): trace every theta_i with the effects it "
                                  "chooses (Fresnel, histograms, energy per k); print a table, write the "
                                  "result JSON.");
  SimulateArgs& sa = commands.add(simu, cmd_simulate);
  sa.cancel = commands.context().cancel;
  add_text(simu, "scene", sa.scene, "scene spec, e.g. data/scenes/gold_groove.json")->required();
  add_text(simu, "--out", sa.out, "result JSON to write (refuses to overwrite without --force)");
  add_threads(simu, sa.threads);
  simu->add_flag("--force", sa.force, "overwrite an existing result");
  add_shard(simu, sa.shard, "`vgroove merge` joins them");
}

}  // namespace vgroove::app
