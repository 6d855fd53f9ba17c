#include "vgroove/sim/polyline.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

Vec2 Polyline::point(int j, double s) const {
  const std::size_t a = static_cast<std::size_t>(j), b = a + 1;
  const double ex = x[b] - x[a], ey = y[b] - y[a];
  // 1 - s is exact for s >= 1/2 (Sterbenz).
  if (s <= 0.5) return Vec2(x[a] + s * ex, y[a] + s * ey);
  const double r = 1.0 - s;
  return Vec2(x[b] - r * ex, y[b] - r * ey);
}

double Polyline::length(int j) const {
  const std::size_t a = static_cast<std::size_t>(j), b = a + 1;
  return std::hypot(x[b] - x[a], y[b] - y[a]);
}

Polyline make_polyline(std::vector<double> xs, std::vector<double> ys) {
  assert(xs.size() == ys.size() && xs.size() >= 2);
  assert(ys.back() == ys.front());
  Polyline p;
  p.x = std::move(xs);
  p.y = std::move(ys);
  const int n = p.segments();
  p.period = p.x[static_cast<std::size_t>(n)] - p.x[0];
  p.normal.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const std::size_t a = static_cast<std::size_t>(j);
    const double ex = p.x[a + 1] - p.x[a], ey = p.y[a + 1] - p.y[a];
    assert(ex > 0.0 && std::isfinite(ey));
    const double len = std::hypot(ex, ey);
    // The edge turned counter-clockwise by 90 deg: up, since ex > 0.
    p.normal[a] = Vec2(-ey / len, ex / len);
  }
  p.y_max = *std::max_element(p.y.begin(), p.y.end());
  p.y_min = *std::min_element(p.y.begin(), p.y.end());
  // The pyramid: level 0 from the vertices, each level above from the one below, until one block
  // covers the whole period.
  std::vector<double> below;
  for (int b = 0; b * Polyline::kBlock < n; ++b) {
    const int lo = b * Polyline::kBlock, hi = std::min(n, lo + Polyline::kBlock);
    below.push_back(*std::max_element(p.y.begin() + lo, p.y.begin() + hi + 1));
  }
  p.levels.push_back(below);
  while (below.size() > 1) {
    std::vector<double> up;
    for (std::size_t b = 0; b < below.size(); b += Polyline::kBlock)
      up.push_back(
          *std::max_element(below.begin() + static_cast<std::ptrdiff_t>(b),
                            below.begin() + static_cast<std::ptrdiff_t>(std::min(below.size(), b + Polyline::kBlock))));
    p.levels.push_back(up);
    below = std::move(up);
  }
  return p;
}

Polyline vgroove_polyline(const std::vector<double>& theta_m) {
  const std::size_t g = theta_m.size();
  std::vector<double> x(2 * g + 1), y(2 * g + 1, 0.0);
  for (std::size_t v = 0; v <= 2 * g; ++v) x[v] = static_cast<double>(v);
  for (std::size_t j = 0; j < g; ++j) {
    assert(theta_m[j] >= 0.0 && theta_m[j] < 0.5 * std::numbers::pi);
    y[2 * j + 1] = -std::tan(theta_m[j]);
  }
  return make_polyline(std::move(x), std::move(y));
}

}  // namespace vgroove::sim
