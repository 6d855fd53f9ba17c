// vgroove sim: periodic heightfields on an N x N grid, the explicit random surfaces traced in 3D
// by sim/heightfield_tracer.h: two triangles per cell (split along the diagonal), period N along x
// and y, counting triangles weights their normals by projected area. Gaussian fields have the
// autocorrelation sigma^2 exp(-dx^2 / l_x^2 - dy^2 / l_y^2) with sigma and l_y chosen so that the
// triangles' finite-difference slopes are Gaussian with the Beckmann variances alpha_x^2 / 2 and
// alpha_y^2 / 2 exactly (one triangle's two slopes correlate by -(1 - q) / 2, q = exp(-1 / l^2)),
// synthesized by circular convolution of white noise (relative 2 exp(-pi^2 l^2 / 4); l >= 2).
// Validation fields: flat, and one V-groove family the lifted tracer traces exactly. Memory with
// the hierarchy: 29.3 bytes per cell (4096^2: 492 MB). Deterministic per seed.
// Tests: tests/sim/heightfield_test.cpp
// (GaussianHeightfieldStats.SlopeVarianceRmsHeightAndCorrelationMatchTheParameters,
// GaussianHeightfieldNdf.TriangleSlopesFollowBeckmann,
// GaussianHeightfield.IsDeterministicPerSeedAndDiffersBetweenSeeds, ValidationHeightfields.FlatAndVGrooveHeights,
// HeightfieldMemory.BytesPerCellAsStated). Derivation: docs/derivations/heightfield.md.
#pragma once

#include <cstdint>
#include <vector>

namespace vgroove::sim {

struct Heightfield {
  int n = 0;              // vertices (and cells) per side; a power of two, >= 2
  std::vector<double> h;  // [j * n + i]

  double height(std::int64_t i, std::int64_t j) const {  // any integers: periodic
    const std::int64_t m = n - 1;                        // n is a power of two
    return h[static_cast<std::size_t>((j & m) * n + (i & m))];
  }
};

// Bytes a field of n x n cells takes with its hierarchy (heights + min-max levels), as above.
double heightfield_bytes(int n);

inline constexpr std::uint64_t kHeightfieldStream = 0x6866696c6c64ULL;  // "hfilld"

struct GaussianHeightfieldOptions {
  int n = 256;                      // power of two in [2, 65536]
  double alpha_x = 0.5;             // Beckmann roughness along x, > 0
  double alpha_y = 0.5;             // along y, > 0
  double correlation_length = 8.0;  // l_x in cells, in [2, n / 8]
  std::uint64_t seed = 0;
};

// The parameters the synthesis uses (header formulas): sigma and l_y from alpha_x, alpha_y, l_x.
struct GaussianHeightfieldParameters {
  double sigma = 0.0;  // rms height, cells
  double l_x = 0.0, l_y = 0.0;
};
GaussianHeightfieldParameters gaussian_heightfield_parameters(const GaussianHeightfieldOptions& opt);

Heightfield make_gaussian_heightfield(const GaussianHeightfieldOptions& opt);
Heightfield make_flat_heightfield(int n, double height = 0.0);
// Grooves along y: h(i, j) = s |(i mod 2P) - P|. n a multiple of 2P.
Heightfield make_vgroove_heightfield(int n, int half_period, double slope);

}  // namespace vgroove::sim
