#include "vgroove/app/options.h"

#include "vgroove/support/user_error.h"

#include <cctype>
#include <charconv>
#include <limits>
#include <numbers>
#include <optional>

namespace vgroove::app {

namespace {
std::string quoted(const std::string& text) { return "\"" + text.substr(0, 60) + (text.size() > 60 ? "...\"" : "\""); }

// The parts of a decimal number: sign, digits before and after the point, exponent.
struct Decimal {
  bool negative = false;
  std::string digits;   // all mantissa digits, the point removed
  long long point = 0;  // digits before the point, after applying the exponent
};
bool parse_decimal(const std::string& t, Decimal& d) {
  std::size_t i = 0;
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) d.negative = t[i++] == '-';
  std::size_t before = 0, after = 0;
  while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) d.digits += t[i++], ++before;
  if (i < t.size() && t[i] == '.') {
    ++i;
    while (i < t.size() && std::isdigit(static_cast<unsigned char>(t[i]))) d.digits += t[i++], ++after;
  }
  if (before + after == 0) return false;
  d.point = static_cast<long long>(before);
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    bool neg = false;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) neg = t[i++] == '-';
    long long e = 0;
    std::size_t n = 0;
    for (; i < t.size() && std::isdigit(static_cast<unsigned char>(t[i])); ++i, ++n)
      e = std::min<long long>(e * 10 + (t[i] - '0'), 1'000'000);
    if (n == 0) return false;
    d.point += neg ? -e : e;
  }
  return i == t.size();
}
}  // namespace

std::string integer_text(const std::string& text, const std::string& option, long long lo, long long hi,
                         const std::string& note) {
  Decimal d;
  std::string range(1, '[');  // appended piecewise: GCC 12 warns on "[" + std::string (bug 105651)
  range += std::to_string(lo);
  range += ", ";
  range += std::to_string(hi);
  range += ']';
  range += note;
  if (!parse_decimal(text, d)) throw support::UserError(option + " = " + quoted(text) + " is not an integer");
  const std::size_t first = d.digits.find_first_not_of('0');
  std::string whole = "0";  // every digit zero: 0, whatever the exponent
  if (first != std::string::npos) {
    // The value is digits[first..] x 10^(point - digits.size()): whole when every digit past the
    // point is zero.
    const long long len = static_cast<long long>(d.digits.size());
    for (long long k = std::max(0LL, d.point); k < len; ++k)
      if (d.digits[static_cast<std::size_t>(k)] != '0')
        throw support::UserError(option + " = " + quoted(text) + " is not an integer");
    if (d.point - static_cast<long long>(first) > 19)  // more digits than any 64-bit value
      throw support::UserError(option + " = " + text + " is out of range " + range);
    if (d.point > static_cast<long long>(first)) {
      whole = d.digits.substr(first, static_cast<std::size_t>(std::min(len, d.point)) - first);
      whole.append(static_cast<std::size_t>(std::max(0LL, d.point - len)), '0');
    }
  }
  const unsigned long long mag = std::stoull(whole);
  if (mag == 0) d.negative = false;  // -0 is 0
  bool in;
  if (!d.negative) {
    in = mag <= static_cast<unsigned long long>(std::numeric_limits<long long>::max()) &&
         static_cast<long long>(mag) >= lo && static_cast<long long>(mag) <= hi;
  } else {
    // -mag in [lo, hi], in unsigned magnitudes: mag <= |lo| and (hi >= 0 or mag >= |hi|).
    auto magnitude = [](long long x) { return static_cast<unsigned long long>(-(x + 1)) + 1ULL; };
    in = lo < 0 && mag <= magnitude(lo) && (hi >= 0 || mag >= magnitude(hi));
  }
  if (!in) throw support::UserError(option + " = " + text + " is out of range " + range);
  return (d.negative ? "-" : "") + whole;
}

std::string real_text(const std::string& text, const std::string& option) {
  Decimal d;
  if (!parse_decimal(text, d)) throw support::UserError(option + " = " + quoted(text) + " is not a number");
  return text;
}

validation::GrooveParams groove_from(const GrooveArgs& g) {
  if (!g.nonsymmetric) return validation::groove_from_degrees(g.theta_v_deg, std::nullopt, std::nullopt, {});
  return validation::groove_from_degrees(g.theta_v_given ? std::optional<double>(g.theta_v_deg) : std::nullopt,
                                         g.theta_l_deg, g.theta_r_deg, {});
}

}  // namespace vgroove::app
