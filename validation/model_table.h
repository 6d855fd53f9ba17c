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
// of finite numbers >= 0.
#pragma once

#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/check_brdf.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

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
// rays > 0 overrides the suite's.
ModelTableRun run_model_table(const BrdfSuite& suite, const ModelTable& table, long rays, int threads,
                              const std::atomic<bool>* cancel = nullptr);
nlohmann::json model_table_report_json(const BrdfSuite& suite, const ModelTable& table, const ModelTableRun& run);
void print_model_table(std::ostream& os, const BrdfSuite& suite, const ModelTable& table, const ModelTableRun& run);

}  // namespace vgroove::validation
