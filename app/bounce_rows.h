// vgroove CLI: the table that `trace` and `analytic` share, one row per (facet hit first, k).
#pragma once

#include <nlohmann/json.hpp>

namespace vgroove::app {

// One row of the trace/analytic JSON: the same shape from both, so the two can be diffed.
nlohmann::json bounce_row(const char* facet, int k, double fraction, double theta_o);
void print_rows(const nlohmann::json& rows);

}  // namespace vgroove::app
