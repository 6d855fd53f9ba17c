// vgroove sim: a periodic heightfield of finite V-grooves at random orientations (the non-parallel
// grooves that Lee et al. 2018, "Practical Multiple Scattering for Rough Surfaces", Sec. 9, name as
// future work). Each groove is a row of seeds along a segment (centre uniform, axis azimuth
// uniform); the plane is split among the grooves by the nearest seed, and groove G's surface is
// h = -s_G max_{i in G} min_{j not in G} d_ij(x), d_ij the distance to the bisector of seeds i and
// j: a pit that is 0 on the groove's border (no cliffs) and whose facets all have the slope s_G,
// drawn from the NDF's tilt law (Beckmann or GGX, projected-area weighted), independent of the
// groove's area. Vertical rows of seeds one cell apart give the V-groove family (make_vgroove_heightfield).
// Deterministic per seed; bucketed seed search. Triangles across a crease are chords.
// Tests: tests/sim/heightfield_test.cpp (GrooveField.OneOrientationIsTheVGrooveFamily,
// GrooveField.NoCliffs, GrooveField.DeterministicPerSeedAndOutOfRangeRefused,
// GrooveField.AreaWeightedTiltsFollowTheNdfAndAzimuthsAreUniform, GrooveField.SlopesFollowTheTiltLaw,
// GrooveField.BucketSearchIsTheDefinition, GrooveField.TheTracerTakesIt).
// Derivation: docs/derivations/heightfield_grooves.md.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/heightfield.h"

#include <cstdint>
#include <vector>

namespace vgroove::sim {

inline constexpr std::uint64_t kGrooveFieldStream = 0x6866677276ULL;  // "hfgrv"

// One finite groove: centre (cells), axis azimuth phi (radians from x), length (cells, >= 0) and
// the slope s = tan(theta) of its facets.
struct FiniteGroove {
  double x = 0.0, y = 0.0, phi = 0.0, length = 0.0, slope = 1.0;
};

struct GrooveFieldOptions {
  int n = 256;                      // power of two in [8, 4096]
  NdfKind ndf = NdfKind::beckmann;  // Beckmann or GGX
  double alpha = 0.5;               // > 0
  double groove_length = 24.0;      // cells, in [0, n/4]
  double groove_spacing = 24.0;     // cells: round(n^2 / spacing^2) >= 2 grooves; in [4, n/4]
  double seed_step = 4.0;           // cells between seeds along a groove, in [1, groove_length] (or any if 0)
  std::uint64_t seed = 0;
};

// The tilt slope of the NDF's facets, projected-area weighted, from u in [0, 1):
// Beckmann s = alpha sqrt(-log(1 - u)), GGX s = alpha sqrt(u / (1 - u)).
double groove_slope(NdfKind ndf, double alpha, double u);

// The grooves of a random field (one Rng stream per groove: centre, azimuth, slope).
std::vector<FiniteGroove> random_finite_grooves(const GrooveFieldOptions& opt);

// Per vertex, for the tests: the groove (index) whose seed is nearest, and the facet: the pair
// (i, j) of seeds whose bisector distance sets the height (i * K + j).
struct GrooveFieldLabels {
  std::vector<int> groove;
  std::vector<std::int64_t> facet;
};

// The field of the given grooves on n x n vertices (n a power of two), seeds seed_step apart along
// each (floor(length / seed_step) + 1 of them, the ends included). Throws std::invalid_argument.
Heightfield make_finite_groove_field(int n, const std::vector<FiniteGroove>& grooves, double seed_step,
                                     GrooveFieldLabels* labels = nullptr);
Heightfield make_random_groove_field(const GrooveFieldOptions& opt, GrooveFieldLabels* labels = nullptr);

}  // namespace vgroove::sim
