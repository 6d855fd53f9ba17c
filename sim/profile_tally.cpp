#include "vgroove/sim/profile_tally.h"

#include "vgroove/sim/beam.h"
#include "vgroove/sim/polyline_tracer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

double landing_x(const Polyline& p, double u) {
  const double x = p.x.front() + u * p.period;
  // u < 1, but u period may round up to the period itself: that point is x_0 of the next period.
  return x < p.x.back() ? x : std::nextafter(p.x.back(), p.x.front());
}

MicrosurfaceTally trace_profile_chunk(const Polyline& p, const MicrosurfaceTraceOptions& opt, std::int64_t chunk) {
  assert(std::abs(opt.theta_i) < 0.5 * std::numbers::pi && opt.rays >= 0);
  MicrosurfaceTally tally(opt.theta_o_bins, opt.max_k);
  const std::int64_t begin = chunk * kRaysPerChunk;
  const std::int64_t end = std::min(opt.rays, begin + kRaysPerChunk);
  Rng rng(opt.seed, kRayStream, static_cast<std::uint64_t>(chunk));
  const Vec2 dir = beam_direction(opt.theta_i);
  for (std::int64_t j = begin; j < end; ++j) {
    const double u = opt.sampling == Sampling::stratified
                         ? (static_cast<double>(j) + 0.5) / static_cast<double>(opt.rays)
                         : uniform_open(rng);
    const PolylineTraceResult r = trace_polyline(p, landing_x(p, u), dir, opt.trace);
    tally.add(r.how, r.bounces, r.exit_dir);
  }
  return tally;
}

MicrosurfaceTally trace_profile(const Polyline& p, const MicrosurfaceTraceOptions& opt,
                                const std::atomic<bool>* cancel) {
  MicrosurfaceTally total(opt.theta_o_bins, opt.max_k);
  const std::int64_t n = chunk_count(opt);
  for (std::int64_t c = 0; c < n && !(cancel && cancel->load(std::memory_order_relaxed)); ++c)
    total.merge(trace_profile_chunk(p, opt, c));
  return total;
}

}  // namespace vgroove::sim
