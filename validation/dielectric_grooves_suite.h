// vgroove validation: the suite kind "dielectric_grooves" (data/suites/dielectric_grooves.json): per
// single symmetric groove, theta_i and eta, the kaleidoscopic dielectric model
// (analytic/kaleidoscope_dielectric.h) against exact split tracing, to rounding by breakpoint search,
// and the light the single-groove model cannot know (validation/dielectric_grooves_case.h), each
// case's error next to its rays and wall time. A case passes when the model's paths match to
// max_l1 (shares) and max_direction_error_rad plus the model's own rounding bound (its change under a
// 64-ulp change of theta_i), the traced unknown share equals the model's KD-4 share as closely, every
// ray conserves energy to max_l1, no zone search cell is uncertified and nothing is NaN. Cases lit from
// below ("from_below") hold analytic/kaleidoscope_dielectric_below.h per path signature. The periodic
// surface's unknown share (from above) is measured and reported, never judged.
// Tests: tests/analytic/kaleidoscope_dielectric_test.cpp (DielectricGroovesSuite.*),
// tests/analytic/kaleidoscope_dielectric_below_test.cpp (DielectricGroovesSuiteBelow.*),
// tests/cluster/shards_test.sh (shards merge to the one-process report).
// Derivation: docs/derivations/kaleidoscope_dielectric.md.
#pragma once

#include "vgroove/validation/dielectric_grooves_case.h"
#include "vgroove/validation/item_work.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

// The largest breakpoint grid per lit facet ("grid", --rays).
inline constexpr long kMaxDielectricGrid = 1'000'000;

struct DielectricGroovesSuite {
  std::string file, name, description;
  std::vector<double> theta_v, theta_i;  // radians
  // Cases lit from below ("from_below": its own theta_v_deg and theta_i_deg, the same eta), after
  // the cases lit from above.
  std::vector<double> below_theta_v, below_theta_i;
  std::vector<double> eta;        // with the inverses when the file asks for them
  std::vector<double> eta_given;  // as the file gave it
  bool inverses = false;
  DielectricCaseOptions options;
  double max_l1 = 1e-12, max_direction_error = 1e-12;
  std::size_t above_cases() const { return eta.size() * theta_v.size() * theta_i.size(); }
  std::size_t cases() const { return above_cases() + eta.size() * below_theta_v.size() * below_theta_i.size(); }
  // Order: from above, then from below; each by eta, theta_v, theta_i (innermost).
  DielectricGrooveCase case_at(std::size_t c) const;
};

struct DielectricGroovesOutcome {
  DielectricGrooveCase c;  // the suite's (not written)
  int k_left = 0, k_right = 0;
  double l1 = 0.0, direction_error = 0.0, conservation = 0.0, missed_bound = 0.0;
  double l1_bound = 0.0, direction_bound = 0.0;
  std::int64_t uncertified_cells = 0, zones = 0;
  double reflected = 0.0, transmitted = 0.0;
  double unknown = 0.0, unknown_model = 0.0, unknown_recross = 0.0;
  std::int64_t surface_rays = 0;
  double surface_unknown = 0.0, surface_recross = 0.0, surface_cut = 0.0;
  std::int64_t rays = 0, interactions = 0;
  bool non_finite = false, pass = false;
  double wall_s = 0.0;
};

template <class F>
void fields(DielectricGroovesOutcome& o, F&& f) {
  f("k_left", o.k_left), f("k_right", o.k_right);
  f("l1", o.l1), f("direction_error", o.direction_error), f("conservation", o.conservation);
  f("missed_bound", o.missed_bound), f("l1_bound", o.l1_bound), f("direction_bound", o.direction_bound),
      f("uncertified_cells", o.uncertified_cells), f("zones", o.zones);
  f("reflected", o.reflected), f("transmitted", o.transmitted);
  f("unknown", o.unknown), f("unknown_model", o.unknown_model), f("unknown_recross", o.unknown_recross);
  f("surface_rays", o.surface_rays), f("surface_unknown", o.surface_unknown);
  f("surface_recross", o.surface_recross), f("surface_cut", o.surface_cut);
  f("rays", o.rays), f("interactions", o.interactions);
  f("non_finite", o.non_finite), f("pass", o.pass), f("wall_s", o.wall_s);
}

struct DielectricGroovesRun {
  std::vector<DielectricGroovesOutcome> cases;
  int threads = 1;
  double wall_s = 0.0;
  bool pass = false;
};

// Strictly: support::UserError naming the file, the JSON path and the range.
DielectricGroovesSuite parse_dielectric_grooves_suite(const nlohmann::json& j, const std::string& file);
DielectricGroovesOutcome run_dielectric_grooves_case(const DielectricGroovesSuite& s, const DielectricGrooveCase& c);

using DielectricGroovesWork = ItemWork<DielectricGroovesOutcome>;
Job<DielectricGroovesWork> dielectric_grooves_job(const DielectricGroovesSuite& s, nlohmann::json descriptor);
DielectricGroovesRun dielectric_grooves_run_from(const DielectricGroovesSuite& s,
                                                 const std::vector<UnitResult<DielectricGroovesWork>>& results);
nlohmann::json dielectric_grooves_report_json(const DielectricGroovesSuite& s, const DielectricGroovesRun& run);
void print_dielectric_grooves_table(std::ostream& os, const DielectricGroovesSuite& s, const DielectricGroovesRun& run);

}  // namespace vgroove::validation
