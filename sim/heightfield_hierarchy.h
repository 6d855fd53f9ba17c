// vgroove sim: the min-max mipmap over a periodic heightfield (sim/heightfield.h), the height
// bound the 3D tracer (sim/heightfield_tracer.h) descends to skip cells a ray passes above.
//
// Level 0 holds, per cell (i, j), the least and the greatest of its four vertex heights (the
// cell's two triangles lie between them: a triangle's heights are convex combinations of its
// vertices'). Level k holds, per node (i, j) covering the 2^k x 2^k cells [i 2^k, (i+1) 2^k) x
// [j 2^k, (j+1) 2^k), the least min and the greatest max of its four children; the last level is
// one node over the whole period. The bounds are exact copies of heights (min and max round
// nothing).
//
// Memory: min and max (16 bytes) per node, n^2 (1 + 1/4 + 1/16 + ...) nodes: 21.3 bytes per cell
// (sim/heightfield.h gives the total with the heights, heightfield_bytes).
#pragma once

#include "vgroove/sim/heightfield.h"

#include <cstddef>
#include <vector>

namespace vgroove::sim {

struct HeightBounds {
  double lo, hi;
};

struct HeightfieldHierarchy {
  int n = 0;
  int levels = 0;                                // log2(n) + 1
  std::vector<std::vector<HeightBounds>> level;  // [k][j * (n >> k) + i]

  const HeightBounds& node(int k, int i, int j) const {
    return level[static_cast<std::size_t>(k)][static_cast<std::size_t>(j) * (n >> k) + i];
  }
  const HeightBounds& root() const { return level.back().front(); }
};

HeightfieldHierarchy make_heightfield_hierarchy(const Heightfield& f);

}  // namespace vgroove::sim
