#include "vgroove/support/json_reader.h"
#include "vgroove/support/printable.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <vector>

namespace vgroove::support {

namespace {
// A key as a JSON pointer segment ("~" and "/" escaped), cut to 64 bytes for messages.
std::string key_segment(const std::string& key) {
  std::string out;
  for (char c : key.substr(0, 64))
    out += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
  return key.size() > 64 ? out + "..." : out;
}

}  // namespace

std::string JsonObject::path(const std::string& key) const { return pointer_ + "/" + key_segment(key); }

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

void JsonObject::fail_at(const std::string& key, std::size_t index, const std::string& what) const {
  throw UserError(file_ + ": " + path(key) + "/" + std::to_string(index) + " " + what);
}

const nlohmann::json& JsonObject::raw(const std::string& key) {
  if (!has(key)) fail(key, "is missing (required)");
  return j_.at(key);
}

JsonObject JsonObject::object(const std::string& key) { return JsonObject(raw(key), file_, path(key)); }

std::string JsonObject::string(const std::string& key) {
  const auto& v = raw(key);
  if (!v.is_string()) fail(key, "= " + value_text(v) + " must be a string");
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
  if (!v.is_number()) fail(key, "= " + value_text(v) + " must be a number");
  const double x = v.get<double>();
  const bool ok = std::isfinite(x) && (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
  if (!ok) fail(key, "= " + value_text(v) + " is out of range " + interval_text(lo, lo_closed, hi, hi_closed));
  return x;
}

double JsonObject::number_or(const std::string& key, double fallback, double lo, bool lo_closed, double hi,
                             bool hi_closed) {
  return has(key) ? number(key, lo, lo_closed, hi, hi_closed) : fallback;
}

long long JsonObject::integer(const std::string& key, long long lo, long long hi) {
  const auto& v = raw(key);
  if (!v.is_number_integer()) fail(key, "= " + value_text(v) + " must be an integer");
  // Unsigned values above the signed range are out of range, not wrapped.
  if (v.is_number_unsigned() && v.get<unsigned long long>() > static_cast<unsigned long long>(hi))
    fail(key, "= " + value_text(v) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  const long long x = v.get<long long>();
  if (x < lo || x > hi)
    fail(key, "= " + value_text(v) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return x;
}

bool JsonObject::boolean_or(const std::string& key, bool fallback) {
  if (!has(key)) return fallback;
  const auto& v = raw(key);
  if (!v.is_boolean()) fail(key, "= " + value_text(v) + " must be true or false");
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

namespace {

// The first pass over a spec: the JSON path of every value, keys seen twice and the depth.
class StrictSax : public nlohmann::json_sax<nlohmann::json> {
 public:
  explicit StrictSax(const std::string& file) : file_(file) {}
  std::string error;  // the parser's message when the text is not JSON

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(true); }
  bool key(string_t& k) override {
    Level& l = stack_.back();
    if (!l.keys.insert(k).second)
      throw UserError(file_ + ": " + pointer(stack_.size() - 1) + "/" + key_segment(k) +
                      " is given twice (duplicate key: a strict reader does not pick one)");
    l.key = k;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& ex) override {
    error = ex.what();
    return false;
  }

 private:
  struct Level {
    bool object = false;
    std::set<std::string> keys;
    std::string key;
    std::size_t index = 0;
  };
  // The path to the value being read, through the first `levels` levels (all by default).
  std::string pointer(std::size_t levels = static_cast<std::size_t>(-1)) const {
    std::string p;
    for (std::size_t n = 0; n < std::min(levels, stack_.size()); ++n) {
      if (p.size() > 200) return p + "/...";
      const Level& l = stack_[n];
      p += "/" + (l.object ? key_segment(l.key) : std::to_string(l.index));
    }
    return p;
  }
  bool value() {
    if (!stack_.empty() && !stack_.back().object) ++stack_.back().index;
    return true;
  }
  bool open(bool object) {
    if (static_cast<int>(stack_.size()) >= kMaxJsonDepth)
      throw UserError(file_ + ": " + pointer() + " is nested more than " + std::to_string(kMaxJsonDepth) +
                      " levels deep (a spec needs a few)");
    stack_.push_back(Level{object, {}, {}, 0});
    return true;
  }
  bool close() {
    stack_.pop_back();
    return value();
  }
  const std::string& file_;
  std::vector<Level> stack_;
};

}  // namespace

namespace {
// The parser's message quotes the offending token, which may be megabytes long: cut it.
std::string brief(const std::string& s) { return s.size() > 200 ? s.substr(0, 200) + "..." : s; }
}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& file) {
  StrictSax sax(file);
  if (!nlohmann::json::sax_parse(text, &sax)) throw UserError(file + ": not valid JSON: " + brief(sax.error));
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw UserError(file + ": not valid JSON: " + brief(e.what()));
  }
}

nlohmann::json read_json_file(const std::string& file, std::size_t max_bytes) {
  check_file_name(file);
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw UserError(file + ": cannot open the file (" + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) {
    ::close(fd);
    throw UserError(file + ": is a directory, not a JSON file");
  }
  // One pass, whatever the file is (a pipe cannot be read twice), and no more than the limit.
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      ::close(fd);
      throw UserError(file + ": cannot read the file (" + std::strerror(e) + ")");
    }
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > max_bytes) {
      ::close(fd);
      throw UserError(file + ": is larger than " + std::to_string(max_bytes >> 20) + " MB; not a spec or report file");
    }
  }
  ::close(fd);
  return parse_json_text(text, file);
}

namespace {
void append_value(std::string& out, const nlohmann::json& v, std::size_t budget) {
  if (out.size() > budget) return;
  if (v.is_object() || v.is_array()) {
    const bool obj = v.is_object();
    out += obj ? '{' : '[';
    bool first = true;
    for (auto it = v.begin(); it != v.end(); ++it) {
      if (out.size() > budget) break;
      if (!first) out += ", ";
      first = false;
      if (obj) out += nlohmann::json(it.key()).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + ": ";
      append_value(out, *it, budget);
    }
    out += obj ? '}' : ']';
    return;
  }
  out += v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}
}  // namespace

std::string value_text(const nlohmann::json& v) {
  constexpr std::size_t kLength = 60;
  std::string out;
  append_value(out, v, kLength);
  if (out.size() > kLength) out = out.substr(0, kLength) + "...";
  return out;
}

}  // namespace vgroove::support
