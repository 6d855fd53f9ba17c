// vgroove sim: 2D geometry and the one sign convention everything else uses.
//
//            n (+y)                 Angles are measured from the macrosurface normal n,
//            ^                      counter-clockwise positive (Lee et al. 2018, Sec. 4.1:
//   i  \     |     / o              "a clockwise angle is negative while counterclockwise
//       \ th_i    /                 is positive"). A direction at angle theta is
//        \   |   /                  (-sin theta, cos theta).
//  ---a_L-\--+--/-a_R---  rim line  The incident direction i points towards the light; the ray
//          \ | /                    travels along -i. The exit direction o points away from
//           \|/                     the surface. A flat mirror gives theta_o = -theta_i.
//            apex (origin)
//
// In the picture theta_i > 0: the light comes from the upper left. The left facet runs from
// the apex to its rim a_L (x < 0), the right facet to a_R (x > 0).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace vgroove::sim {

using Vec2 = Eigen::Vector2d;

// z-component of the 3D cross product: positive when b is counter-clockwise from a.
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Unit direction at angle theta from n, counter-clockwise positive.
inline Vec2 direction_at(double theta) { return Vec2(-std::sin(theta), std::cos(theta)); }

// Angle of a direction from n, counter-clockwise positive, in (-pi, pi].
inline double angle_from_normal(const Vec2& v) { return std::atan2(-v.x(), v.y()); }

// Signed angle from a to b via atan2(cross, dot): counter-clockwise positive.
inline double angle_between(const Vec2& a, const Vec2& b) { return std::atan2(cross(a, b), a.dot(b)); }

inline Vec2 rotate_ccw_90(const Vec2& v) { return Vec2(-v.y(), v.x()); }

// Mirror reflection of direction d on a line with unit normal m.
inline Vec2 reflect(const Vec2& d, const Vec2& m) { return d - 2.0 * d.dot(m) * m; }

}  // namespace vgroove::sim
