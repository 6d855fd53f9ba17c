// vgroove sim: the light a periodic polyline profile (sim/polyline.h) scatters, traced exactly
// with sim/polyline_tracer.h and tallied by bounce count k and exit angle (sim::MicrosurfaceTally).
//
// A parallel beam from theta_i lands uniformly on the top line y = y_max over one period: ray j of
// chunk c lands at x_0 + u period, u the stratified midpoint (j + 1/2) / rays or drawn from
// Rng(seed, kRayStream, c) (sim/microsurface.h's for_each_landing, the same numbers). On the
// V-groove polyline of a sim::Microsurface (vgroove_polyline) the landing points are exactly those
// of trace_microsurface scaled by 2, so the two tallies agree ray for ray (tested).
//
// Determinism: chunks of kRaysPerChunk rays with their own streams; integer counts merged in any
// order give bit-identical tallies for any thread count.
#pragma once

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/polyline.h"

#include <atomic>
#include <cstdint>

namespace vgroove::sim {

// Where ray j of the beam lands: x_0 + u period, strictly inside [x_0, x_0 + period).
double landing_x(const Polyline& p, double u);

// The rays of chunk c (kRaysPerChunk of them; the last chunk holds the rest).
MicrosurfaceTally trace_profile_chunk(const Polyline& p, const MicrosurfaceTraceOptions& opt, std::int64_t chunk);

// All chunks, merged in order (one thread). `cancel` (may be null) is read before each chunk; once
// set, the chunks traced so far are returned (an incomplete tally, for the caller to discard).
MicrosurfaceTally trace_profile(const Polyline& p, const MicrosurfaceTraceOptions& opt,
                                const std::atomic<bool>* cancel = nullptr);

}  // namespace vgroove::sim
