// vgroove validation: the lists that suite specs share (names from a set, numbers in a range,
// NDF names), read strictly: each message names the file, the JSON path and what was allowed.
#pragma once

#include "vgroove/analytic/ndf.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/ranges.h"

#include <string>
#include <vector>

namespace vgroove::validation {

// A non-empty list of strings, each one of `allowed`.
std::vector<std::string> read_names(support::JsonObject& o, const std::string& key,
                                    const std::vector<std::string>& allowed);
// A non-empty list of numbers in the range.
std::vector<double> read_numbers(support::JsonObject& o, const std::string& key, double lo, bool lo_closed, double hi,
                                 bool hi_closed);
// "ndf": a non-empty list of "ggx", "beckmann", "phong".
std::vector<analytic::NdfKind> read_ndfs(support::JsonObject& o);

}  // namespace vgroove::validation
