// vgroove validation: the suite of kind "table2" (Lee et al. 2018, Table 2).
#pragma once

#include "vgroove/analytic/ndf.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
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
nlohmann::json table2_report_json(const Table2Suite& suite, const Table2Run& run);
void print_table2(std::ostream& os, const Table2Suite& suite, const Table2Run& run);

}  // namespace vgroove::validation
