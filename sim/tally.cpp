#include "vgroove/sim/tally.h"

namespace vgroove::sim {

namespace {
// Adds n rays that left along dir, within (spread_sin, reversed) of it.
void add_to_bin(BounceBin& b, std::int64_t n, const Vec2& dir, double spread_sin, bool reversed) {
  if (b.count == 0) {
    b.exit_dir = dir;
    b.spread_sin = spread_sin;
    b.reversed = reversed;
  } else {
    b.spread_sin = std::max(b.spread_sin, std::abs(cross(b.exit_dir, dir)) + spread_sin);
    b.reversed = b.reversed || reversed || b.exit_dir.dot(dir) <= 0.0;
  }
  b.count += n;
}
}  // namespace

void Tally::add_first(BounceBin& b, const Vec2& dir) { add_to_bin(b, 1, dir, 0.0, false); }

BounceBin& BounceBins::find_or_insert(int k) {
  const auto it = std::lower_bound(e_.begin(), e_.end(), k, [](const Entry& e, int key) { return e.k < key; });
  last_ = static_cast<std::size_t>(it - e_.begin());
  if (it == e_.end() || it->k != k) e_.insert(it, Entry{k, BounceBin{}});
  return e_[last_].bin;
}

void Tally::merge(const Tally& o) {
  merge_fates(o);
  for (int f = 0; f < 2; ++f)
    for (const BounceBins::Entry& e : o.bins[f])
      if (e.bin.count > 0) add_to_bin(bins[f].bin(e.k), e.bin.count, e.bin.exit_dir, e.bin.spread_sin, e.bin.reversed);
}

std::int64_t Tally::count(Side first, int k) const { return bins[static_cast<int>(first)][k].count; }

int Tally::max_bounces() const { return std::max(bins[0].max_k(), bins[1].max_k()); }

}  // namespace vgroove::sim
