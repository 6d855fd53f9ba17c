#include "vgroove/app/options.h"
#include "vgroove/common/angles.h"

#include "vgroove/support/user_error.h"

#include <cctype>
#include <charconv>
#include <limits>
#include <numbers>

namespace vgroove::app {

using namespace validation;

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

void check_seed(long long seed, const std::string& what) {
  if (seed < 0)
    throw support::UserError(what + " = " + std::to_string(seed) + " is out of range [0, " + std::to_string(kMaxSeed) +
                             "]");
}

void check_rays(long rays, const std::string& what) {
  if (rays < 1 || rays > kMaxRays)
    throw support::UserError(what + " = " + std::to_string(rays) + " is out of range [1, " + std::to_string(kMaxRays) +
                             "]");
}

sim::Sampling parse_sampling(const std::string& s, const std::string& what) {
  if (s == "stratified") return sim::Sampling::stratified;
  if (s == "random") return sim::Sampling::random;
  throw support::UserError(what + " = \"" + s + "\" is not one of \"stratified\", \"random\"");
}

analytic::Eq6Form parse_form(const std::string& s, const std::string& what) {
  if (s == "corrected") return analytic::Eq6Form::corrected;
  if (s == "printed") return analytic::Eq6Form::printed;
  throw support::UserError(what + " = \"" + s + "\" is not one of \"corrected\", \"printed\"");
}

GrooveParams groove_from(const GrooveArgs& g) {
  if (!g.nonsymmetric) {
    check_theta_v(g.theta_v_deg, "--theta-v-deg");
    return GrooveParams::make_symmetric(g.theta_v_deg * kRadPerDeg);
  }
  if (g.theta_v_given)
    throw support::UserError(
        "--theta-v-deg cannot be combined with --theta-l-deg/--theta-r-deg (the aperture follows from them)");
  check_theta_l(g.theta_l_deg, "--theta-l-deg");
  check_theta_r(g.theta_r_deg, "--theta-r-deg");
  GrooveParams p = GrooveParams::make_nonsymmetric(g.theta_l_deg * kRadPerDeg, g.theta_r_deg * kRadPerDeg);
  const double v = 180.0 + g.theta_l_deg - g.theta_r_deg;
  if (p.degenerate() || v < kMinApertureDeg)
    throw support::UserError("--theta-l-deg = " + support::number_text(g.theta_l_deg) +
                             " with --theta-r-deg = " + support::number_text(g.theta_r_deg) +
                             " gives the aperture theta_v = 180 + theta_l - theta_r = " + support::number_text(v) +
                             ", out of range [" + support::number_text(kMinApertureDeg) + ", 180]");
  return p;
}

CaseOptions options_with_overrides(const Suite& suite, long rays, const std::string& sampling, const std::string& form,
                                   long long seed) {
  CaseOptions o = suite.options;
  if (rays != kUnset) check_rays(rays, "--rays"), o.rays = rays;
  if (!sampling.empty()) o.sampling = parse_sampling(sampling, "--sampling");
  if (!form.empty()) o.form = parse_form(form, "--eq6-form");
  if (seed != kUnsetSeed) check_seed(seed, "--seed"), o.seed = static_cast<std::uint64_t>(seed);
  return o;
}
void check_threads(int threads) {
  if (threads < 0 || threads > kMaxThreads)
    throw support::UserError("--threads = " + std::to_string(threads) + " is out of range [0, " +
                             std::to_string(kMaxThreads) + "] (0: all cores)");
}

}  // namespace vgroove::app
