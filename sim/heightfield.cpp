#include "vgroove/sim/heightfield.h"

#include "vgroove/sim/heightfield_hierarchy.h"
#include "vgroove/sim/rng.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vgroove::sim {
namespace {

bool power_of_two(int n) { return n >= 2 && (n & (n - 1)) == 0; }

std::string gigabytes(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", bytes / 1e9);
  return buf;
}

// The kernel exp(-2 d^2 / l^2) wrapped over the period n, for d = -r..r (index d + r).
std::vector<double> wrapped_kernel(int n, double l, double c, int& r) {
  const double sd = 0.5 * l;
  r = std::min(static_cast<int>(std::ceil(8.0 * sd)), (n - 1) / 2);
  std::vector<double> k(static_cast<std::size_t>(2 * r + 1), 0.0);
  const int images = static_cast<int>(std::ceil(8.0 * sd / n)) + 1;
  for (int d = -r; d <= r; ++d) {
    double s = 0.0;
    for (int m = -images; m <= images; ++m) {
      const double x = d + static_cast<double>(m) * n;
      s += std::exp(-2.0 * x * x / (l * l));
    }
    k[static_cast<std::size_t>(d + r)] = c * s;
  }
  return k;
}

}  // namespace

double heightfield_bytes(int n) {
  // Heights: one double per vertex (sim/heightfield.h); hierarchy: one HeightBounds (two doubles)
  // per node over the levels n^2, n^2/4, ..., 1 (sim/heightfield_hierarchy.h).
  const double cells = static_cast<double>(n) * n;
  double nodes = 0.0;
  for (double c = cells; c >= 1.0; c /= 4.0) nodes += c;
  return static_cast<double>(sizeof(double)) * cells + static_cast<double>(sizeof(HeightBounds)) * nodes;
}

int heightfield_max_n(double budget_bytes) {
  int best = 0;
  for (int n = 2; n <= 65536; n *= 2)
    if (heightfield_bytes(n) <= budget_bytes) best = n;
  return best;
}

void check_heightfield_memory(int n, double budget_bytes) {
  const double need = heightfield_bytes(n);
  if (!(need <= budget_bytes)) {
    const int max_n = heightfield_max_n(budget_bytes);
    throw std::invalid_argument("heightfield n = " + std::to_string(n) + " needs " + gigabytes(need) +
                                " GB with its hierarchy, more than the memory budget of " + gigabytes(budget_bytes) +
                                " GB: n must be a power of two in " +
                                (max_n == 0 ? std::string("[] (none fits)") : "[2, " + std::to_string(max_n) + "]"));
  }
}

GaussianHeightfieldParameters gaussian_heightfield_parameters(const GaussianHeightfieldOptions& opt) {
  if (!power_of_two(opt.n) || opt.n > 65536)
    throw std::invalid_argument("heightfield n = " + std::to_string(opt.n) + " is not a power of two in [2, 65536]");
  check_heightfield_memory(opt.n, opt.max_bytes);
  if (!(opt.alpha_x > 0.0) || !(opt.alpha_y > 0.0))
    throw std::invalid_argument("heightfield alpha_x, alpha_y must be > 0");
  if (!(opt.correlation_length >= 2.0) || opt.correlation_length > opt.n / 8.0)
    throw std::invalid_argument("heightfield correlation_length = " + std::to_string(opt.correlation_length) +
                                " is out of range [2, n/8]");
  GaussianHeightfieldParameters p;
  p.l_x = opt.correlation_length;
  const double one_minus_q = -std::expm1(-1.0 / (p.l_x * p.l_x));
  p.sigma = opt.alpha_x / (2.0 * std::sqrt(one_minus_q));
  const double r = opt.alpha_y * opt.alpha_y / (4.0 * p.sigma * p.sigma);
  if (!(r < 1.0)) throw std::invalid_argument("heightfield alpha_y / alpha_x is too large for correlation_length");
  p.l_y = 1.0 / std::sqrt(-std::log1p(-r));
  if (!(p.l_y >= 2.0) || p.l_y > opt.n / 8.0)
    throw std::invalid_argument("heightfield l_y = " + std::to_string(p.l_y) +
                                " (from alpha_x, alpha_y, correlation_length) is out of range [2, n/8]");
  return p;
}

Heightfield make_gaussian_heightfield(const GaussianHeightfieldOptions& opt) {
  const GaussianHeightfieldParameters p = gaussian_heightfield_parameters(opt);
  const int n = opt.n;
  const auto nn = static_cast<std::size_t>(n) * n;
  // White noise, one stream per row (Box-Muller; 1 - u in (0, 1] keeps the log finite).
  std::vector<double> w(nn);
  for (int j = 0; j < n; ++j) {
    Rng rng(opt.seed, kHeightfieldStream, static_cast<std::uint64_t>(j));
    for (int i = 0; i < n; i += 2) {
      const double rad = std::sqrt(-2.0 * std::log(1.0 - rng.uniform()));
      const double ang = 2.0 * std::numbers::pi * rng.uniform();
      w[static_cast<std::size_t>(j) * n + i] = rad * std::cos(ang);
      w[static_cast<std::size_t>(j) * n + i + 1] = rad * std::sin(ang);
    }
  }
  // g = c exp(-2x^2/l_x^2) exp(-2y^2/l_y^2), c = 2 sigma / sqrt(pi l_x l_y), split over the axes.
  const double c = 2.0 * p.sigma / std::sqrt(std::numbers::pi * p.l_x * p.l_y);
  int rx = 0, ry = 0;
  const std::vector<double> kx = wrapped_kernel(n, p.l_x, std::sqrt(c), rx);
  const std::vector<double> ky = wrapped_kernel(n, p.l_y, std::sqrt(c), ry);
  const int m = n - 1;
  std::vector<double> t(nn);
  for (int j = 0; j < n; ++j)  // along x
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      for (int d = -rx; d <= rx; ++d)
        s += kx[static_cast<std::size_t>(d + rx)] * w[static_cast<std::size_t>(j) * n + ((i - d) & m)];
      t[static_cast<std::size_t>(j) * n + i] = s;
    }
  Heightfield f;
  f.n = n;
  f.h.assign(nn, 0.0);
  for (int j = 0; j < n; ++j)  // along y
    for (int i = 0; i < n; ++i) {
      double s = 0.0;
      for (int d = -ry; d <= ry; ++d)
        s += ky[static_cast<std::size_t>(d + ry)] * t[static_cast<std::size_t>((j - d) & m) * n + i];
      f.h[static_cast<std::size_t>(j) * n + i] = s;
    }
  return f;
}

double ggx_height_map_derivative(double x) {
  // E = -log(1 - Phi_N(x)): log1p of the small Phi_N below the median, the log of the small upper
  // tail above it (each side from erfc, no cancellation).
  const double e = x < 0.0 ? -std::log1p(-0.5 * std::erfc(-x / std::numbers::sqrt2))
                           : -std::log(0.5 * std::erfc(x / std::numbers::sqrt2));
  return 1.0 / std::sqrt(e);
}

Heightfield make_ggx_heightfield(const GaussianHeightfieldOptions& opt) {
  const GaussianHeightfieldParameters p = gaussian_heightfield_parameters(opt);
  Heightfield f = make_gaussian_heightfield(opt);
  // Phi(g) = integral of Phi' from the lowest vertex: the vertices in increasing g (ties by
  // index: the same order on every platform), each gap by 4-point Gauss-Legendre (Phi' is smooth
  // and changes by a few percent over a gap), summed in that order; heights overwrite g in place.
  const std::size_t nn = f.h.size();
  std::vector<std::uint64_t> order(nn);
  for (std::size_t k = 0; k < nn; ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::uint64_t a, std::uint64_t b) { return f.h[a] < f.h[b] || (f.h[a] == f.h[b] && a < b); });
  static constexpr double kNode[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static constexpr double kWeight[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  double prev = f.h[order[0]], height = 0.0;
  for (std::size_t k = 0; k < nn; ++k) {
    const double t = f.h[order[k]];
    if (t > prev) {
      const double mid = 0.5 * (t + prev), half = 0.5 * (t - prev);
      double s = 0.0;
      for (int q = 0; q < 4; ++q) s += kWeight[q] * ggx_height_map_derivative((mid + half * kNode[q]) / p.sigma);
      height += half * s;
    }
    prev = t;
    f.h[order[k]] = height;
  }
  return f;
}

Heightfield make_flat_heightfield(int n, double height) {
  if (!power_of_two(n)) throw std::invalid_argument("heightfield n = " + std::to_string(n) + " is not a power of two");
  Heightfield f;
  f.n = n;
  f.h.assign(static_cast<std::size_t>(n) * n, height);
  return f;
}

Heightfield make_vgroove_heightfield(int n, int half_period, double slope) {
  if (!power_of_two(n) || half_period < 1 || n % (2 * half_period) != 0)
    throw std::invalid_argument("vgroove heightfield: n a power of two, a multiple of 2 half_period");
  Heightfield f;
  f.n = n;
  f.h.resize(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      f.h[static_cast<std::size_t>(j) * n + i] = slope * std::abs((i % (2 * half_period)) - half_period);
  return f;
}

}  // namespace vgroove::sim
