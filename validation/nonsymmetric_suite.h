// vgroove validation: the suite of kind "nonsymmetric_brdf" (Lee et al. 2018, Sec. 5.2-5.3, Fig.
// 7-8): the nonsymmetric V-groove BRDF and anisotropic roughness against light traced exactly in
// procedural nonsymmetric microsurfaces (sim/microsurface_nonsymmetric.h). Cases: an isotropic
// grid ndf x alpha x theta_i x dimension and an anisotropic 3D block (alpha_x, alpha_y, phi_i,
// partner law). Each compares the traced (k, bin) fractions and the lobe with the model's
// push-forward lobe (analytic/lobe_nonsymmetric.h) within expected L1 + sigmas sd +
// model_tolerance (validation/histogram_metrics.h), and reports whether the other partner law's
// model is rejected (Fig. 8, measured). Reciprocity: worst relative asymmetry below 1e-8.
// Tests: tests/validation/nonsymmetric_suite_test.cpp (NonsymmetricSuite.SmallRunPassesAndRejectsTheSymmetricModel,
// NonsymmetricSuite.BadSpecsNameTheFieldAndRange, NonsymmetricSuite.ShippedSuiteParses).
// Derivation: docs/derivations/validation.md.
#pragma once

#include "vgroove/analytic/ndf.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/item_work.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

struct NonsymmetricCase {
  analytic::NdfKind ndf = analytic::NdfKind::beckmann;
  double alpha_x = 0.5, alpha_y = 0.5;
  double theta_i = 0.0;  // radians
  double phi_i = 0.0;    // radians: the light's azimuth over the alpha_x axis (3D)
  SurfaceDim dim = SurfaceDim::flatland;
  bool symmetric = false;    // partner law: B = A instead of Eq. (20)
  bool anisotropic = false;  // from the anisotropic block
};

struct NonsymmetricSuite {
  std::string file, name, description;
  // The isotropic grid.
  std::vector<analytic::NdfKind> ndfs;
  std::vector<double> alphas;
  std::vector<double> theta_i;  // radians
  std::vector<SurfaceDim> dims;
  // The anisotropic block (3D; empty when absent).
  std::vector<analytic::NdfKind> aniso_ndfs;
  std::vector<double> alpha_x, alpha_y, aniso_theta_i, phi_i;  // radians
  std::vector<bool> partners_symmetric;                        // false: independent, true: symmetric
  long rays = 100000;
  int grooves = 100000;
  std::uint64_t seed = 1;
  int flatland_bins = 90;
  int theta_bins = 15;
  int phi_bins = 12;
  int max_k = 16;
  int plane_k = 4;
  int reciprocity_pairs = 20;
  double sigmas = 5.0;
  double model_tolerance_flatland = 1e-3;
  double model_tolerance_3d = 3e-3;
  std::vector<NonsymmetricCase> cases() const;  // the grid (dimension, ndf, alpha, theta_i), then the block
};

struct NonsymmetricOutcome : LobeOutcome {
  NonsymmetricCase c;
  double l1_other = 0.0;        // the traced lobe against the other partner law's model (normalized)
  bool other_rejected = false;  // l1_other > l1_threshold
  std::vector<double> by_k_other, plane_other;
  std::vector<std::vector<double>> plane_other_k;  // k = 1..plane_k
};

struct ReciprocityRow {
  analytic::NdfKind ndf = analytic::NdfKind::beckmann;
  double alpha_x = 0.5, alpha_y = 0.5;
  SurfaceDim dim = SurfaceDim::three_d;
  int pairs = 0, evaluated = 0;  // pairs, and (pair, k) values above 1e-300 compared
  double worst = 0.0;            // largest |rho(i, o) - rho(o, i)| / max
  bool pass = false;             // worst <= 1e-8
};

// Their members for a shard part (outcome_fields.h); the case and the row's surface are the suite's.
template <class F>
void fields(NonsymmetricOutcome& o, F&& f) {
  lobe_fields(o, f);
  f("l1_other", o.l1_other), f("other_rejected", o.other_rejected), f("by_k_other", o.by_k_other);
  f("plane_other", o.plane_other), f("plane_other_k", o.plane_other_k);
}
template <class F>
void fields(ReciprocityRow& r, F&& f) {
  f("evaluated", r.evaluated), f("worst", r.worst), f("pass", r.pass);
}
// One item of the run (item_work.h): a case, then a reciprocity row (the one it is set).
struct NonsymmetricItem {
  std::optional<NonsymmetricOutcome> outcome;
  std::optional<ReciprocityRow> reciprocity;
};
template <class F>
void fields(NonsymmetricItem& o, F&& f) {
  f("case", o.outcome), f("reciprocity", o.reciprocity);
}

struct NonsymmetricRun {
  std::vector<NonsymmetricOutcome> cases;
  std::vector<ReciprocityRow> reciprocity;
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
};

NonsymmetricSuite parse_nonsymmetric_suite(const nlohmann::json& j, const std::string& file);
// An upper bound of the memory the run needs (support/memory.h): per worker a surface of `grooves`
// grooves, its tallies and the two models' lobes over the joint (k, bin) cells; per case its
// outcome, and with `report` its JSON.
double nonsymmetric_run_memory_bytes(const NonsymmetricSuite& suite, int threads, bool report);
// The suite as work items (item_work.h): one per case, then one per reciprocity row. rays > 0
// overrides the suite's; `cancel` (may be null) is read inside each item.
using NonsymmetricWork = ItemWork<NonsymmetricItem>;
Job<NonsymmetricWork> nonsymmetric_job(const NonsymmetricSuite& suite, long rays, nlohmann::json descriptor,
                                       const std::atomic<bool>* cancel = nullptr);
NonsymmetricRun nonsymmetric_run_from(const NonsymmetricSuite& suite,
                                      const std::vector<UnitResult<NonsymmetricWork>>& results);
// rays > 0 overrides the suite's.
NonsymmetricRun run_nonsymmetric_suite(const NonsymmetricSuite& suite, long rays, int threads,
                                       const support::ProgressFn& progress = {},
                                       const std::atomic<bool>* cancel = nullptr);
// `cancel` (may be null) is read between chunks of rays and inside the lobes' quadrature; once set,
// the case stops there and its outcome is incomplete (the suite says interrupted).
NonsymmetricOutcome run_nonsymmetric_case(const NonsymmetricSuite& suite, const NonsymmetricCase& c, long rays,
                                          const std::atomic<bool>* cancel = nullptr);
nlohmann::json nonsymmetric_report_json(const NonsymmetricSuite& suite, const NonsymmetricRun& run);
void print_nonsymmetric_table(std::ostream& os, const NonsymmetricSuite& suite, const NonsymmetricRun& run);

}  // namespace vgroove::validation
