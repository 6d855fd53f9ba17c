#include "vgroove/sim/profile_visibility.h"

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/polyline_tracer.h"
#include "vgroove/sim/profile_tally.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

std::int64_t VisibilityTally::seen_total() const {
  std::int64_t s = 0;
  for (std::int64_t c : seen) s += c;
  return s;
}

void VisibilityTally::merge(const VisibilityTally& o) {
  assert(o.seen.size() == seen.size());
  rays += o.rays;
  vertex_hits += o.vertex_hits;
  back_face += o.back_face;
  shadow_vertex += o.shadow_vertex;
  for (std::size_t s = 0; s < seen.size(); ++s) seen[s] += o.seen[s], seen_lit[s] += o.seen_lit[s];
}

VisibilityTally trace_visibility_chunk(const Polyline& p, const VisibilityOptions& opt, std::int64_t chunk) {
  assert(std::abs(opt.theta_view) < 0.5 * std::numbers::pi && opt.rays >= 0);
  VisibilityTally t(p.segments());
  const std::int64_t begin = chunk * kRaysPerChunk;
  const std::int64_t end = std::min(opt.rays, begin + kRaysPerChunk);
  Rng rng(opt.seed, kRayStream, static_cast<std::uint64_t>(chunk));
  const Vec2 dir = beam_direction(opt.theta_view);
  const Vec2 light = opt.theta_light ? direction_at(*opt.theta_light) : Vec2::Zero();
  for (std::int64_t j = begin; j < end; ++j) {
    const double u = opt.sampling == Sampling::stratified
                         ? (static_cast<double>(j) + 0.5) / static_cast<double>(opt.rays)
                         : uniform_open(rng);
    ++t.rays;
    const PolylineHit h = first_hit_from_top(p, landing_x(p, u), dir);
    if (h.kind != PolylineHit::Kind::segment) {
      ++t.vertex_hits;  // from the top line a ray always meets the profile
      continue;
    }
    const std::size_t s = static_cast<std::size_t>(h.segment);
    if (!(dir.dot(p.normal[s]) < 0.0)) {
      ++t.back_face;
      continue;
    }
    ++t.seen[s];
    if (!opt.theta_light || !(light.dot(p.normal[s]) > 0.0)) continue;
    const PolylineHit shadow = first_hit_from(p, h.segment, h.s, light);
    if (shadow.kind == PolylineHit::Kind::escaped)
      ++t.seen_lit[s];
    else if (shadow.kind == PolylineHit::Kind::vertex)
      ++t.shadow_vertex;
  }
  return t;
}

VisibilityTally trace_visibility(const Polyline& p, const VisibilityOptions& opt, const std::atomic<bool>* cancel) {
  VisibilityTally total(p.segments());
  const std::int64_t n = (opt.rays + kRaysPerChunk - 1) / kRaysPerChunk;
  for (std::int64_t c = 0; c < n && !(cancel && cancel->load(std::memory_order_relaxed)); ++c)
    total.merge(trace_visibility_chunk(p, opt, c));
  return total;
}

}  // namespace vgroove::sim
