// vgroove sim: periodic heightfields on an N x N grid, the explicit random surfaces traced in 3D
// by sim/heightfield_tracer.h: two triangles per cell (split along the diagonal), period N along x
// and y, counting triangles weights their normals by projected area. Gaussian fields have the
// autocorrelation sigma^2 exp(-dx^2 / l_x^2 - dy^2 / l_y^2) with sigma and l_y chosen so that the
// triangles' finite-difference slopes are Gaussian with the Beckmann variances alpha_x^2 / 2 and
// alpha_y^2 / 2 exactly, by circular convolution of white noise. GGX fields: the Gaussian field
// through a monotone height map whose slope scale makes GGX's Student-t slopes (below). Validation
// fields: flat, and one V-groove family. Memory with the hierarchy: 29.3 bytes per cell (4096^2:
// 492 MB), refused above a budget in one line. Deterministic per seed.
// Tests: tests/sim/heightfield_test.cpp (GaussianHeightfieldStats.*, GaussianHeightfieldNdf.*,
// GgxHeightfieldNdf.TriangleSlopesFollowGgx, GgxHeightfield.*, GaussianHeightfield.*,
// ValidationHeightfields.FlatAndVGrooveHeights, HeightfieldMemory.EstimateIsWhatTheContainersAllocate,
// HeightfieldMemory.HeapAndResidentPeakMatchTheEstimate, HeightfieldMemory.TooLargeForTheBudgetIsRefusedInOneLine).
// Derivation: docs/derivations/heightfield.md.
#pragma once

#include <cmath>
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

// Bytes a field of n x n cells (fields are square) takes with its hierarchy: 8 per height plus 16
// per min-max node over the levels n^2, n^2/4, ..., 1, i.e. (8 + 64/3) n^2 - 16/3 (29.3 per
// cell). It is also the peak of building one (the synthesis' temporaries, 16 bytes per cell, are
// freed before the hierarchy is made). 4096^2: 492 MB; 8192^2: 1.97 GB; 65536^2: 126 GB.
double heightfield_bytes(int n);
// The largest power of two n in [2, 65536] whose heightfield_bytes(n) <= budget_bytes; 0 if none.
int heightfield_max_n(double budget_bytes);
// Throws std::invalid_argument naming n, its bytes, the budget and the allowed range of n when
// heightfield_bytes(n) > budget_bytes (one line; called before any allocation).
void check_heightfield_memory(int n, double budget_bytes);

inline constexpr std::uint64_t kHeightfieldStream = 0x6866696c6c64ULL;  // "hfilld"

struct GaussianHeightfieldOptions {
  int n = 256;                      // power of two in [2, 65536]
  double alpha_x = 0.5;             // Beckmann roughness along x, > 0
  double alpha_y = 0.5;             // along y, > 0
  double correlation_length = 8.0;  // l_x in cells, in [2, n / 8]
  std::uint64_t seed = 0;
  double max_bytes = HUGE_VAL;  // memory budget: n refused above it (check_heightfield_memory)
};

// The parameters the synthesis uses (header formulas): sigma and l_y from alpha_x, alpha_y, l_x.
struct GaussianHeightfieldParameters {
  double sigma = 0.0;  // rms height, cells
  double l_x = 0.0, l_y = 0.0;
};
GaussianHeightfieldParameters gaussian_heightfield_parameters(const GaussianHeightfieldOptions& opt);

Heightfield make_gaussian_heightfield(const GaussianHeightfieldOptions& opt);

// GGX slopes: the Gaussian field g above (Beckmann slopes alpha_x, alpha_y; rms height sigma)
// mapped through h = Phi(g), Phi'(t) = 1 / sqrt(E(t)), E(t) = -log(1 - Phi_N(t / sigma)) (an
// Exp(1) variable when t ~ N(0, sigma^2)): at each point g and its gradient are independent, so
// the gradient Phi'(g) grad g is the Gaussian scale mixture that is GGX's slope law (Student-t,
// 2 degrees of freedom). The triangles' slopes are chords (Phi varies across a cell); the steep
// facets sit low (E small where g is low): heights and slopes are dependent. The lowest vertex is
// at height 0. docs/derivations/heightfield.md says what is and is not matched.
Heightfield make_ggx_heightfield(const GaussianHeightfieldOptions& opt);
// Phi' above, for the tests: 1 / sqrt(E), with x = t / sigma.
double ggx_height_map_derivative(double x);
Heightfield make_flat_heightfield(int n, double height = 0.0);
// Grooves along y: h(i, j) = s |(i mod 2P) - P|. n a multiple of 2P.
Heightfield make_vgroove_heightfield(int n, int half_period, double slope);

}  // namespace vgroove::sim
