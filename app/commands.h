// vgroove CLI: the subcommands, each a function from parsed options to an exit status, and the
// function that registers its subcommand and flags (add_*_command, in the same cmd_*.cpp; run_cli
// calls them in the order of `vgroove --help`). The cmd_* functions validate values (UserError
// naming the option) and run.
#pragma once

#include "vgroove/analytic/sampling_3d.h"

#include <atomic>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace vgroove::app {

class Commands;  // cli_options.h

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
void add_trace_command(CLI::App& app, Commands& commands);

struct AnalyticArgs {
  bool dry_run = false;  // check the values, do no work
  GrooveArgs groove;
  double theta_i_deg = 0.0;
  std::string eq6_form = "corrected";
  bool json = false;
};
int cmd_analytic(const AnalyticArgs& a);
void add_analytic_command(CLI::App& app, Commands& commands);

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
  std::string shard;                          // "I/N": write the I-th of N parts as a partial report
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) to stop: no report is written
};
int cmd_validate(const ValidateArgs& a);
void add_validate_command(CLI::App& app, Commands& commands);

struct AccuracyArgs {
  bool dry_run = false;  // check the values, do no work
  std::string suite;
  std::string out;
  std::vector<long> rays{1000, 10000, 100000};
  std::vector<std::string> samplings{"stratified", "random"};
  int threads = 0;
  bool force = false;
  std::string shard;  // "I/N": write the I-th of N parts as a partial report
  const std::atomic<bool>* cancel = nullptr;
};
int cmd_bench_accuracy(const AccuracyArgs& a);
void add_bench_accuracy_command(CLI::App& bench, Commands& commands);  // under `vgroove bench`

struct PlotArgs {
  bool dry_run = false;  // check the report, draw nothing
  std::string report;
  std::string out;     // default: the report's name without .json; a suffix per figure
  std::string format;  // png (default), svg or pdf
  bool force = false;
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) before the script starts: it does not start
};
int cmd_plot(const PlotArgs& a);
void add_plot_command(CLI::App& app, Commands& commands);

// `vgroove report`: one self-contained HTML page of the reports in a directory (html_report.py).
struct ReportArgs {
  bool dry_run = false;  // find the script, start nothing
  std::string directory;
  std::string out;  // default: DIRECTORY/index.html
  bool force = false;
  bool no_draw = false;  // name plots that are missing beside their reports instead of drawing them
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) before the script starts: it does not start
};
int cmd_report(const ReportArgs& a);
void add_report_command(CLI::App& app, Commands& commands);

struct SimulateArgs {
  bool dry_run = false;  // check the values, do no work
  std::string scene;
  std::string out;
  int threads = 0;  // 0: all cores
  bool force = false;
  std::string shard;                          // "I/N": write the I-th of N parts as a partial report
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) to stop: no result is written
};
int cmd_simulate(const SimulateArgs& a);
void add_simulate_command(CLI::App& app, Commands& commands);

// Importance sampling of the symmetric V-groove BRDF: n directions, their chi-square against the
// sampler's pdf and the weights' statistics.
struct SampleArgs {
  bool dry_run = false;  // check the values, do no work
  std::string ndf = "ggx";
  double alpha = 0.5;
  double theta_i_deg = 30.0;
  long n = 100000;
  std::string strategy = "vndf";
  std::string dim = "3d";
  std::string model = "vgroove";       // or "vgroove-nonsymmetric" (Eq. 23), "walter" (analytic/walter_sampling.h)
  int max_k = analytic::kSamplerMaxK;  // analytic::kNonsymmetricSamplerMaxK for that model, unless given
  bool max_k_given = false;
  bool strategy_given = false;
  // walter only: eta = n_far / n_near (not 1) and the G2 ("smith", "smith_separable", "vcavity").
  double eta = 1.5;
  bool eta_given = false;
  std::string masking = "smith_separable";
  bool masking_given = false;
  long long seed = 1;
  int cos_bins = 8, phi_bins = 16, theta_bins = 36;
  std::string out;
  bool force = false;
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) to stop: nothing is printed or written
};
int cmd_sample(const SampleArgs& a);
void add_sample_command(CLI::App& app, Commands& commands);

// `vgroove bins`: a "brdf" suite's bin layout, for a foreign model's table.
struct BinsArgs {
  bool dry_run = false;
  std::string suite;
  std::string out;  // empty: stdout
  bool force = false;
};
int cmd_bins(const BinsArgs& a);
void add_bins_command(CLI::App& app, Commands& commands);

// `vgroove brdf`: the BRDF at one pair of directions, or at every pair of a JSON file.
struct BrdfArgs {
  bool dry_run = false;
  std::string model = "vgroove";
  std::string ndf = "ggx";
  double alpha = 0.5;
  std::string dim = "3d";
  double theta_i_deg = 0.0, phi_i_deg = 0.0;
  double theta_o_deg = 0.0, phi_o_deg = 180.0;
  bool theta_o_given = false, phi_i_given = false, phi_o_given = false;
  // vgroove-nonsymmetric only: the roughness across the --alpha axis (3D, GGX and Beckmann) and the
  // partner law ("independent": Eq. 20; "symmetric": B = A).
  double alpha_y = 0.0;
  bool alpha_y_given = false;
  std::string partner = "independent";
  bool partner_given = false;
  // walter only: eta = n_far / n_near and the G2 ("smith", "smith_separable", "vcavity").
  double eta = 1.5;
  bool eta_given = false;
  std::string masking = "smith_separable";
  bool masking_given = false;
  int max_k = 1'000'000;  // when not given: analytic::default_max_k (every order in 3D, 4096 flatland, 64 nonsymmetric)
  bool max_k_given = false;
  bool per_k = false;
  int per_k_max = 16;
  std::string directions;  // JSON file of direction pairs
  bool json = false;
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) to stop between pairs: nothing is printed
};
int cmd_brdf(const BrdfArgs& a);
void add_brdf_command(CLI::App& app, Commands& commands);

// `vgroove energy`: exact energy tables E(mu, alpha) per bounce order (validation/energy_table.h).
struct EnergyArgs {
  bool dry_run = false;
  std::vector<std::string> ndfs{"ggx", "beckmann", "phong"};
  std::vector<std::string> dims{"flatland", "3d"};
  std::vector<double> mu;     // empty: --mu-points
  int mu_points = 8;          // midpoints of (0, 1]
  std::vector<double> alpha;  // empty: --alpha-points
  int alpha_points = 8;       // midpoints of (0, 1]
  long long rays = 100000;
  long long seed = 1;
  int max_k = 16;
  int threads = 0;
  std::string out;
  bool npy = false;   // arrays as .npy files beside the JSON whatever their size
  std::string shard;  // "I/N": write the I-th of N parts as a partial report
  bool force = false;
  const std::atomic<bool>* cancel = nullptr;
  // --audit: the energy audit (validation/energy_audit.h) over the grid; --rays: walk paths per cell.
  bool audit = false;
  // --export BASE: tables engines can load (validation/energy_export.h), BASE.json, .npz, .h, .png, .exr.
  std::string export_base;
  std::string layout = "cycles";
  int size = 32;
  std::string masking = "smith";      // smith, smith_separable, vcavity (without --ms-reference)
  std::string ms_reference = "none";  // none, vgroove, smith_walk
  std::vector<double> ms_F0;          // empty: 0.04, 0.25, 0.5, 0.75, 1
  std::vector<std::string> formats{"json", "npz", "h", "png", "exr"};
  // --lobe-shape: the compensated lobes' shape (validation/energy_lobe_shape.h); --rays per theta_i.
  bool lobe_shape = false;
  // --eta: rough glass tables E_R, E_T (validation/glass_energy.h), for light from --side.
  std::vector<double> eta;
  std::vector<std::string> sides{"above", "below"};
  bool sides_given = false;
  int grooves = 10000;
  bool grooves_given = false;
  std::string reference = "vgroove";  // --eta's: vgroove (traced surfaces) or smith_walk
  bool reference_given = false;
};
int cmd_energy(const EnergyArgs& a);
// Its --audit and --export (app/cmd_energy_tables.cpp).
int cmd_energy_audit(const EnergyArgs& a);
int cmd_energy_export(const EnergyArgs& a);
// Its --lobe-shape (app/cmd_energy_lobe_shape.cpp).
int cmd_energy_lobe_shape(const EnergyArgs& a);
// Its --eta glass tables (app/cmd_energy_glass.cpp).
int cmd_energy_glass(const EnergyArgs& a);
void add_energy_command(CLI::App& app, Commands& commands);

// `vgroove merge`: partial reports of one run (`--shard I/N`) into the run's report.
struct MergeArgs {
  bool dry_run = false;
  std::vector<std::string> parts;
  std::string out;
  bool npy = false;  // energy tables: arrays as .npy files
  bool force = false;
};
int cmd_merge(const MergeArgs& a);
void add_merge_command(CLI::App& app, Commands& commands);

// Exit status of a run stopped by Ctrl-C (128 + SIGINT, as a shell reports it).
inline constexpr int kExitInterrupted = 130;

}  // namespace vgroove::app
