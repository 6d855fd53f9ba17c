// vgroove sim: the exact 3D tracer of a periodic heightfield (sim/heightfield.h) in double
// precision: the field's triangles (two per cell), descended through the min-max hierarchy
// (sim/heightfield_hierarchy.h) over the periodic tiling, met by the watertight ray-triangle test
// (sim/triangle_watertight.h), reflected specularly.
//
// Frame: the macrosurface normal is (0, 0, 1); the light at i = dir(theta_i, phi_i) (the
// direction3 convention of sim/microsurface3d.h); rays travel along -i. A parallel beam crosses
// the plane z = max height + 1 uniformly over one period [0, n)^2, which is uniform over the
// macrosurface.
//
// What is exact and what is rounded. Which triangle a ray meets is decided by the watertight
// test: the triangles' vertices have integer x, y (exact, also in every periodic image: the ray's
// origin is moved by whole periods, which is exact) and the field's heights, so no ray passes
// between two triangles. The hierarchy only chooses which triangles are tested: its boxes are
// widened by 2^-20 cells and its heights by 2^-20 max(1, |h|) so that rounding in the slab
// distances never skips a triangle (a widened box costs a test, never an answer). Hit points and
// reflected directions are rounded (as in the 2D tracer).
//
// No epsilons. A hit is on a triangle's interior, on an edge (one barycentric weight exactly 0)
// or on a vertex (two). The ray leaves the hit point and no triangle touching the hit feature (1,
// 2 or 6 of them) is tested on its next segment: a ray leaving a point of a planar triangle's
// boundary cannot meet that plane again, so this drops only the zero-distance self-hits (a ray
// leaving an interior point is handled the same way with its one triangle).
// Front-face culling (a ray in the air meets triangles only from above) and t > 0 already reject
// most zero-distance hits; the rule catches the rest: a ray leaving an edge point, rounded to
// the far side of the neighbour's plane, met it again at t ~ 1e-16 in 3 of 122880 rays exactly
// on the edges of rough fields (tests/sim/heightfield_tracer_test.cpp). Edge and vertex hits
// are counted and reflected by the limit of the neighbouring interior hits: reflect off the
// triangle hit; then, while the direction points into one of the touching triangles (its xy
// sector at the feature, decided by exact sign tests on integer edges) from below its plane
// (d . n < 0), reflect off that one too, counting each reflection as a bounce. A concave edge
// (a valley) so gives the wedge's two or more reflections, a convex one (a ridge) one.
//
// Buckets (every ray in exactly one): escaped (going up above the field's max height; binned),
// bounce_limit (more than max_bounces reflections), lost (found below the field's min height, or
// a horizontal ray that meets nothing over max_tiles periods: neither is expected; tests require
// lost = 0).
//
// Determinism. The rays are cut into chunks of kHeightfieldRaysPerChunk; chunk c draws from
// Rng(seed, kHeightfieldRayStream, c) and its tally depends only on (surface, options, c). The
// counts are integers; the energies are sums of doubles, added ray by ray within a chunk and
// chunk by chunk in chunk order by trace_heightfield (a caller running chunks on several threads
// keeps the per-chunk tallies and merges them in chunk order: the same bits for any thread count).
//
// Memory: the surface holds the field and its hierarchy, 29.3 bytes per cell (sim/heightfield.h:
// heightfield_bytes); 4096^2: 492 MB. Tracing allocates only the tally.
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

struct HeightfieldRayOptions {
  int max_bounces = 1000;
  std::int64_t max_tiles = 1 << 22;  // periods a horizontal ray may cross before it is lost
  HeightfieldFresnel fresnel;
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
