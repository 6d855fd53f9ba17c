#include "vgroove/support/json_reader.h"

#include <cmath>
#include <fstream>

namespace vgroove::support {

JsonObject::JsonObject(const nlohmann::json& j, std::string file, std::string pointer)
    : j_(j), file_(std::move(file)), pointer_(std::move(pointer)) {
  if (!j_.is_object())
    throw UserError(file_ + ": " + (pointer_.empty() ? std::string("/") : pointer_) + " must be a JSON object, found " +
                    j_.type_name());
}

bool JsonObject::has(const std::string& key) const {
  known_.insert(key);
  return j_.contains(key);
}

void JsonObject::fail(const std::string& key, const std::string& what) const {
  throw UserError(file_ + ": " + path(key) + " " + what);
}

const nlohmann::json& JsonObject::raw(const std::string& key) {
  if (!has(key)) fail(key, "is missing (required)");
  return j_.at(key);
}

JsonObject JsonObject::object(const std::string& key) { return JsonObject(raw(key), file_, path(key)); }

std::string JsonObject::string(const std::string& key) {
  const auto& v = raw(key);
  if (!v.is_string()) fail(key, "= " + v.dump() + " must be a string");
  return v.get<std::string>();
}

std::string JsonObject::string_or(const std::string& key, const std::string& fallback) {
  return has(key) ? string(key) : fallback;
}

std::string JsonObject::one_of(const std::string& key, const std::vector<std::string>& allowed,
                               const std::string* fallback) {
  if (fallback && !has(key)) return *fallback;
  const std::string s = string(key);
  for (const auto& a : allowed)
    if (s == a) return s;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + ("\"" + a + "\"");
  fail(key, "= \"" + s + "\" is not one of " + list);
}

double JsonObject::number(const std::string& key, double lo, bool lo_closed, double hi, bool hi_closed) {
  const auto& v = raw(key);
  if (!v.is_number()) fail(key, "= " + v.dump() + " must be a number");
  const double x = v.get<double>();
  const bool ok = std::isfinite(x) && (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
  if (!ok) fail(key, "= " + v.dump() + " is out of range " + interval_text(lo, lo_closed, hi, hi_closed));
  return x;
}

double JsonObject::number_or(const std::string& key, double fallback, double lo, bool lo_closed, double hi,
                             bool hi_closed) {
  return has(key) ? number(key, lo, lo_closed, hi, hi_closed) : fallback;
}

long long JsonObject::integer(const std::string& key, long long lo, long long hi) {
  const auto& v = raw(key);
  if (!v.is_number_integer()) fail(key, "= " + v.dump() + " must be an integer");
  // Unsigned values above the signed range are out of range, not wrapped.
  if (v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(hi))
    fail(key, "= " + v.dump() + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  const long long x = v.get<long long>();
  if (x < lo || x > hi)
    fail(key, "= " + v.dump() + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return x;
}

bool JsonObject::boolean_or(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const auto& v = raw(key);
  if (!v.is_boolean()) fail(key, "= " + v.dump() + " must be true or false");
  return v.get<bool>();
}

long long JsonObject::integer_or(const std::string& key, long long fallback, long long lo, long long hi) {
  return has(key) ? integer(key, lo, hi) : fallback;
}

void JsonObject::finish() const {
  for (auto it = j_.begin(); it != j_.end(); ++it) {
    if (known_.count(it.key())) continue;
    std::string list;
    for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
    throw UserError(file_ + ": " + path(it.key()) + " is not a known key (known here: " + list + ")");
  }
}

nlohmann::json read_json_file(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw UserError(file + ": cannot open the file (missing or unreadable)");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw UserError(file + ": not valid JSON: " + e.what());
  }
}

}  // namespace vgroove::support
