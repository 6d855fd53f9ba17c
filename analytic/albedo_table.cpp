// vgroove analytic: albedo tables in named layouts (albedo_table.h).
#include "vgroove/analytic/albedo_table.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

TableLayout cycles_ggx_E_layout() {
  TableLayout l;
  l.n_direction = 32;
  l.n_roughness = 32;
  l.direction = DirectionAxis::cos_theta;
  l.roughness = RoughnessAxis::roughness_squared;
  l.placement = TexelPlacement::endpoints;
  l.fast = FastAxis::roughness;
  l.s_min = 1e-4;
  l.float_coordinates = true;
  l.saturate = true;
  return l;
}

double layout_coordinate(const TableLayout& l, int i, int n) {
  assert(n >= 1 && i >= 0 && i < n);
  if (l.float_coordinates) {
    // Cycles: clamp(float(x) / float(nx - 1), 1e-4f, 1.0f), in float.
    const float s = l.placement == TexelPlacement::endpoints
                        ? (n == 1 ? 1.0f : static_cast<float>(i) / static_cast<float>(n - 1))
                        : (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
    return std::clamp(s, static_cast<float>(l.s_min), 1.0f);
  }
  const double s =
      l.placement == TexelPlacement::endpoints ? (n == 1 ? 1.0 : static_cast<double>(i) / (n - 1)) : (i + 0.5) / n;
  return std::clamp(s, l.s_min, 1.0);
}

double layout_mu(const TableLayout& l, int i) {
  const double s = layout_coordinate(l, i, l.n_direction);
  if (l.direction == DirectionAxis::cos_theta) return s;
  // Rows in theta: s = theta / (pi / 2), the row at s = 1 grazing; the clamp keeps mu > 0.
  const double mu = std::cos(0.5 * std::numbers::pi * std::min(s, 1.0 - l.s_min));
  return l.float_coordinates ? static_cast<double>(static_cast<float>(mu)) : mu;
}

double layout_alpha(const TableLayout& l, int j) {
  const double r = layout_coordinate(l, j, l.n_roughness);
  if (l.roughness == RoughnessAxis::alpha) return r;
  // Cycles: alpha_x = sqr(rough) in float.
  return l.float_coordinates ? static_cast<double>(static_cast<float>(r) * static_cast<float>(r)) : r * r;
}

int layout_index(const TableLayout& l, int i, int j) {
  return l.fast == FastAxis::roughness ? i * l.n_roughness + j : j * l.n_direction + i;
}

namespace {

void put(AlbedoTable& t, int k, const BoundedValue& v) {
  t.values[k] = t.layout.saturate ? std::clamp(v.value, 0.0, 1.0) : v.value;
  t.errors[k] = v.error;
  t.max_error = std::max(t.max_error, v.error);
  t.converged = t.converged && v.converged;
  t.evaluations += v.evaluations;
}

AlbedoTable empty_table(const TableLayout& l, std::size_t n) {
  AlbedoTable t;
  t.layout = l;
  t.values.assign(n, 0.0);
  t.errors.assign(n, 0.0);
  return t;
}

}  // namespace

AlbedoTable albedo_table(const MicrofacetModel& m, const TableLayout& l, const AlbedoOptions& opt) {
  AlbedoTable t = empty_table(l, static_cast<std::size_t>(l.n_direction) * l.n_roughness);
  for (int i = 0; i < l.n_direction; ++i)
    for (int j = 0; j < l.n_roughness; ++j)
      put(t, layout_index(l, i, j), albedo_single(m, layout_alpha(l, j), layout_mu(l, i), opt));
  return t;
}

AlbedoTable albedo_average_table(const MicrofacetModel& m, const TableLayout& l, const AlbedoOptions& opt) {
  AlbedoTable t = empty_table(l, static_cast<std::size_t>(l.n_roughness));
  for (int j = 0; j < l.n_roughness; ++j) put(t, j, albedo_average(m, layout_alpha(l, j), opt));
  return t;
}

SplitSumTable dfg_table(const MicrofacetModel& m, const TableLayout& l, const AlbedoOptions& opt) {
  const std::size_t n = static_cast<std::size_t>(l.n_direction) * l.n_roughness;
  SplitSumTable t{empty_table(l, n), empty_table(l, n)};
  for (int i = 0; i < l.n_direction; ++i)
    for (int j = 0; j < l.n_roughness; ++j) {
      const SplitSum s = dfg_split_sum(m, layout_alpha(l, j), layout_mu(l, i), opt);
      put(t.scale, layout_index(l, i, j), s.scale);
      put(t.bias, layout_index(l, i, j), s.bias);
    }
  return t;
}

}  // namespace vgroove::analytic
