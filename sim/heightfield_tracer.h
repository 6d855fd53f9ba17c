// vgroove sim: the exact 3D tracer of a periodic heightfield (sim/heightfield.h) in double
// precision: the field's triangles (two per cell), descended through the min-max hierarchy
// (sim/heightfield_hierarchy.h) over the periodic tiling, met by the watertight ray-triangle test
// (sim/triangle_watertight.h), reflected specularly. No epsilons: no ray passes between two
// triangles; the widened hierarchy never skips a triangle; edge and vertex hits are counted and
// reflected by the limit of the neighbouring interior hits; the triangles touching the feature
// just hit are not tested again. Buckets: escaped (binned), bounce_limit, lost (expected 0).
// Deterministic per chunk, merged in chunk order: the same bits for any thread count. Memory:
// 29.3 bytes per cell (heightfield_bytes). Tests: tests/sim/heightfield_tracer_test.cpp
// (HeightfieldTracer.FlatFieldIsAMirrorToTheBit, HeightfieldTracer.VGrooveFamilyMatchesTheLiftedTracer,
// HeightfieldTracer.EdgeAndVertexRaysTakeTheLimitOfOneSide,
// HeightfieldTracer.ExactEdgeRaysNeverHitTheirEdgeTwice, HeightfieldTracer.HierarchyPrunesWithoutChangingAnyAnswer,
// HeightfieldEnergy.EveryRayLeavesAndEnergyIsExactlyOne,
// HeightfieldTracer.TwoThreadsMergedInChunkOrderGiveTheSameBits,
// HeightfieldTracer.BounceCosinesGiveEveryReflectanceOfOneTrace). Derivation: docs/derivations/heightfield.md.
#pragma once

#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/heightfield_hierarchy.h"

#include <Eigen/Core>

#include <cstdint>
#include <numbers>
#include <vector>

namespace vgroove::sim {

struct HeightfieldSurface {
  Heightfield field;
  HeightfieldHierarchy hierarchy;
};
HeightfieldSurface make_heightfield_surface(Heightfield f);

// The reflectance at each bounce's local angle, the throughput their product (Lee et al. 2018,
// Eq. 11): the functors of sim/effects.h. F = 1 (unit) costs nothing per bounce.
enum class HeightfieldReflectance : unsigned char { unit, conductor, dielectric, schlick };
struct HeightfieldFresnel {
  HeightfieldReflectance kind = HeightfieldReflectance::unit;
  double eta = 1.0, kappa = 0.0;  // conductor: eta + i kappa; dielectric: eta
  double F0 = 1.0;                // schlick
};

// cosines: when set, the trace clears it and appends each reflection's local cosine |<d, m_j>| / |m_j|
// (clamped to 1; the value the reflectance is evaluated at), in bounce order, up to max_bounces + 1
// entries (a ray over the limit), so that one trace serves any number of reflectances: the
// product of F_c(cos_j) is the throughput of fresnel = F_c. Null (the default) costs nothing; one
// vector per thread.
struct HeightfieldRayOptions {
  int max_bounces = 1000;
  std::int64_t max_tiles = 1 << 22;  // periods a horizontal ray may cross before it is lost
  HeightfieldFresnel fresnel;
  std::vector<double>* cosines = nullptr;
};

enum class HeightfieldFate : unsigned char { escaped, bounce_limit, lost };

struct HeightfieldRayResult {
  HeightfieldFate how = HeightfieldFate::escaped;
  int bounces = 0;
  Eigen::Vector3d o = Eigen::Vector3d::Zero();  // travel direction on exit (|o| = 1 to rounding)
  double throughput = 1.0;                      // product of the reflectances
  int edge_hits = 0, vertex_hits = 0;           // hits with one / two barycentric weights exactly 0
};

// One ray from `org` (any point above the surface: z > the field's height below it) along `dir`
// (unit).
HeightfieldRayResult trace_heightfield_ray(const HeightfieldSurface& s, const Eigen::Vector3d& org,
                                           const Eigen::Vector3d& dir, const HeightfieldRayOptions& opt = {});

// The first triangle a ray from `org` (above the surface) along `dir` (unit) meets, no reflection:
// cell (cx, cy) of the tiling in org's frame (any integers; the field's cell is (cx mod n, cy mod
// n)) and half (sim/heightfield.h), and whether the hit is on an edge or a vertex (the watertight
// test's ties: either touching triangle). how: escaped (no hit) or lost.
struct HeightfieldFirstHit {
  HeightfieldFate how = HeightfieldFate::escaped;
  bool hit = false;
  std::int64_t cx = 0, cy = 0;
  int half = 0;
  bool edge = false, vertex = false;
};
HeightfieldFirstHit first_heightfield_hit(const HeightfieldSurface& s, const Eigen::Vector3d& org,
                                          const Eigen::Vector3d& dir, const HeightfieldRayOptions& opt = {});

struct HeightfieldTraceOptions {
  double theta_i = 0.0;             // light polar angle, [0, pi/2)
  double phi_i = std::numbers::pi;  // light azimuth
  std::int64_t rays = 100000;
  std::uint64_t seed = 0;
  int theta_bins = 90;  // equal bins over [0, pi/2)
  int phi_bins = 72;    // equal bins centred on the mirror azimuth phi_i - pi (bin p: (p - 1/2, p + 1/2) widths)
  int max_k = 16;       // rows k = 0..max_k, larger k share the last row
  HeightfieldRayOptions ray;
};

inline constexpr std::int64_t kHeightfieldRaysPerChunk = 4096;
inline constexpr std::uint64_t kHeightfieldRayStream = 0x68667261797333ULL;  // "hfrays3"

struct HeightfieldTally {
  int theta_bins = 0, phi_bins = 0, max_k = 0;
  double phi_i = std::numbers::pi;
  std::int64_t rays = 0, escaped = 0, bounce_limit = 0, lost = 0;
  std::int64_t bounces = 0;  // summed over escaped rays
  std::int64_t edge_hits = 0, vertex_hits = 0;
  int max_k_seen = 0;
  std::vector<std::int64_t> by_k;       // escaped rays per row
  std::vector<double> energy_by_k;      // their summed throughput per row
  std::vector<std::int64_t> hist_by_k;  // [(row * theta_bins + t) * phi_bins + p]

  HeightfieldTally() = default;
  HeightfieldTally(int theta_bins_, int phi_bins_, int max_k_, double phi_i_);
  int row_of(int k) const { return k > max_k ? max_k + 1 : k; }
  std::size_t index(int row, int t, int p) const {
    return (static_cast<std::size_t>(row) * theta_bins + t) * phi_bins + p;
  }
  void add(const HeightfieldRayResult& r);
  void merge(const HeightfieldTally& other);  // same bins
  double energy() const;                      // sum of energy_by_k in row order
};

std::int64_t heightfield_chunk_count(const HeightfieldTraceOptions& opt);
HeightfieldTally trace_heightfield_chunk(const HeightfieldSurface& s, const HeightfieldTraceOptions& opt,
                                         std::int64_t chunk);
// All chunks merged in chunk order (one thread).
HeightfieldTally trace_heightfield(const HeightfieldSurface& s, const HeightfieldTraceOptions& opt);

}  // namespace vgroove::sim
