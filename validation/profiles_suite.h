// vgroove validation: the suite of kind "profiles": masking, shadowing and multiple scattering
// traced exactly on random height profiles (sim/random_profile.h) and on V-groove profiles of the
// same NDF (sim/microsurface.h as a polyline), against Smith (Heitz 2014), the V-cavity, the
// flatland Smith walk (analytic/smith_walk_flatland.h) and the V-groove model
// (analytic/brdf_flatland.h). Per case (ndf, alpha, theta), `realizations` profiles, three beams
// of `rays` each (view, lit length, per-k lobe). Pass or fail only on what must hold: no ray lost
// and the projected-area identity on every profile; on V-groove profiles the V-cavity G1 and G2
// (chi-square, p >= p_min / tests), the lit fraction (|z| <= sigmas) and the V-groove model's
// per-k lobe (validation/histogram_metrics.h). Everything else is a measured result with its
// standard error. Tests: tests/validation/profiles_suite_test.cpp
// (ProfilesSuite.SmallRunPassesAndIsTheSameOnOneAndTwoThreads, ProfilesSuite.ReportedErrorsAreTheVerdicts,
// ProfilesSuite.BadSpecsNameTheFieldAndRange, ProfilesSuite.ShippedSuiteParses).
// Derivation: docs/derivations/profiles.md.
#pragma once

#include "vgroove/analytic/ndf.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/chi_square.h"
#include "vgroove/validation/item_work.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

enum class ProfileSurface : unsigned char { random, vgroove };
const char* profile_surface_name(ProfileSurface s);

struct ProfilesCase {
  analytic::NdfKind ndf = analytic::NdfKind::beckmann;
  double alpha = 0.5;
  double theta = 0.0;  // radians, >= 0: view and incidence; the light of G2 at -theta
};

struct ProfilesSuite {
  std::string file, name, description;
  std::vector<analytic::NdfKind> ndfs;
  std::vector<double> alphas;
  std::vector<double> theta;  // radians
  std::vector<ProfileSurface> surfaces;
  int realizations = 4;
  int segments = 1 << 16;
  int samples_per_length = 16;
  long rays = 200000;         // per beam and realization
  long walk_paths = 1000000;  // per case
  int normal_bins = 18;       // facet normal over (-90, 90) deg
  int lobe_bins = 90;         // exit angle over (-90, 90) deg
  int max_k = 8;
  std::uint64_t seed = 1;
  double p_min = 1e-3;
  double sigmas = 5.0;
  double model_tolerance = 1e-5;
  std::size_t cases() const { return ndfs.size() * alphas.size() * theta.size(); }
  ProfilesCase case_at(std::size_t c) const;  // order: ndf, alpha, theta (innermost)
  // Tests that decide the verdict (for the Bonferroni correction of the chi-squares).
  int verdict_tests() const;
};

// Mean and standard error over the realizations, per bin (NaN where fewer than two have a value).
struct BinStat {
  std::vector<double> mean, se;
};

// A model against the traced per-bin values: weighted by the bins' mean weight, the mean of
// |traced - model| and the value noise alone would give (sqrt(2 / pi) se per bin, se the
// realizations' standard error but at least the rays' binomial one), and the largest
// |traced - model| / se.
struct ModelDistance {
  double mean_abs = 0.0, noise = 0.0, max_abs_z = 0.0;
};

// A model's lobe against the traced one, per k row and over all rows: L1, the L1 expected from
// the noise (mean and sd), z = (L1 - mean) / sd (NaN where neither side has any noise but they
// differ).
struct LobeDistance {
  std::vector<double> l1, expected, sd, z;  // per row
  double l1_total = 0.0, expected_total = 0.0, sd_total = 0.0, z_total = 0.0;
  double max_z = 0.0;         // the largest row z (NaN if any row's is)
  bool within_noise = false;  // every row's z and z_total <= sigmas
};

// A lit fraction (per unit macro length or per unit arc length) over the realizations, with the
// predictions made on the same profiles. Each realization's prediction is that profile's, so
// traced - V-cavity differs from 0 by the ray counting alone where V-cavity is exact: se (the
// error of the verdict's z_vcavity) is the counting error of the mean, sqrt(sum_r sd_r^2) / R;
// realization_se is the spread of the traced value over the surfaces (the error of the
// ensemble's mean against a model of the ensemble).
struct LitFraction {
  double traced = 0.0, se = 0.0, realization_se = 0.0, smith = 0.0, vcavity = 0.0, z_vcavity = 0.0;
};

struct SurfaceOutcome {
  ProfileSurface surface = ProfileSurface::random;
  std::int64_t rays = 0, lost = 0, shadow_vertex = 0, bounces = 0;
  double identity_error = 0.0;                         // largest |traced average G1 - identity| / identity
  double g1_identity = 0.0, g1_average_vcavity = 0.0;  // means over realizations
  BinStat g1_weight, g1_traced, g1_vcavity, g2_weight, g2_traced, g2_vcavity;
  double g1_smith = 0.0, g2_smith_separable = 0.0, g2_smith_correlated = 0.0;
  ModelDistance g1_d_smith, g1_d_vcavity, g2_d_separable, g2_d_correlated, g2_d_vcavity;
  // Per bin, the standard error model_distance uses: the realizations' spread (g1_traced.se) but
  // at least the rays' binomial error (g1_counting_se).
  std::vector<double> g1_se, g1_counting_se, g2_se, g2_counting_se;
  LitFraction lit;      // per unit macro length (Smith's classic illuminated fraction)
  LitFraction lit_arc;  // per unit arc length (its z_vcavity is the verdict on V-groove profiles)
  // Against V-cavity, over all realizations (the verdict on V-groove profiles).
  OrderedChiSquare g1_chi2, g2_chi2;
  // The per-k lobe: joint (k row, bin) fractions of the incident flux, mean and se.
  BinStat lobe;
  std::vector<double> by_k;
  double albedo = 0.0;
  LobeDistance d_walk, d_vgroove;
  // The V-groove model on this surface against the pooled histogram (fig11's rule).
  double l1_pooled = 0.0, l1_pooled_threshold = 0.0;
  bool identity_holds = false;
  bool pass = false;
  double wall_s = 0.0;
};

struct ProfilesOutcome {
  ProfilesCase c;
  std::vector<double> walk_lobe, walk_by_k;  // joint fractions, rows k = 0..max_k + 1
  std::int64_t walk_paths = 0, walk_left = 0;
  std::vector<double> model_lobe, model_by_k;  // the V-groove model (analytic/brdf_flatland.h)
  std::vector<SurfaceOutcome> surfaces;
  double walk_wall_s = 0.0;
  bool non_finite = false;
  bool pass = false;
};

// Their members for a shard part (outcome_fields.h); the case and each surface's kind are the suite's.
template <class F>
void fields(BinStat& b, F&& f) {
  f("mean", b.mean), f("se", b.se);
}
template <class F>
void fields(ModelDistance& d, F&& f) {
  f("mean_abs", d.mean_abs), f("noise", d.noise), f("max_abs_z", d.max_abs_z);
}
template <class F>
void fields(LobeDistance& d, F&& f) {
  f("l1", d.l1), f("expected", d.expected), f("sd", d.sd), f("z", d.z), f("l1_total", d.l1_total);
  f("expected_total", d.expected_total), f("sd_total", d.sd_total), f("z_total", d.z_total), f("max_z", d.max_z);
  f("within_noise", d.within_noise);
}
template <class F>
void fields(LitFraction& l, F&& f) {
  f("traced", l.traced), f("se", l.se), f("realization_se", l.realization_se), f("smith", l.smith);
  f("vcavity", l.vcavity), f("z_vcavity", l.z_vcavity);
}
template <class F>
void fields(SurfaceOutcome& o, F&& f) {
  f("rays", o.rays), f("lost", o.lost), f("shadow_vertex", o.shadow_vertex), f("bounces", o.bounces);
  f("identity_error", o.identity_error), f("g1_identity", o.g1_identity);
  f("g1_average_vcavity", o.g1_average_vcavity), f("g1_weight", o.g1_weight), f("g1_traced", o.g1_traced);
  f("g1_vcavity", o.g1_vcavity), f("g2_weight", o.g2_weight), f("g2_traced", o.g2_traced);
  f("g2_vcavity", o.g2_vcavity), f("g1_smith", o.g1_smith), f("g2_smith_separable", o.g2_smith_separable);
  f("g2_smith_correlated", o.g2_smith_correlated), f("g1_d_smith", o.g1_d_smith), f("g1_d_vcavity", o.g1_d_vcavity);
  f("g2_d_separable", o.g2_d_separable), f("g2_d_correlated", o.g2_d_correlated);
  f("g2_d_vcavity", o.g2_d_vcavity), f("g1_se", o.g1_se), f("g1_counting_se", o.g1_counting_se);
  f("g2_se", o.g2_se), f("g2_counting_se", o.g2_counting_se), f("lit", o.lit), f("lit_arc", o.lit_arc);
  f("g1_chi2", o.g1_chi2), f("g2_chi2", o.g2_chi2), f("lobe", o.lobe), f("by_k", o.by_k), f("albedo", o.albedo);
  f("d_walk", o.d_walk), f("d_vgroove", o.d_vgroove), f("l1_pooled", o.l1_pooled);
  f("l1_pooled_threshold", o.l1_pooled_threshold), f("identity_holds", o.identity_holds), f("pass", o.pass);
  f("wall_s", o.wall_s);
}
template <class F>
void fields(ProfilesOutcome& o, F&& f) {
  f("walk_lobe", o.walk_lobe), f("walk_by_k", o.walk_by_k), f("walk_paths", o.walk_paths);
  f("walk_left", o.walk_left), f("model_lobe", o.model_lobe), f("model_by_k", o.model_by_k);
  f("surfaces", o.surfaces), f("walk_wall_s", o.walk_wall_s), f("non_finite", o.non_finite), f("pass", o.pass);
}

struct ProfilesRun {
  std::vector<ProfilesOutcome> cases;
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
};

ProfilesSuite parse_profiles_suite(const nlohmann::json& j, const std::string& file);
// The suite as work items (item_work.h): one per case. rays > 0 overrides the suite's; `cancel`
// (may be null) is read inside each case.
using ProfilesWork = ItemWork<ProfilesOutcome>;
Job<ProfilesWork> profiles_job(const ProfilesSuite& suite, long rays, nlohmann::json descriptor,
                               const std::atomic<bool>* cancel = nullptr);
ProfilesRun profiles_run_from(const ProfilesSuite& suite, const std::vector<UnitResult<ProfilesWork>>& results);
// rays > 0 overrides the suite's rays per beam.
// An upper bound of the memory run_profiles_suite needs (support/memory.h): per worker (one case
// at a time) its profile with its generation, visibility tallies and masking measures, counted
// as 200 bytes per segment (measured: 146 by the maximum resident set between 2^20 and 2^22
// segments on one thread); per case its lobes and per-realization figures.
double profiles_run_memory_bytes(const ProfilesSuite& suite, int threads);
ProfilesRun run_profiles_suite(const ProfilesSuite& suite, long rays, int threads,
                               const support::ProgressFn& progress = {}, const std::atomic<bool>* cancel = nullptr);
// `cancel` (may be null) is read between the beams' chunks of rays and the walk's chunks of paths;
// once set, the case stops there and its outcome is incomplete (the suite says interrupted).
ProfilesOutcome run_profiles_case(const ProfilesSuite& suite, std::size_t case_index, long rays,
                                  const std::atomic<bool>* cancel = nullptr);

nlohmann::json profiles_report_json(const ProfilesSuite& suite, const ProfilesRun& run);
void print_profiles_table(std::ostream& os, const ProfilesSuite& suite, const ProfilesRun& run);

}  // namespace vgroove::validation
