// vgroove sim: random periodic height profiles from a seed, as polylines (sim/polyline.h), whose
// facet normals follow the flatland Beckmann or GGX distribution of roughness alpha exactly, at any
// sampling step. Beckmann: a stationary Gaussian process with Gaussian autocorrelation (unit
// correlation length) by periodic convolution of white noise, scaled so the segment slopes have
// variance alpha^2 / 2. GGX: the Gaussian process's standardized slopes mapped through the
// flatland GGX quantile (a Student-t with 2 degrees of freedom scaled by alpha / sqrt 2), summed
// over half the period and mirrored to close it. Deterministic: a profile depends only on its options.
// Tests: tests/sim/random_profile_test.cpp (RandomProfile.ClosesItsPeriodExactlyAndIsReproducible,
// RandomProfile.BeckmannSlopesAreGaussianOfVarianceAlphaSquaredOverTwo,
// RandomProfile.BeckmannAutocorrelationIsGaussianOfUnitLength, RandomProfile.GgxSlopeQuantileTransform,
// RandomProfile.GgxProfileIsTheTransformedProcessThenItsMirror).
// Derivation: docs/derivations/profiles.md.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/polyline.h"

#include <cstdint>
#include <vector>

namespace vgroove::sim {

inline constexpr std::uint64_t kProfileStream = 0x70726f66696c65ULL;  // "profile"
inline constexpr int kNoiseBlock = 4096;

struct RandomProfileOptions {
  NdfKind ndf = NdfKind::beckmann;  // beckmann or ggx
  double alpha = 0.5;               // roughness, > 0
  int segments = 1 << 16;           // even, >= 2 (8 samples_per_length + 1): twice the kernel
  int samples_per_length = 16;      // segments per correlation length
  std::uint64_t seed = 0;
};

Polyline make_random_profile(const RandomProfileOptions& opt);

// The standardized Gaussian process behind both families: n values z_j with <z_j z_{j+m}> the
// correlation of the segment slopes (sum_i d_i d_{i+m} / sum_i d_i^2, d_i = g_i - g_{i-1}),
// z_j ~ N(0, 1). Exposed for the tests.
std::vector<double> gaussian_slope_process(int n, int samples_per_length, std::uint64_t seed);

// The flatland GGX slope with standard-normal score z: Q_ggx(Phi(z)) (see above), accurate in
// both tails.
double ggx_slope_from_normal(double z, double alpha);

}  // namespace vgroove::sim
