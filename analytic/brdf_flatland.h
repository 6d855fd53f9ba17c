// vgroove analytic: the flatland (2D) multiple-scattering BRDF of a profile of symmetric V-grooves
// whose facet normals follow a flatland NDF, per bounce count k and summed, and its single-
// scattering (Cook-Torrance) analogue. Lee et al. 2018, Sec. 5.1 (Eq. 10-17) and 5.3 (Eq. 25),
// written for flatland: D2 (analytic/ndf.h) instead of D, theta instead of solid angle.
//
// TODO(helper flatland): derivation, conventions, limits.
#pragma once

#include "analytic/ndf.h"

#include <vector>

namespace vgroove::analytic {

// Pointwise flatland BRDF rho2(theta_i, theta_o; k), F = 1, k >= 1.
double flatland_brdf_k(NdfKind ndf, double alpha, double theta_i, double theta_o, int k);
// Sum over k = 1..max_k.
double flatland_brdf(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k);
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
};

FlatlandLobe flatland_lobe(NdfKind ndf, double alpha, double theta_i, int bins, int max_k);
// The single-scattering lobe (k = 1 only, V-cavity G): albedo < 1, the energy Cook-Torrance loses.
FlatlandLobe flatland_single_lobe(NdfKind ndf, double alpha, double theta_i, int bins);

}  // namespace vgroove::analytic
