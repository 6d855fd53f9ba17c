// vgroove analytic: importance sampling of the flatland symmetric V-groove BRDF (brdf_flatland.h),
// the density of the exit angles it produces, and the weight rho2 cos / pdf. F = 1.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 6, written for flatland as brdf_flatland.h writes Eq. (10)-(17).
//
// The routine is sampling_3d.h's in one dimension less: a facet angle theta_s from the strategy
// (vndf.h: D2 cos for the printed one, the V-cavity's or the Smith-GGX visible normals), the groove
// of aperture pi - 2 |theta_s| with theta_s its left facet (theta_s < 0) or its right one, Eq. (4)
// and (6) at theta_i, u3 choosing the outcome (printed: G = width / f_a, the share f_b / f_a and
// unlit facets giving no direction; the others: width / (f_a - f_b)), and theta_o from Eq. (5).
// The density of theta_o sums every path that ends there with the flatland Jacobian
// |d theta_s / d theta_o| = 1 / (2k) (brdf_flatland.h, step c):
//   pdf(theta_o) = sum_k sum_m q(theta_sm) P(k | theta_sm) / (2k),
// and for the V-cavity's visible normals it equals rho2 cos(theta_o). The paths are those of
// kaleidoscope_solutions.h in the frame where t_h <= 0 (the profile is mirror symmetric).
// Zero-weight returns as in 3D: the printed strategy's shadowed or unlit draws, paths beyond
// max_k, exits at |theta_o| >= pi/2 by rounding, |theta_i| >= pi/2. No flatland direction is
// singular (the Jacobian 1/(2k) is bounded).
#pragma once

#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/sampling_3d.h"

#include <array>

namespace vgroove::analytic {

struct VgrooveSampleFlatland {
  double theta_o = 0.0;  // the exit angle (-theta_i on a zero-weight return)
  int k = 0;
  double pdf = 0.0;  // per radian
  double weight = 0.0;
  bool beyond_max_k = false;  // zero weight because the drawn path has more than max_k reflections
};

VgrooveSampleFlatland sample_vgroove_flatland(double theta_i, const std::array<double, 4>& u, NdfKind ndf, double alpha,
                                              const SamplerOptions& opt);

// pdf(theta_o) and rho2(theta_i, theta_o) cos(theta_o) (k <= max_k, F = 1) in one pass over the
// paths; the rho2 part is flatland_brdf's sum (brdf_flatland.h) visited in a single pass.
struct PdfAndBrdf2 {
  double pdf = 0.0;
  double rho_cos = 0.0;
};
PdfAndBrdf2 vgroove_pdf_and_brdf_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha,
                                          const SamplerOptions& opt);
double vgroove_pdf_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha, const SamplerOptions& opt);
double vgroove_pdf_flatland_k(double theta_i, double theta_o, NdfKind ndf, double alpha, const SamplerOptions& opt,
                              int k_lo, int k_hi);
// The printed p(theta_o) = |s.n| D2(s) G summed over the paths (not a density, ERRATA E-IS1).
double printed_p_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha, int max_k);

// The probability of no direction, integrated over the facet angle (independent of pdf).
double sampler_failure_probability_flatland(double theta_i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                            double tol = 1e-11);
// Its part from the paths of more than max_k reflections (sampling_3d.h).
double sampler_beyond_max_k_probability_flatland(double theta_i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                                 double tol = 1e-11);

// The flatland cosine law: pdf = cos(theta_o) / 2 over (-pi/2, pi/2), theta_o = asin(2 u - 1).
double sample_cosine_flatland(double u);
double cosine_flatland_pdf(double theta_o);

}  // namespace vgroove::analytic
