#include "vgroove/sim/random_profile.h"

#include "vgroove/sim/rng.h"

#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

namespace {

// Kernel half-width in correlation lengths: g(4 l) = exp(-32) = 1.3e-14.
constexpr int kKernelLengths = 4;

// Uniform in (0, 1), never 0 (the log below).
double uniform_open_01(Rng& rng) { return (static_cast<double>(rng.next_u64() >> 11) + 0.5) * 0x1.0p-53; }

// n independent standard normals by Box-Muller, in blocks of kNoiseBlock from their own streams.
std::vector<double> white_noise(int n, std::uint64_t seed) {
  std::vector<double> w(static_cast<std::size_t>(n));
  for (int b = 0; b * kNoiseBlock < n; ++b) {
    Rng rng(seed, kProfileStream, static_cast<std::uint64_t>(b));
    const int end = std::min(n, (b + 1) * kNoiseBlock);
    for (int k = b * kNoiseBlock; k < end; k += 2) {
      const double r = std::sqrt(-2.0 * std::log(uniform_open_01(rng)));
      const double phi = 2.0 * std::numbers::pi * rng.uniform();
      w[static_cast<std::size_t>(k)] = r * std::cos(phi);
      if (k + 1 < end) w[static_cast<std::size_t>(k) + 1] = r * std::sin(phi);
    }
  }
  return w;
}

// The kernel g_i = exp(-2 (i dx)^2), i = -K..K, stored at i + K.
std::vector<double> kernel(int samples_per_length) {
  const int K = kKernelLengths * samples_per_length;
  const double dx = 1.0 / samples_per_length;
  std::vector<double> g(static_cast<std::size_t>(2 * K + 1));
  for (int i = -K; i <= K; ++i) g[static_cast<std::size_t>(i + K)] = std::exp(-2.0 * (i * dx) * (i * dx));
  return g;
}

// sum_i (g_i - g_{i-1})^2 over the whole support (g = 0 outside): the variance of h_{j+1} - h_j
// per unit noise variance.
double difference_variance(const std::vector<double>& g) {
  double sum = 0.0, prev = 0.0;
  for (double v : g) sum += (v - prev) * (v - prev), prev = v;
  return sum + prev * prev;
}

// h_j = sum_i g_i w_{(j - i) mod n}: the periodic convolution (over the noise padded by K on
// each side with its periodic continuation).
std::vector<double> gaussian_heights(int n, const std::vector<double>& g, std::uint64_t seed) {
  const int K = static_cast<int>(g.size() / 2);
  assert(n >= 2 * static_cast<int>(g.size()));
  const std::vector<double> w = white_noise(n, seed);
  std::vector<double> wp(static_cast<std::size_t>(n + 2 * K));
  for (int t = -K; t < n + K; ++t) wp[static_cast<std::size_t>(t + K)] = w[static_cast<std::size_t>((t + n) % n)];
  std::vector<double> h(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j < n; ++j) {
    // w_{j - i} for i = -K..K is wp[j - i + K], i.e. wp[j + 2K - (i + K)].
    const double* wj = wp.data() + j + 2 * K;
    double sum = 0.0;
    for (int i = 0; i <= 2 * K; ++i) sum += g[static_cast<std::size_t>(i)] * wj[-i];
    h[static_cast<std::size_t>(j)] = sum;
  }
  return h;
}

}  // namespace

std::vector<double> gaussian_slope_process(int n, int samples_per_length, std::uint64_t seed) {
  const std::vector<double> g = kernel(samples_per_length);
  const std::vector<double> h = gaussian_heights(n, g, seed);
  const double sd = std::sqrt(difference_variance(g));
  std::vector<double> z(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j)
    z[static_cast<std::size_t>(j)] = (h[static_cast<std::size_t>((j + 1) % n)] - h[static_cast<std::size_t>(j)]) / sd;
  return z;
}

double ggx_slope_from_normal(double z, double alpha) {
  // u = Phi(z) and 1 - u, each from erfc on its own side (no cancellation in either tail);
  // 2u - 1 = erf(z / sqrt 2).
  const double t = z / std::numbers::sqrt2;
  const double u = 0.5 * std::erfc(-t), v = 0.5 * std::erfc(t);
  return alpha * std::erf(t) / (2.0 * std::sqrt(u * v));
}

Polyline make_random_profile(const RandomProfileOptions& opt) {
  assert(opt.alpha > 0.0 && opt.samples_per_length > 0 && opt.segments % 2 == 0);
  assert(opt.ndf == NdfKind::beckmann || opt.ndf == NdfKind::ggx);
  const int n = opt.segments;
  const double dx = 1.0 / opt.samples_per_length;
  std::vector<double> x(static_cast<std::size_t>(n) + 1), y(static_cast<std::size_t>(n) + 1);
  for (int v = 0; v <= n; ++v) x[static_cast<std::size_t>(v)] = v * dx;
  const std::vector<double> g = kernel(opt.samples_per_length);
  if (opt.ndf == NdfKind::beckmann) {
    // Slope variance (c^2 sum d_i^2) / dx^2 = alpha^2 / 2.
    const std::vector<double> h = gaussian_heights(n, g, opt.seed);
    const double c = opt.alpha / std::numbers::sqrt2 * dx / std::sqrt(difference_variance(g));
    for (int v = 0; v < n; ++v) y[static_cast<std::size_t>(v)] = c * h[static_cast<std::size_t>(v)];
    y[static_cast<std::size_t>(n)] = y[0];
  } else {
    const std::vector<double> z = gaussian_slope_process(n, opt.samples_per_length, opt.seed);
    const int half = n / 2;
    y[0] = 0.0;
    for (int j = 0; j < half; ++j)
      y[static_cast<std::size_t>(j) + 1] =
          y[static_cast<std::size_t>(j)] + ggx_slope_from_normal(z[static_cast<std::size_t>(j)], opt.alpha) * dx;
    for (int j = 1; j <= half; ++j) y[static_cast<std::size_t>(half + j)] = y[static_cast<std::size_t>(half - j)];
  }
  return make_polyline(std::move(x), std::move(y));
}

}  // namespace vgroove::sim
