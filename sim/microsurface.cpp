#include "vgroove/sim/microsurface.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

Microsurface make_microsurface(const MicrosurfaceOptions& opt) {
  assert(opt.alpha > 0.0 && opt.grooves > 0);
  Microsurface m;
  m.options = opt;
  m.theta_m.reserve(static_cast<std::size_t>(opt.grooves));
  m.grooves.reserve(static_cast<std::size_t>(opt.grooves));
  // The steepest facet that still leaves an opening: a slope that rounds to +-pi/2 would close the
  // groove (aperture 0); the next angle down gives an aperture of ~4e-16 rad, whose rays end in
  // the bounce-limit bucket instead of being lost to an invalid groove.
  const double steepest = std::nextafter(0.5 * std::numbers::pi, 0.0);
  for (int j = 0; j < opt.grooves; ++j) {
    Rng rng(opt.seed, kGrooveStream, static_cast<std::uint64_t>(j));
    const double t = std::min(steepest, std::abs(sample_theta_m(opt.ndf, opt.alpha, uniform_open(rng))));
    m.theta_m.push_back(t);
    // make_symmetric_groove's left facet normal is at -(pi - theta_v)/2 = -t, the right one at +t.
    m.grooves.push_back(make_symmetric_groove(std::numbers::pi - 2.0 * t));
  }
  return m;
}

MicrosurfaceTally::MicrosurfaceTally(int bins_, int max_k_)
    : bins(bins_),
      max_k(max_k_),
      by_k(static_cast<std::size_t>(max_k_) + 2, 0),
      theta_o(static_cast<std::size_t>(bins_), 0),
      theta_o_by_k((static_cast<std::size_t>(max_k_) + 2) * static_cast<std::size_t>(bins_), 0) {
  assert(bins_ > 0 && max_k_ >= 0);
}

int MicrosurfaceTally::bin_of(double theta) const {
  const int j = static_cast<int>(std::floor((theta + 0.5 * std::numbers::pi) / bin_width()));
  // theta is inside (-pi/2, pi/2) here; the clamp only absorbs rounding of the division there.
  return std::clamp(j, 0, bins - 1);
}

void MicrosurfaceTally::add(Termination how, int k, const Vec2& exit_dir) {
  if (!count(how, k, exit_dir.y() > 0.0)) return;
  const int row = row_of(k);
  const int bin = bin_of(angle_from_normal(exit_dir));
  ++by_k[static_cast<std::size_t>(row)];
  ++theta_o[static_cast<std::size_t>(bin)];
  ++theta_o_by_k[static_cast<std::size_t>(row) * bins + bin];
}

void MicrosurfaceTally::merge(const MicrosurfaceTally& o) {
  assert(o.bins == bins && o.max_k == max_k);
  merge_fates(o);
  for (std::size_t i = 0; i < by_k.size(); ++i) by_k[i] += o.by_k[i];
  for (std::size_t i = 0; i < theta_o.size(); ++i) theta_o[i] += o.theta_o[i];
  for (std::size_t i = 0; i < theta_o_by_k.size(); ++i) theta_o_by_k[i] += o.theta_o_by_k[i];
}

std::int64_t chunk_count(const MicrosurfaceTraceOptions& opt) { return (opt.rays + kRaysPerChunk - 1) / kRaysPerChunk; }

MicrosurfaceTally trace_microsurface_chunk(const Microsurface& surface, const MicrosurfaceTraceOptions& opt,
                                           std::int64_t chunk) {
  assert(std::abs(opt.theta_i) < 0.5 * std::numbers::pi && opt.rays >= 0);
  MicrosurfaceTally tally(opt.theta_o_bins, opt.max_k);
  for_each_landing(surface.grooves, opt.theta_i, opt.sampling, opt.rays, opt.seed, chunk,
                   [&](const Groove& groove, const Ray2& ray) { tally.add(trace(groove, ray, opt.trace)); });
  return tally;
}

MicrosurfaceTally trace_microsurface(const Microsurface& surface, const MicrosurfaceTraceOptions& opt) {
  MicrosurfaceTally total(opt.theta_o_bins, opt.max_k);
  const std::int64_t n = chunk_count(opt);
  for (std::int64_t c = 0; c < n; ++c) total.merge(trace_microsurface_chunk(surface, opt, c));
  return total;
}

}  // namespace vgroove::sim
