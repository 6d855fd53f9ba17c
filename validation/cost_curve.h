// vgroove validation: what the tracer and the analytic model cost as the groove narrows.
//
// The tracer's cost per ray grows with the bounce count, about pi / theta_v (Lee et al. 2018,
// Eq. 4); the kaleidoscopic model's does not: Eq. 4-6 are a handful of trigonometric functions
// whatever k is. `vgroove bench accuracy` prints both over theta_v (issue: "show both curves").
// These are wall-clock measurements of one thread, reported, never asserted.
#pragma once

#include <vector>

namespace vgroove::validation {

struct CostPoint {
  double theta_v = 0.0;          // radians
  double bounces_per_ray = 0.0;  // traced, averaged over the opening
  double tracer_ns_per_ray = 0.0;
  double model_ns_per_eval = 0.0;  // Eq. 4-6 for both facets: k, theta_o and G of each
};

// Symmetric grooves of the given apertures lit at theta_i, `rays` stratified across the opening,
// traced as the validation traces them (sim::BeamTracer's batch trace).
std::vector<CostPoint> cost_vs_theta_v(const std::vector<double>& theta_v, double theta_i, long rays);

}  // namespace vgroove::validation
