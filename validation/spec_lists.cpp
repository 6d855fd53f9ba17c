#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <cmath>

namespace vgroove::validation {

std::vector<std::string> read_names(support::JsonObject& o, const std::string& key,
                                    const std::vector<std::string>& allowed) {
  const nlohmann::json& v = o.raw(key);
  if (!v.is_array() || v.empty()) o.fail(key, "= " + support::value_text(v) + " must be a non-empty list");
  std::vector<std::string> out;
  for (std::size_t n = 0; n < v.size(); ++n) {
    const std::string where = o.path(key) + "/" + std::to_string(n);
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
    if (!v[n].is_string() || std::find(allowed.begin(), allowed.end(), v[n].get<std::string>()) == allowed.end())
      throw support::UserError(o.file() + ": " + where + " = " + support::value_text(v[n]) + " is not one of " + list);
    out.push_back(v[n].get<std::string>());
  }
  return out;
}

std::vector<double> read_numbers(support::JsonObject& o, const std::string& key, double lo, bool lo_closed, double hi,
                                 bool hi_closed) {
  const nlohmann::json& v = o.raw(key);
  if (!v.is_array() || v.empty()) o.fail(key, "= " + support::value_text(v) + " must be a non-empty list of numbers");
  std::vector<double> out;
  for (std::size_t n = 0; n < v.size(); ++n) {
    const std::string where = o.path(key) + "/" + std::to_string(n);
    if (!v[n].is_number())
      throw support::UserError(o.file() + ": " + where + " = " + support::value_text(v[n]) + " must be a number");
    const double x = v[n].get<double>();
    const bool ok = std::isfinite(x) && (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
    if (!ok)
      throw support::UserError(o.file() + ": " + where + " = " + support::number_text(x) + " is out of range " +
                               support::interval_text(lo, lo_closed, hi, hi_closed));
    out.push_back(x);
  }
  return out;
}

std::vector<analytic::NdfKind> read_ndfs(support::JsonObject& o) {
  std::vector<analytic::NdfKind> out;
  for (const auto& s : read_names(o, "ndf", {"ggx", "beckmann", "phong"})) out.push_back(*ndf_from_name(s));
  return out;
}

}  // namespace vgroove::validation
