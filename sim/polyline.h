// vgroove sim: a periodic polyline height profile, the geometry the polyline tracer runs on:
// vertices (x_v, y_v), v = 0..n, x strictly increasing, x_n = x_0 + period, y_n = y_0; segment
// normals point up, at theta_m = atan(slope) (conventions of sim/geometry.h). When every x_v and
// the period are multiples of one small power of two (the generators make them so), the shifted
// copies of a vertex are exact and every period is the same profile. Segments are grouped into a
// max pyramid of blocks of kBlock, each keeping its highest vertex, so a ray passing above a
// block skips it whole.
// Tests: tests/sim/polyline_tracer_test.cpp (PolylineTracer.VGroovePolylineGeometry,
// PolylineTracer.EveryStepIsTheBruteForceHit, PolylineTracer.NearlyLevelRaysMeetTheNextPeakOrLeave).
// Derivation: docs/derivations/profiles.md.
#pragma once

#include "vgroove/sim/geometry.h"

#include <cstddef>
#include <vector>

namespace vgroove::sim {

struct Polyline {
  static constexpr int kBlock = 16;  // segments per block of the first level; blocks per block above

  std::vector<double> x, y;  // n + 1 vertices; x[n] = x[0] + period, y[n] = y[0]
  std::vector<Vec2> normal;  // per segment, unit, pointing up
  double period = 0.0;
  double y_max = 0.0, y_min = 0.0;  // over all vertices
  // levels[L][b]: the highest vertex of segments [b B, (b + 1) B) (their end vertex included),
  // B = kBlock^(L + 1); the last block of a level may be partial.
  std::vector<std::vector<double>> levels;

  int segments() const { return static_cast<int>(x.size()) - 1; }
  Vec2 vertex(int v) const { return Vec2(x[static_cast<std::size_t>(v)], y[static_cast<std::size_t>(v)]); }
  // The point at parameter s in [0, 1] of segment j, measured from the nearer end vertex (so that
  // a point close to either end is as exact as that vertex).
  Vec2 point(int j, double s) const;
  // Angle of segment j's normal from the macrosurface normal, in (-pi/2, pi/2).
  double normal_angle(int j) const { return angle_from_normal(normal[static_cast<std::size_t>(j)]); }
  double length(int j) const;
};

// The profile through the vertices x[0..n], y[0..n] (n >= 1; x strictly increasing, finite;
// y[n] == y[0]); the period is x[n] - x[0]. Computes the normals, the extremes and the pyramid.
Polyline make_polyline(std::vector<double> x, std::vector<double> y);

// The procedural V-groove surface of sim/microsurface.h as one polyline: groove g spans
// [2g, 2g + 2], its rims at y = 0 and its apex at (2g + 1, -tan theta_m[g]), so its left facet's
// normal is at -theta_m[g] and its right facet's at +theta_m[g]. Period 2G, every x an integer.
// theta_m in [0, pi/2).
Polyline vgroove_polyline(const std::vector<double>& theta_m);

}  // namespace vgroove::sim
