// vgroove CLI: the outputs that a run and `vgroove merge` of its parts write alike.
#pragma once

#include "vgroove/app/commands.h"
#include "vgroove/scene/simulate.h"
#include "vgroove/support/work_plan.h"
#include "vgroove/validation/energy_table.h"
#include "vgroove/validation/glass_energy.h"
#include "vgroove/validation/groove_suite_run.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/validate.h"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace vgroove::app {

// "--shard I/N" checked; it needs --out (the partial report). Nothing when no shard was given.
std::optional<support::Shard> shard_from(const std::string& text, const std::string& out);
// Writes a partial report (whole or absent) and says so on stdout.
void write_partial(const std::string& out, const nlohmann::json& part, bool force);

// Energy tables: the .npy files beside `out` (empty when the arrays go inline): OUT.NAME.npy,
// OUT without its .json. Used when `npy` is asked for or an array is too large to inline.
std::vector<std::string> energy_npy_files(const validation::EnergyGrid& g, const std::string& out, bool npy);
// Prints the table; writes the .npy files then the JSON (each whole or absent).
void write_energy_table(const validation::EnergyTable& t, const std::string& out, bool npy, bool force);
// Glass tables (`energy --eta`): prints the table; writes the JSON (whole or absent).
void write_glass_table(const validation::GlassTable& t, const std::string& out, bool force);

// Scenes: the job descriptor of `vgroove simulate`, and its table and result JSON.
nlohmann::json simulate_descriptor(const scene::Scene& scene);
// The table and (out non-empty) the result file; exit status 0, or 1 with one line on stderr and
// nothing written when a theta_i lost more rays than a run may (scene::lost_rays_problem).
int write_simulation(const scene::Scene& scene, const scene::SimulationResult& r, const std::string& out, bool force);

// `bench accuracy`: the table and report of its runs (sampling outer, rays inner), and its parts merged.
void write_accuracy_report(const validation::GrooveSuite& suite, const std::vector<validation::GrooveSuiteRun>& runs,
                           const std::string& out, bool force);
int merge_accuracy(const std::vector<validation::Part>& parts, const MergeArgs& a);

// `vgroove validate` split over shards (--shard) or MPI ranks, and its parts merged.
validation::ValidateOptions validate_options(const ValidateArgs& a);  // the command line's overrides
int validate_split(const ValidateArgs& a);
int merge_validate(const std::vector<validation::Part>& parts, const MergeArgs& a);

}  // namespace vgroove::app
