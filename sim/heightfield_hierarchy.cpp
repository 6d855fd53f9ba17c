#include "vgroove/sim/heightfield_hierarchy.h"

#include <algorithm>
#include <bit>

namespace vgroove::sim {

HeightfieldHierarchy make_heightfield_hierarchy(const Heightfield& f) {
  HeightfieldHierarchy m;
  m.n = f.n;
  m.levels = std::countr_zero(static_cast<unsigned>(f.n)) + 1;
  m.level.resize(static_cast<std::size_t>(m.levels));
  const int n = f.n;
  auto& l0 = m.level[0];
  l0.resize(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double a = f.height(i, j), b = f.height(i + 1, j), c = f.height(i, j + 1), d = f.height(i + 1, j + 1);
      l0[static_cast<std::size_t>(j) * n + i] = {std::min({a, b, c, d}), std::max({a, b, c, d})};
    }
  for (int k = 1; k < m.levels; ++k) {
    const int s = n >> k;
    auto& lk = m.level[static_cast<std::size_t>(k)];
    lk.resize(static_cast<std::size_t>(s) * s);
    for (int j = 0; j < s; ++j)
      for (int i = 0; i < s; ++i) {
        const HeightBounds& a = m.node(k - 1, 2 * i, 2 * j);
        const HeightBounds& b = m.node(k - 1, 2 * i + 1, 2 * j);
        const HeightBounds& c = m.node(k - 1, 2 * i, 2 * j + 1);
        const HeightBounds& d = m.node(k - 1, 2 * i + 1, 2 * j + 1);
        lk[static_cast<std::size_t>(j) * s + i] = {std::min({a.lo, b.lo, c.lo, d.lo}),
                                                   std::max({a.hi, b.hi, c.hi, d.hi})};
      }
  }
  return m;
}

}  // namespace vgroove::sim
