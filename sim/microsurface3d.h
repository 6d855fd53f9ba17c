// vgroove sim: a 3D microsurface of infinitely long symmetric V-grooves whose facet normals follow
// a 3D NDF, traced exactly with the 2D tracer in each groove's cross-section and lifted back to 3D
// (DESIGN.md, "3D from 2D").
//
// TODO(helper 3D sim): derivation, conventions.
#pragma once

#include "sim/microsurface.h"

namespace vgroove::sim {

// Histogram layout shared with analytic::Lobe3d (analytic/brdf_3d.h): theta_o in [0, pi/2) in
// theta_bins equal bins; phi_o in phi_bins equal bins centred on phi = 0, phi_bins even; the light
// at polar angle theta_i and azimuth pi; rows k = 0..max_k (+1 for k > max_k);
// index [(row * theta_bins + t) * phi_bins + p].

}  // namespace vgroove::sim
