// vgroove analytic: the kaleidoscopic dielectric model over an NDF (kaleidoscope_dielectric_lobe.h) at a
// point: the BSDF f(i, o), reflected and transmitted, per interaction count k and summed, flatland and
// 3D (lifted), light from above or below, and the density of sample_vgroove_dielectric_*'s directions.
// f = sum over chain ends and over the groove slopes theta_m sending that end to o of
// dP(theta_m) f_a / opening x share / |Jacobian| / |cos theta_o| (KD-9..KD-12); roots bracketed on
// pieces where the exit angle is monotone (closed form when reflected) and bisected to rounding.
// Holds: integrated over a bin it is the binned lobe within the lobe's error; F = 1 gives the conductor
// BRDFs (flatland_brdf_k, vgroove_brdf_k); reflection is reciprocal; finite at grazing angles, mirror
// directions and total internal reflection; pdf = f |cos theta_o| and E[f |cos| / pdf] = R + T.
// Tests: tests/analytic/kaleidoscope_dielectric_point_test.cpp (KaleidoscopeDielectricPoint.*, the bins and the
// pdf: KaleidoscopeDielectricPointLong.*, KaleidoscopeDielectricPdfLong.*).
// Derivation: docs/derivations/kaleidoscope_dielectric.md, "The BSDF at a point" (KD-9 to KD-12).
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/kaleidoscope_dielectric_lobe.h"
#include "vgroove/analytic/ndf.h"

#include <vector>

namespace vgroove::analytic {

// Deliberately wrong variants, for the tests' power.
enum class DielectricPointBreak : unsigned char {
  none,
  no_cosine,          // the density not divided by |cos theta_o|
  section_jacobian,   // 3D: the lifted area element A (KD-11) left out (1 / |dt/dtheta_m| only)
  no_index_jacobian,  // transmitted: |dt/dtheta_m| without the refraction's factor (KD-10's 1/2 term only)
};

struct DielectricPointOptions {
  DielectricLightFrom from = DielectricLightFrom::above;
  int k_cap = 32;         // grooves with Eq. (4)'s k above it contribute nothing (the lobe's `unresolved`)
  FresnelFn reflectance;  // empty: the unpolarized dielectric Fresnel (3D: at the 3D local angle)
  DielectricPointBreak broken = DielectricPointBreak::none;
};

struct DielectricPointValue {
  double f = 0.0;            // the BSDF (flatland per radian: flux per unit theta_o / cos theta_o)
  std::vector<double> by_k;  // rows k = 0..max_k and max_k + 1 for every k > max_k
};

// Flatland: theta_i signed in (-pi/2, pi/2), theta_o in (-pi/2, pi/2) from the exit side's normal (the
// lobe's bin convention), `reflected`: o on the light's side. eta > 0, alpha > 0, max_k >= 0, else
// std::invalid_argument.
DielectricPointValue kaleidoscope_dielectric_bsdf_flatland(NdfKind ndf, double alpha, double eta, double theta_i,
                                                           double theta_o, bool reflected, int max_k,
                                                           const DielectricPointOptions& opt = {});
// 3D: i and o unit, pointing away from the surface (i towards the light, i.z != 0: the light's side
// decides from-above or below and opt.from is ignored); o on either side (o.z of i's sign: reflected).
DielectricPointValue kaleidoscope_dielectric_bsdf_3d(NdfKind ndf, double alpha, double eta, const Dir3& i,
                                                     const Dir3& o, int max_k, const DielectricPointOptions& opt = {});

// The density of the directions sample_vgroove_dielectric_flatland / _3d return (per radian of
// theta_o in flatland, per steradian in 3D): f |cos theta_o|. It integrates to albedo_r + albedo_t
// (the rest are the sampler's failures).
double kaleidoscope_dielectric_pdf_flatland(NdfKind ndf, double alpha, double eta, double theta_i, double theta_o,
                                            bool reflected, const DielectricPointOptions& opt = {});
double kaleidoscope_dielectric_pdf_3d(NdfKind ndf, double alpha, double eta, const Dir3& i, const Dir3& o,
                                      const DielectricPointOptions& opt = {});

}  // namespace vgroove::analytic
