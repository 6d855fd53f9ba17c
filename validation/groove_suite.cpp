#include "vgroove/validation/groove_suite.h"
#include "vgroove/common/angles.h"

#include "vgroove/support/json_reader.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

constexpr std::size_t kMaxValues = 1'000'000;

// A list of degrees, or {"from", "to", "step"} (inclusive of "to" when the steps land on it).
std::vector<double> read_degrees(support::JsonObject& o, const std::string& key, double lo, bool lo_closed, double hi,
                                 bool hi_closed) {
  const nlohmann::json& v = o.raw(key);
  std::vector<double> out;
  auto check = [&](double x, const std::string& where) {
    const bool ok = std::isfinite(x) && (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
    if (!ok)
      throw support::UserError(o.file() + ": " + where + " = " + support::number_text(x) + " is out of range " +
                               support::interval_text(lo, lo_closed, hi, hi_closed));
  };
  if (v.is_array()) {
    if (v.empty()) o.fail(key, "is an empty list");
    for (std::size_t n = 0; n < v.size(); ++n) {
      const std::string where = o.path(key) + "/" + std::to_string(n);
      if (!v[n].is_number())
        throw support::UserError(o.file() + ": " + where + " = " + support::value_text(v[n]) + " must be a number");
      check(v[n].get<double>(), where);
      out.push_back(v[n].get<double>());
    }
    return out;
  }
  if (!v.is_object())
    o.fail(key, "= " + support::value_text(v) + " must be a list of numbers or {\"from\", \"to\", \"step\"}");
  support::JsonObject r(v, o.file(), o.path(key));
  const double inf = std::numeric_limits<double>::infinity();
  const double from = r.number("from", -inf, false, inf, false);
  const double to = r.number("to", -inf, false, inf, false);
  const double step = r.number("step", 0.0, false, inf, false);
  r.finish();
  check(from, r.path("from"));
  check(to, r.path("to"));
  if (to < from)
    throw support::UserError(o.file() + ": " + r.path("to") + " = " + support::number_text(to) +
                             " is below from = " + support::number_text(from));
  // Count the steps once, so no rounding accumulates: from + n * step.
  const double span = (to - from) / step;
  if (span > static_cast<double>(kMaxValues))
    throw support::UserError(o.file() + ": " + o.path(key) + " has more than " + std::to_string(kMaxValues) +
                             " values");
  const auto n = static_cast<std::size_t>(std::floor(span + 1e-9)) + 1;
  for (std::size_t m = 0; m < n; ++m) out.push_back(std::min(to, from + static_cast<double>(m) * step));
  return out;
}

// A nonsymmetric aperture 180 + theta_l - theta_r is 0 (degenerate: listed, not compared) or at
// least kMinApertureDeg.
void check_aperture(double l, double r, const std::string& where) {
  const double v = 180.0 + l - r;
  if (v != 0.0 && v < kMinApertureDeg)
    throw support::UserError(where + ": theta_l = " + support::number_text(l) + ", theta_r = " +
                             support::number_text(r) + " give the aperture " + support::number_text(v) +
                             " deg, out of range [" + support::number_text(kMinApertureDeg) + ", 180] (or exactly 0)");
}

std::vector<GrooveParams> read_grooves(support::JsonObject& groove) {
  std::vector<GrooveParams> out;
  if (groove.one_of("type", {"symmetric", "nonsymmetric"}) == "symmetric") {
    for (double d : read_degrees(groove, "theta_v_deg", kMinApertureDeg, true, 180.0, true))
      out.push_back(GrooveParams::make_symmetric(d * kRadPerDeg));
  } else {
    const auto ls = read_degrees(groove, "theta_l_deg", -90.0, true, 0.0, true);
    const auto rs = read_degrees(groove, "theta_r_deg", 0.0, true, 90.0, true);
    for (double l : ls)
      for (double r : rs) {
        check_aperture(l, r, groove.file() + ": " + groove.pointer());
        out.push_back(GrooveParams::make_nonsymmetric(l * kRadPerDeg, r * kRadPerDeg));
      }
  }
  return out;
}

}  // namespace

int default_max_bounces(double theta_v) {
  const double bound = std::ceil(std::numbers::pi / theta_v) + 1.0;
  return bound > kDefaultMaxBounces ? static_cast<int>(std::min<double>(bound, kMaxBounces)) : kDefaultMaxBounces;
}

void check_theta_v(double deg, const std::string& what) {
  if (!(std::isfinite(deg) && deg >= kMinApertureDeg && deg <= 180.0))
    throw support::UserError(
        what + " = " + support::number_text(deg) + " is out of range [" + support::number_text(kMinApertureDeg) +
        ", 180]" +
        (deg < kMinApertureDeg
             ? " (below " + support::number_text(kMinApertureDeg) +
                   " deg the tracer's rounding moves the bounce counts' boundaries: it and the model disagree)"
             : std::string()));
}

std::string theta_i_range_text() { return support::interval_text(-kMaxThetaIDeg, true, kMaxThetaIDeg, true); }

void check_theta_i(double deg, const std::string& what) {
  // NaN as the command line reads it (a float argument of the Python module can hold it).
  if (std::isnan(deg)) throw support::UserError(what + " = \"nan\" is not a number");
  if (!(std::isfinite(deg) && deg >= -kMaxThetaIDeg && deg <= kMaxThetaIDeg))
    throw support::UserError(what + " = " + support::number_text(deg) + " is out of range " + theta_i_range_text());
}

void check_theta_l(double deg, const std::string& what) {
  if (!(std::isfinite(deg) && deg >= -90.0 && deg <= 0.0))
    throw support::UserError(what + " = " + support::number_text(deg) + " is out of range [-90, 0]" +
                             (deg > 0.0 ? " (the left facet's normal leans right: theta_l <= 0)" : ""));
}

void check_theta_r(double deg, const std::string& what) {
  if (!(std::isfinite(deg) && deg >= 0.0 && deg <= 90.0))
    throw support::UserError(what + " = " + support::number_text(deg) + " is out of range [0, 90]" +
                             (deg < 0.0 ? " (the right facet's normal leans left: theta_r >= 0)" : ""));
}

GrooveSuite parse_groove_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  GrooveSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"table1"});
  if (root.has("groove") || root.has("theta_i_deg")) {
    support::JsonObject groove = root.object("groove");
    s.grooves = read_grooves(groove);
    groove.finish();
    for (double d : read_degrees(root, "theta_i_deg", -kMaxThetaIDeg, true, kMaxThetaIDeg, true))
      s.theta_i.push_back(d * kRadPerDeg);
  }
  if (root.has("cases")) {
    const nlohmann::json& list = root.raw("cases");
    if (!list.is_array()) root.fail("cases", "must be a list of {theta_v_deg | theta_l_deg, theta_r_deg; theta_i_deg}");
    for (std::size_t n = 0; n < list.size(); ++n) {
      support::JsonObject c(list[n], file, root.path("cases") + "/" + std::to_string(n));
      GrooveSuiteCase sc;
      if (c.has("theta_v_deg")) {
        sc.groove =
            GrooveParams::make_symmetric(c.number("theta_v_deg", kMinApertureDeg, true, 180.0, true) * kRadPerDeg);
      } else {
        const double l = c.number("theta_l_deg", -90.0, true, 0.0, true);
        const double r = c.number("theta_r_deg", 0.0, true, 90.0, true);
        check_aperture(l, r, file + ": " + c.pointer());
        sc.groove = GrooveParams::make_nonsymmetric(l * kRadPerDeg, r * kRadPerDeg);
      }
      sc.theta_i = c.number("theta_i_deg", -kMaxThetaIDeg, true, kMaxThetaIDeg, true) * kRadPerDeg;
      c.string_or("note", "");
      c.finish();
      s.listed.push_back(sc);
    }
  }
  if (s.cases() == 0) root.fail("cases", "is missing: a suite needs \"groove\" with \"theta_i_deg\", or \"cases\"");
  s.options.rays = static_cast<long>(root.integer("rays", 1, kMaxRays));
  const std::string stratified = "stratified";
  const std::string sampling = root.one_of("sampling", {"stratified", "random", "breakpoints"}, &stratified);
  s.options.sampling = sampling == "random"        ? sim::Sampling::random
                       : sampling == "breakpoints" ? sim::Sampling::breakpoints
                                                   : sim::Sampling::stratified;
  s.options.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, std::numeric_limits<long long>::max()));
  // By default every ray of every groove of the suite may leave (default_max_bounces).
  int max_bounces = kDefaultMaxBounces;
  for (std::size_t c = 0; c < s.grooves.size() + s.listed.size(); ++c) {
    const GrooveParams& g = c < s.grooves.size() ? s.grooves[c] : s.listed[c - s.grooves.size()].groove;
    if (!g.degenerate()) max_bounces = std::max(max_bounces, default_max_bounces(g.theta_v));
  }
  s.options.max_bounces = static_cast<int>(root.integer_or("max_bounces", max_bounces, 1, kMaxBounces));
  s.options.probe_vertices = root.boolean_or("probe_vertices", false);
  const std::string corrected = "corrected";
  s.options.form = root.one_of("eq6_form", {"corrected", "printed"}, &corrected) == "printed"
                       ? analytic::Eq6Form::printed
                       : analytic::Eq6Form::corrected;
  {
    support::JsonObject t = root.object("thresholds");
    s.thresholds.max_l1 = t.number("max_l1", 0.0, true, 2.0, true);
    s.thresholds.mean_l1 = t.number("mean_l1", 0.0, true, 2.0, true);
    s.thresholds.max_theta_o_error_rad = t.number("max_theta_o_error_rad", 0.0, true, std::numbers::pi, true);
    t.finish();
  }
  if (root.has("paper")) {
    support::JsonObject p = root.object("paper");
    s.paper = PaperFigures{p.string("source"), p.number("max_l1", 0.0, true, 2.0, true),
                           p.number("mean_l1", 0.0, true, 2.0, true), "", ""};
    const std::string none;
    s.paper->placement = p.one_of("placement", {"stratified", "random", "unknown"}, &none);
    s.paper->placement_evidence = p.string_or("placement_evidence", "");
    p.finish();
  }
  root.finish();
  return s;
}

GrooveSuite load_groove_suite(const std::string& file) {
  const nlohmann::json j = support::read_json_file(file);
  if (j.is_object() && j.contains("suites"))
    throw support::UserError(file + ": is a set of suites (it has /suites); run it with `vgroove validate`");
  return parse_groove_suite(j, file);
}

GrooveSuiteSet load_groove_suite_set(const std::string& file) {
  return parse_groove_suite_set(support::read_json_file(file), file);
}

GrooveSuiteSet parse_groove_suite_set(const nlohmann::json& j, const std::string& file) {
  GrooveSuiteSet set;
  set.file = file;
  if (!(j.is_object() && j.contains("suites"))) {
    set.suites.push_back(parse_groove_suite(j, file));
    set.name = set.suites.front().name;
    set.description = set.suites.front().description;
    return set;
  }
  support::JsonObject root(j, file, "");
  set.name = root.string("name");
  set.description = root.string_or("description", "");
  const nlohmann::json& list = root.raw("suites");
  if (!list.is_array() || list.empty()) root.fail("suites", "must be a non-empty list of suite files");
  root.finish();
  const std::filesystem::path dir = std::filesystem::path(file).parent_path();
  for (std::size_t n = 0; n < list.size(); ++n) {
    if (!list[n].is_string())
      throw support::UserError(file + ": /suites/" + std::to_string(n) + " = " + support::value_text(list[n]) +
                               " must be a file name");
    const std::string sub = (dir / list[n].get<std::string>()).string();
    set.suites.push_back(load_groove_suite(sub));
  }
  return set;
}

}  // namespace vgroove::validation
