// vgroove validation: exact energy tables of V-groove surfaces: the directional albedo E(mu,
// alpha) per bounce order k (what renderers precompute for energy compensation: Kulla and Conty
// 2017, Turquin 2019), measured by exact tracing. A cell is (NDF, dimension, alpha, mu); its rays
// each fall into a groove of their own (sim/ndf_grooves.h), so E_k = n_k / N with standard error
// sqrt(E_k (1 - E_k) / N). Beside it the analytic model's table (Lee et al. 2018, Eq. 16-17,
// analytic/lobe_3d.h, analytic/brdf_flatland.h) and Cook-Torrance's albedo (Eq. 1-3). One work
// unit per cell (work_run.h): tables shard and merge exactly.
// Tests: tests/cluster/shards_test.sh and tests/cluster/mpi_test.sh (energy: shards and ranks
// merge to the one-process table); no unit test holds E_k against the model by name.
// Derivation: docs/derivations/energy_compensation.md.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/ndf_grooves.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/work_plan.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/work_run.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

struct EnergyCell {
  NdfKind ndf = NdfKind::ggx;
  SurfaceDim dim = SurfaceDim::three_d;
  double alpha = 0.5;
  double mu = 1.0;  // cos theta_i
};

struct EnergyGrid {
  std::vector<NdfKind> ndfs{NdfKind::ggx, NdfKind::beckmann, NdfKind::phong};
  std::vector<SurfaceDim> dims{SurfaceDim::flatland, SurfaceDim::three_d};
  std::vector<double> alphas;  // each in (0, 2]
  std::vector<double> mus;     // each in (0, 1]
  long long rays = 100000;     // per cell
  std::uint64_t seed = 1;
  int max_k = 16;
  std::size_t cells() const { return ndfs.size() * dims.size() * alphas.size() * mus.size(); }
  // Order: ndf, dimension, alpha, mu (innermost).
  EnergyCell cell_at(std::size_t c) const;
};

// (i + 1/2) / n for i = 0..n-1: the midpoints of n equal steps of (0, 1].
std::vector<double> midpoints(int n);
// A UserError naming the flag for a value out of range: --mu in (0, 1], --alpha in (0, 2], ...
void check_energy_grid(const EnergyGrid& g);

// The analytic side of a cell: E_k per row (rows k = 0..max_k, max_k + 1 for k > max_k), the
// albedo (their sum, 1 with F = 1 to quadrature accuracy) and Cook-Torrance's albedo.
struct EnergyModel {
  std::vector<double> by_k;
  double albedo = 0.0;
  double cook_torrance = 0.0;
};
EnergyModel energy_model(const EnergyCell& c, int max_k);

// The work of a table (work_run.h).
struct EnergyWork {
  struct Context {};
  using Tally = sim::BounceCounts;
  using Fixed = EnergyModel;
  EnergyGrid grid;
  std::shared_ptr<const Context> prepare(std::size_t) const { return std::make_shared<Context>(); }
  sim::NdfGrooveOptions options(std::size_t cell) const;
  Tally run_chunks(const Context&, std::size_t cell, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t cell) const { return energy_model(grid.cell_at(cell), grid.max_k); }
  static void merge(Tally& into, const Tally& from) { into.merge(from); }
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed& f);
  Tally read_tally(support::JsonObject& j, std::size_t cell, const std::vector<ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject& j, std::size_t cell) const;
};

nlohmann::json energy_grid_json(const EnergyGrid& g);
EnergyGrid energy_grid_from_json(const nlohmann::json& j, const std::string& where);
// The table's job: units with cost estimates from a short pilot trace of every cell.
Job<EnergyWork> energy_job(const EnergyGrid& g);

struct EnergyCellResult {
  EnergyCell cell;
  sim::BounceCounts counts;
  EnergyModel model;
};
struct EnergyTable {
  EnergyGrid grid;
  std::vector<EnergyCellResult> cells;
  int threads = 1;
  double wall_s = 0.0;
};
EnergyTable energy_table_from(const EnergyGrid& g, std::vector<UnitResult<EnergyWork>> results);

// Every cell in this process; nothing when *cancel was set.
std::optional<EnergyTable> run_energy_table(const EnergyGrid& g, int threads, const support::ProgressFn& progress = {},
                                            const std::atomic<bool>* cancel = nullptr);

// The arrays of a table, indexed [ndf][dimension][alpha][mu][row] (rows k = 1..max_k and one
// for k > max_k) or [ndf][dimension][alpha][mu]: name, shape, values (row-major).
struct EnergyArray {
  std::string name;
  std::vector<std::size_t> shape;
  std::vector<double> values;
};
std::vector<EnergyArray> energy_arrays(const EnergyTable& t);
// Arrays of at most this many values are written inline in the JSON; larger ones as .npy files.
inline constexpr std::size_t kInlineArrayValues = 65536;

// The table's JSON: provenance, grid, definitions, summary and the arrays, inline or, when
// `npy_files` names a file per array (same order as energy_arrays), as references to them.
nlohmann::json energy_table_json(const EnergyTable& t, const std::vector<std::string>& npy_files = {});
void print_energy_table(std::ostream& os, const EnergyTable& t);

}  // namespace vgroove::validation
