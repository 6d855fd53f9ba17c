// vgroove validation: the light of a procedural V-groove surface, traced exactly and binned: what
// a model's bin-integrated lobe is held against (check_brdf.h, model_table.h).
//
// The surface is the Fig. 11 suite's (sim/microsurface.h in flatland, sim/microsurface3d.h in 3D)
// for the NDF, alpha, groove count and seed; the rays of each incidence are cut into chunks
// (sim::kRaysPerChunk) drawn from the same seed, so a suite case and this trace see the same rays.
// Bins: 3D theta_o in [0, pi/2) in theta_bins times phi_o in phi_bins bins centred on the mirror
// direction's azimuth (the light at azimuth pi); flatland theta_o in (-pi/2, pi/2) in
// flatland_bins bins. Work items are (incidence, chunk); tallies merge in chunk order, so the
// result does not depend on the thread count.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/validation/brdf_suite.h"

#include <atomic>
#include <cstdint>
#include <vector>

namespace vgroove::validation {

struct LobeSetup {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;
  SurfaceDim dim = SurfaceDim::three_d;
  long rays = 1'000'000;  // per incidence
  int grooves = 250'000;
  std::uint64_t seed = 1;
  int theta_bins = 30, phi_bins = 24;  // 3D
  int flatland_bins = 90;
  bool k1 = false;  // also tally the single-scattering rays apart (TracedLobe::flux_k1)
  int bins() const { return dim == SurfaceDim::flatland ? flatland_bins : theta_bins * phi_bins; }
};

struct TracedLobe {
  std::vector<double> flux;     // fraction of the incident rays leaving into each bin
  std::vector<double> flux_k1;  // the same for the rays leaving after one reflection (setup.k1)
  std::int64_t rays = 0;
  double thread_s = 0.0;  // tracing time summed over the chunks (thread time)
};

// The lobes at every incidence theta_i (radians, in [0, pi/2)); empty when *cancel was set.
std::vector<TracedLobe> trace_lobes(const LobeSetup& setup, const std::vector<double>& theta_i, int threads,
                                    const std::atomic<bool>* cancel = nullptr);

}  // namespace vgroove::validation
