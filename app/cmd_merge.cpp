#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"

#include "vgroove/app/outputs.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_table.h"
#include "vgroove/validation/glass_energy.h"
#include "vgroove/validation/partial_report.h"

#include <algorithm>
#include <iostream>

namespace vgroove::app {

using namespace validation;

namespace {

int merge_energy(const std::vector<Part>& parts, const MergeArgs& a) {
  const EnergyGrid g = energy_grid_from_json(parts.front().header.job.at("input"), parts.front().file);
  if (!a.out.empty())
    for (const std::string& f : energy_npy_files(g, a.out, a.npy)) support::check_writable_target(f, a.force, a.parts);
  if (a.dry_run) return 0;
  EnergyTable t = energy_table_from(g, merge_job_parts(energy_job(g), parts));
  for (const Part& p : parts) t.threads += p.header.threads, t.wall_s = std::max(t.wall_s, p.header.wall_s);
  t.threads -= 1;  // energy_table_from starts at 1
  write_energy_table(t, a.out, a.npy, a.force);
  return 0;
}

int merge_glass(const std::vector<Part>& parts, const MergeArgs& a) {
  const GlassGrid g = glass_grid_from_json(parts.front().header.job.at("input"), parts.front().file);
  if (a.dry_run) return 0;
  GlassTable t = glass_table_from(g, merge_job_parts(glass_job(g), parts));
  t.threads = 0;
  for (const Part& p : parts) t.threads += p.header.threads, t.wall_s = std::max(t.wall_s, p.header.wall_s);
  write_glass_table(t, a.out, a.force);
  return 0;
}

int merge_simulate(const std::vector<Part>& parts, const MergeArgs& a) {
  const std::string file = input_file_of(parts.front());
  const scene::Scene sc = scene::load_scene(file);
  validation::check_input_unchanged(parts.front().header.job, {file}, parts.front().file);
  if (a.dry_run) return 0;
  scene::SimulationResult r =
      scene::simulation_from(sc, merge_job_parts(scene::simulate_job(sc, simulate_descriptor(sc)), parts));
  for (const Part& p : parts) r.threads += p.header.threads, r.wall_s = std::max(r.wall_s, p.header.wall_s);
  return write_simulation(sc, r, a.out, a.force);
}

}  // namespace

int cmd_merge(const MergeArgs& a) {
  std::vector<Part> parts;
  for (const std::string& f : a.parts) parts.push_back(read_part(f));
  parts = check_parts(std::move(parts));
  // The parts and the job's input file are never overwritten by the merged report.
  std::vector<std::string> inputs = a.parts;
  if (const auto& job = parts.front().header.job; !job.value("input_file", "").empty())
    inputs.push_back(input_file_of(parts.front()));
  if (!a.out.empty()) support::check_writable_target(a.out, a.force, inputs);
  const std::string command = parts.front().header.job.value("command", "");
  if (command == "energy") return merge_energy(parts, a);
  if (command == "energy --eta") return merge_glass(parts, a);
  if (command == "simulate") return merge_simulate(parts, a);
  if (command == "bench accuracy") return merge_accuracy(parts, a);
  if (command == "validate") return merge_validate(parts, a);
  throw support::UserError("merge: " + parts.front().file + " is a part of `" + command +
                           "`, which this build cannot merge");
}

void add_merge_command(CLI::App& app, Commands& commands) {
  auto* merge = app.add_subcommand(
      "merge",
      "Join the partial reports of one sharded run (--shard 1/N ... N/N) into the report the run gives in one "
      "process, bit for bit (timings aside). Refuses parts of different runs, versions or splits, missing or "
      "repeated shards, and damaged files.");
  MergeArgs& ma = commands.add(merge, cmd_merge);
  add_text(merge, "parts", ma.parts, "partial reports, in any order")->required();
  add_text(merge, "--out", ma.out, "report to write (refuses to overwrite without --force)");
  merge->add_flag("--npy", ma.npy, "energy tables: the arrays as .npy files beside the JSON");
  merge->add_flag("--force", ma.force, "overwrite existing files");
}

}  // namespace vgroove::app
