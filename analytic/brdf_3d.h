// vgroove analytic: the 3D multiple-scattering BRDF of symmetric V-grooves, Lee et al. 2018,
// Eq. (13)-(17), and Cook-Torrance, Eq. (1)-(3) with the V-cavity G; Fresnel as a plug-in term.
//
// TODO(helper 3D analytic): derivation, conventions, errata, limits.
#pragma once

#include "analytic/ndf.h"

#include <vector>

namespace vgroove::analytic {

// Unit vectors in the frame of the macrosurface: n = (0, 0, 1). The direction at polar angle
// theta and azimuth phi is (sin theta cos phi, sin theta sin phi, cos theta).
struct Dir3 {
  double x = 0.0, y = 0.0, z = 1.0;
};
Dir3 dir3(double theta, double phi);

// Eq. (16), F = 1: the k-resolved BRDF, k >= 1. i and o point away from the surface.
double vgroove_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha);
// Eq. (17): the sum over k = 1..max_k.
double vgroove_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k);
// Eq. (1)-(3): Cook-Torrance with the V-cavity G (Eq. 2), F = 1.
double cook_torrance(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha);

// The fraction of the incident flux leaving into each (theta_o, phi_o) bin, per k. Layout shared
// with sim::Microsurface3dTally: theta_o in [0, pi/2) in theta_bins equal bins; phi_o in
// phi_bins equal bins centred on phi = 0 (bin 0 covers [-d/2, d/2), d = 2 pi / phi_bins),
// phi_bins even, so that the plane of incidence runs through the centres of bins 0 and
// phi_bins / 2. The light is at i = dir3(theta_i, pi) (its mirror direction at phi = 0).
// Rows k = 0..max_k, row max_k + 1 holds every k > max_k; index [(row * theta_bins + t) * phi_bins + p].
struct Lobe3d {
  int theta_bins = 0;
  int phi_bins = 0;
  int max_k = 0;
  std::vector<double> by_k;    // [row]
  std::vector<double> hist;    // [t * phi_bins + p], all k
  std::vector<double> hist_by_k;
  double albedo = 0.0;
};

Lobe3d vgroove_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k);
Lobe3d cook_torrance_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins);

}  // namespace vgroove::analytic
