// vgroove validation: one case's procedural V-groove surface and its rays, traced chunk by chunk.
//
// The surface is built from the case's NDF, alpha, groove count and seed (sim/microsurface.h in
// flatland, sim/microsurface3d.h in 3D); the rays are cut into chunks of sim::kRaysPerChunk, chunk
// c drawn from its own stream, and any run of chunks is traced into one tally of integer counts:
// the fates, the rays per bounce count k and the histograms of exit direction (total and per k).
// The brdf suites, the model tables and check_brdf's traced lobes trace through it, so a suite
// case and a traced lobe see the same rays, and a tally summed over any split of the chunks is
// the same to the count.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/parallel.h"

#include <cstdint>
#include <vector>

namespace vgroove::validation {

enum class SurfaceDim : unsigned char { flatland, three_d };
const char* surface_dim_name(SurfaceDim d);

// The surface check_brdf (check_brdf.h) and the "brdf" suites' model tables (model_table.h) trace:
// the procedural V-grooves below, or random heightfields (check_brdf.h: check_field).
enum class CheckSurface : unsigned char { vgroove, heightfield };
const char* check_surface_name(CheckSurface s);  // "vgroove", "heightfield"

struct CaseSurface {
  SurfaceDim dim = SurfaceDim::three_d;
  sim::Microsurface flat;       // in flatland
  sim::Microsurface3d three_d;  // in 3D
};
CaseSurface make_case_surface(SurfaceDim dim, NdfKind ndf, double alpha, int grooves, std::uint64_t seed);

// A case's rays and their bins (flatland: theta_o in (-pi/2, pi/2); 3D: theta_o in [0, pi/2)
// times phi_o centred on the mirror azimuth, the light at azimuth pi).
struct CaseRays {
  double theta_i = 0.0;  // radians
  std::int64_t rays = 0;
  std::uint64_t seed = 0;
  int flatland_bins = 90;
  int theta_bins = 90, phi_bins = 72;
  int max_k = 0;  // rows k = 0..max_k, and one for more
};

// The counts of a run of chunks (layouts of sim::MicrosurfaceTally and sim::Microsurface3dTally).
struct BinnedTally : sim::RayFates {
  std::vector<std::int64_t> by_k, hist, hist_by_k;
  double thread_s = 0.0;  // time spent tracing (a timing: never compared)
};

// Chunks [begin, end) of the case's rays over its surface; `cancel` is polled before each chunk.
BinnedTally trace_case_chunks(const CaseSurface& surface, const CaseRays& r, std::int64_t begin, std::int64_t end,
                              support::CancelFlag cancel = nullptr);

}  // namespace vgroove::validation
