#include "vgroove/validation/cost_curve.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/groove.h"
#include "vgroove/sim/tracer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace vgroove::validation {

namespace {
using support::Clock;
double ns_since(Clock::time_point t0) { return std::chrono::duration<double, std::nano>(Clock::now() - t0).count(); }
}  // namespace

std::vector<CostPoint> cost_vs_theta_v(const std::vector<double>& theta_v, double theta_i, long rays) {
  std::vector<CostPoint> out;
  for (double v : theta_v) {
    CostPoint p;
    p.theta_v = v;
    const sim::Groove g = sim::make_symmetric_groove(v);
    const sim::Vec2 dir = sim::beam_direction(theta_i);
    const sim::Interval open = sim::opening(g);
    std::int64_t bounces = 0;
    double sink = 0.0;
    // The tracer as the validation runs it (validation/groove_case.cpp): one BeamTracer per beam,
    // its construction timed too, and the stratified rays through sim::trace_beam.
    sim::Rng unused(0, 0, 0);
    auto t0 = Clock::now();
    const sim::BeamTracer beam(g, dir);
    sim::trace_beam(beam, sim::Sampling::stratified, open, rays, unused, [&](long, const sim::TraceResult& t) {
      bounces += t.bounces;
      sink += t.exit_dir.x();
    });
    p.tracer_ns_per_ray = ns_since(t0) / static_cast<double>(rays);
    p.bounces_per_ray = static_cast<double>(bounces) / static_cast<double>(rays);
    // The model at as many incident angles (a spread of 1e-3 rad, so nothing is hoisted out of
    // the loop), both facets.
    const long evals = rays;
    t0 = Clock::now();
    for (long r = 0; r < evals; ++r) {
      const double ti = theta_i + 1e-3 * static_cast<double>(r) / static_cast<double>(evals);
      for (analytic::FacetSide side : {analytic::FacetSide::left, analytic::FacetSide::right}) {
        const analytic::FacetPrediction f = analytic::G_kaleidoscopic(ti, v, side);
        sink +=
            f.fewer.G + f.more.G + analytic::exit_angle(ti, v, f.k, side) + analytic::exit_angle(ti, v, f.k - 1, side);
      }
    }
    p.model_ns_per_eval = ns_since(t0) / static_cast<double>(evals);
    // Keep the work observable.
    if (std::isnan(sink)) p.model_ns_per_eval = -1.0;
    out.push_back(p);
  }
  return out;
}

}  // namespace vgroove::validation
