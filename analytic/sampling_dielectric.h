// vgroove analytic: sampling the kaleidoscopic dielectric model over an NDF (kaleidoscope_dielectric_lobe.h),
// flatland and 3D: the groove slope from the NDF by its macrosurface width, the groove azimuth uniform
// (3D, its cross-section lifted as the lobe lifts it), the first facet by the width of the entering
// beam it takes (f_a - f_b), then one chain's end: reflected after n hits or transmitted at hit j, in
// proportion to its energy (Eq. 11, KD-2). Returned directions thus have the model's BSDF x |cos| as
// their density; the rest (transmitted lobes travelling back up, k > k_cap, rounding) are failures.
// Holds: the histogram of the samples is the lobe's bins (reflected, transmitted, failures) by a
// chi-square test, light from either side; a facet drawn 50/50 or Fresnel at a wrong eta is rejected.
// Tests: tests/analytic/sampling_dielectric_test.cpp (SamplingDielectric.*, SamplingDielectricLong.*).
// Derivation: docs/derivations/sampling.md, "The kaleidoscopic dielectric model".
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/kaleidoscope_dielectric_lobe.h"
#include "vgroove/analytic/ndf.h"

#include <array>

namespace vgroove::analytic {

// Deliberately wrong samplers, for the tests' power.
enum class DielectricSamplerBreak : unsigned char {
  none,
  facet_uniform,                // the first facet drawn 50/50 instead of by its lit width
  fresnel_eta,                  // Fresnel evaluated at 1.1 eta (the directions still Snell's at eta)
  fresnel_cross_section_angle,  // 3D: Fresnel at the cross-section's local angle, not the 3D one
};

struct DielectricSamplerOptions {
  DielectricLightFrom from = DielectricLightFrom::above;
  int k_cap = 32;         // grooves with Eq. (4)'s k above it: failure (the lobe's `unresolved`)
  FresnelFn reflectance;  // empty: the unpolarized dielectric Fresnel at eta (3D: at the 3D local angle)
  DielectricSamplerBreak broken = DielectricSamplerBreak::none;
};

// Why no direction was returned.
enum class DielectricSampleFailure : unsigned char { none, upward, unresolved, other };

struct DielectricSampleFlatland {
  double theta_o = 0.0;    // from the exit side's normal, the lobe's bin convention (its flat_bin)
  bool reflected = false;  // exits on the light's side
  int k = 0;               // interactions: n hits reflected, j (the refracting hit) transmitted; 0 on failure
  double weight = 0.0;     // BSDF |cos| / density: 1, or 0 on failure
  DielectricSampleFailure failure = DielectricSampleFailure::none;
};

struct DielectricSample3d {
  Dir3 o;  // world direction: z > 0 above the macrosurface (light from above: reflected)
  bool reflected = false;
  int k = 0;
  double weight = 0.0;
  DielectricSampleFailure failure = DielectricSampleFailure::none;
};

// theta_i signed in (-pi/2, pi/2) (kaleidoscope_dielectric_lobe_flatland's), eta > 0, u in [0, 1)^4.
DielectricSampleFlatland sample_vgroove_dielectric_flatland(double theta_i, const std::array<double, 4>& u, NdfKind ndf,
                                                            double alpha, double eta,
                                                            const DielectricSamplerOptions& opt = {});
// theta_i in [0, pi/2), the light at phi = pi (kaleidoscope_dielectric_lobe_3d's), u in [0, 1)^5.
DielectricSample3d sample_vgroove_dielectric_3d(double theta_i, const std::array<double, 5>& u, NdfKind ndf,
                                                double alpha, double eta, const DielectricSamplerOptions& opt = {});

}  // namespace vgroove::analytic
