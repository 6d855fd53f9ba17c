// vgroove common: degrees at the edges, radians inside. The one conversion.
#pragma once

#include <numbers>

namespace vgroove {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;

constexpr double deg_to_rad(double deg) { return deg * kRadPerDeg; }
constexpr double rad_to_deg(double rad) { return rad * kDegPerRad; }

}  // namespace vgroove
