#include "vgroove/sim/microsurface.h"

#include "vgroove/common/simd.h"
#include "vgroove/sim/exit_bins.h"

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
  m.data.reserve(static_cast<std::size_t>(opt.grooves));
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
    m.data.push_back(symmetric_groove_data(m.grooves.back()));
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

void MicrosurfaceTally::add_binned(Termination how, int k, bool upward, int bin) {
  if (!count(how, k, upward)) return;
  const int row = row_of(k);
  ++by_k[static_cast<std::size_t>(row)];
  ++theta_o[static_cast<std::size_t>(bin)];
  ++theta_o_by_k[static_cast<std::size_t>(row) * bins + bin];
}

void MicrosurfaceTally::add_binned_block(const Termination* how, const int* k, const double* exit_y, const double* bin,
                                         int n) {
  std::int64_t up = 0, sum_k = 0;
  int k_max = 0;
  // The arrays' addresses in registers (a count written through a pointer could otherwise be
  // any of them).
  std::int64_t* const rows = by_k.data();
  std::int64_t* const cells = theta_o.data();
  std::int64_t* const row_cells = theta_o_by_k.data();
  const int last_row = max_k + 1;
  const std::ptrdiff_t per_row = bins;
  for (int q = 0; q < n; ++q) {
    const int kq = k[q];
    if (how[q] != Termination::escaped || !(exit_y[q] > 0.0)) [[unlikely]] {
      count(how[q], kq, exit_y[q] > 0.0);  // a lost ray: counted, not binned
      continue;
    }
    ++up, sum_k += kq, k_max = std::max(k_max, kq);
    const int row = std::min(kq, last_row);  // row_of(kq)
    const auto b = static_cast<std::ptrdiff_t>(static_cast<int>(bin[q]));
    ++rows[row];
    ++cells[b];
    ++row_cells[row * per_row + b];
  }
  add_escaped(up, sum_k, k_max);
}

void MicrosurfaceTally::merge(const MicrosurfaceTally& o) {
  assert(o.bins == bins && o.max_k == max_k);
  merge_fates(o);
  for (std::size_t i = 0; i < by_k.size(); ++i) by_k[i] += o.by_k[i];
  for (std::size_t i = 0; i < theta_o.size(); ++i) theta_o[i] += o.theta_o[i];
  for (std::size_t i = 0; i < theta_o_by_k.size(); ++i) theta_o_by_k[i] += o.theta_o_by_k[i];
}

std::int64_t chunk_count(const MicrosurfaceTraceOptions& opt) { return (opt.rays + kRaysPerChunk - 1) / kRaysPerChunk; }

VGROOVE_TARGET_CLONES
void trace_microsurface_chunk(const Microsurface& surface, const MicrosurfaceTraceOptions& opt, std::int64_t chunk,
                              MicrosurfaceTally& tally) {
  assert(std::abs(opt.theta_i) < 0.5 * std::numbers::pi && opt.rays >= 0);
  assert(tally.bins == opt.theta_o_bins && tally.max_k == opt.max_k);
  if (surface.data.size() != surface.grooves.size() || opt.trace.max_bounces < 1) {
    tally.merge(trace_microsurface_chunk_reference(surface, opt, chunk));
    return;
  }
  const std::int64_t begin = chunk * kRaysPerChunk;
  const std::int64_t end = std::min(opt.rays, begin + kRaysPerChunk);
  if (begin >= end || surface.grooves.empty()) return;
  // for_each_landing's landing points, in the same order from the same stream.
  Rng rng(opt.seed, kRayStream, static_cast<std::uint64_t>(chunk));
  const Vec2 dir = beam_direction(opt.theta_i);
  const double g_count = static_cast<double>(surface.grooves.size());
  const int last = static_cast<int>(surface.grooves.size()) - 1;
  const AngleEdges edges(-0.5 * std::numbers::pi, std::numbers::pi / opt.theta_o_bins, opt.theta_o_bins);
  SymmetricBlock in;
  for (int q = 0; q < kSymmetricBlock; ++q) in.dx[q] = dir.x(), in.dy[q] = dir.y();  // one beam
  SymmetricHits hits;
  Termination how[kSymmetricBlock];
  int k_of[kSymmetricBlock];
  double ex[kSymmetricBlock], ey[kSymmetricBlock], g_of[kSymmetricBlock], b_of[kSymmetricBlock];
  double u_of[kSymmetricBlock];
  std::uint64_t bits[kSymmetricBlock];
  for (std::int64_t j0 = begin; j0 < end; j0 += kSymmetricBlock) {
    const int m = static_cast<int>(std::min<std::int64_t>(kSymmetricBlock, end - j0));
    if (opt.sampling != Sampling::stratified) {
      rng.next_u64s(bits, m);
      uniform_open_of(bits, u_of, m);
    }
    for (int q = 0; q < m; ++q) {
      int g;
      double f;
      if (opt.sampling == Sampling::stratified) {
        const Landing at = stratified_landing(j0 + q, opt.rays, static_cast<std::int64_t>(surface.grooves.size()));
        g = at.groove, f = at.f;
      } else {
        const double x = u_of[q] * g_count;
        g = std::min(last, static_cast<int>(x));
        f = x - g;
      }
      const SymmetricGrooveData& d = surface.data[static_cast<std::size_t>(g)];
      in.left_x[q] = d.left_x;
      in.right_x[q] = d.right_x;
      in.rim_height[q] = d.rim_height;
      in.x[q] = d.left_x + f * (d.right_x - d.left_x);
    }
    block_reflections(in, m, opt.trace.max_bounces, kBlockRounds, hits);
    // Every lane as the block settled it; then the lanes it did not settle, one by one.
    for (int q = 0; q < m; ++q) {
      how[q] = Termination::escaped, k_of[q] = static_cast<int>(hits.k[q]), ex[q] = hits.d1x[q], ey[q] = hits.d1y[q];
    }
    for (int q = 0; q < m; ++q) {
      if (hits.path[q] == 0) [[likely]]
        continue;
      const TraceResult r = finish_lane(in, hits, q, opt.trace);
      how[q] = r.how, k_of[q] = r.bounces, ex[q] = r.exit_dir.x(), ey[q] = r.exit_dir.y();
    }
    // The bins (angle_from_normal(e) = atan2(-e.x, e.y), the angle of (e.y, -e.x)) from the
    // guesses where they are far from every edge (vectorized), the edge tests for the rest.
    for (int q = 0; q < m; ++q) {
      g_of[q] = atan2_guess(-ex[q], ey[q]);
      b_of[q] = edges.bin_if_far(g_of[q]);
    }
    for (int q = 0; q < m; ++q) {
      if (b_of[q] < 0.0) [[unlikely]]
        b_of[q] = edges.bin(ey[q], -ex[q], g_of[q]);
    }
    tally.add_binned_block(how, k_of, ey, b_of, m);
  }
}

MicrosurfaceTally trace_microsurface_chunk(const Microsurface& surface, const MicrosurfaceTraceOptions& opt,
                                           std::int64_t chunk) {
  MicrosurfaceTally tally(opt.theta_o_bins, opt.max_k);
  trace_microsurface_chunk(surface, opt, chunk, tally);
  return tally;
}

MicrosurfaceTally trace_microsurface_chunk_reference(const Microsurface& surface, const MicrosurfaceTraceOptions& opt,
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
  for (std::int64_t c = 0; c < n; ++c) trace_microsurface_chunk(surface, opt, c, total);
  return total;
}

}  // namespace vgroove::sim
