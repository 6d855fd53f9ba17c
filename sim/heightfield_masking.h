// vgroove sim: traced masking G1(o) of a periodic heightfield (sim/heightfield.h), overall and per
// facet-normal bin: the fraction of the surface's projected area towards o that is visible from o.
// Points are drawn uniformly over the macrosurface (a triangle uniformly, then a point uniformly on
// it); a point on a triangle of upward normal N = (-s_x, -s_y, 1) carries its projected area
// towards o per unit macro area, w = (o.N)+, and is visible (V = 1) when the ray from far along o
// towards it first meets its own triangle (sim/heightfield_tracer.h: first_heightfield_hit, exact).
// G1 = sum w V / sum w per bin and overall. The visible projected area, mean(w V), is cos theta_o
// on every surface (each line from o meets the surface once): an identity of the tracer, not of
// any masking model. Bins: theta_m equal over [0, pi/2), the facet azimuth relative to phi_o with
// bin 0 centred on it. Deterministic: chunk c of kHeightfieldPointsPerChunk points draws from
// Rng(seed, kHeightfieldMaskingStream, c), merged in chunk order. Tests:
// tests/sim/heightfield_masking_test.cpp, tests/validation/heightfield_masking_smith_test.cpp.
// Derivation: docs/derivations/heightfield.md.
#pragma once

#include "vgroove/sim/heightfield_tracer.h"

#include <cstdint>
#include <vector>

namespace vgroove::sim {

struct HeightfieldMaskingOptions {
  double theta_o = 0.0;  // view polar angle, [0, pi/2)
  double phi_o = 0.0;    // view azimuth
  std::int64_t points = 100000;
  std::uint64_t seed = 0;
  int theta_m_bins = 6;  // equal bins of the facet polar angle over [0, pi/2)
  int phi_m_bins = 4;    // equal bins of phi_m - phi_o, bin 0 centred on 0 (facets tilted towards o)
  HeightfieldRayOptions ray;
};

inline constexpr std::int64_t kHeightfieldPointsPerChunk = 4096;
inline constexpr std::uint64_t kHeightfieldMaskingStream = 0x68666d61736bULL;  // "hfmask"

struct HeightfieldMaskingTally {
  int theta_m_bins = 0, phi_m_bins = 0;
  std::int64_t points = 0, front = 0, visible = 0;  // drawn, facing o, of those visible
  std::int64_t lost = 0, edge_hits = 0, vertex_hits = 0;
  double sum_w = 0.0, sum_wv = 0.0, sum_wv2 = 0.0;  // over all points
  std::vector<double> weight, visible_weight;       // per bin [t * phi_m_bins + p]
  std::vector<std::int64_t> count;                  // front-facing points per bin

  HeightfieldMaskingTally() = default;
  HeightfieldMaskingTally(int theta_m_bins_, int phi_m_bins_);
  void merge(const HeightfieldMaskingTally& other);  // same bins
  // NaN where no drawn point faces o (a bin without weight), as validation/profile_masking.h.
  double g1() const { return sum_wv / sum_w; }
  double g1(int bin) const {
    return visible_weight[static_cast<std::size_t>(bin)] / weight[static_cast<std::size_t>(bin)];
  }
  // mean(w V) and its standard error over the points: the visible projected area per unit macro
  // area (cos theta_o on every surface, header).
  double visible_area() const { return sum_wv / static_cast<double>(points); }
  double visible_area_se() const;
};

std::int64_t heightfield_masking_chunk_count(const HeightfieldMaskingOptions& opt);
HeightfieldMaskingTally heightfield_masking_chunk(const HeightfieldSurface& s, const HeightfieldMaskingOptions& opt,
                                                  std::int64_t chunk);
// All chunks merged in chunk order (one thread). Throws std::invalid_argument naming the field and
// its range for theta_o outside [0, pi/2), points < 1, or bins < 1.
HeightfieldMaskingTally heightfield_masking(const HeightfieldSurface& s, const HeightfieldMaskingOptions& opt);

}  // namespace vgroove::sim
