// vgroove sim: the bins of exit directions found by comparisons, without inverse trigonometry
// (the procedural surfaces' tallies, microsurface.cpp and microsurface3d.cpp).
//
// A guess from a cheap arctangent (error below 1e-7 rad, far below any bin) is corrected by the
// exact test against the bin's edges: a direction lies at or past an edge at angle e exactly when
// its cross product with the edge's direction is >= 0. The bins are those of the tallies'
// bin_of functions (floor of the angle over the bin width); the two differ only for a direction
// within rounding (~1e-16 rad) of an edge, where the library's atan2 or acos decides one way and
// the cross product the other (probability ~1e-15 per ray).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::sim {

// atan2(y, x) to 1e-7 rad (octant reduction and the odd polynomial of Abramowitz & Stegun 4.4.49,
// |error| <= 2e-8 on [0, 1]; measured 3.8e-8 over all angles, tests/sim/exit_bins_test.cpp): only
// a guess.
inline constexpr double kAtan2GuessError = 1e-7;
inline double atan2_guess(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
  const double a = lo / (hi > 0.0 ? hi : 1.0), s = a * a;
  double r = (((((((-0.0040540580 * s + 0.0218612288) * s - 0.0559098861) * s + 0.0964200441) * s - 0.1390853351) * s +
                0.1994653599) *
                   s -
               0.3332985605) *
                  s +
              0.9999993329) *
             a;
  r = ay > ax ? 0.5 * std::numbers::pi - r : r;
  r = x < 0.0 ? std::numbers::pi - r : r;
  return y < 0.0 ? -r : r;
}

// Equal bins of width w from the angle lo, n of them; the edges' unit directions (cos, sin) in
// the (x, y) plane where the angle is atan2(y, x).
struct AngleEdges {
  double lo = 0.0, w = 1.0, inv_w = 1.0;
  int n = 0;
  std::vector<double> c, s;  // edge b at lo + b w, b = 0..n
  AngleEdges() = default;
  AngleEdges(double lo_, double w_, int n_) : lo(lo_), w(w_), inv_w(1.0 / w_), n(n_) {
    for (int b = 0; b <= n; ++b) {
      c.push_back(std::cos(lo + b * w));
      s.push_back(std::sin(lo + b * w));
    }
  }
  // Whether the direction (x, y) lies at or past edge b (counter-clockwise), for directions
  // within pi of it.
  bool at_or_past(int b, double x, double y) const { return c[b] * y - s[b] * x >= 0.0; }
  // The bin of (x, y) among bins 0..n-1 (clamped at the ends, as the tallies clamp), from a
  // guess of its angle.
  int bin(double x, double y, double angle_guess) const {
    int j = std::clamp(static_cast<int>(std::floor((angle_guess - lo) / w)), 0, n - 1);
    while (j > 0 && !at_or_past(j, x, y)) --j;
    while (j < n - 1 && at_or_past(j + 1, x, y)) ++j;
    return j;
  }
  // The same without branches, for the blocks' loops: the guess is within 1e-7 rad, far less
  // than a bin, so one step each way is all the correction there is. Requires bins of width
  // > 1e-7 (the suites' finest, 10,000 over 90 deg, are 1.6e-4 wide).
  double bin_branchless(double x, double y, double angle_guess) const {
    const double last = static_cast<double>(n - 1);
    // The guess's bin: clamped at 0 first, so truncation is the floor (a NaN guess gives 0).
    double j = (angle_guess - lo) * inv_w;
    j = j >= 0.0 ? (j > last ? last : j) : 0.0;
    const int b = static_cast<int>(j);
    j = static_cast<double>(b);
    const int b1 = b + 1 > n ? n : b + 1;
    j -= (j > 0.0) & !at_or_past(b, x, y) ? 1.0 : 0.0;
    j += (j < last) & at_or_past(b1, x, y) ? 1.0 : 0.0;
    return j;
  }
  // bin_branchless's bin from the guess alone, where the guess lies farther than the guess's
  // error (and the edges' rounding) from every edge, inside the range: there the edge tests
  // cannot disagree with it. -1 elsewhere (within ~2e-7 rad of an edge, or clamped at either
  // end), for the caller to ask bin_branchless. No memory read: the blocks' loops vectorize.
  double bin_if_far(double angle_guess) const {
    const double last = static_cast<double>(n - 1), margin = 2.0 * kAtan2GuessError * inv_w;
    const double j = (angle_guess - lo) * inv_w;
    const double jc = j >= 0.0 ? (j > last + 1.0 ? last + 1.0 : j) : 0.0;  // NaN: 0, declined below
    const double b = static_cast<double>(static_cast<int>(jc));
    const double frac = jc - b;
    const bool far = (frac > margin) & (frac < 1.0 - margin) & (b <= last);
    return far ? b : -1.0;
  }
};

}  // namespace vgroove::sim
