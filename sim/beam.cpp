#include "vgroove/sim/beam.h"

#include "vgroove/common/simd.h"

namespace vgroove::sim {

const char* sampling_name(Sampling s) {
  switch (s) {
    case Sampling::stratified:
      return "stratified";
    case Sampling::random:
      return "random";
    case Sampling::breakpoints:
      return "breakpoints";
  }
  return "?";
}

Interval opening(const Groove& g) { return {g.rim_x(Side::left), g.rim_x(Side::right)}; }

namespace {
// x where the line through p with direction -i (i at theta_i) crosses the rim line.
double rim_line_x(const Groove& g, double theta_i, const Vec2& p) {
  // Going back towards the light from p: p + u i, i = (-sin, cos); reach y = rim_height.
  const double u = (g.rim_height - p.y()) / std::cos(theta_i);
  return p.x() - u * std::sin(theta_i);
}
}  // namespace

// Four divisions per instruction in the AVX2 copy (common/simd.h).
VGROOVE_TARGET_CLONES
void sample_positions(Sampling sampling, const Interval& iv, long j0, int count, long n, Rng& rng,
                      double* __restrict out) {
  const double lo = iv.lo, width = iv.hi - iv.lo;
  if (sampling != Sampling::random) {
    // static_cast<double>(j) + 0.5 as sample_position forms it: j0 + i is exact in a double
    // (j < 2^53), and the loop's counter is that double, so the lanes need no integer conversion.
    const double nd = static_cast<double>(n), jd0 = static_cast<double>(j0);
    for (int i = 0; i < count; ++i) out[i] = lo + ((jd0 + static_cast<double>(i)) + 0.5) / nd * width;
  } else {
    for (int i = 0; i < count; ++i) out[i] = lo + rng.uniform() * width;
  }
}

Interval aimed_at(const Groove& g, double theta_i, Side side) {
  const double x_apex = rim_line_x(g, theta_i, Vec2::Zero());
  const double x_rim = g.rim_x(side);
  return side == Side::left ? Interval{x_rim, x_apex} : Interval{x_apex, x_rim};
}

}  // namespace vgroove::sim
