// vgroove sim: what happened to the rays of a beam, per facet hit first and bounce count k.
//
// Each (facet, k) bin keeps its ray count, the exit direction of its first ray, and the largest
// angle between any later ray's exit direction and that one (all rays of a bin should leave in
// one direction), so no per-ray trigonometry is needed. Tallies merge exactly: counts add, and a
// merged bin keeps the first tally's reference direction.
#pragma once

#include "vgroove/sim/ray_fates.h"
#include "vgroove/sim/tracer.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace vgroove::sim {

struct BounceBin {
  std::int64_t count = 0;
  Vec2 exit_dir = Vec2::Zero();  // of the first ray in the bin
  // Largest sine of the angle between any ray's exit direction and exit_dir (a bound after
  // merging: sin(a + b) <= sin a + sin b), and whether any ray left at more than 90 deg from it.
  double spread_sin = 0.0;
  bool reversed = false;
  double theta_o() const { return angle_from_normal(exit_dir); }
  // Largest angle between two exit directions of the bin, bounded from above (radians).
  double spread() const { return reversed ? std::numbers::pi : std::asin(std::min(1.0, spread_sin)); }
};

// The fates of the rays (sim::RayFates: every ray in one bucket; a single groove's escaped rays
// all count as upward, so not_upward stays 0), and the escaped ones by (facet hit first, k).
struct Tally : RayFates {
  std::vector<BounceBin> bins[2];  // [first facet][k], k = bounce count

  void add(const TraceResult& r) {  // inline: called once per ray in the hot loop
    if (!count(r.how, r.bounces, true)) return;
    auto& v = bins[static_cast<int>(r.first)];
    if (static_cast<int>(v.size()) <= r.bounces) {
      v.resize(r.bounces + 1);
    } else if (BounceBin& b = v[r.bounces]; b.count > 0) {
      // The common case: a bin that has rays already.
      b.spread_sin = std::max(b.spread_sin, std::abs(cross(b.exit_dir, r.exit_dir)));
      b.reversed = b.reversed || b.exit_dir.dot(r.exit_dir) <= 0.0;
      ++b.count;
      return;
    }
    add_first(v[r.bounces], r.exit_dir);
  }
  void merge(const Tally& other);
  using RayFates::count;
  std::int64_t count(Side first, int k) const;
  int max_bounces() const;  // largest k with a ray, 0 if none

 private:
  static void add_first(BounceBin& b, const Vec2& dir);
};

}  // namespace vgroove::sim
