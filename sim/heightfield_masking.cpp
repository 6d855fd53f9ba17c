#include "vgroove/sim/heightfield_masking.h"

#include "vgroove/sim/rng.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

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

void check_joint_options(const HeightfieldJointMaskingOptions& opt) {
  for (const auto& [name, theta] : {std::pair{"theta_i", opt.theta_i}, std::pair{"theta_o", opt.theta_o}})
    if (!(theta >= 0.0 && theta < 0.5 * std::numbers::pi))
      throw std::invalid_argument(std::string("joint masking ") + name + " = " + std::to_string(theta) +
                                  " is out of range [0, pi/2)");
  if (opt.points < 1)
    throw std::invalid_argument("joint masking points = " + std::to_string(opt.points) + " must be >= 1");
  if (opt.theta_m_bins < 1 || opt.phi_m_bins < 1)
    throw std::invalid_argument("joint masking theta_m_bins, phi_m_bins must be >= 1");
}

Vec3 direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// A point uniform over the macrosurface: a triangle uniformly (all have the macro area 1/2), then
// a point uniformly on it. Three draws per point whatever happens next (the stream's layout).
struct SurfacePoint {
  int i = 0, j = 0, half = 0;
  Vec3 p, N;  // the point, and its triangle's upward normal N = (-s_x, -s_y, 1)
};
SurfacePoint draw_point(const HeightfieldSurface& s, Rng& rng) {
  const std::uint64_t pick = rng.next_u64();
  const double u1 = rng.uniform(), u2 = rng.uniform();
  const int n = s.field.n;
  const auto cells = static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(n);
  const std::uint64_t tri = pick % (2 * cells);
  SurfacePoint q;
  q.half = static_cast<int>(tri / cells);
  const int i = q.i = static_cast<int>((tri % cells) % static_cast<std::uint64_t>(n));
  const int j = q.j = static_cast<int>((tri % cells) / static_cast<std::uint64_t>(n));
  // Corners counter-clockwise (sim/heightfield.h).
  const Vec3 a(i, j, s.field.height(i, j));
  const Vec3 c =
      q.half == 0 ? Vec3(i + 1, j, s.field.height(i + 1, j)) : Vec3(i + 1, j + 1, s.field.height(i + 1, j + 1));
  const Vec3 d =
      q.half == 0 ? Vec3(i + 1, j + 1, s.field.height(i + 1, j + 1)) : Vec3(i, j + 1, s.field.height(i, j + 1));
  q.N = q.half == 0 ? Vec3(-(c.z() - a.z()), -(d.z() - c.z()), 1.0) : Vec3(-(c.z() - d.z()), -(d.z() - a.z()), 1.0);
  // Uniform barycentrics (sqrt u1 folds the square onto the triangle).
  const double su = std::sqrt(u1);
  q.p = (1.0 - su) * a + su * (1.0 - u2) * c + su * u2 * d;
  return q;
}

// The ray from above the field, along -d, through q: q is visible from d when it meets q's
// triangle first (the same copy, not a periodic image).
bool visible(const HeightfieldSurface& s, const SurfacePoint& q, const Vec3& d, const HeightfieldRayOptions& ray,
             std::int64_t& lost, std::int64_t& edge_hits, std::int64_t& vertex_hits) {
  const double z_top = s.hierarchy.root().hi + 1.0;
  const double t_up = (z_top - q.p.z()) / d.z();
  const HeightfieldFirstHit hit = first_heightfield_hit(s, q.p + t_up * d, -d, ray);
  lost += hit.how == HeightfieldFate::lost;
  edge_hits += hit.edge;
  vertex_hits += hit.vertex;
  return hit.hit && hit.cx == q.i && hit.cy == q.j && hit.half == q.half;
}

// The facet normal's bin: its polar angle (equal bins over [0, pi/2)) and its azimuth relative to
// phi_ref (bin 0 centred on it).
struct Binning {
  int theta_m_bins, phi_m_bins;
  double phi_ref, theta_w, phi_w;
  Binning(int t, int p, double ref)
      : theta_m_bins(t),
        phi_m_bins(p),
        phi_ref(ref),
        theta_w(0.5 * std::numbers::pi / t),
        phi_w(2.0 * std::numbers::pi / p) {}
  std::size_t of(const Vec3& N) const {
    const double theta_m = std::atan(std::hypot(N.x(), N.y()));
    const int tb = std::min(theta_m_bins - 1, static_cast<int>(theta_m / theta_w));
    int pb = static_cast<int>(std::floor((std::atan2(N.y(), N.x()) - phi_ref) / phi_w + 0.5));
    pb %= phi_m_bins;
    if (pb < 0) pb += phi_m_bins;
    return static_cast<std::size_t>(tb * phi_m_bins + pb);
  }
};

}  // namespace

double heightfield_joint_bin_azimuth(double theta_i, double phi_i, double theta_o, double phi_o) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  // A direction at the normal has no azimuth: the other's (either when both are).
  if (theta_i == 0.0 && theta_o == 0.0) return 0.0;
  if (theta_i == 0.0) return phi_o;
  if (theta_o == 0.0) return phi_i;
  const auto wrap = [two_pi](double phi) {
    const double w = std::fmod(phi, two_pi);
    return w < 0.0 ? w + two_pi : w;
  };
  // Only min and max of the two: the same bits for (i, o) and (o, i).
  const double a = wrap(phi_i), b = wrap(phi_o);
  const double lo = std::min(a, b), hi = std::max(a, b), d = hi - lo;
  if (d < std::numbers::pi) return lo + 0.5 * d;
  if (d > std::numbers::pi) return wrap(hi + 0.5 * (two_pi - d));
  const double r = lo + 0.5 * std::numbers::pi;  // opposite: the bisector in [0, pi)
  return r >= std::numbers::pi ? r - std::numbers::pi : r;
}

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
  const Vec3 o = direction(opt.theta_o, opt.phi_o);
  const Binning bins(opt.theta_m_bins, opt.phi_m_bins, opt.phi_o);
  for (std::int64_t r = 0; r < count; ++r) {
    const SurfacePoint q = draw_point(s, rng);
    ++tally.points;
    const double w = o.dot(q.N);
    if (!(w > 0.0)) continue;  // facing away from o: no projected area towards it
    ++tally.front;
    const bool v = visible(s, q, o, opt.ray, tally.lost, tally.edge_hits, tally.vertex_hits);
    const auto b = bins.of(q.N);
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

HeightfieldJointMaskingTally::HeightfieldJointMaskingTally(int theta_m_bins_, int phi_m_bins_)
    : theta_m_bins(theta_m_bins_), phi_m_bins(phi_m_bins_) {
  const auto bins = static_cast<std::size_t>(theta_m_bins) * phi_m_bins;
  weight.assign(bins, 0.0);
  weight_i.assign(bins, 0.0);
  weight_o.assign(bins, 0.0);
  weight_io.assign(bins, 0.0);
  count.assign(bins, 0);
}

void HeightfieldJointMaskingTally::merge(const HeightfieldJointMaskingTally& o) {
  points += o.points;
  front += o.front;
  visible_i += o.visible_i;
  visible_o += o.visible_o;
  visible_both += o.visible_both;
  lost += o.lost;
  edge_hits += o.edge_hits;
  vertex_hits += o.vertex_hits;
  sum_w += o.sum_w;
  sum_wi += o.sum_wi;
  sum_wo += o.sum_wo;
  sum_wio += o.sum_wio;
  for (std::size_t b = 0; b < weight.size(); ++b) {
    weight[b] += o.weight[b];
    weight_i[b] += o.weight_i[b];
    weight_o[b] += o.weight_o[b];
    weight_io[b] += o.weight_io[b];
    count[b] += o.count[b];
  }
}

std::int64_t heightfield_joint_masking_chunk_count(const HeightfieldJointMaskingOptions& opt) {
  return (opt.points + kHeightfieldPointsPerChunk - 1) / kHeightfieldPointsPerChunk;
}

HeightfieldJointMaskingTally heightfield_joint_masking_chunk(const HeightfieldSurface& s,
                                                             const HeightfieldJointMaskingOptions& opt,
                                                             std::int64_t chunk) {
  check_joint_options(opt);
  HeightfieldJointMaskingTally tally(opt.theta_m_bins, opt.phi_m_bins);
  const std::int64_t first = chunk * kHeightfieldPointsPerChunk;
  const std::int64_t count = std::min(kHeightfieldPointsPerChunk, opt.points - first);
  Rng rng(opt.seed, kHeightfieldMaskingStream, static_cast<std::uint64_t>(chunk));
  const Vec3 wi = direction(opt.theta_i, opt.phi_i), wo = direction(opt.theta_o, opt.phi_o);
  const Binning bins(opt.theta_m_bins, opt.phi_m_bins,
                     heightfield_joint_bin_azimuth(opt.theta_i, opt.phi_i, opt.theta_o, opt.phi_o));
  for (std::int64_t r = 0; r < count; ++r) {
    const SurfacePoint q = draw_point(s, rng);
    ++tally.points;
    const double ci = wi.dot(q.N), co = wo.dot(q.N);
    if (!(ci > 0.0 && co > 0.0)) continue;  // facing away from i or o: no weight
    ++tally.front;
    // |N| (i.m) (o.m), the product written symmetrically in i and o.
    const double w = ci * co / q.N.norm();
    const bool vi = visible(s, q, wi, opt.ray, tally.lost, tally.edge_hits, tally.vertex_hits);
    const bool vo = visible(s, q, wo, opt.ray, tally.lost, tally.edge_hits, tally.vertex_hits);
    const auto b = bins.of(q.N);
    tally.sum_w += w;
    tally.weight[b] += w;
    ++tally.count[b];
    if (vi) ++tally.visible_i, tally.sum_wi += w, tally.weight_i[b] += w;
    if (vo) ++tally.visible_o, tally.sum_wo += w, tally.weight_o[b] += w;
    if (vi && vo) ++tally.visible_both, tally.sum_wio += w, tally.weight_io[b] += w;
  }
  return tally;
}

HeightfieldJointMaskingTally heightfield_joint_masking(const HeightfieldSurface& s,
                                                       const HeightfieldJointMaskingOptions& opt) {
  check_joint_options(opt);
  HeightfieldJointMaskingTally tally(opt.theta_m_bins, opt.phi_m_bins);
  for (std::int64_t c = 0; c < heightfield_joint_masking_chunk_count(opt); ++c)
    tally.merge(heightfield_joint_masking_chunk(s, opt, c));
  return tally;
}

}  // namespace vgroove::sim
