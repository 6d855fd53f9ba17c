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
// "ndf": a non-empty list of "ggx", "beckmann", "phong", and where student_t is true "student_t",
// which then takes "gamma", a non-empty list of tails in (kMinStudentTGamma, kMaxStudentTGamma]:
// each "student_t" stands for one NDF per gamma, in the list's order.
std::vector<analytic::NdfKind> read_ndfs(support::JsonObject& o, bool student_t = false);
// A suite's "ndf" list as the file gave it (each name once per entry, "student_t" once) and its
// "gamma" list beside it when Student-T is among them.
void put_ndfs(nlohmann::json& inputs, const std::vector<analytic::NdfKind>& ndfs);
// A case's Student-T tail, "gamma", beside its "ndf" (nothing for the other NDFs).
void put_gamma(nlohmann::json& c, analytic::NdfKind ndf);
// An NDF in a printed table: its name, Student-T as "t" and its gamma ("t1.6").
std::string ndf_label(analytic::NdfKind ndf);

}  // namespace vgroove::validation
