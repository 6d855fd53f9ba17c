// vgroove CLI: the subcommands, each a function from parsed options to an exit status.
// main.cpp only parses; these validate values (UserError naming the option) and run.
#pragma once

#include <atomic>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace vgroove::app {

// A groove on the command line: --theta-v-deg (symmetric) or --theta-l-deg with --theta-r-deg.
struct GrooveArgs {
  double theta_v_deg = 90.0;
  double theta_l_deg = 0.0, theta_r_deg = 0.0;
  bool nonsymmetric = false;  // set when --theta-l-deg / --theta-r-deg were given
  bool theta_v_given = false;
};

struct TraceArgs {
  bool dry_run = false;  // check the values, do no work
  GrooveArgs groove;
  double theta_i_deg = 0.0;
  long rays = 1000;
  std::string sampling = "stratified";
  long long seed = 1;   // >= 0
  int max_bounces = 0;  // 0: the default (validation::default_max_bounces for the groove)
  bool json = false;
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) to stop: nothing is printed
};
int cmd_trace(const TraceArgs& a);

struct AnalyticArgs {
  bool dry_run = false;  // check the values, do no work
  GrooveArgs groove;
  double theta_i_deg = 0.0;
  std::string eq6_form = "corrected";
  bool json = false;
};
int cmd_analytic(const AnalyticArgs& a);

// An option the user did not give (any value they can give is checked).
inline constexpr long kUnset = std::numeric_limits<long>::min();
inline constexpr long long kUnsetSeed = std::numeric_limits<long long>::min();

struct ValidateArgs {
  bool dry_run = false;  // check the values, do no work
  std::string suite;
  std::string out;
  long rays = kUnset;           // kUnset: the suite's
  int threads = 0;              // 0: all cores
  std::string sampling;         // empty: the suite's
  std::string eq6_form;         // empty: the suite's
  long long seed = kUnsetSeed;  // kUnsetSeed: the suite's
  std::string model_table;      // a foreign model's bin-integrated lobes ("brdf" suites)
  bool force = false;
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) to stop: no report is written
};
int cmd_validate(const ValidateArgs& a);

struct AccuracyArgs {
  bool dry_run = false;  // check the values, do no work
  std::string suite;
  std::string out;
  std::vector<long> rays{1000, 10000, 100000};
  std::vector<std::string> samplings{"stratified", "random"};
  int threads = 0;
  bool force = false;
  const std::atomic<bool>* cancel = nullptr;
};
int cmd_bench_accuracy(const AccuracyArgs& a);

struct PlotArgs {
  bool dry_run = false;
  std::string report;
  std::string out;  // default: the report's name with .svg
  bool force = false;
};
int cmd_plot(const PlotArgs& a);

struct SimulateArgs {
  bool dry_run = false;  // check the values, do no work
  std::string scene;
  std::string out;
  int threads = 0;  // 0: all cores
  bool force = false;
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) to stop: no result is written
};
int cmd_simulate(const SimulateArgs& a);

// `vgroove bins`: a "brdf" suite's bin layout, for a foreign model's table.
struct BinsArgs {
  bool dry_run = false;
  std::string suite;
  std::string out;  // empty: stdout
  bool force = false;
};
int cmd_bins(const BinsArgs& a);

// `vgroove brdf`: the BRDF at one pair of directions, or at every pair of a JSON file.
struct BrdfArgs {
  bool dry_run = false;
  std::string model = "vgroove";
  std::string ndf = "ggx";
  double alpha = 0.5;
  std::string dim = "3d";
  double theta_i_deg = 0.0, phi_i_deg = 0.0;
  double theta_o_deg = 0.0, phi_o_deg = 180.0;
  bool theta_o_given = false;
  int max_k = 1'000'000;
  bool per_k = false;
  int per_k_max = 16;
  std::string directions;  // JSON file of direction pairs
  bool json = false;
};
int cmd_brdf(const BrdfArgs& a);

// Exit status of a run stopped by Ctrl-C (128 + SIGINT, as a shell reports it).
inline constexpr int kExitInterrupted = 130;

}  // namespace vgroove::app
