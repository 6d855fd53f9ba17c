// vgroove sim: one explicit V-groove, two facets meeting at an apex.
//
// The apex is the origin; each facet is the segment from the apex to its rim, rim = length * edge.
// Both rims lie on the rim line y = rim_height (the macrosurface: Lee et al. 2018, Sec. 5 assumes
// all peaks lie on it). A symmetric groove of aperture theta_v has unit facets (the paper's
// bounding circle of radius 1).
#pragma once

#include "vgroove/common/side.h"
#include "vgroove/sim/geometry.h"

namespace vgroove::sim {

using vgroove::other;
using vgroove::Side;
using vgroove::side_name;

struct Facet {
  Vec2 edge;      // unit vector from the apex towards the rim
  double length;  // apex to rim
  Vec2 normal;    // unit normal pointing into the groove
  // Mirror reflection on the facet, I - 2 n n^T (symmetric): d' = (r_xx d.x + r_xy d.y,
  // r_xy d.x + r_yy d.y), shorter to evaluate than d - 2 (d.n) n.
  double r_xx, r_xy, r_yy;
  // cross(edge, other facet's edge): its sign says on which side the other facet lies.
  double turn_to_other;
  Vec2 rim() const { return length * edge; }
  Vec2 reflect(const Vec2& d) const { return Vec2(r_xx * d.x() + r_xy * d.y(), r_xy * d.x() + r_yy * d.y()); }
};

struct Groove {
  Facet facet[2];     // indexed by Side
  double rim_height;  // y of both rims
  double theta_v;     // aperture (radians)
  double rim_xs[2];   // facet[s].rim().x(), kept by finish_groove: the tracer's first test per ray
  const Facet& operator[](Side s) const { return facet[static_cast<int>(s)]; }
  // x of the rims on the rim line: the opening is [rim_x(left), rim_x(right)].
  double rim_x(Side s) const { return rim_xs[static_cast<int>(s)]; }
};

// Fills the derived members (reflection matrices, turn_to_other, rim_xs) from edges, normals and
// lengths.
void finish_groove(Groove& g);

// Symmetric groove, aperture theta_v in (0, pi]; facets of unit length.
Groove make_symmetric_groove(double theta_v);

// Nonsymmetric groove from the angles of the facets' inward normals (Lee et al. 2018, Fig. 5):
// theta_l in [-pi/2, 0] for the left facet (its normal leans right), theta_r in [0, pi/2] for the
// right one; aperture theta_v = pi + theta_l - theta_r > 0. The rims lie at one height, so the facets
// differ in length; the longer has unit length.
Groove make_nonsymmetric_groove(double theta_l, double theta_r);

}  // namespace vgroove::sim
