#include "vgroove/support/json_text.h"

#include <cmath>

namespace vgroove::support {

namespace {

bool holds_non_finite(const nlohmann::json& j) {
  if (j.is_number_float()) return !std::isfinite(j.get<double>());
  if (j.is_structured())
    for (const auto& e : j)
      if (holds_non_finite(e)) return true;
  return false;
}

void replace_non_finite(nlohmann::json& j) {
  if (j.is_number_float()) {
    const double v = j.get<double>();
    if (!std::isfinite(v)) j = non_finite_text(v);
    return;
  }
  if (j.is_structured())
    for (auto& e : j) replace_non_finite(e);
}

}  // namespace

const char* non_finite_text(double v) {
  if (std::isnan(v)) return "nan";
  return v > 0 ? "inf" : "-inf";
}

nlohmann::json with_non_finite_as_text(const nlohmann::json& j) {
  nlohmann::json out = j;
  replace_non_finite(out);
  return out;
}

std::string json_text(const nlohmann::json& j, int indent) {
  if (!holds_non_finite(j)) return j.dump(indent);
  return with_non_finite_as_text(j).dump(indent);
}

}  // namespace vgroove::support
