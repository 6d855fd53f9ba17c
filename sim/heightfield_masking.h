// vgroove sim: traced masking G1(o) and masking-shadowing G2(i, o) of a periodic heightfield
// (sim/heightfield.h), overall and per facet-normal bin. Points are drawn uniformly over the
// macrosurface (a triangle uniformly, then a point on it); a point of a triangle of upward normal
// N = (-s_x, -s_y, 1) is visible from o (V = 1) when the ray from far along o towards it first
// meets its own triangle (first_heightfield_hit, exact). G1 = sum w V / sum w with w = (o.N)+, its
// projected area towards o per unit macro area; mean(w V) = cos theta_o on every surface (each
// line from o meets the surface once): an identity of the tracer. G2: below. Bins: theta_m equal
// over [0, pi/2), the facet azimuth (bin 0 centred on the reference, counter-clockwise) from phi_o
// (G1) or from the bisector of i's and o's azimuths (G2, heightfield_joint_bin_azimuth). Deterministic:
// chunk c of kHeightfieldPointsPerChunk points draws from Rng(seed, kHeightfieldMaskingStream, c),
// merged in chunk order. Tests: tests/sim/heightfield_masking_test.cpp (HeightfieldMasking.*,
// HeightfieldJointMasking.*), tests/validation/heightfield_masking_smith_test.cpp.
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

// The joint masking-shadowing G2(i, o): the same points as heightfield_masking for the same seed
// (its stream and layout), each weighted by w = (i.N)+ (o.N)+ / |N| = |N| (i.m)+ (o.m)+ (its
// microsurface area |N| per unit macro area times the microfacet BRDF's weight (i.m)(o.m), Heitz
// 2014 Eq. 15 with Eq. 13 and G2 for G1, Eq. 18; m = N / |N|) and traced towards both directions:
// G2 = sum w V_i V_o / sum w per bin and overall, beside the G1s under the same weight, sum w V_i
// / sum w and sum w V_o / sum w. Points facing away from i or o (w = 0) are drawn, not traced.
// Exact per realization: G2 <= min(G1_i, G1_o) bin by bin; i = o gives G2 = G1_i = G1_o and the
// visible count of heightfield_masking(o); swapping i and o gives the same sums bin by bin to the
// bit (reciprocity: the weight, the pair of traces and the bins are symmetric in i and o).
//
// G2's azimuth reference, a function of the unordered pair of directions (the same bits for (i,
// o) and (o, i)): the bisector of the smaller angle between phi_i and phi_o (phi_o + phi_i) / 2
// for |phi_o - phi_i| < pi; opposite azimuths (the mirror plane when theta_i = theta_o): the
// bisector in [0, pi), that is pi / 2 for the suite's light at 0 and o at pi; a direction at the
// normal (theta 0) has no azimuth: the other's (0 when both are). Result in [0, 2 pi) or the
// other's phi as given.
double heightfield_joint_bin_azimuth(double theta_i, double phi_i, double theta_o, double phi_o);

struct HeightfieldJointMaskingOptions {
  double theta_i = 0.0, phi_i = 0.0;  // light, [0, pi/2)
  double theta_o = 0.0, phi_o = 0.0;  // view, [0, pi/2)
  std::int64_t points = 100000;
  std::uint64_t seed = 0;
  int theta_m_bins = 6;  // as HeightfieldMaskingOptions
  int phi_m_bins = 4;    // from heightfield_joint_bin_azimuth
  HeightfieldRayOptions ray;
};

struct HeightfieldJointMaskingTally {
  int theta_m_bins = 0, phi_m_bins = 0;
  std::int64_t points = 0, front = 0;                           // drawn, facing both i and o
  std::int64_t visible_i = 0, visible_o = 0, visible_both = 0;  // of the front-facing
  std::int64_t lost = 0, edge_hits = 0, vertex_hits = 0;
  double sum_w = 0.0, sum_wi = 0.0, sum_wo = 0.0, sum_wio = 0.0;  // w, w V_i, w V_o, w V_i V_o
  // Per bin [t * phi_m_bins + p], the same four sums and the front-facing points.
  std::vector<double> weight, weight_i, weight_o, weight_io;
  std::vector<std::int64_t> count;

  HeightfieldJointMaskingTally() = default;
  HeightfieldJointMaskingTally(int theta_m_bins_, int phi_m_bins_);
  void merge(const HeightfieldJointMaskingTally& other);  // same bins
  // NaN where no point faces both.
  double g2() const { return sum_wio / sum_w; }
  double g1_i() const { return sum_wi / sum_w; }
  double g1_o() const { return sum_wo / sum_w; }
  double g2(int bin) const { return at(weight_io, bin) / at(weight, bin); }
  double g1_i(int bin) const { return at(weight_i, bin) / at(weight, bin); }
  double g1_o(int bin) const { return at(weight_o, bin) / at(weight, bin); }

 private:
  static double at(const std::vector<double>& v, int bin) { return v[static_cast<std::size_t>(bin)]; }
};

std::int64_t heightfield_joint_masking_chunk_count(const HeightfieldJointMaskingOptions& opt);
HeightfieldJointMaskingTally heightfield_joint_masking_chunk(const HeightfieldSurface& s,
                                                             const HeightfieldJointMaskingOptions& opt,
                                                             std::int64_t chunk);
// All chunks merged in chunk order. Throws std::invalid_argument naming the field and its range
// for theta_i or theta_o outside [0, pi/2), points < 1, or bins < 1.
HeightfieldJointMaskingTally heightfield_joint_masking(const HeightfieldSurface& s,
                                                       const HeightfieldJointMaskingOptions& opt);

}  // namespace vgroove::sim
