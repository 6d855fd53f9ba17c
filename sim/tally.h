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

// The bins of one first facet, by bounce count k. Only the k that hold rays are stored, in
// ascending order: memory grows with the bounce counts the rays make (a beam in one groove makes
// two to four), not with the largest (10^8 in the narrowest grooves).
class BounceBins {
 public:
  struct Entry {
    int k;
    BounceBin bin;
  };
  // The bin of k; an empty one (count 0) when no ray made k bounces.
  const BounceBin& operator[](int k) const {
    const Entry* e = find(k);
    return e ? e->bin : empty_;
  }
  // The bin of k, added (empty) if absent. Inline only the common case, the k of the previous
  // ray (a beam's rays come in runs of one k), so that Tally::add stays small enough to inline.
  BounceBin& bin(int k) {
    if (last_ < e_.size() && e_[last_].k == k) [[likely]]
      return e_[last_].bin;
    return find_or_insert(k);
  }
  std::vector<Entry>::const_iterator begin() const { return e_.begin(); }
  std::vector<Entry>::const_iterator end() const { return e_.end(); }
  bool empty() const { return e_.empty(); }
  int max_k() const { return e_.empty() ? 0 : e_.back().k; }  // largest k with a ray, 0 if none

 private:
  BounceBin& find_or_insert(int k);
  const Entry* find(int k) const {
    const auto it = std::lower_bound(e_.begin(), e_.end(), k, [](const Entry& e, int key) { return e.k < key; });
    return it != e_.end() && it->k == k ? &*it : nullptr;
  }
  std::vector<Entry> e_;
  std::size_t last_ = 0;
  static inline const BounceBin empty_{};
};

// The fates of the rays (sim::RayFates: every ray in one bucket; a single groove's escaped rays
// all count as upward, so not_upward stays 0), and the escaped ones by (facet hit first, k).
struct Tally : RayFates {
  BounceBins bins[2];  // [first facet], then by k = bounce count

  void add(const TraceResult& r) {  // inline: called once per ray in the hot loop
    if (!count(r.how, r.bounces, true)) return;
    BounceBin& b = bins[static_cast<int>(r.first)].bin(r.bounces);
    if (b.count > 0) {
      // The common case: a bin that has rays already.
      b.spread_sin = std::max(b.spread_sin, std::abs(cross(b.exit_dir, r.exit_dir)));
      b.reversed = b.reversed || b.exit_dir.dot(r.exit_dir) <= 0.0;
      ++b.count;
      return;
    }
    add_first(b, r.exit_dir);
  }
  void merge(const Tally& other);
  using RayFates::count;
  std::int64_t count(Side first, int k) const;
  int max_bounces() const;  // largest k with a ray, 0 if none

 private:
  static void add_first(BounceBin& b, const Vec2& dir);
};

}  // namespace vgroove::sim
