// vgroove validation: the suites of kind "brdf" (Lee et al. 2018, Fig. 11: the BRDF against the
// light traced in procedural rough surfaces; the white furnace is validation/furnace_suite.h).
// A suite is the grid ndf x alpha x theta_i x dimension; each case traces N rays on a surface of
// G grooves (sim/microsurface.h, sim/microsurface3d.h) and compares the exit histograms (total and
// per k) with the BRDF integrated over the same bins (analytic/brdf_flatland.h, brdf_3d.h).
// Thresholds come from the sample count: with v_b = p_b (1 - p_b) (1/N + 1/G), a correct model's
// L1 error has mean about sum_b sqrt(2 v_b / pi) and sd about sqrt(sum_b (1 - 2/pi) v_b); the
// threshold is expected + sigmas x sd + model_tolerance.
// Tests: tests/validation/brdf_suite_test.cpp (BrdfSuite.ExpectedL1MatchesMultinomialHistograms,
// BrdfSuite.FlatlandThresholdHasPowerAgainstSmallErrors, BrdfSuite.ThreeDCasePassesWithCoarseBins,
// BrdfSuite.BadSpecsNameTheFieldAndRange, BrdfSuite.ShippedSuitesParse).
// Derivation: docs/derivations/validation.md.
#pragma once

#include "vgroove/analytic/ndf.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/case_surface.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/lobe_outcome.h"
#include "vgroove/validation/work_run.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

struct BrdfCase {
  analytic::NdfKind ndf = analytic::NdfKind::ggx;
  double alpha = 0.5;
  double theta_i = 0.0;  // radians, >= 0
  SurfaceDim dim = SurfaceDim::flatland;
};

// Case c of the grid dimension x ndf x alpha x theta_i (theta_i innermost), as the "brdf" and
// "furnace" suites number their cases.
BrdfCase grid_case(const std::vector<analytic::NdfKind>& ndfs, const std::vector<double>& alphas,
                   const std::vector<double>& theta_i, const std::vector<SurfaceDim>& dims, std::size_t c);

struct BrdfSuite {
  std::string file, name, description;
  std::string kind;  // "brdf" (Fig. 11: lobes and albedo)
  std::vector<analytic::NdfKind> ndfs;
  std::vector<double> alphas;
  std::vector<double> theta_i;  // radians
  std::vector<SurfaceDim> dims;
  long rays = 1000000;
  int grooves = 250000;
  std::uint64_t seed = 1;
  int flatland_bins = 90;  // theta_o over (-90, 90) deg
  int theta_bins = 30;     // 3D: theta_o over [0, 90) deg
  int phi_bins = 24;       // 3D: phi_o, centred on the plane of incidence
  int max_k = 16;
  double sigmas = 5.0;
  double model_tolerance_flatland = 1e-6;
  double model_tolerance_3d = 1e-4;
  // The traced surface: "vgroove" (grooves above) or "heightfield": `fields` random fields of
  // field_size^2 cells, correlation length in cells (check_brdf.h's options and ranges; 3D, beckmann
  // or ggx; held against a model table only).
  CheckSurface surface = CheckSurface::vgroove;
  int field_size = 256;
  double correlation_length = 8.0;
  int fields = 4;
  std::size_t cases() const { return ndfs.size() * alphas.size() * theta_i.size() * dims.size(); }
  // Order: dimension, ndf, alpha, theta_i (innermost).
  BrdfCase case_at(std::size_t c) const;
};

struct BrdfOutcome : LobeOutcome {
  BrdfCase c;
  // Rays still inside after the tracer's bounce limit (10^5 reflections): grooves narrower than
  // pi / 10^5 rad, which only the roughest Phong surfaces (alpha >= 1.5, exponent < -1) draw often.
  std::int64_t in_flight = 0;
  double albedo_single = 0.0;        // Cook-Torrance (V-cavity G)
  std::vector<double> plane_single;  // its lobe on the plane of incidence (plane_sim's points)
};
inline constexpr int kPlotK = 4;

struct BrdfRun {
  std::vector<BrdfOutcome> cases;
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
};

BrdfSuite parse_brdf_suite(const nlohmann::json& j, const std::string& file);
// An upper bound of the memory run_brdf_suite needs (support/memory.h): per worker a surface of
// `grooves` grooves, its tallies and lobes; per case its outcome, and with `report` its JSON.
double brdf_run_memory_bytes(const BrdfSuite& suite, int threads, bool report);
// rays > 0 overrides the suite's.
BrdfRun run_brdf_suite(const BrdfSuite& suite, long rays, int threads, const support::ProgressFn& progress = {},
                       const std::atomic<bool>* cancel = nullptr);
// `cancel` (may be null) is read between chunks of rays and inside the 3D lobes' quadrature; once
// set the outcome is incomplete.
BrdfOutcome run_brdf_case(const BrdfSuite& suite, const BrdfCase& c, long rays, support::CancelFlag cancel = nullptr);

// The suite as work items (work_run.h): a unit per case, its rays in chunks (sim::kRaysPerChunk,
// the procedural surface's streams, case_surface.h), the analytic lobes its fixed part. The traced
// histograms of flatland (theta_o) and 3D ((theta_o, phi_o)) have the same layout: rows k, bins.
struct BrdfModel {
  std::vector<double> by_k, hist, hist_by_k;  // Lee et al. 2018 (flatland lobe; Eq. 16-17 in 3D)
  std::vector<double> single_hist;            // Cook-Torrance, V-cavity G
  double albedo = 0.0, single_albedo = 0.0;
  double wall_s = 0.0;  // a timing
};
struct BrdfWork {
  using Context = CaseSurface;
  using Tally = BinnedTally;
  using Fixed = BrdfModel;
  BrdfSuite suite;
  long rays = 0;                              // per case
  const std::atomic<bool>* cancel = nullptr;  // polled between chunks and inside the 3D lobes
  std::shared_ptr<const Context> prepare(std::size_t c) const;
  Tally run_chunks(const Context& ctx, std::size_t c, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t c) const;
  static void merge(Tally& into, const Tally& from);
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed& f);
  Tally read_tally(support::JsonObject& j, std::size_t c, const std::vector<ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject& j, std::size_t c) const;
};
// `descriptor`: what identifies the run in its parts (partial_report.h); rays > 0 overrides the suite's.
Job<BrdfWork> brdf_job(const BrdfSuite& suite, long rays, nlohmann::json descriptor);
// The run from every case's merged results (each case compared with its model).
BrdfRun brdf_run_from(const BrdfSuite& suite, long rays, const std::vector<UnitResult<BrdfWork>>& results);
nlohmann::json brdf_report_json(const BrdfSuite& suite, const BrdfRun& run);
void print_brdf_table(std::ostream& os, const BrdfSuite& suite, const BrdfRun& run);

}  // namespace vgroove::validation
