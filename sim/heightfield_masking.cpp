#include "vgroove/sim/heightfield_masking.h"

#include "vgroove/sim/rng.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vgroove::sim {
namespace {

using Vec3 = Eigen::Vector3d;

void check_options(const HeightfieldMaskingOptions& opt) {
  if (!(opt.theta_o >= 0.0 && opt.theta_o < 0.5 * std::numbers::pi))
    throw std::invalid_argument("masking theta_o = " + std::to_string(opt.theta_o) + " is out of range [0, pi/2)");
  if (opt.points < 1) throw std::invalid_argument("masking points = " + std::to_string(opt.points) + " must be >= 1");
  if (opt.theta_m_bins < 1 || opt.phi_m_bins < 1)
    throw std::invalid_argument("masking theta_m_bins, phi_m_bins must be >= 1");
}

}  // namespace

HeightfieldMaskingTally::HeightfieldMaskingTally(int theta_m_bins_, int phi_m_bins_)
    : theta_m_bins(theta_m_bins_), phi_m_bins(phi_m_bins_) {
  const auto bins = static_cast<std::size_t>(theta_m_bins) * phi_m_bins;
  weight.assign(bins, 0.0);
  visible_weight.assign(bins, 0.0);
  count.assign(bins, 0);
}

void HeightfieldMaskingTally::merge(const HeightfieldMaskingTally& o) {
  points += o.points;
  front += o.front;
  visible += o.visible;
  lost += o.lost;
  edge_hits += o.edge_hits;
  vertex_hits += o.vertex_hits;
  sum_w += o.sum_w;
  sum_wv += o.sum_wv;
  sum_wv2 += o.sum_wv2;
  for (std::size_t b = 0; b < weight.size(); ++b) {
    weight[b] += o.weight[b];
    visible_weight[b] += o.visible_weight[b];
    count[b] += o.count[b];
  }
}

double HeightfieldMaskingTally::visible_area_se() const {
  const double m = static_cast<double>(points);
  const double mean = sum_wv / m;
  return std::sqrt(std::max(0.0, sum_wv2 / m - mean * mean) / (m - 1.0));
}

std::int64_t heightfield_masking_chunk_count(const HeightfieldMaskingOptions& opt) {
  return (opt.points + kHeightfieldPointsPerChunk - 1) / kHeightfieldPointsPerChunk;
}

HeightfieldMaskingTally heightfield_masking_chunk(const HeightfieldSurface& s, const HeightfieldMaskingOptions& opt,
                                                  std::int64_t chunk) {
  check_options(opt);
  HeightfieldMaskingTally tally(opt.theta_m_bins, opt.phi_m_bins);
  const std::int64_t first = chunk * kHeightfieldPointsPerChunk;
  const std::int64_t count = std::min(kHeightfieldPointsPerChunk, opt.points - first);
  Rng rng(opt.seed, kHeightfieldMaskingStream, static_cast<std::uint64_t>(chunk));
  const Vec3 o(std::sin(opt.theta_o) * std::cos(opt.phi_o), std::sin(opt.theta_o) * std::sin(opt.phi_o),
               std::cos(opt.theta_o));
  const int n = s.field.n;
  const double z_top = s.hierarchy.root().hi + 1.0;
  const double theta_w = 0.5 * std::numbers::pi / opt.theta_m_bins, phi_w = 2.0 * std::numbers::pi / opt.phi_m_bins;
  for (std::int64_t r = 0; r < count; ++r) {
    // A triangle uniformly (all have the macro area 1/2), then a point uniformly on it: uniform
    // over the macrosurface. Three draws per point whatever happens next (the stream's layout).
    const std::uint64_t pick = rng.next_u64();
    const double u1 = rng.uniform(), u2 = rng.uniform();
    const auto cells = static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(n);
    const std::uint64_t tri = pick % (2 * cells);
    const int half = static_cast<int>(tri / cells);
    const int i = static_cast<int>((tri % cells) % static_cast<std::uint64_t>(n));
    const int j = static_cast<int>((tri % cells) / static_cast<std::uint64_t>(n));
    ++tally.points;
    // Corners counter-clockwise (sim/heightfield.h) and the upward normal N = (-s_x, -s_y, 1).
    const Vec3 a(i, j, s.field.height(i, j));
    const Vec3 c =
        half == 0 ? Vec3(i + 1, j, s.field.height(i + 1, j)) : Vec3(i + 1, j + 1, s.field.height(i + 1, j + 1));
    const Vec3 d =
        half == 0 ? Vec3(i + 1, j + 1, s.field.height(i + 1, j + 1)) : Vec3(i, j + 1, s.field.height(i, j + 1));
    const Vec3 N =
        half == 0 ? Vec3(-(c.z() - a.z()), -(d.z() - c.z()), 1.0) : Vec3(-(c.z() - d.z()), -(d.z() - a.z()), 1.0);
    const double w = o.dot(N);
    if (!(w > 0.0)) continue;  // facing away from o: no projected area towards it
    ++tally.front;
    // Uniform barycentrics (sqrt u1 folds the square onto the triangle).
    const double su = std::sqrt(u1);
    const Vec3 p = (1.0 - su) * a + su * (1.0 - u2) * c + su * u2 * d;
    // The ray from above the field, along -o, through p: p is visible when it meets p's triangle first.
    const double t_up = (z_top - p.z()) / o.z();
    const HeightfieldFirstHit hit = first_heightfield_hit(s, p + t_up * o, -o, opt.ray);
    tally.lost += hit.how == HeightfieldFate::lost;
    tally.edge_hits += hit.edge;
    tally.vertex_hits += hit.vertex;
    const bool v = hit.hit && hit.cx == i && hit.cy == j && hit.half == half;  // the same copy, not an image
    // Bins: the facet normal's polar angle and its azimuth relative to phi_o.
    const double theta_m = std::atan(std::hypot(N.x(), N.y()));
    const int tb = std::min(opt.theta_m_bins - 1, static_cast<int>(theta_m / theta_w));
    int pb = static_cast<int>(std::floor((std::atan2(N.y(), N.x()) - opt.phi_o) / phi_w + 0.5));
    pb %= opt.phi_m_bins;
    if (pb < 0) pb += opt.phi_m_bins;
    const auto b = static_cast<std::size_t>(tb * opt.phi_m_bins + pb);
    tally.sum_w += w;
    tally.weight[b] += w;
    ++tally.count[b];
    if (v) {
      ++tally.visible;
      tally.sum_wv += w;
      tally.sum_wv2 += w * w;
      tally.visible_weight[b] += w;
    }
  }
  return tally;
}

HeightfieldMaskingTally heightfield_masking(const HeightfieldSurface& s, const HeightfieldMaskingOptions& opt) {
  check_options(opt);
  HeightfieldMaskingTally tally(opt.theta_m_bins, opt.phi_m_bins);
  for (std::int64_t c = 0; c < heightfield_masking_chunk_count(opt); ++c)
    tally.merge(heightfield_masking_chunk(s, opt, c));
  return tally;
}

}  // namespace vgroove::sim
