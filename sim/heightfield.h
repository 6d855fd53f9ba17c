// vgroove sim: periodic heightfields on an N x N grid, the explicit random surfaces traced in 3D
// by sim/heightfield_tracer.h.
//
// Geometry. Vertex (i, j), 0 <= i, j < N, sits at (i, j, h[j N + i]) in cell units (the grid
// spacing is 1, heights in the same unit); the surface repeats with period N along x and y, so
// vertex (i + a N, j + b N) has the height of (i, j). Cell (i, j) spans [i, i+1] x [j, j+1] and
// holds two triangles split along its diagonal from (i, j) to (i+1, j+1):
//   lower (half 0): (i, j), (i+1, j), (i+1, j+1)     upper (half 1): (i, j), (i+1, j+1), (i, j+1)
// both counter-clockwise seen from above. A triangle's plane has the gradient (s_x, s_y) of its
// finite differences (lower: (h10 - h00, h11 - h10), upper: (h11 - h01, h01 - h00)) and the
// upward normal (-s_x, -s_y, 1) / |.|; every triangle covers half a cell of the macrosurface, so
// counting triangles is weighting their normals by projected area: the histogram of the
// triangles' gradients is the slope distribution P22(s) = D(m) cos^4 theta_m.
//
// Gaussian surfaces (Beckmann slopes). Heights are a stationary Gaussian process with the
// autocorrelation C(dx, dy) = sigma^2 exp(-dx^2 / l_x^2 - dy^2 / l_y^2). The slope along x of the
// continuous surface has the variance -C_xx(0) = 2 sigma^2 / l_x^2; the triangles' slopes are
// finite differences over one cell, with the variance 2 (C(0) - C(1, 0)) = 2 sigma^2 (1 -
// exp(-1 / l_x^2)). Beckmann's D with roughness alpha_x has the slope variance alpha_x^2 / 2 per
// axis (P22 = exp(-s_x^2 / alpha_x^2 - s_y^2 / alpha_y^2) / (pi alpha_x alpha_y)), so the field
// takes
//   sigma^2 = alpha_x^2 / (4 (1 - exp(-1 / l_x^2))),   l_y = 1 / sqrt(-log(1 - alpha_y^2 / (4 sigma^2))),
// and its triangles' slopes are Gaussian with the variances alpha_x^2 / 2 and alpha_y^2 / 2
// exactly (up to the synthesis' sums, below). One triangle's two slopes are correlated by
// -(1 - q) / 2, q = exp(-1 / l^2) (isotropic: -0.0078 at l = 8 cells): the diagonal split's
// one departure from Beckmann, which a longer correlation length shrinks as 1 / (2 l^2).
//
// Synthesis. White noise w (one standard normal per vertex, Rng(seed, kHeightfieldStream, row))
// convolved circularly with the separable kernel g(x, y) = c exp(-2 x^2 / l_x^2 - 2 y^2 / l_y^2),
// c = 2 sigma / sqrt(pi l_x l_y): the sum over u of g(x - u) g(y - u) is the Riemann sum of a
// Gaussian of standard deviation l / (2 sqrt 2) cells, which equals the integral, C, to a relative
// 2 exp(-pi^2 l^2 / 4) (1e-17 at l = 4; l >= 2 is required). The kernel is wrapped over the
// period and cut at 8 of its standard deviations (l/2): the cut drops exp(-32) of its weight.
//
// Validation fields: a flat field (all heights equal) and one V-groove family (grooves along y,
// the profile along x a triangle wave of slope +-s, period 2 P cells, ridges at height P s and
// bottoms at 0), which the lifted tracer (sim/microsurface3d.h) traces exactly.
//
// Memory: 8 bytes per cell for the heights (N^2 doubles); the synthesis holds two more N^2
// arrays while it runs (16 bytes per cell). With the min-max hierarchy
// (sim/heightfield_hierarchy.h, 21.3 bytes per cell) a field takes 29.3 bytes per cell:
// 4096^2 is 492 MB (508 MB peak with the synthesis temporaries, 0.77 GB), 2048^2 is 123 MB.
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
