// vgroove sim: a procedural flatland microsurface of many symmetric V-grooves, and the light it
// scatters, traced exactly. Lee et al. 2018 ("Practical Multiple Scattering for Rough Surfaces",
// ACM TOG 37(6)), Sec. 5 (each facet belongs to one groove, all peaks on the macrosurface) and
// Sec. 7.1 (brute-force simulation, Fig. 11). G grooves of equal width 1/G; groove j has facet
// normals at -+theta_j, theta_j = |sample_theta_m(u_j)| drawn from 2 D2 cos (the width is what the
// draw weights). A ray lands uniformly on the macrosurface and is traced with sim::trace in the
// groove under it (it cannot reach another). Deterministic: groove j from Rng(surface seed,
// kGrooveStream, j), chunk c from Rng(ray seed, kRayStream, c); any split gives the same bits.
// Holds: the grooves cover the length as the NDF says; every ray is accounted (albedo 1); mirror
// symmetry and reciprocity within statistics; chunk order does not matter.
// Tests: tests/sim/microsurface_test.cpp (Microsurface.GroovesCoverTheLengthAsTheNdfSays,
// Microsurface.AlbedoIsOneAndEveryRayIsAccounted, Microsurface.MirrorSymmetry,
// MicrosurfaceReciprocity.TracedFlatlandSurfaceIsReciprocalWithinStatistics,
// Microsurface.ResultsDoNotDependOnHowChunksAreMerged).
// Derivation: docs/derivations/microsurface.md.
#pragma once

#include "vgroove/sim/beam.h"
#include "vgroove/sim/groove.h"
#include "vgroove/sim/ray_fates.h"
#include "vgroove/sim/rng.h"
#include "vgroove/sim/slope_sampling.h"
#include "vgroove/sim/symmetric_block.h"
#include "vgroove/sim/tracer.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <numbers>
#include <vector>

namespace vgroove::sim {

struct MicrosurfaceOptions {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;  // roughness, > 0
  int grooves = 10000;
  std::uint64_t seed = 0;
};

struct Microsurface {
  MicrosurfaceOptions options;
  std::vector<double> theta_m;  // |theta_m| of each groove, in [0, pi/2)
  std::vector<Groove> grooves;  // aperture pi - 2 theta_m[j], unit facets (make_symmetric_groove)
  // The same grooves in 24 bytes each (symmetric_block.h), what the batch trace reads; a surface
  // without them (built by hand) is traced one ray at a time.
  std::vector<SymmetricGrooveData> data;
};

inline constexpr std::uint64_t kGrooveStream = 0x67726f6f7665ULL;  // "groove"
inline constexpr std::uint64_t kRayStream = 0x72617973ULL;         // "rays"
inline constexpr std::int64_t kRaysPerChunk = 1 << 15;

// uniform_open: uniform in the open interval (0, 1), never 0 or 1 (an endpoint would put a facet at exactly
// +-pi/2, or a ray exactly on a peak): (v + 1/2) 2^-53 for the top 53 bits v of a draw, the
// midpoints of 2^53 equal strata below 1/2; above, v + 1/2 rounds to an even neighbour (doubles
// there are 1 apart), and for v = 2^53 - 1 it would round to 2^53, so u = 1: that one value is
// taken to the largest double below 1.
inline constexpr double kBelowOne = 1.0 - 0x1.0p-53;
// The uniforms of n values of next_u64 (or next_u64s), in a loop that vectorizes: v = b >> 11
// (< 2^53) converted exactly as its low 52 bits (the exponent of 2^52 put above them, 2^52
// subtracted) plus its top bit times 2^52, which is static_cast<double>(v) without a 64-bit
// integer conversion (AVX2 has none).
inline void uniform_open_of(const std::uint64_t* bits, double* u, int n) {
  constexpr std::uint64_t two52 = 0x4330000000000000ULL;  // the bits of 2^52
  for (int q = 0; q < n; ++q) {
    const std::uint64_t v = bits[q] >> 11;
    const double lo = std::bit_cast<double>(two52 | (v & 0xfffffffffffffULL)) - 0x1.0p52;
    const double hi = std::bit_cast<double>(two52 | (v >> 52)) - 0x1.0p52;
    const double w = (lo + hi * 0x1.0p52 + 0.5) * 0x1.0p-53;
    u[q] = w < kBelowOne ? w : kBelowOne;
  }
}
// The stream's next uniform.
inline double uniform_open(Rng& rng) {
  const std::uint64_t b = rng.next_u64();
  double u;
  uniform_open_of(&b, &u, 1);
  return u;
}

Microsurface make_microsurface(const MicrosurfaceOptions& opt);

struct MicrosurfaceTraceOptions {
  double theta_i = 0.0;  // direction towards the light, in (-pi/2, pi/2)
  std::int64_t rays = 100000;
  Sampling sampling = Sampling::random;  // landing points: seeded uniform, or stratified midpoints
  std::uint64_t seed = 0;
  int theta_o_bins = 90;  // equal bins over (-pi/2, pi/2)
  int max_k = 16;         // per-k histograms for k = 0..max_k; larger k share the last row
  TraceOptions trace;
};

// What happened to the rays. Every ray is in exactly one of escaped, blocked, vertex_hits,
// bounce_limit, not_upward; every escaped ray in one k row and one theta_o bin.
struct MicrosurfaceTally : RayFates {
  int bins = 0;
  int max_k = 0;
  std::vector<std::int64_t> by_k;          // [k], k = 0..max_k + 1 (the last: more than max_k)
  std::vector<std::int64_t> theta_o;       // [bin], all escaped rays
  std::vector<std::int64_t> theta_o_by_k;  // [k * bins + bin], rows as in by_k

  MicrosurfaceTally() = default;
  MicrosurfaceTally(int bins_, int max_k_);

  double bin_width() const { return std::numbers::pi / bins; }
  double bin_lo(int j) const { return -0.5 * std::numbers::pi + j * bin_width(); }
  double bin_center(int j) const { return bin_lo(j) + 0.5 * bin_width(); }
  int bin_of(double theta) const;
  int row_of(int k) const { return k > max_k ? max_k + 1 : k; }
  std::int64_t hist(int k_row, int bin) const { return theta_o_by_k[static_cast<std::size_t>(k_row) * bins + bin]; }

  void add(const TraceResult& r) { add(r.how, r.bounces, r.exit_dir); }
  void add(Termination how, int k, const Vec2& exit_dir);
  // A ray whose bin is known (the chunks find it among the edges, sim/exit_bins.h).
  void add_binned(Termination how, int k, bool upward, int bin);
  // add_binned for n rays (bin[q] a whole number; exit_y[q] > 0: upward), the same counts: the
  // fates' totals kept in registers over the block instead of in memory ray by ray.
  void add_binned_block(const Termination* how, const int* k, const double* exit_y, const double* bin, int n);
  void merge(const MicrosurfaceTally& other);  // same bins and max_k
};

std::int64_t chunk_count(const MicrosurfaceTraceOptions& opt);

// The rays of chunk c of a beam of `rays` rays from theta_i over grooves of equal width side by
// side (all of a microsurface's, or a single groove): for each ray in order, the groove its
// landing point falls in and the ray crossing that groove's opening, handed to fn(groove, ray).
// Landing points are stratified (stratified_landing), or drawn from Rng(seed, kRayStream, c).
// Stratified landing point j of `rays` on `grooves` grooves: the midpoint (j + 1/2) G / rays of
// the j-th of `rays` equal strata of [0, G), in exact integer arithmetic: groove (2j + 1) G div
// 2 rays, f = r / (2 rays) with r = (2j + 1) G mod 2 rays. A midpoint is a multiple of
// 1 / (2 rays) and falls exactly on a ridge (r = 0) whenever (2j + 1) G / (2 rays) is whole (for
// G = 2 rays, every one): such a point is moved into the groove on its right by 1 / (4 rays) of a
// groove, half the midpoints' granularity, so that no ray lands on a ridge (a vertex hit). One
// groove never needs it: its midpoints are f = (j + 1/2) / rays, bit for bit.
struct Landing {
  int groove = 0;
  double f = 0.0;  // in (0, 1)
};
inline Landing stratified_landing(std::int64_t j, std::int64_t rays, std::int64_t grooves) {
  __extension__ using Wide = __int128;  // (2j + 1) G exactly, for any j, rays and G
  const Wide num = static_cast<Wide>(2 * j + 1) * grooves, den = 2 * static_cast<Wide>(rays);
  const auto r = static_cast<std::int64_t>(num % den);
  Landing at;
  at.groove = static_cast<int>(num / den);
  at.f = r == 0 ? 0.25 / static_cast<double>(rays) : static_cast<double>(r) / static_cast<double>(den);
  return at;
}

template <class Fn>
void for_each_landing(const std::vector<Groove>& grooves, double theta_i, Sampling sampling, std::int64_t rays,
                      std::uint64_t seed, std::int64_t chunk, Fn&& fn) {
  const std::int64_t begin = chunk * kRaysPerChunk;
  const std::int64_t end = std::min(rays, begin + kRaysPerChunk);
  if (begin >= end || grooves.empty()) return;
  Rng rng(seed, kRayStream, static_cast<std::uint64_t>(chunk));
  const Vec2 dir = beam_direction(theta_i);
  const double g_count = static_cast<double>(grooves.size());
  const int last = static_cast<int>(grooves.size()) - 1;
  for (std::int64_t j = begin; j < end; ++j) {
    // Landing point on the macrosurface [0, G) in units of the groove width: groove index and
    // fraction f across its opening (one groove: f = u exactly).
    int g;
    double f;
    if (sampling == Sampling::stratified) {
      const Landing at = stratified_landing(j, rays, static_cast<std::int64_t>(grooves.size()));
      g = at.groove, f = at.f;
    } else {
      const double x = uniform_open(rng) * g_count;
      g = std::min(last, static_cast<int>(x));
      f = x - g;
    }
    const Groove& groove = grooves[static_cast<std::size_t>(g)];
    const double xl = groove.rim_x(Side::left), xr = groove.rim_x(Side::right);
    // f = 0 lands exactly on the left peak: sim::trace reports it as a vertex hit.
    fn(groove, beam_ray(groove, dir, xl + f * (xr - xl)));
  }
}

// The rays of chunk c (kRaysPerChunk of them; the last chunk holds the rest): the landing points of
// for_each_landing, traced in blocks (symmetric_block.h: each ray's first reflection computed
// with the block's, without branches; bit for bit sim::trace) and binned from an arctangent
// guess, by the edge tests where it lies near an edge (sim/exit_bins.h; the same bins).
MicrosurfaceTally trace_microsurface_chunk(const Microsurface& surface, const MicrosurfaceTraceOptions& opt,
                                           std::int64_t chunk);
// The same rays added to `tally` (bins and max_k of opt), for callers that sum chunks.
void trace_microsurface_chunk(const Microsurface& surface, const MicrosurfaceTraceOptions& opt, std::int64_t chunk,
                              MicrosurfaceTally& tally);
// The same one ray at a time with sim::trace on surface.grooves, binned by atan2: the path before
// the blocks, kept for the tests and the benchmarks' side-by-side.
MicrosurfaceTally trace_microsurface_chunk_reference(const Microsurface& surface, const MicrosurfaceTraceOptions& opt,
                                                     std::int64_t chunk);

// All chunks, merged in order (one thread; a caller may run the chunks on several and merge).
MicrosurfaceTally trace_microsurface(const Microsurface& surface, const MicrosurfaceTraceOptions& opt);

}  // namespace vgroove::sim
