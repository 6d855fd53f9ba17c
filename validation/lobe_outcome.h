// vgroove validation: what a traced lobe held against a model's gives, for every kind that bins
// exit directions by bounce count ("brdf", "nonsymmetric_brdf"): the trace's counts, the
// comparison of lobe_comparison.h, the rows per k and the plane of incidence for plots
// (plane_cut.h), and their JSON. A kind's outcome derives from it and adds its own figures.
// Tested through the kinds' suites (tests/validation/microsurface_suite_test.cpp,
// nonsymmetric_suite_test.cpp) and their reports (scripts/compare_reports.sh).
#pragma once

#include "vgroove/validation/lobe_comparison.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <vector>

namespace vgroove::validation {

struct LobeOutcome {
  std::int64_t rays = 0, escaped = 0, lost = 0, bounces = 0;
  int max_k_seen = 0;
  double sim_wall_s = 0.0, model_wall_s = 0.0;
  double albedo_sim = 0.0, albedo_model = 0.0, albedo_threshold = 0.0;  // albedo_sim: escaped / rays
  double l1 = 0.0, l1_expected = 0.0, l1_threshold = 0.0;               // normalized lobes, all k
  double l1_k = 0.0, l1_k_expected = 0.0, l1_k_threshold = 0.0;         // joint (k, bin) fractions of the flux
  std::vector<double> by_k_sim, by_k_model;                             // rows k = 0..max_k + 1
  // The lobe on the plane of incidence (plane_cut.h) as densities: per radian (flatland) or per
  // steradian (3D); all k, and per k = 1.. the kind's plot rows.
  std::vector<double> plane_theta_deg, plane_sim, plane_model;
  std::vector<std::vector<double>> plane_sim_k, plane_model_k;
  bool non_finite = false;
  bool pass = false;
};

// The counts of a traced tally (rays, escaped, lost(), bounces, max_k_seen) and albedo_sim.
template <class Tally>
void take_counts(LobeOutcome& o, const Tally& t) {
  o.rays = t.rays, o.escaped = t.escaped, o.lost = t.lost(), o.bounces = t.bounces;
  o.max_k_seen = t.max_k_seen;
  o.albedo_sim = static_cast<double>(t.escaped) / static_cast<double>(t.rays);
}

// The comparison's figures into o (l1*, l1_k*), and albedo_threshold for o.albedo_model at N rays
// over G grooves; returns whether the albedo and both L1 tests hold.
bool take_comparison(LobeOutcome& o, const LobeComparison& c, double rays, double grooves, double sigmas,
                     double tolerance);

// The shared keys of a case in the report: counts, times, albedos, L1 tests, rows per k and
// "plane" (its "unit" by `flatland`), "non_finite" and "pass".
nlohmann::json lobe_case_json(const LobeOutcome& o, bool flatland);

// The members for a shard part (outcome_fields.h).
template <class F>
void lobe_fields(LobeOutcome& o, F&& f) {
  f("rays", o.rays), f("escaped", o.escaped), f("lost", o.lost), f("bounces", o.bounces);
  f("max_k_seen", o.max_k_seen), f("sim_wall_s", o.sim_wall_s), f("model_wall_s", o.model_wall_s);
  f("albedo_sim", o.albedo_sim), f("albedo_model", o.albedo_model), f("albedo_threshold", o.albedo_threshold);
  f("l1", o.l1), f("l1_expected", o.l1_expected), f("l1_threshold", o.l1_threshold);
  f("l1_k", o.l1_k), f("l1_k_expected", o.l1_k_expected), f("l1_k_threshold", o.l1_k_threshold);
  f("by_k_sim", o.by_k_sim), f("by_k_model", o.by_k_model);
  f("plane_theta_deg", o.plane_theta_deg), f("plane_sim", o.plane_sim), f("plane_model", o.plane_model);
  f("plane_sim_k", o.plane_sim_k), f("plane_model_k", o.plane_model_k);
  f("non_finite", o.non_finite), f("pass", o.pass);
}

}  // namespace vgroove::validation
