// vgroove validation: the lobe shape of the energy compensation formulas, beyond their energy (the
// energy audit's item "the compensated lobe against the traced lobe, by the Fig. 11 metric"). With
// F = 1 the compensated BRDFs of analytic/compensation.h take three shapes: `single` (f_ss alone),
// `kulla_conty` (f_ss + (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 - E_avg))) and `view_scaled`
// (f_ss / E(mu_o): Turquin, Filament, Bevy and Cycles, whose factors all become 1 / E_o at F0 = 1).
// Each is held against two references with check_brdf's metric (validation/check_brdf.h: L1 of
// the normalized lobes and of the flux fractions, albedo, thresholds from the sample count): the
// traced procedural V-groove surface (f_ss = Cook-Torrance with the V-cavity G, its exact k = 1)
// and the 3D Smith random walk (analytic/smith_walk_3d.h; f_ss = Smith height-correlated), binned
// alike. Controls, which must pass: the V-groove model (Eq. 17) against the traced surface, and
// f_ss against each reference's k = 1 lobe. E(mu) is a table of albedo_single in mu, linearly
// interpolated; its largest error at the midpoints is reported. Deterministic per seed.
// Tests: tests/validation/energy_lobe_shape_test.cpp.
// Derivation: docs/derivations/energy_compensation.md (Lobe shape).
#pragma once

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/validation/check_brdf.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

enum class CompensatedLobe : unsigned char { single, kulla_conty, view_scaled };
const char* compensated_lobe_name(CompensatedLobe lobe);

// E_ss(mu) of a model at one alpha on `points` equal steps of sqrt(mu) in [0, 1] (denser at
// grazing, where E_ss bends most; mu = 0 taken at 1e-6 of a step), linear between them, and E_avg.
struct AlbedoCurve {
  std::vector<double> E;  // at mu_j = (j / (points - 1))^2
  double E_avg = 0.0;
  double interpolation_error = 0.0;  // max |table - albedo_single| at the midpoints
  double operator()(double mu) const;
};
AlbedoCurve albedo_curve(const analytic::MicrofacetModel& m, double alpha, int points = 257);

// The single-scattering BRDF f_ss(i, o) of m (V-cavity: Cook-Torrance, Lee et al. Eq. 1-3;
// Smith height-correlated: D G2 / (4 |i.n| |o.n|), G2 = 1 / (1 + Lambda(i) + Lambda(o))), F = 1.
double single_scattering_brdf(const analytic::MicrofacetModel& m, double alpha, const analytic::Dir3& i,
                              const analytic::Dir3& o);
// The compensated BRDF of `lobe` with F = 1 over m, E from `curve`.
double compensated_brdf(CompensatedLobe lobe, const analytic::MicrofacetModel& m, double alpha,
                        const AlbedoCurve& curve, const analytic::Dir3& i, const analytic::Dir3& o);

struct LobeShapeOptions {
  NdfKind ndf = NdfKind::ggx;  // ggx or beckmann (Smith's Lambda)
  std::vector<double> alpha = {0.5, 1.0};
  std::vector<double> theta_i_deg = {0, 40, 70};
  long rays = 200'000;  // per (alpha, theta_i) and reference
  int grooves = 100'000;
  std::uint64_t seed = 1;
  int theta_bins = 15, phi_bins = 12;
  double sigmas = 5.0;
  double model_tolerance = 1e-4;
  int threads = 0;
  const std::atomic<bool>* cancel = nullptr;
};

struct LobeShapeRow {
  std::string reference;  // "vgroove_surface", "smith_walk"; the controls: "..._k1"
  std::string lobe;       // compensated_lobe_name, or "vgroove_model"
  double alpha = 0.0;
  CheckBrdfCase c;  // theta_i, rays, albedos, L1 of shape and flux with their thresholds, pass
};

struct LobeShapeResult {
  LobeShapeOptions options;
  std::vector<LobeShapeRow> rows;
  double max_interpolation_error = 0.0;  // of the albedo curves
  double wall_s = 0.0;
  bool interrupted = false;
  bool controls_pass = false;  // every control row passes
  nlohmann::json to_json() const;
};

// Throws support::UserError naming the option when one is out of range.
void check_lobe_shape_options(const LobeShapeOptions& opt);
// check_lobe_shape_options, then the rows; interrupted (and no rows) when opt.cancel was set.
LobeShapeResult audit_lobe_shapes(const LobeShapeOptions& opt);
// The rows as a table, per alpha and theta_i: each lobe's L1 (shape) and albedo beside the
// reference's, with the noise thresholds and whether it is within them.
void print_lobe_shapes(std::ostream& os, const LobeShapeResult& r);

}  // namespace vgroove::validation
