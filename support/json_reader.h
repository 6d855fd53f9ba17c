// vgroove support: strict reading of JSON specs.
//
// Every value is read through a Field that knows its file and JSON pointer, so every message
// names both: "data/suites/x.json: /theta_v_deg/from = 195 is out of range (0, 180]".
// Required keys use required(), optional ones optional(); finish() rejects any key that was
// not read, so a typo like "roughnes" fails instead of falling back to a default.
#pragma once

#include "vgroove/support/user_error.h"

#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <vector>

namespace vgroove::support {

class JsonObject {
 public:
  JsonObject(const nlohmann::json& j, std::string file, std::string pointer);

  bool has(const std::string& key) const;
  const nlohmann::json& raw(const std::string& key);  // marks the key as read
  std::string path(const std::string& key) const { return pointer_ + "/" + key; }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  JsonObject object(const std::string& key);
  std::string string(const std::string& key);
  std::string string_or(const std::string& key, const std::string& fallback);
  std::string one_of(const std::string& key, const std::vector<std::string>& allowed,
                     const std::string* fallback = nullptr);
  double number(const std::string& key, double lo, bool lo_closed, double hi, bool hi_closed);
  double number_or(const std::string& key, double fallback, double lo, bool lo_closed, double hi, bool hi_closed);
  long long integer(const std::string& key, long long lo, long long hi);
  bool boolean_or(const std::string& key, bool fallback);
  long long integer_or(const std::string& key, long long fallback, long long lo, long long hi);

  // Rejects every key that no call above has read.
  void finish() const;

  const std::string& file() const { return file_; }
  const std::string& pointer() const { return pointer_; }

 private:
  const nlohmann::json& j_;
  std::string file_;
  std::string pointer_;
  mutable std::set<std::string> known_;  // every key the schema asked about, present or not
};

// Parses a JSON file; a missing or unreadable file or a syntax error is a UserError naming it.
nlohmann::json read_json_file(const std::string& file);

}  // namespace vgroove::support
