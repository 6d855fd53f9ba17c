// vgroove sim: random periodic height profiles from a seed, as polylines (sim/polyline.h), whose
// facet normals follow the flatland Beckmann or GGX distribution of roughness alpha.
//
// Units: the correlation length l is 1; the profile is sampled every dx = 1 / samples_per_length
// and has `segments` segments, so its period is segments dx. A power of two for
// samples_per_length keeps every x exact (sim/polyline.h: exact period shifts).
//
// Beckmann: a stationary Gaussian process with Gaussian autocorrelation,
//   <h(x) h(x + r)> = sigma_h^2 exp(-r^2 / l^2),
// made by periodic convolution of white Gaussian noise w_k with the kernel g(x) = exp(-2 x^2 / l^2)
// (the autocorrelation of g is proportional to exp(-r^2 / l^2)), sampled at the vertices and cut
// at |x| <= 4 l (g(4 l) = e^-32). The vertices are joined by straight segments; each segment's
// slope (h_{j+1} - h_j) / dx is a fixed linear combination of the w_k, hence exactly Gaussian, of
// variance sum_i (g_i - g_{i-1})^2 / dx^2 per unit noise; the heights are scaled so that this is
// alpha^2 / 2, the slope variance of the flatland Beckmann law (analytic/ndf.h, sim/slope_sampling.h:
// P(s) = exp(-s^2 / alpha^2) / (alpha sqrt(pi))). So the segments' normals follow D2_beckmann
// exactly at any sampling step; finer steps only make the polyline closer to the smooth process
// (sigma_h -> alpha l / 2, the continuous -C''(0) = 2 sigma_h^2 / l^2 = alpha^2 / 2). The
// profile is periodic by construction (periodic convolution).
//
// GGX: no Gaussian process has GGX's heavy-tailed slopes, so the slopes are made from one: the
// Gaussian process's standardized segment slopes z_j are mapped through the quantile transform
// s_j = Q_ggx(Phi(z_j)) (Phi the standard normal distribution function, Q_ggx the flatland GGX
// slope quantile, a Student-t with 2 degrees of freedom scaled by alpha / sqrt 2:
// Q(u) = alpha (2u - 1) / (2 sqrt(u (1 - u)))), so each slope follows the GGX law exactly and
// neighbouring slopes are correlated as the Gaussian ones are in rank. Heights are the running sum
// of the slopes over the first half of the period; the second half is its mirror image
// (y_{n/2 + j} = y_{n/2 - j}), which keeps every slope's law (the law is symmetric) and closes the
// period exactly (a sum of GGX slopes has no reason to vanish). Its mirror symmetry halves the
// independent length of a GGX profile.
//
// Determinism: the white noise comes from Rng(seed, kProfileStream, block) in blocks of
// kNoiseBlock numbers, so a profile depends only on its options.
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
