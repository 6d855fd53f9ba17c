#include "sim/groove.h"

#include <cassert>

namespace vgroove::sim {

Groove make_symmetric_groove(double theta_v) {
  assert(theta_v > 0.0 && theta_v <= M_PI);
  const double half = 0.5 * theta_v;
  Groove g;
  // The left edge is at angle +half from n, the right edge at -half (counter-clockwise positive).
  g.facet[0].edge = direction_at(half);
  g.facet[1].edge = direction_at(-half);
  for (Facet& f : g.facet) f.length = 1.0;
  // Inward normals: the left facet faces right-up, the right facet faces left-up.
  g.facet[0].normal = Vec2(std::cos(half), std::sin(half));
  g.facet[1].normal = Vec2(-std::cos(half), std::sin(half));
  g.rim_height = std::cos(half);
  g.theta_v = theta_v;
  return g;
}

}  // namespace vgroove::sim
