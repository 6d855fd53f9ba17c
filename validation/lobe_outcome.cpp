#include "vgroove/validation/lobe_outcome.h"

#include <cmath>

namespace vgroove::validation {

bool take_comparison(LobeOutcome& o, const LobeComparison& c, double rays, double grooves, double sigmas,
                     double tolerance) {
  o.l1 = c.shape.l1, o.l1_expected = c.shape.expected, o.l1_threshold = c.shape.threshold;
  o.l1_k = c.joint.l1, o.l1_k_expected = c.joint.expected, o.l1_k_threshold = c.joint.threshold;
  o.albedo_threshold = albedo_threshold(o.albedo_model, rays, grooves, sigmas, tolerance);
  return std::abs(o.albedo_sim - o.albedo_model) <= o.albedo_threshold && c.shape.holds() && c.joint.holds();
}

nlohmann::json lobe_case_json(const LobeOutcome& o, bool flatland) {
  return {{"rays", o.rays},
          {"escaped", o.escaped},
          {"lost", o.lost},
          {"bounces", o.bounces},
          {"max_k_seen", o.max_k_seen},
          {"sim_wall_s", o.sim_wall_s},
          {"model_wall_s", o.model_wall_s},
          {"albedo_sim", o.albedo_sim},
          {"albedo_model", o.albedo_model},
          {"albedo_threshold", o.albedo_threshold},
          {"l1", o.l1},
          {"l1_expected", o.l1_expected},
          {"l1_threshold", o.l1_threshold},
          {"l1_by_k", o.l1_k},
          {"l1_by_k_expected", o.l1_k_expected},
          {"l1_by_k_threshold", o.l1_k_threshold},
          {"by_k_sim", o.by_k_sim},
          {"by_k_model", o.by_k_model},
          {"plane",
           {{"theta_deg", o.plane_theta_deg},
            {"unit", flatland ? "fraction of the flux per radian" : "fraction of the flux per steradian"},
            {"sim", o.plane_sim},
            {"model", o.plane_model},
            {"sim_by_k", o.plane_sim_k},
            {"model_by_k", o.plane_model_k}}},
          {"non_finite", o.non_finite},
          {"pass", o.pass}};
}

}  // namespace vgroove::validation
