// vgroove validation: the suites of kind "dielectric_brdf" (issue #32 item 4): rough dielectric
// surfaces traced exactly (procedural V-groove surfaces in flatland and lifted to 3D,
// sim/dielectric_microsurface.h, sim/dielectric_lifted.h; random polyline profiles in flatland,
// sim/dielectric_polyline.h) against Walter et al. 2007 (analytic/walter.h: V-cavity, Smith
// separable and height-correlated G), the dielectric Smith walk (analytic/smith_walk_*_dielectric.h)
// and the kaleidoscopic model (analytic/kaleidoscope_dielectric_lobe.h, when listed).
// Per case: the reflected and transmitted lobes per k, binned as the "brdf" suites bin, the energy by
// k and by R/T path signature, and per model the L1 miss of its lobes and of its R and T albedos
// against thresholds from the sample count (lobe_comparison.h). A model that misses is a result; the
// verdict holds the tracer's own checks (R + T + cut + bounce limit + vertex = 1 per ray) and the
// walk's control (its k = 1 share is Walter-Smith height-correlated within noise).
// Tests: tests/validation/dielectric_brdf_suite_test.cpp (DielectricBrdfSuite.TinySuitePassesItsChecks,
// DielectricBrdfSuite.EnergyIsConservedPerRay, DielectricBrdfSuite.ThreadCountChangesNothing,
// DielectricBrdfSuite.ABrokenControlFails, DielectricBrdfSuite.TheKaleidoscopicModelIsWiredFromBothSides,
// DielectricBrdfSuite.BadSpecsNameTheFieldAndRange, DielectricBrdfSuite.ShippedSuitesParse).
#pragma once

#include "vgroove/analytic/ndf.h"
#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/validation/case_surface.h"
#include "vgroove/validation/item_work.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

enum class DielectricSurface : unsigned char { vgroove, profiles };
const char* dielectric_surface_name(DielectricSurface s);

// The models a suite names by default; "kaleidoscopic" (analytic/kaleidoscope_dielectric_lobe.h, about
// 1 s a 3D case) only when listed.
inline constexpr const char* kDielectricModels[] = {"walter_vcavity", "walter_smith_separable",
                                                    "walter_smith_correlated", "smith_walk"};

struct DielectricBrdfCase {
  DielectricSurface surface = DielectricSurface::vgroove;
  SurfaceDim dim = SurfaceDim::flatland;  // profiles: flatland only
  analytic::NdfKind ndf = analytic::NdfKind::ggx;
  double alpha = 0.5;
  double theta_i = 0.0;                   // radians, >= 0, from the normal of the light's side
  double eta = 1.5;                       // n2 / n1 (medium 1 above)
  sim::Medium side = sim::Medium::above;  // where the light comes from
};

struct DielectricBrdfSuite {
  std::string file, name, description;
  std::vector<DielectricBrdfCase> case_list;  // order: surface, dimension, ndf, alpha, theta_i, eta, side
  std::vector<std::string> models;
  long rays = 200000;                                                 // per case (profiles: over all realizations)
  long walk_paths = 200000;                                           // per case
  int grooves = 100000;                                               // V-groove surfaces
  int realizations = 4, segments = 1 << 14, samples_per_length = 16;  // profiles
  int flatland_bins = 90, theta_bins = 15, phi_bins = 12, max_k = 8;
  int max_interactions = 100000;
  std::uint64_t seed = 1;
  double sigmas = 5.0;
  double model_tolerance_flatland = 1e-4, model_tolerance_3d = 1e-3;  // bin quadrature of the models
  // Tests only (never read from a file): the walk's control held against Walter-Smith with 1 / eta.
  bool break_control = false;
  std::size_t cases() const { return case_list.size(); }
  int bins(SurfaceDim d) const { return d == SurfaceDim::flatland ? flatland_bins : theta_bins * phi_bins; }
  int rows() const { return max_k + 2; }  // k = 0..max_k and one row for every k > max_k
  bool has_model(const std::string& m) const;
};

// A lobe leaving into one side: joint (k row, bin) fractions of the incident flux.
struct SideLobe {
  std::vector<double> joint, by_k;
  double energy = 0.0;
};
template <class F>
void fields(SideLobe& s, F&& f) {
  f("joint", s.joint), f("by_k", s.by_k), f("energy", s.energy);
}

// One model against the traced lobe on one side: the k = 1 row and all rows summed; the L1 of the
// lobes against l1_test's threshold; the albedos (k = 1, all) with the standard error of their
// difference and its threshold (albedo_threshold).
struct SideFit {
  double l1_k1 = 0.0, threshold_k1 = 0.0, l1_all = 0.0, threshold_all = 0.0;
  double energy_k1 = 0.0, energy_all = 0.0;  // the model's
  double se_k1 = 0.0, se_all = 0.0;          // of traced - model
  double energy_threshold_k1 = 0.0, energy_threshold_all = 0.0;
  bool matches_k1 = false, matches_all = false;
};
template <class F>
void fields(SideFit& s, F&& f) {
  f("l1_k1", s.l1_k1), f("threshold_k1", s.threshold_k1), f("l1_all", s.l1_all), f("threshold_all", s.threshold_all);
  f("energy_k1", s.energy_k1), f("energy_all", s.energy_all), f("se_k1", s.se_k1), f("se_all", s.se_all);
  f("energy_threshold_k1", s.energy_threshold_k1), f("energy_threshold_all", s.energy_threshold_all);
  f("matches_k1", s.matches_k1), f("matches_all", s.matches_all);
}

struct ModelOutcome {
  std::string name;
  SideLobe reflected, transmitted;
  SideFit fit_reflected, fit_transmitted;
  std::int64_t paths = 0;  // the walk's (0: a closed form)
  bool matches_k1 = false, matches_all = false;
};
template <class F>
void fields(ModelOutcome& m, F&& f) {
  f("name", m.name), f("reflected", m.reflected), f("transmitted", m.transmitted);
  f("fit_reflected", m.fit_reflected), f("fit_transmitted", m.fit_transmitted), f("paths", m.paths);
  f("matches_k1", m.matches_k1), f("matches_all", m.matches_all);
}

// The energy of one R/T path signature ("T", "RT", ...; k <= max_k), traced and walked (-1: no walk).
struct PathShare {
  std::string path;
  double traced = 0.0, walk = -1.0;
};
template <class F>
void fields(PathShare& p, F&& f) {
  f("path", p.path), f("traced", p.traced), f("walk", p.walk);
}

// The walk's control: its k = 1 lobes and energies against Walter-Smith height-correlated.
struct WalkControl {
  double l1_reflected = 0.0, threshold_reflected = 0.0, l1_transmitted = 0.0, threshold_transmitted = 0.0;
  double z_reflected = 0.0, z_transmitted = 0.0;  // k = 1 energy, walk - Walter, in its se
  bool holds = false;
};
template <class F>
void fields(WalkControl& c, F&& f) {
  f("l1_reflected", c.l1_reflected), f("threshold_reflected", c.threshold_reflected);
  f("l1_transmitted", c.l1_transmitted), f("threshold_transmitted", c.threshold_transmitted);
  f("z_reflected", c.z_reflected), f("z_transmitted", c.z_transmitted), f("holds", c.holds);
}

struct DielectricBrdfOutcome {
  DielectricBrdfCase c;
  std::int64_t rays = 0, interactions = 0;
  double cut = 0.0, bounce_limit = 0.0, vertex = 0.0;  // fractions of the rays
  std::int64_t unbalanced = 0;                         // rays whose R + T + cut + bounce limit + vertex differs from 1
  double largest_imbalance = 0.0;
  double grooves_eff = 0.0;  // the independent surface features behind the noise (lobe_comparison.h's G)
  SideLobe reflected, transmitted;
  std::vector<ModelOutcome> models;
  std::vector<PathShare> paths;
  std::optional<WalkControl> control;
  bool non_finite = false;
  bool pass = false;
  double wall_s = 0.0;
};
template <class F>
void fields(DielectricBrdfOutcome& o, F&& f) {
  f("rays", o.rays), f("interactions", o.interactions), f("cut", o.cut), f("bounce_limit", o.bounce_limit);
  f("vertex", o.vertex), f("unbalanced", o.unbalanced), f("largest_imbalance", o.largest_imbalance);
  f("grooves_eff", o.grooves_eff), f("reflected", o.reflected), f("transmitted", o.transmitted);
  f("models", o.models), f("paths", o.paths), f("control", o.control), f("non_finite", o.non_finite);
  f("pass", o.pass), f("wall_s", o.wall_s);
}

struct DielectricBrdfRun {
  std::vector<DielectricBrdfOutcome> cases;
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
};

// Strict: support::UserError naming the file, the key and its range.
DielectricBrdfSuite parse_dielectric_brdf_suite(const nlohmann::json& j, const std::string& file);

using DielectricBrdfWork = ItemWork<DielectricBrdfOutcome>;
// One item per case; rays > 0 overrides the suite's. `cancel` (may be null) is read between chunks.
Job<DielectricBrdfWork> dielectric_brdf_job(const DielectricBrdfSuite& suite, long rays, nlohmann::json descriptor,
                                            const std::atomic<bool>* cancel = nullptr);
DielectricBrdfRun dielectric_brdf_run_from(const DielectricBrdfSuite& suite,
                                           const std::vector<UnitResult<DielectricBrdfWork>>& results);
DielectricBrdfOutcome run_dielectric_brdf_case(const DielectricBrdfSuite& suite, std::size_t case_index, long rays,
                                               const std::atomic<bool>* cancel = nullptr);
DielectricBrdfRun run_dielectric_brdf_suite(const DielectricBrdfSuite& suite, long rays, int threads,
                                            const std::atomic<bool>* cancel = nullptr);
// Per thread: one surface (V-grooves: 200 B per groove; profiles: 200 B per segment) and the lobes.
double dielectric_brdf_memory_bytes(const DielectricBrdfSuite& suite, int threads);

nlohmann::json dielectric_brdf_report_json(const DielectricBrdfSuite& suite, const DielectricBrdfRun& run);
void print_dielectric_brdf_table(std::ostream& os, const DielectricBrdfSuite& suite, const DielectricBrdfRun& run);

}  // namespace vgroove::validation
