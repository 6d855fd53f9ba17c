// vgroove validation: plots drawn from a report JSON, never recomputed.
//
// SVG written by hand: no plotting library to install, and the file diffs as text.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace vgroove::validation {

// The accuracy-versus-time report of `vgroove bench accuracy`: max and mean L1 against wall time,
// log-log, one line per ray placement, each point labelled with its rays per facet.
// Throws UserError naming `file` if the JSON is not such a report.
std::string accuracy_svg(const nlohmann::json& report, const std::string& file);

}  // namespace vgroove::validation
