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

void Tally::merge(const Tally& o) {
  merge_fates(o);
  for (int f = 0; f < 2; ++f) {
    if (bins[f].size() < o.bins[f].size()) bins[f].resize(o.bins[f].size());
    for (std::size_t k = 0; k < o.bins[f].size(); ++k)
      if (const BounceBin& b = o.bins[f][k]; b.count > 0)
        add_to_bin(bins[f][k], b.count, b.exit_dir, b.spread_sin, b.reversed);
  }
}

std::int64_t Tally::count(Side first, int k) const {
  const auto& v = bins[static_cast<int>(first)];
  return k >= 0 && k < static_cast<int>(v.size()) ? v[k].count : 0;
}

int Tally::max_bounces() const {
  int m = 0;
  for (const auto& v : bins)
    for (int k = static_cast<int>(v.size()) - 1; k > m; --k)
      if (v[k].count > 0) {
        m = k;
        break;
      }
  return m;
}

}  // namespace vgroove::sim
