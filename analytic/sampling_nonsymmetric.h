// vgroove analytic: importance sampling of the nonsymmetric V-groove BRDF (Lee et al. 2018,
// "Practical Multiple Scattering for Rough Surfaces", Sec. 6 "Nonsymmetric BRDF", Eq. (7)-(9),
// (20)-(23); isotropic roughness, the independent partner law of Eq. 20) in 3D and flatland, the
// density of the directions it produces (every path ending at o, with the Jacobian printed after
// Eq. 23, by adaptive Gauss-Kronrod to `tolerance` per B-piece) and the weight rho cos / pdf.
// The pdf holds P (Eq. 20); the draw uses the table P_tab, int |P_tab - P| dB < 1e-5
// (partner_table.h), which bounds the difference. The printed p(o) is not a density (ERRATA E-IS1).
// Default kNonsymmetricSamplerMaxK = 256: the share lost beyond it ~1e-6 at GGX alpha 1.
// Holds: pdf integrates to 1 - failure probability; weight = rho cos / pdf; mean weight = albedo.
// Tests: tests/analytic/sampling_nonsymmetric_test.cpp
// (SamplingNonsymmetric.FlatlandPdfIntegratesToOneMinusTheFailureProbability,
// SamplingNonsymmetric.WeightIsEvalCosOverPdf, SamplingNonsymmetric.MeanWeightIsTheAlbedo,
// SamplingNonsymmetric.HardCases), tests/analytic/sampling_chi2_test.cpp. Timings: docs/performance.md.
// Derivation: docs/derivations/nonsymmetric.md.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/analytic/partner_table.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_flatland.h"

#include <array>

namespace vgroove::analytic {

inline constexpr int kNonsymmetricSamplerMaxK = 256;

// The sampler of one material: NDF, alpha, strategy and the partner table, built once.
struct NonsymmetricSampler {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;
  SamplerOptions opt{FacetStrategy::vndf, kNonsymmetricSamplerMaxK};
  bool flatland = false;
  double tolerance = 1e-9;  // relative, per integrated B-piece of the pdf
  PartnerTable partner;     // P (3D) or P2 (flatland), tabulated
};

// Throws std::domain_error when the partner law does not exist (Phong, alpha >= sqrt(2)) or the
// strategy is not available (facet_strategy.h, strategy_supports).
NonsymmetricSampler make_nonsymmetric_sampler(NdfKind ndf, double alpha, const SamplerOptions& opt, bool flatland,
                                              int table_cells = kPartnerTableCells);

// ---- 3D -------------------------------------------------------------------------------------------

// u = (u0, u1, u2, u3, u4) in [0, 1)^5. F: the Fresnel plug-in of the weight's BRDF (Eq. 23).
// sample_nonsymmetric_3d = draw_nonsymmetric_3d (steps 1-4: o and k; k = 0 when no direction)
// followed by pdf(o) and the weight; the chi-square tests histogram the draws alone.
struct NonsymmetricDraw3d {
  Dir3 o;
  int k = 0;
  bool beyond_max_k = false;  // no direction because the drawn path has more than max_k reflections
};
NonsymmetricDraw3d draw_nonsymmetric_3d(const NonsymmetricSampler& s, const Dir3& i, const std::array<double, 5>& u);
VgrooveSample3d sample_nonsymmetric_3d(const NonsymmetricSampler& s, const Dir3& i, const std::array<double, 5>& u,
                                       const FresnelFn& F = {});
double nonsymmetric_pdf_3d(const NonsymmetricSampler& s, const Dir3& i, const Dir3& o);
double nonsymmetric_pdf_3d_k(const NonsymmetricSampler& s, const Dir3& i, const Dir3& o, int k_lo, int k_hi);
// The probability of no direction, over the facets and the partner (independent of pdf).
double nonsymmetric_failure_probability_3d(const NonsymmetricSampler& s, const Dir3& i, double tol = 1e-8);

// ---- Flatland (F = 1) -------------------------------------------------------------------------------

struct NonsymmetricDrawFlatland {
  double theta_o = 0.0;
  int k = 0;
  bool beyond_max_k = false;
};
NonsymmetricDrawFlatland draw_nonsymmetric_flatland(const NonsymmetricSampler& s, double theta_i,
                                                    const std::array<double, 5>& u);
VgrooveSampleFlatland sample_nonsymmetric_flatland(const NonsymmetricSampler& s, double theta_i,
                                                   const std::array<double, 5>& u);
double nonsymmetric_pdf_flatland(const NonsymmetricSampler& s, double theta_i, double theta_o);
double nonsymmetric_pdf_flatland_k(const NonsymmetricSampler& s, double theta_i, double theta_o, int k_lo, int k_hi);
double nonsymmetric_failure_probability_flatland(const NonsymmetricSampler& s, double theta_i, double tol = 1e-10);

}  // namespace vgroove::analytic
