#include "vgroove/sim/ndf_grooves.h"

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/sim/slope_sampling.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

void BounceCounts::merge(const BounceCounts& o) {
  assert(o.max_k == max_k);
  merge_fates(o);
  for (std::size_t i = 0; i < by_k.size(); ++i) by_k[i] += o.by_k[i];
}

std::int64_t chunk_count(const NdfGrooveOptions& opt) { return (opt.rays + kRaysPerChunk - 1) / kRaysPerChunk; }

BounceCounts trace_ndf_grooves_chunk(const NdfGrooveOptions& opt, std::int64_t chunk) {
  assert(opt.alpha > 0.0 && opt.rays >= 0 && std::abs(opt.theta_i) < 0.5 * std::numbers::pi);
  BounceCounts counts(opt.max_k);
  const std::int64_t begin = chunk * kRaysPerChunk, end = std::min(opt.rays, begin + kRaysPerChunk);
  Rng rng(splitmix64(opt.seed ^ kNdfGrooveStream), opt.stream, static_cast<std::uint64_t>(chunk));
  // The steepest facet that still leaves an opening (as make_microsurface and add_groove3d).
  const double steepest = std::nextafter(0.5 * std::numbers::pi, 0.0);
  auto tally = [&](const TraceResult& r, bool upward) {
    if (counts.count(r.how, r.bounces, upward)) ++counts.by_k[static_cast<std::size_t>(counts.row_of(r.bounces))];
  };
  if (opt.three_d) {
    // dir(theta_i, pi), its y the exact 0 (as trace_microsurface3d_chunk).
    const Vec3 i(-std::sin(opt.theta_i), 0.0, std::cos(opt.theta_i));
    for (std::int64_t j = begin; j < end; ++j) {
      const double t = std::min(steepest, sample_theta_m_3d(opt.ndf, opt.alpha, uniform_open(rng)));
      const double phi = std::numbers::pi * uniform_open(rng);
      const Groove g = make_symmetric_groove(std::numbers::pi - 2.0 * t);
      const Trace3dResult r =
          trace_groove3d(g, GrooveFrame3d{std::cos(phi), std::sin(phi)}, i, uniform_open(rng), opt.trace);
      tally(r.trace, r.o.z() > 0.0);
    }
  } else {
    const Vec2 dir = beam_direction(opt.theta_i);
    for (std::int64_t j = begin; j < end; ++j) {
      const double t = std::min(steepest, std::abs(sample_theta_m(opt.ndf, opt.alpha, uniform_open(rng))));
      const Groove g = make_symmetric_groove(std::numbers::pi - 2.0 * t);
      const double xl = g.rim_x(Side::left), xr = g.rim_x(Side::right);
      const TraceResult r = trace(g, beam_ray(g, dir, xl + uniform_open(rng) * (xr - xl)), opt.trace);
      tally(r, r.exit_dir.y() > 0.0);
    }
  }
  return counts;
}

}  // namespace vgroove::sim
