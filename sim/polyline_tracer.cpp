#include "vgroove/sim/polyline_tracer.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace vgroove::sim {

namespace {

// A conservative bound on the rounding of one side computation relative to its terms' size.
constexpr double kSideRounding = 8.0 * std::numeric_limits<double>::epsilon();

// The ray p + t d (t >= 0) of one step, with what every side computation of the step shares.
struct Ray {
  Vec2 p, d;
  double abs_dx, abs_dy, abs_px, abs_py;
  Ray(const Vec2& p_, const Vec2& d_)
      : p(p_),
        d(d_),
        abs_dx(std::abs(d_.x())),
        abs_dy(std::abs(d_.y())),
        abs_px(std::abs(p_.x())),
        abs_py(std::abs(p_.y())) {}
  // cross(v - p, d): positive for a point below the line of a ray moving right, negative for a
  // ray moving left.
  double side(double vx, double vy) const { return (vx - p.x()) * d.y() - (vy - p.y()) * d.x(); }
  // True when (vx, vy) lies below the ray's line by more than the rounding of side(vx, vy).
  template <int Dir>
  bool surely_below(double vx, double vy) const {
    const double tol = kSideRounding * ((std::abs(vx) + abs_px) * abs_dy + (std::abs(vy) + abs_py) * abs_dx);
    return Dir * side(vx, vy) > tol;
  }
};

PolylineHit vertex_hit() { return PolylineHit{PolylineHit::Kind::vertex, -1, 0.0}; }
PolylineHit escaped() { return PolylineHit{PolylineHit::Kind::escaped, -1, 0.0}; }

// Segments in a block of level L.
long block_size(int level) {
  long size = Polyline::kBlock;
  for (int l = 0; l < level; ++l) size *= Polyline::kBlock;
  return size;
}

// The march of one ray step in direction Dir (+1: d.x > 0, segments k, k + 1, ...; -1: d.x < 0,
// segments k, k - 1, ...), from segment k in period m (its vertices at x + m period). Below: the
// ray travels under the profile (the dielectric tracer's medium 2), where the roles of up and down
// swap: going down it leaves once below the lowest vertex, going up it always meets the profile
// within a period, and the blocks it skips are those it passes below (pyramid: the lowest vertex
// of each block, PolylineLows; above the profile P.levels, the highest).
template <int Dir, bool Below = false>
PolylineHit march(const Polyline& P, const Ray& r, int k, long m, const std::vector<std::vector<double>>& pyramid) {
  const int n = P.segments();
  const int levels = static_cast<int>(pyramid.size());
  const bool up = r.d.y() > 0.0, down = r.d.y() < 0.0;
  auto X = [&](int v, double sh) { return P.x[static_cast<std::size_t>(v)] + sh; };
  auto Y = [&](int v) { return P.y[static_cast<std::size_t>(v)]; };
  // Vertex through which the march enters segment k.
  auto entry = [](int seg) { return Dir > 0 ? seg : seg + 1; };
  double shift = static_cast<double>(m) * P.period;
  double s_in = r.side(X(entry(k), shift), Y(entry(k)));
  long traversed = 0;  // segments passed, tested or skipped
  auto advance = [&](long count, int next) {
    traversed += count;
    k = next;
    if (k >= n) k -= n, ++m, shift = static_cast<double>(m) * P.period;
    if (k < 0) k += n, --m, shift = static_cast<double>(m) * P.period;
  };
  for (;;) {
    if (traversed > n) {
      // A whole period passed without a hit. Moving up or level, the ray never hits (header
      // comment). Moving down it cannot happen: the copy of the highest vertex within a period
      // ahead lies above the descending ray. Only a ray that left its segment within rounding of
      // an end vertex, on the vertex's far side, gets here: it is reported as the vertex hit it is.
      // Below the profile the same holds with up and down swapped (the copy of the lowest vertex
      // within a period ahead lies below a rising ray).
      if constexpr (Below) return up ? vertex_hit() : escaped();
      return down ? vertex_hit() : escaped();
    }
    const int v_in = entry(k);
    if constexpr (Below) {
      // Going down under the profile: below the lowest vertex here, below all from here on.
      if (down && r.surely_below<-Dir>(X(v_in, shift), P.y_min)) return escaped();
    } else {
      // Going up: above the highest vertex here, above all from here on.
      if (up && r.surely_below<Dir>(X(v_in, shift), P.y_max)) return escaped();
    }
    // At a block boundary, skip the largest block the ray passes above (below, under the profile).
    if (Dir > 0 ? k % Polyline::kBlock == 0 : ((k + 1) % Polyline::kBlock == 0 || k == n - 1)) {
      bool skipped = false;
      for (int L = levels - 1; L >= 0 && !skipped; --L) {
        const long size = block_size(L);
        const long b = k / size;
        const int first = static_cast<int>(b * size);
        const int last = static_cast<int>(std::min<long>((b + 1) * size, n)) - 1;
        if ((Dir > 0 ? k != first : k != last)) continue;
        // The ray is lowest over the block at its far end when descending, at its near end when
        // rising; every vertex of the block is at or below the block's maximum. Under the profile:
        // highest at the far end when rising, and every vertex at or above the block's minimum.
        const bool far_end = Below ? up : down;
        const int v_low = (Dir > 0) == far_end ? last + 1 : first;
        const double bound = pyramid[static_cast<std::size_t>(L)][static_cast<std::size_t>(b)];
        if (Below ? !r.surely_below<-Dir>(X(v_low, shift), bound) : !r.surely_below<Dir>(X(v_low, shift), bound))
          continue;
        advance(last - first + 1, Dir > 0 ? last + 1 : first - 1);
        s_in = r.side(X(entry(k), shift), Y(entry(k)));
        skipped = true;
      }
      if (skipped) continue;
    }
    const int v_out = Dir > 0 ? k + 1 : k;
    const double s_out = r.side(X(v_out, shift), Y(v_out));
    if (s_in == 0.0 || s_out == 0.0) return vertex_hit();  // the ray's line through a vertex
    if ((s_in > 0.0) != (s_out > 0.0)) {
      // The sides at the segment's own start and end vertices.
      const double sa = Dir > 0 ? s_in : s_out, sb = Dir > 0 ? s_out : s_in;
      const double s = sa / (sa - sb);
      if (!(s > 0.0 && s < 1.0)) return vertex_hit();  // rounds onto an end vertex
      return PolylineHit{PolylineHit::Kind::segment, k, s};
    }
    s_in = s_out;
    advance(1, k + Dir);
  }
}

}  // namespace

PolylineHit first_hit_from_top(const Polyline& p, double x, const Vec2& dir) {
  assert(dir.y() < 0.0 && x >= p.x.front() && x < p.x.back());
  const Ray r(Vec2(x, p.y_max), dir);
  const int n = p.segments();
  if (dir.x() > 0.0) {
    // The segment with x_j <= x < x_{j+1}: its entry vertex is not ahead of the start.
    const int j = static_cast<int>(std::upper_bound(p.x.begin(), p.x.end(), x) - p.x.begin()) - 1;
    return march<+1>(p, r, j, 0, p.levels);
  }
  if (dir.x() < 0.0) {
    // The segment with x_j < x <= x_{j+1}; x = x_0 is the end of the last segment one period back.
    const int j = static_cast<int>(std::lower_bound(p.x.begin(), p.x.end(), x) - p.x.begin()) - 1;
    return j < 0 ? march<-1>(p, r, n - 1, -1, p.levels) : march<-1>(p, r, j, 0, p.levels);
  }
  // Straight down: the segment under x, or the vertex at x.
  const int j = static_cast<int>(std::upper_bound(p.x.begin(), p.x.end(), x) - p.x.begin()) - 1;
  const double sa = r.side(p.x[static_cast<std::size_t>(j)], p.y[static_cast<std::size_t>(j)]);
  const double sb = r.side(p.x[static_cast<std::size_t>(j) + 1], p.y[static_cast<std::size_t>(j) + 1]);
  if (sa == 0.0) return vertex_hit();
  const double s = sa / (sa - sb);
  if (!(s > 0.0 && s < 1.0)) return vertex_hit();
  return PolylineHit{PolylineHit::Kind::segment, j, s};
}

PolylineHit first_hit_from(const Polyline& p, int j, double s, const Vec2& dir) {
  const int n = p.segments();
  const Ray r(p.point(j, s), dir);
  if (dir.x() > 0.0) return j + 1 == n ? march<+1>(p, r, 0, 1, p.levels) : march<+1>(p, r, j + 1, 0, p.levels);
  if (dir.x() < 0.0) return j == 0 ? march<-1>(p, r, n - 1, -1, p.levels) : march<-1>(p, r, j - 1, 0, p.levels);
  // Straight up leaves. Straight down would go through segment j itself, which a reflected ray
  // cannot (its direction has d.n > 0); it is reported with its direction, below the horizon.
  return escaped();
}

PolylineLows polyline_lows(const Polyline& p) {
  // make_polyline's pyramid with min for max.
  const int n = p.segments();
  PolylineLows lows;
  std::vector<double> below;
  for (int b = 0; b * Polyline::kBlock < n; ++b) {
    const int lo = b * Polyline::kBlock, hi = std::min(n, lo + Polyline::kBlock);
    below.push_back(*std::min_element(p.y.begin() + lo, p.y.begin() + hi + 1));
  }
  lows.levels.push_back(below);
  while (below.size() > 1) {
    std::vector<double> up;
    for (std::size_t b = 0; b < below.size(); b += Polyline::kBlock)
      up.push_back(
          *std::min_element(below.begin() + static_cast<std::ptrdiff_t>(b),
                            below.begin() + static_cast<std::ptrdiff_t>(std::min(below.size(), b + Polyline::kBlock))));
    lows.levels.push_back(up);
    below = std::move(up);
  }
  return lows;
}

PolylineHit first_hit_from_bottom(const Polyline& p, const PolylineLows& lows, double x, const Vec2& dir) {
  assert(dir.y() > 0.0 && x >= p.x.front() && x < p.x.back());
  const Ray r(Vec2(x, p.y_min), dir);
  const int n = p.segments();
  if (dir.x() > 0.0) {
    const int j = static_cast<int>(std::upper_bound(p.x.begin(), p.x.end(), x) - p.x.begin()) - 1;
    return march<+1, true>(p, r, j, 0, lows.levels);
  }
  if (dir.x() < 0.0) {
    const int j = static_cast<int>(std::lower_bound(p.x.begin(), p.x.end(), x) - p.x.begin()) - 1;
    return j < 0 ? march<-1, true>(p, r, n - 1, -1, lows.levels) : march<-1, true>(p, r, j, 0, lows.levels);
  }
  // Straight up: the segment over x, or the vertex at x.
  const int j = static_cast<int>(std::upper_bound(p.x.begin(), p.x.end(), x) - p.x.begin()) - 1;
  const double sa = r.side(p.x[static_cast<std::size_t>(j)], p.y[static_cast<std::size_t>(j)]);
  const double sb = r.side(p.x[static_cast<std::size_t>(j) + 1], p.y[static_cast<std::size_t>(j) + 1]);
  if (sa == 0.0) return vertex_hit();
  const double s = sa / (sa - sb);
  if (!(s > 0.0 && s < 1.0)) return vertex_hit();
  return PolylineHit{PolylineHit::Kind::segment, j, s};
}

PolylineHit first_hit_from_below(const Polyline& p, const PolylineLows& lows, int j, double s, const Vec2& dir) {
  const int n = p.segments();
  const Ray r(p.point(j, s), dir);
  if (dir.x() > 0.0)
    return j + 1 == n ? march<+1, true>(p, r, 0, 1, lows.levels) : march<+1, true>(p, r, j + 1, 0, lows.levels);
  if (dir.x() < 0.0)
    return j == 0 ? march<-1, true>(p, r, n - 1, -1, lows.levels) : march<-1, true>(p, r, j - 1, 0, lows.levels);
  // Straight down leaves (a height profile meets a vertical line once). Straight up would go
  // through segment j itself, which a ray leaving it downward cannot; it is reported with its
  // direction, as first_hit_from does.
  return escaped();
}

}  // namespace vgroove::sim
