// vgroove analytic: the flatland (2D) multiple-scattering BRDF of a profile of symmetric V-grooves
// whose facet normals follow a flatland NDF, per bounce count k and summed, its single-scattering
// (Cook-Torrance) analogue, and the lobe binned over exit angles. Lee, Jarabo, Jeon, Gutierrez,
// Kim, "Practical Multiple Scattering for Rough Surfaces", ACM TOG 37(6), 2018: Eq. (10)-(17) and
// (25) written for flatland (D2 of analytic/ndf.h instead of D, theta instead of solid angle):
//   rho2(theta_i, theta_o; k) = sum_{solutions} D2(theta_s) w_k(theta_s) / (2 k cos theta_i cos theta_o).
// Conventions of analytic/kaleidoscope.h; F = 1. Holds: rho2(k = 1) equals the flatland
// Cook-Torrance exactly; rho2 cos cos is reciprocal per k and summed; the lobe's rows sum to 1
// (white furnace) and its bins agree with the pointwise BRDF; flux beyond n_resolved (below 1e-13
// or resolve_cap) is binned by its narrow-groove limit and reported as FlatlandLobe::tail.
// Tests: tests/analytic/brdf_flatland_test.cpp (FlatlandBrdf.Reciprocity,
// FlatlandBrdf.CookTorranceIsTheSingleBounceTerm, FlatlandLobe.WhiteFurnace,
// FlatlandLobe.PointwiseAgreesWithBinned, FlatlandLobe.TailLimitAgreesWithResolvedBins).
// Derivation: docs/derivations/brdf_flatland.md.
#pragma once

#include "vgroove/analytic/ndf.h"

#include <atomic>
#include <vector>

namespace vgroove::analytic {

// Pointwise flatland BRDF rho2(theta_i, theta_o; k), F = 1, k >= 1, from the solutions Eq. (4)
// allows (kaleidoscope_solutions.h, in the frame where t_h <= 0, the profile being mirror
// symmetric) with Eq. (6)'s widths written as products, which keep their relative accuracy where
// the ends nearly meet and at the horizon.
double flatland_brdf_k(NdfKind ndf, double alpha, double theta_i, double theta_o, int k);
// Sum over k = 1..max_k in one pass over those solutions, whatever max_k is: the cost of a few k
// (docs/performance.md, BM_flatland_brdf).
double flatland_brdf(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k);
// The same as flatland_brdf (the name the furnace suite uses).
double flatland_brdf_fast(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k);
// The same sums evaluated straightforwardly, per k over every m of step (d) with Eq. (6) through
// G_kaleidoscopic (differences of sines): O(max_k^2), equal to the single pass to 1e-10 relative
// away from the horizon, and within ~1e-5 deg of it off by up to all of the value (the differences
// of offsets near 1 lose the widths there). The tests' independent route to the single pass.
double flatland_brdf_k_reference(NdfKind ndf, double alpha, double theta_i, double theta_o, int k);
double flatland_brdf_reference(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k);
// Single scattering (the Cook-Torrance analogue, V-cavity G).
double flatland_brdf_single(NdfKind ndf, double alpha, double theta_i, double theta_o);

// The fraction of the incident flux leaving into each theta_o bin, per k: the analytic
// counterpart of sim::MicrosurfaceTally, with the same layout (bins equal over (-pi/2, pi/2);
// rows k = 0..max_k, row max_k + 1 holds every k > max_k).
struct FlatlandLobe {
  int bins = 0;
  int max_k = 0;
  std::vector<double> by_k;          // [row]
  std::vector<double> theta_o;       // [bin], all k
  std::vector<double> theta_o_by_k;  // [row * bins + bin]
  double albedo = 0.0;               // sum of by_k
  int n_resolved = 0;                // bounce counts binned exactly: n <= n_resolved
  double tail = 0.0;                 // flux with n > n_resolved, binned by the narrow-groove limit
  double below = 0.0;                // flux the model sends below the horizon (expected 0)
};

struct FlatlandLobeOptions {
  int quadrature_order = 16;  // Gauss-Legendre points on the pieces with k <= 8 (fewer above)
  int resolve_cap = 4096;     // largest n_resolved
  // Read every 8 MB of the histogram's zeroing, before each bounce count's pieces and every 4096
  // bins a piece crosses (may be null): once set, the rest is skipped and the lobe is incomplete
  // (the caller, stopped by Ctrl-C, discards it). 10^5 bins at max_k 300 take ~3-5 s; set at any
  // moment, the lobe returns within 30 ms.
  const std::atomic<bool>* cancel = nullptr;
};

FlatlandLobe flatland_lobe(NdfKind ndf, double alpha, double theta_i, int bins, int max_k);
FlatlandLobe flatland_lobe(NdfKind ndf, double alpha, double theta_i, int bins, int max_k,
                           const FlatlandLobeOptions& opt);
// The single-scattering lobe (k = 1 only, V-cavity G): albedo < 1, the energy Cook-Torrance loses.
// Layout with max_k = 1 (everything in row 1). Integrated over theta_h from Eq. (1)-(3), not from
// the kaleidoscope, so that the tests compare two derivations.
FlatlandLobe flatland_single_lobe(NdfKind ndf, double alpha, double theta_i, int bins);

}  // namespace vgroove::analytic
