#include "vgroove/sim/groove.h"

#include <algorithm>
#include <cassert>
#include <numbers>

namespace vgroove::sim {

void finish_groove(Groove& g) {
  for (Facet& f : g.facet) {
    const Vec2& n = f.normal;
    f.r_xx = 1.0 - 2.0 * n.x() * n.x();
    f.r_xy = -2.0 * n.x() * n.y();
    f.r_yy = 1.0 - 2.0 * n.y() * n.y();
  }
  g.facet[0].turn_to_other = cross(g.facet[0].edge, g.facet[1].edge);
  g.facet[1].turn_to_other = cross(g.facet[1].edge, g.facet[0].edge);
  for (int i = 0; i < 2; ++i) g.rim_xs[i] = g.facet[i].rim().x();
}

Groove make_symmetric_groove(double theta_v) {
  assert(theta_v > 0.0 && theta_v <= std::numbers::pi);
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
  finish_groove(g);
  return g;
}

Groove make_nonsymmetric_groove(double theta_l, double theta_r) {
  assert(theta_l <= 0.0 && theta_l >= -0.5 * std::numbers::pi && theta_r >= 0.0 && theta_r <= 0.5 * std::numbers::pi);
  assert(std::numbers::pi + theta_l - theta_r > 0.0);
  Groove g;
  // Edges perpendicular to the normals, pointing up from the apex.
  g.facet[0].edge = direction_at(theta_l + 0.5 * std::numbers::pi);
  g.facet[1].edge = direction_at(theta_r - 0.5 * std::numbers::pi);
  g.facet[0].normal = direction_at(theta_l);
  g.facet[1].normal = direction_at(theta_r);
  // Equal rim heights: length * edge.y equal for both facets.
  // A facet at 0 deg is flat (edge.y is 0 up to rounding): the other facet then has (almost) no
  // length, and both flat is the flat mirror, with unit facets.
  const double h_l = std::max(0.0, g.facet[0].edge.y()), h_r = std::max(0.0, g.facet[1].edge.y());
  const double h_max = std::max(h_l, h_r);
  g.facet[0].length = h_max > 0.0 ? h_r / h_max : 1.0;
  g.facet[1].length = h_max > 0.0 ? h_l / h_max : 1.0;
  g.rim_height = g.facet[0].length * h_l;
  g.theta_v = std::numbers::pi + theta_l - theta_r;
  finish_groove(g);
  return g;
}

}  // namespace vgroove::sim
