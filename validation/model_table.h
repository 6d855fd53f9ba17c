// vgroove validation: a foreign model held against the simulation without C++: vgroove writes a
// "brdf" suite's bin layout (`vgroove bins SUITE --out layout.json`), the user fills in their
// model's bin-integrated lobe per case (a model table), and `vgroove validate SUITE --model-table
// FILE` holds it against the traced surfaces with the suite's thresholds (check_brdf.h's
// comparison: normalized-lobe L1, flux L1 and albedo, each against its sample-count bound).
//
// Model table (schema docs/schemas/model_table.schema.json):
//   {"kind": "model_table", "suite": "<the suite's name>", "model": "<free text>",
//    "cases": [{"case": 0, "ndf": "ggx", "alpha": 0.3, "theta_i_deg": 0, "dimension": "3d",
//               "flux": [<fraction of the incident flux in each bin, in the layout's order>]}, ...]}
// Every case of the suite exactly once; ndf, alpha, theta_i_deg and dimension must repeat the
// layout's (a table made for another suite is refused); each flux a list of the layout's length
// of finite numbers >= 0. A suite with "surface": "heightfield" is traced on check_brdf's fields.
// Tests: tests/validation/model_table_test.cpp, tests/validation/model_table_heightfield_test.cpp.
#pragma once

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/check_brdf.h"
#include "vgroove/validation/work_run.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

// check_brdf's options for case c of a suite (rays > 0 overriding the suite's): its ndf, alpha,
// dimension, rays, grooves, seed, bins, sigmas, 3D tolerance and surface with its fields, and
// theta_i_deg the suite's whole list, so that case c's rays are those check_brdf draws at incidence
// c % theta_i.size() (check_field_trace): a table and check_brdf see the same fields and rays.
CheckBrdfOptions case_check_options(const BrdfSuite& suite, std::size_t c, long rays);
// With surface heightfield: check_options on every case (ranges of fields, field_size and
// correlation_length, 3D, beckmann or ggx, a field that fits memory), throwing support::UserError
// "<file>: surface heightfield: <what>" (one line); nothing for the V-groove surface.
void check_suite_surface(const BrdfSuite& suite, long rays);

// The layout of a "brdf" suite: its cases, the bins' edges and order, the frame.
nlohmann::json bin_layout_json(const BrdfSuite& suite);

struct ModelTable {
  std::string file;
  std::string model;
  std::vector<std::vector<double>> flux;  // per suite case, in suite order
};
// Throws support::UserError naming the file, the JSON path and what was expected.
ModelTable parse_model_table(const nlohmann::json& j, const std::string& file, const BrdfSuite& suite);

struct ModelTableRun {
  std::vector<CheckBrdfCase> cases;  // in suite order
  int threads = 1;
  long rays = 0;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
};
// The run as work items (work_run.h): a unit per case, its rays in chunks (sim::kRaysPerChunk,
// the procedural surface's streams, as trace_lobes draws them); the tally is the case's traced
// histogram, the model the table's lobe. With surface heightfield a unit per case and field
// (unit c x fields + r: field r, check_field, its rays check_field_trace's in chunks of
// sim::kHeightfieldRaysPerChunk), so the per-field tallies give the fields' spread as check_brdf's.
// rays > 0 overrides the suite's; `cancel` (may be null) is polled between chunks.
struct LobeTally {
  std::vector<std::int64_t> hist;  // escaped rays per bin
  std::int64_t rays = 0;
  double thread_s = 0.0;  // time spent tracing (a timing: never compared)
};
struct ModelTableSurface {
  CaseSurface grooves;            // surface vgroove
  sim::HeightfieldSurface field;  // surface heightfield
};
struct ModelTableWork {
  using Context = ModelTableSurface;
  struct Fixed {};
  using Tally = LobeTally;
  BrdfSuite suite;
  long rays = 0;
  const std::atomic<bool>* cancel = nullptr;
  std::shared_ptr<const Context> prepare(std::size_t c) const;
  Tally run_chunks(const Context& ctx, std::size_t c, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t c) const;
  static void merge(Tally& into, const Tally& from);
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed&) { return nlohmann::json::object(); }
  Tally read_tally(support::JsonObject& j, std::size_t c, const std::vector<ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject& j, std::size_t c) const;
  // Unit u's case and field (field 0 on the V-groove surface).
  std::size_t case_of(std::size_t u) const;
  int field_of(std::size_t u) const;
};
Job<ModelTableWork> model_table_job(const BrdfSuite& suite, long rays, nlohmann::json descriptor,
                                    const std::atomic<bool>* cancel = nullptr);
ModelTableRun model_table_run_from(const BrdfSuite& suite, const ModelTable& table, long rays,
                                   const std::vector<UnitResult<ModelTableWork>>& results);
// rays > 0 overrides the suite's.
ModelTableRun run_model_table(const BrdfSuite& suite, const ModelTable& table, long rays, int threads,
                              const std::atomic<bool>* cancel = nullptr);
nlohmann::json model_table_report_json(const BrdfSuite& suite, const ModelTable& table, const ModelTableRun& run);
void print_model_table(std::ostream& os, const BrdfSuite& suite, const ModelTable& table, const ModelTableRun& run);

}  // namespace vgroove::validation
