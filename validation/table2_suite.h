// vgroove validation: the suite of kind "table2" (Lee et al. 2018, Table 2).
#pragma once

#include "vgroove/analytic/ndf.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/sim/ndf_grooves.h"
#include "vgroove/validation/work_run.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

// Table 2: the paper's maximum bounce counts at percentiles of D, recomputed (analytic/
// bounce_percentiles.h) under each reading of "percentile", and the bounce counts traced on
// procedural 3D surfaces at normal incidence beside them.
struct Table2Suite {
  std::string file, name, description, source;
  std::vector<analytic::NdfKind> ndfs;
  std::vector<double> alphas;
  std::vector<double> percentiles;  // fractions in (0, 1)
  std::vector<int> paper;           // [row (percentile)][ndf][alpha], row-major
  long rays = 200000;
  int grooves = 100000;
  std::uint64_t seed = 1;
};
struct Table2Run {
  std::vector<int> ours;                       // the reading that reproduces the table
  std::vector<std::vector<int>> alternatives;  // per other reading, same layout
  std::vector<int> traced;                     // percentile of the traced bounce counts
  long rays = 0;                               // traced per surface (the suite's, or --rays)
  int agree = 0;
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;  // all entries agree
};
Table2Suite parse_table2_suite(const nlohmann::json& j, const std::string& file);
// An upper bound of the memory run_table2_suite needs (support/memory.h): a 3D surface per worker.
double table2_run_memory_bytes(const Table2Suite& suite, int threads);
Table2Run run_table2_suite(const Table2Suite& suite, long rays, int threads, const std::atomic<bool>* cancel = nullptr);

// The traced column as work items (work_run.h): a unit per (ndf, alpha) surface (ndf outer), its
// rays at normal incidence in chunks; bounce counts per k (rows up to kTable2MaxK, one beyond).
inline constexpr int kTable2MaxK = 1000;
struct Table2Work {
  struct Context {
    sim::Microsurface3d surface;
  };
  struct Fixed {};
  using Tally = sim::BounceCounts;
  Table2Suite suite;
  long rays = 0;
  const std::atomic<bool>* cancel = nullptr;  // polled between chunks
  std::shared_ptr<const Context> prepare(std::size_t unit) const;
  Tally run_chunks(const Context& ctx, std::size_t unit, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t) const { return {}; }
  static void merge(Tally& into, const Tally& from) { into.merge(from); }
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed&) { return nlohmann::json::object(); }
  Tally read_tally(support::JsonObject& j, std::size_t unit, const std::vector<ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject&, std::size_t) const { return {}; }
};
// rays > 0 overrides the suite's.
Job<Table2Work> table2_job(const Table2Suite& suite, long rays, nlohmann::json descriptor);
// The table (the rule under each reading, and the traced percentiles from the merged counts).
// `cancel` (may be null) is read between the model's entries; once set the run is interrupted.
Table2Run table2_run_from(const Table2Suite& suite, const std::vector<UnitResult<Table2Work>>& results,
                          const std::atomic<bool>* cancel = nullptr);
nlohmann::json table2_report_json(const Table2Suite& suite, const Table2Run& run);
void print_table2(std::ostream& os, const Table2Suite& suite, const Table2Run& run);

}  // namespace vgroove::validation
