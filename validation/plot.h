// vgroove validation: plots drawn from a report JSON, never recomputed.
//
// SVG written by hand: no plotting library to install, and the file diffs as text.
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace vgroove::validation {

// The accuracy-versus-time report of `vgroove bench accuracy`: max and mean L1 against wall time,
// log-log, one line per ray placement, each point labelled with its rays per facet.
// Throws UserError naming `file` if the JSON is not such a report.
std::string accuracy_svg(const nlohmann::json& report, const std::string& file);

// The tracer's cost per ray and the model's per evaluation against theta_v, log-log, from the
// `cost_vs_theta_v` of a `bench accuracy` report; empty when the report has none.
std::string cost_svg(const nlohmann::json& report);

// The Fig. 11 grid of a "brdf" suite report (`vgroove validate data/suites/fig11.json --out R`):
// one SVG per (NDF, dimension), one panel per (theta_i row, alpha column), each with the traced
// lobe on the plane of incidence as bars, the analytic BRDF integrated over the same bins as a
// line (total, and per k = 1..4 dashed) and Cook-Torrance (V-cavity G) dotted.
// Returns (name suffix such as "ggx-flatland", svg) pairs; UserError naming `file` otherwise.
std::vector<std::pair<std::string, std::string>> brdf_grid_svgs(const nlohmann::json& report, const std::string& file);

// Whether the report is a "brdf" suite report (else an accuracy report is assumed).
bool is_brdf_report(const nlohmann::json& report);

}  // namespace vgroove::validation
