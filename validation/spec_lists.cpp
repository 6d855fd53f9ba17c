#include "vgroove/validation/spec_lists.h"

#include "vgroove/support/format.h"

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

std::vector<analytic::NdfKind> read_ndfs(support::JsonObject& o, bool student_t) {
  std::vector<std::string> allowed{"ggx", "beckmann", "phong"};
  if (student_t) allowed.push_back("student_t");
  const std::vector<std::string> names = read_names(o, "ndf", allowed);
  std::vector<double> gammas{0.0};
  if (std::find(names.begin(), names.end(), "student_t") != names.end())
    gammas = read_numbers(o, "gamma", kMinStudentTGamma, false, kMaxStudentTGamma, true);
  std::vector<analytic::NdfKind> out;
  for (const auto& s : names)
    for (double g : gammas) {
      out.push_back(*ndf_from_name(s, g));
      if (s != "student_t") break;
    }
  return out;
}

void put_ndfs(nlohmann::json& inputs, const std::vector<analytic::NdfKind>& ndfs) {
  nlohmann::json names = nlohmann::json::array(), gammas = nlohmann::json::array();
  bool named = false;
  for (analytic::NdfKind n : ndfs) {
    if (n != analytic::NdfKind::student_t) {
      names.push_back(analytic::ndf_name(n));
      continue;
    }
    if (!named) names.push_back(analytic::ndf_name(n));
    named = true;
    if (std::find(gammas.begin(), gammas.end(), n.gamma) == gammas.end()) gammas.push_back(n.gamma);
  }
  inputs["ndf"] = std::move(names);
  if (named) inputs["gamma"] = std::move(gammas);
}

void put_gamma(nlohmann::json& c, analytic::NdfKind ndf) {
  if (ndf == analytic::NdfKind::student_t) c["gamma"] = ndf.gamma;
}

std::string ndf_label(analytic::NdfKind ndf) {
  if (ndf != analytic::NdfKind::student_t) return analytic::ndf_name(ndf);
  return support::format("t%g", ndf.gamma);
}

}  // namespace vgroove::validation
