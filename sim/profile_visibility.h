// vgroove sim: which points of a polyline profile (sim/polyline.h) a viewer sees and which of
// those the light reaches, traced exactly with sim/polyline_tracer.h: the raw counts behind the
// masking function G1(o, m), the masking-shadowing function G2(i, o, m) and the lit length
// (Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT
// 3(2), Sec. 2-5: G1 is the visible fraction of the facets of normal m seen from o; G2 the
// fraction visible from o and lit from i).
//
// A beam of N parallel rays from the view direction o (travelling along -o) lands uniformly on
// the top line over one period (sim/profile_tally.h's landing points); the segment each ray meets
// first is the point it sees, and counts for that segment. A ray stands for the beam width
// period cos(theta_o) / N, so seen[s] period cos(theta_o) / N estimates the projected length
// (perpendicular to o) of segment s that is visible from o: G1 of the segment times
// length_s (o.n_s)+. With a light direction i, a shadow ray leaves each seen point towards i
// (sim::first_hit_from, the segment itself excluded): the point is lit when the ray escapes (and
// the segment faces the light, i.n > 0), and counts in seen_lit[s].
//
// No model is assumed here: the counts are per segment, and validation/ bins them by normal and
// sets them against Smith's and the V-cavity masking functions.
//
// Determinism: chunks of kRaysPerChunk rays from Rng(seed, kRayStream, chunk); integer counts.
#pragma once

#include "vgroove/sim/beam.h"
#include "vgroove/sim/polyline.h"

#include <atomic>
#include <cstdint>
#include <optional>
#include <vector>

namespace vgroove::sim {

struct VisibilityOptions {
  double theta_view = 0.0;            // o, in (-pi/2, pi/2)
  std::optional<double> theta_light;  // i, in (-pi/2, pi/2); no shadow rays when unset
  std::int64_t rays = 100000;
  Sampling sampling = Sampling::random;
  std::uint64_t seed = 0;
};

struct VisibilityTally {
  std::int64_t rays = 0;
  std::int64_t vertex_hits = 0;        // first hit exactly at a vertex: counted nowhere else
  std::int64_t back_face = 0;          // first hit on a segment facing away from o: never expected
  std::int64_t shadow_vertex = 0;      // shadow rays that met a vertex exactly: counted as not lit
  std::vector<std::int64_t> seen;      // [segment]
  std::vector<std::int64_t> seen_lit;  // [segment]; zeros without a light direction

  explicit VisibilityTally(int segments = 0)
      : seen(static_cast<std::size_t>(segments), 0), seen_lit(static_cast<std::size_t>(segments), 0) {}
  std::int64_t seen_total() const;
  void merge(const VisibilityTally& other);  // same profile
};

VisibilityTally trace_visibility_chunk(const Polyline& p, const VisibilityOptions& opt, std::int64_t chunk);
// All chunks, in order. `cancel` (may be null) is read before each chunk; once set, the chunks
// traced so far are returned (an incomplete tally, for the caller to discard).
VisibilityTally trace_visibility(const Polyline& p, const VisibilityOptions& opt,
                                 const std::atomic<bool>* cancel = nullptr);

}  // namespace vgroove::sim
