// vgroove sim: which points of a polyline profile (sim/polyline.h) a viewer sees and which of
// those the light reaches, traced exactly with sim/polyline_tracer.h: the raw counts per segment
// behind G1(o, m), G2(i, o, m) and the lit length (Heitz 2014, "Understanding the Masking-Shadowing
// Function in Microfacet-Based BRDFs", JCGT 3(2), Sec. 2-5). A beam of N rays from o lands
// uniformly over one period; the segment each meets first counts as seen, and a shadow ray towards
// i decides whether it is lit. No model is assumed here; validation/profile_masking.h bins and
// compares. Deterministic: chunks from Rng(seed, kRayStream, chunk), integer counts.
// Tests: tests/validation/profile_masking_test.cpp (ProfileMasking.VCavityIsExactOnVGrooveProfiles,
// ProfileMasking.LitFractionIsPerMacroLengthAndPerArcLengthByHand, ProfileMasking.FlatProfileIsLitWhole).
// Derivation: docs/derivations/profiles.md.
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
