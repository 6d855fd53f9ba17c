// vgroove support: the JSON text every command writes (reports, shard parts, `--json` on stdout).
//
// JSON has no NaN or infinity. A double that is not finite is written as the string "nan", "inf"
// or "-inf" (docs/conventions.md, "Numbers that are not finite"), never as null: the string says
// which it was (an infinity is a documented limit, e.g. the k >= 2 terms of the 3D BRDF at the
// mirror direction; NaN would be a defect), and it reads back exactly (validation/partial_report.h,
// exact_double; Python's float("inf")). Finite doubles are written as the shortest text that
// reads back as the same double. The Python module's reports hold the same strings.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace vgroove::support {

// "nan", "inf" or "-inf" for a double that is not finite.
const char* non_finite_text(double v);
// j with every non-finite double replaced by its string (the tree is copied only when it holds one).
nlohmann::json with_non_finite_as_text(const nlohmann::json& j);
// The text of j (nlohmann::json's dump with `indent`) with that convention.
std::string json_text(const nlohmann::json& j, int indent = -1);

}  // namespace vgroove::support
