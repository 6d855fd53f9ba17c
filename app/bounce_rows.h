// vgroove CLI: the table that `trace` and `analytic` share, one row per (facet hit first, k).
#pragma once

#include <nlohmann/json.hpp>

namespace vgroove::app {

// Prints the rows of validation::rows_json.
void print_rows(const nlohmann::json& rows);

}  // namespace vgroove::app
