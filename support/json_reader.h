// vgroove support: strict reading of JSON specs.
//
// Every value is read through a Field that knows its file and JSON pointer, so every message
// names both: "data/suites/x.json: /theta_v_deg/from = 195 is out of range (0, 180]".
// Required keys use required(), optional ones optional(); finish() rejects any key that was
// not read, so a typo like "roughnes" fails instead of falling back to a default.
#pragma once

#include "vgroove/support/user_error.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <set>
#include <string>
#include <vector>

namespace vgroove::support {

class JsonObject {
 public:
  JsonObject(const nlohmann::json& j, std::string file, std::string pointer);

  bool has(const std::string& key) const;
  const nlohmann::json& raw(const std::string& key);  // marks the key as read
  std::string path(const std::string& key) const;     // pointer/key ("~", "/" escaped; long keys cut)
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  // The same for entry `index` of the array at `key` (pointer/key/index).
  [[noreturn]] void fail_at(const std::string& key, std::size_t index, const std::string& what) const;

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

// The deepest nesting a spec may have (suites and scenes use five levels), and its largest size.
inline constexpr int kMaxJsonDepth = 64;
inline constexpr std::size_t kMaxJsonBytes = 64u << 20;

// Parses JSON text strictly: a syntax error, a number out of the double range (1e400), a key
// given twice in one object, or nesting deeper than kMaxJsonDepth is a UserError naming `file`
// (and the JSON path). The last two are not JSON errors, but a strict reader refuses them: the
// last of two "rays" would otherwise win silently, and deep nesting costs stack in every reader.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);
// Reads `file` once (a pipe or /dev/stdin works) and parses it as above; a missing, unreadable or
// non-regular file (a directory) or one past kMaxJsonBytes is a UserError naming it.
// max_bytes: a larger limit for files the program wrote itself (shard parts).
nlohmann::json read_json_file(const std::string& file, std::size_t max_bytes = kMaxJsonBytes);

// A JSON value for a message: compact, on one line, at most about 60 characters ("..." after).
std::string value_text(const nlohmann::json& v);

}  // namespace vgroove::support
