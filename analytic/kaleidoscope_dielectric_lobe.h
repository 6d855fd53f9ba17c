// vgroove analytic: the kaleidoscopic dielectric model (kaleidoscope_dielectric.h) over an NDF of
// symmetric grooves: the fraction of the incident flux reflected into each bin above and transmitted
// into each bin below, per interaction count k and summed, flatland and 3D (each groove azimuth's
// cross-section with the lifted law's effective index, Fresnel at the 3D local angle, exits lifted),
// light from above or (the model at 1 / eta, mirrored) from below. Bins as FlatlandLobe (flatland)
// and Lobe3d (3D), angles from the exit side's normal. Deterministic: Gauss-Legendre over the groove
// slope between the points where a lobe changes bin or form, and over the azimuth; error by doubling.
// Holds: F = 1 gives the conductor lobes; eta = 1 transmits into the incident direction's bin;
// albedo_r + albedo_t + shadow_or_unknown = 1; agrees with the exact tracers at small alpha.
// Tests: tests/analytic/kaleidoscope_dielectric_lobe_test.cpp (KaleidoscopeDielectricLobe.*, where the
// model misses: KaleidoscopeDielectricLobeLong.*).
// Derivation: docs/derivations/kaleidoscope_dielectric.md, "The BSDF over an NDF".
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf.h"

#include <vector>

namespace vgroove::analytic {

// Which side the light comes from. below: the model at 1 / eta with the picture mirrored in the
// macrosurface ("Light from the other side"): reflected then means below, transmitted above.
enum class DielectricLightFrom : unsigned char { above, below };

struct DielectricLobeOptions {
  DielectricLightFrom from = DielectricLightFrom::above;
  // Grooves with Eq. (4)'s k above k_cap (the narrowest) are not binned: their flux is `unresolved`.
  int k_cap = 32;
  // A piece of groove slope whose flux (estimated at its middle) is below this is integrated node
  // by node without cuts (the NDF's tail): a bin errs by at most the pieces' flux, `light`.
  double light_piece = 1e-8;
  int order = 8;     // Gauss-Legendre nodes per piece of groove slope
  int samples = 16;  // per band of k: where a lobe's bin or form changes is bisected between samples
  // 3D: the groove azimuth over [0, pi/2] (mirror symmetry) in phi_panels panels of phi_order nodes.
  int phi_panels = 16;
  int phi_order = 4;
  // Also run with every node count above doubled: the finer lobe is returned and error_estimate is
  // the largest change of a bin (or of albedo_r, albedo_t). false: error_estimate = -1.
  bool error_estimate = true;
  // F(cos of the 3D local angle): empty = the unpolarized dielectric Fresnel at eta; F = 1 gives
  // the conductor model. Refraction directions are Snell's (effective index in 3D) whatever F is.
  FresnelFn reflectance;
  // A deliberately wrong 3D model for the tests: Fresnel at the cross-section's local angle.
  bool broken_fresnel_at_cross_section_angle = false;
};

struct DielectricLobe {
  int bins = 0;        // flatland: equal bins over (-pi/2, pi/2); 3D: theta_bins * phi_bins
  int theta_bins = 0;  // 3D only: theta in [0, pi/2), phi bins centred on phi = 0 (lobe_3d.h)
  int phi_bins = 0;    // light at phi = pi (3D) or at +theta_i (flatland)
  int max_k = 0;
  std::vector<double> reflected, transmitted;  // [bin] (3D: t * phi_bins + p)
  // [row][bin], rows k = 0..max_k and max_k + 1 for every k > max_k; k counts interactions.
  std::vector<std::vector<double>> reflected_by_k, transmitted_by_k;
  double albedo_r = 0.0, albedo_t = 0.0;
  // Flux not binned: transmitted lobes travelling back up (KD-4: what one groove cannot follow),
  // reflected ones below the horizon (expected 0) and `unresolved`.
  double shadow_or_unknown = 0.0;
  double upward = 0.0;      // of it: transmitted lobes travelling back towards the surface
  double unresolved = 0.0;  // of it: grooves with k > k_cap
  double light = 0.0;       // binned, but node by node: the pieces lighter than light_piece
  // The largest change of a bin or albedo when every node count doubles, or `light` if larger, plus
  // the cuts' location bound (4 x their bisection tolerance x the largest density).
  double error_estimate = -1.0;
};

// eta > 0 (n2 / n1, light in medium 1; below 1: inside the denser medium), theta_i signed in
// (-pi/2, pi/2) towards the light, bins >= 1, max_k >= 0. Bad input: std::invalid_argument.
DielectricLobe kaleidoscope_dielectric_lobe_flatland(NdfKind ndf, double alpha, double eta, double theta_i, int bins,
                                                     int max_k, const DielectricLobeOptions& opt = {});
// theta_i in [0, pi/2) (the light at phi = pi), phi_bins even (as Lobe3d).
DielectricLobe kaleidoscope_dielectric_lobe_3d(NdfKind ndf, double alpha, double eta, double theta_i, int theta_bins,
                                               int phi_bins, int max_k, const DielectricLobeOptions& opt = {});

}  // namespace vgroove::analytic
