#include "sim/beam.h"

namespace vgroove::sim {

const char* sampling_name(Sampling s) { return s == Sampling::stratified ? "stratified" : "random"; }

Interval opening(const Groove& g) { return {g.rim_x(Side::left), g.rim_x(Side::right)}; }

namespace {
// x where the line through p with direction -i (i at theta_i) crosses the rim line.
double rim_line_x(const Groove& g, double theta_i, const Vec2& p) {
  // Going back towards the light from p: p + u i, i = (-sin, cos); reach y = rim_height.
  const double u = (g.rim_height - p.y()) / std::cos(theta_i);
  return p.x() - u * std::sin(theta_i);
}
}  // namespace

Interval aimed_at(const Groove& g, double theta_i, Side side) {
  const double x_apex = rim_line_x(g, theta_i, Vec2::Zero());
  const double x_rim = g.rim_x(side);
  return side == Side::left ? Interval{x_rim, x_apex} : Interval{x_apex, x_rim};
}

}  // namespace vgroove::sim
