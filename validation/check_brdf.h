// vgroove validation: hold a BRDF of your own against vgroove's exact simulation, in one call:
//   auto result = vgroove::validation::check_brdf(my_brdf, vgroove::validation::CheckBrdfOptions{});
// Per theta_i it traces the procedural V-groove microsurface of the NDF and alpha (the surface of
// the Fig. 11 suite: sim/microsurface3d.h, sim/microsurface.h), bins the exits as that suite
// does, integrates the user's f(wi, wo) cos(theta_o) over the same bins by adaptive Gauss-Legendre
// cubature with an error bound, and compares as the suite does (validation/histogram_metrics.h):
// the L1 of the normalized lobes and of the flux fractions against the noise expected at the sample
// count plus `sigmas` sd plus model_tolerance, and the albedo against its binomial error.
// Surface "heightfield": random heightfields instead (CheckSurface); eta: BSDFs (check_bsdf.h).
// Frame: n = (0, 0, 1), wi = dir3(theta_i, pi) towards the light; F = 1. A value that is NaN,
// infinite or < 0 throws support::UserError naming it and its directions, before any tracing.
// Tests: tests/validation/check_brdf_test.cpp (CheckBrdf.VgrooveModelPasses3d,
// CheckBrdf.VgrooveModelPassesFlatland, CheckBrdf.TwoPercentLessEnergyFails, CheckBrdf.WrongRoughnessFailsOnShape,
// CheckBrdf.AValueThatIsNotABrdfsFailsAtOnceNamingItsDirections, CheckBrdf.ResultsDoNotDependOnThreads).
// Derivation: docs/derivations/validation.md.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/sim/heightfield_tracer.h"
#include "vgroove/validation/brdf_suite.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vgroove::validation {

// The BRDF under test: f(wi, wo), both unit vectors pointing away from the surface (see above),
// called once per direction pair.
using BrdfFn = std::function<double(const analytic::Dir3& wi, const analytic::Dir3& wo)>;
// The same, n directions at a time (for callers that evaluate arrays, such as the Python module):
// out[j] = f(wi_j, wo_j) with wi_j = (wi[3j], wi[3j + 1], wi[3j + 2]), likewise wo_j. Called with
// the nodes of one Gauss-Legendre rule at a time (quadrature_order^2 directions in 3D), from the
// worker threads (several calls may run at once unless opt.threads is 1).
using BrdfBatchFn = std::function<void(const double* wi, const double* wo, std::size_t n, double* out)>;

// The traced surface: procedural V-grooves (the Fig. 11 suite's) or, with `heightfield`, `fields`
// random heightfields of the NDF and alpha (Beckmann: Gaussian heights; GGX: the GGX-slope field;
// validation/heightfield_lobe.h) of field_size^2 cells with correlation length l cells, the rays
// split evenly among them, traced exactly in 3D: the surface Smith's models assume. The same bins,
// L1 distances and albedo, with the noise per bin from the fields' spread (the sample variance of
// the per-field fractions over the fields, at least the multinomial p (1 - p) / N of the rays) in
// place of the bound from rays and grooves. A field that does not fit memory is refused before any
// work (check_options, one line). Tests: tests/validation/heightfield_check_brdf_test.cpp
// (HeightfieldCheckBrdf.*); docs/derivations/heightfield.md.
// (CheckSurface and check_surface_name: case_surface.h.)

struct CheckBrdfOptions {
  std::string name = "check_brdf";  // names the report
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;                                     // (0, 2]
  std::vector<double> theta_i_deg = {0, 20, 40, 60, 80};  // each in [0, 89.9] (kMaxSurfaceThetaIDeg)
  SurfaceDim dim = SurfaceDim::three_d;
  long rays = 1'000'000;  // per theta_i, [1, 1e9]
  int grooves = 250'000;  // grooves of the traced surface, [1, 1e7]
  CheckSurface surface = CheckSurface::vgroove;
  // surface heightfield (3D, beckmann or ggx): cells per side, a power of two in [16, 65536]
  // that fits memory; correlation length in cells, [2, field_size / 8]; fields, [2, min(1000, rays)].
  int field_size = 256;
  double correlation_length = 8.0;
  int fields = 4;
  // A dielectric surface (check_bsdf.h): eta = n2 / n1 in [0.1, 10], not 1, the light on `side`;
  // 0: the conductor (F = 1) check above, untouched. Surface vgroove only.
  double eta = 0.0;
  sim::Medium side = sim::Medium::above;
  std::uint64_t seed = 1;                     // surface and rays
  int theta_bins = 30;                        // 3D: theta_o bins over [0, 90) deg
  int phi_bins = 24;                          // 3D: phi_o bins, even
  int flatland_bins = 90;                     // flatland: theta_o bins over (-90, 90) deg
  double sigmas = 5.0;                        // standard deviations allowed beyond the expected error
  double model_tolerance = 1e-4;              // the bin integration's target error (summed over bins)
  int quadrature_order = 4;                   // Gauss-Legendre nodes per cell and axis
  std::int64_t max_model_evals = 4'000'000;   // per theta_i: the integration stops there
  int threads = 0;                            // 0: all cores; the results do not depend on it
  const std::atomic<bool>* cancel = nullptr;  // set to stop: the result says interrupted
};

// One bin where the simulation and the model differ most (flux fractions of the incident light).
struct WorstBin {
  double theta_o_deg = 0.0, phi_o_deg = 0.0;  // the bin's centre (flatland: signed theta_o, phi 0)
  double sim = 0.0, model = 0.0;
  std::string lobe;  // with eta: "reflected" or "transmitted" (theta_o from that side's normal)
};

// With eta, one exit hemisphere's lobe (check_bsdf.h): the albedo (R or T) with its binomial sd,
// and the L1 of its normalized lobe and of its flux fractions, each against its threshold.
struct CheckLobeSide {
  std::string lobe;  // "reflected" (the light's side), "transmitted"
  double albedo_sim = 0.0, albedo_model = 0.0, albedo_sd = 0.0, albedo_threshold = 0.0;
  double l1 = 0.0, l1_expected = 0.0, l1_threshold = 0.0;
  double l1_flux = 0.0, l1_flux_expected = 0.0, l1_flux_threshold = 0.0;
  std::vector<WorstBin> worst;
  bool pass = false;
};

struct CheckBrdfCase {
  double theta_i_deg = 0.0;
  std::int64_t rays = 0;
  double albedo_sim = 0.0, albedo_model = 0.0, albedo_threshold = 0.0;
  double l1 = 0.0, l1_expected = 0.0, l1_threshold = 0.0;                 // normalized lobes
  double l1_flux = 0.0, l1_flux_expected = 0.0, l1_flux_threshold = 0.0;  // flux fractions
  std::vector<WorstBin> worst;  // the five largest |sim - model|, largest first
  double model_error = 0.0;     // the integration's error estimate, added to every threshold
  std::int64_t model_evals = 0;
  double sim_wall_s = 0.0, model_wall_s = 0.0;
  // A model bin that is not finite or is negative (compare_lobes; check_brdf throws before, at the
  // first such value, and model tables refuse them when read).
  bool non_finite = false;
  // With eta: the reflected and the transmitted lobes (the figures above are then both
  // hemispheres' bins as one lobe); pass = all three hold. Empty without eta.
  std::vector<CheckLobeSide> lobes;
  bool pass = false;
};

struct CheckBrdfResult {
  CheckBrdfOptions options;
  std::vector<CheckBrdfCase> cases;
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
  // The report JSON (provenance, options, every case's figures, pass), as `vgroove validate` writes.
  nlohmann::json to_json() const;
};

// Throws support::UserError naming the option when an option is out of range (and, for a
// heightfield, when its field does not fit memory).
void check_options(const CheckBrdfOptions& opt);
// Throws support::UserError at the first value of f that is not finite and >= 0 (above).
CheckBrdfResult check_brdf(const BrdfFn& f, const CheckBrdfOptions& opt);
// The same check with the model evaluated a rule's nodes at a time: the same nodes, sums and report.
CheckBrdfResult check_brdf(const BrdfBatchFn& f, const CheckBrdfOptions& opt);
// f as a BrdfBatchFn, called once per direction pair (f is held by reference: it must outlive the result).
BrdfBatchFn batch_of(const BrdfFn& f);

// The model's flux fractions per bin at theta_i (degrees), integrated as check_brdf integrates
// them (opt's dimension, bins, quadrature_order, model_tolerance and max_model_evals; f is called
// from this thread only), with the integration's error estimate and evaluation count. Throws
// support::UserError at the first value of f that is not finite and >= 0. Empty flux when
// opt.cancel was set.
struct ModelLobe {
  std::vector<double> flux;
  double error = 0.0;
  std::int64_t evals = 0;
};
ModelLobe integrate_model_lobe(const BrdfBatchFn& f, double theta_i_deg, const CheckBrdfOptions& opt);

// The comparison itself, for a model given as flux fractions per bin (the model-table route of
// `vgroove validate --model-table`): sim and model over the same bins, N rays over G grooves.
// It is validation/lobe_comparison.h's compare_lobes with one row, whose joint test is the flux fractions'.
CheckBrdfCase check_lobes(const std::vector<double>& sim, const std::vector<double>& model, double rays, double grooves,
                          double sigmas, double model_tolerance);
// The heightfield route's pieces, shared with the model tables (model_table.h), so that a table
// sees check_brdf's fields and rays: field r of the options (its seed from opt.seed and r); its
// rays at incidence number c of theta_i (radians), rays / fields of them (one more for r < rays
// mod fields), max_k 0; a chunk's tally added to counts per bin (all bounce orders), returning its
// rays; the fields' counts pooled into the flux fractions with the variance per bin and of the
// albedo from the fields' spread (the sample variance of the per-field fractions over the fields,
// at least the multinomial p (1 - p) / N of all N rays); and check_lobes with these variances in
// place of the bound from rays and grooves (thresholds expected + sigmas sd + tolerance, the
// shape's scaled by 1 / albedo^2; the albedo's sigmas sd + 1 / rays + tolerance).
struct FieldLobe {
  std::vector<double> flux, var;
  double albedo_var = 0.0;
  std::int64_t rays = 0;
};
sim::HeightfieldSurface check_field(const CheckBrdfOptions& opt, int r);
sim::HeightfieldTraceOptions check_field_trace(const CheckBrdfOptions& opt, double theta_i, std::size_t c, int r);
std::int64_t add_field_counts(const sim::HeightfieldTally& t, std::vector<std::int64_t>& counts);
FieldLobe pool_fields(const std::vector<std::vector<std::int64_t>>& counts, const std::vector<std::int64_t>& rays);
CheckBrdfCase check_lobes_with_variance(const std::vector<double>& sim, const std::vector<double>& model,
                                        const std::vector<double>& var, double albedo_var, double rays, double sigmas,
                                        double tolerance);

// The five bins where |sim - model| is largest, largest first, with their centres.
std::vector<WorstBin> worst_bins(const std::vector<double>& sim, const std::vector<double>& model, SurfaceDim dim,
                                 int theta_bins, int phi_bins, int flatland_bins);

}  // namespace vgroove::validation
