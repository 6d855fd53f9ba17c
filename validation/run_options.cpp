#include "vgroove/validation/run_options.h"

#include "vgroove/common/angles.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/spec_lists.h"

#include <limits>

namespace vgroove::validation {

OptionNames OptionNames::keywords() {
  OptionNames n;
  n.rays = "rays", n.threads = "threads", n.sampling = "sampling", n.eq6_form = "eq6_form", n.seed = "seed";
  n.model_table = "model_table";
  n.theta_v = "theta_v_deg", n.theta_l = "theta_l_deg", n.theta_r = "theta_r_deg", n.theta_i = "theta_i_deg";
  return n;
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

void check_threads(int threads, const std::string& what) {
  if (threads < 0 || threads > kMaxThreads)
    throw support::UserError(what + " = " + std::to_string(threads) + " is out of range [0, " +
                             std::to_string(kMaxThreads) + "] (0: all cores)");
}

sim::Sampling parse_sampling(const std::string& s, const std::string& what, bool allow_breakpoints) {
  if (s == "stratified") return sim::Sampling::stratified;
  if (s == "random") return sim::Sampling::random;
  if (allow_breakpoints && s == "breakpoints") return sim::Sampling::breakpoints;
  throw support::UserError(what + " = \"" + s + "\" is not one of \"stratified\", \"random\"" +
                           (allow_breakpoints ? ", \"breakpoints\"" : ""));
}

analytic::Eq6Form parse_form(const std::string& s, const std::string& what) {
  if (s == "corrected") return analytic::Eq6Form::corrected;
  if (s == "printed") return analytic::Eq6Form::printed;
  throw support::UserError(what + " = \"" + s + "\" is not one of \"corrected\", \"printed\"");
}

GrooveParams groove_from_degrees(std::optional<double> theta_v_deg, std::optional<double> theta_l_deg,
                                 std::optional<double> theta_r_deg, const OptionNames& names) {
  if (!theta_l_deg && !theta_r_deg) {
    const double v = theta_v_deg.value_or(90.0);
    check_theta_v(v, names.theta_v);
    return GrooveParams::make_symmetric(v * kRadPerDeg);
  }
  if (!theta_l_deg || !theta_r_deg)
    throw support::UserError(theta_l_deg ? names.theta_l + " needs " + names.theta_r
                                         : names.theta_r + " needs " + names.theta_l);
  if (theta_v_deg)
    throw support::UserError(names.theta_v + " cannot be combined with " + names.theta_l + "/" + names.theta_r +
                             " (the aperture follows from them)");
  const double l = *theta_l_deg, r = *theta_r_deg;
  check_theta_l(l, names.theta_l);
  check_theta_r(r, names.theta_r);
  GrooveParams p = GrooveParams::make_nonsymmetric(l * kRadPerDeg, r * kRadPerDeg);
  const double v = 180.0 + l - r;
  if (p.degenerate() || v < kMinApertureDeg)
    throw support::UserError(names.theta_l + " = " + support::number_text(l) + " with " + names.theta_r + " = " +
                             support::number_text(r) +
                             " gives the aperture theta_v = 180 + theta_l - theta_r = " + support::number_text(v) +
                             ", out of range [" + support::number_text(kMinApertureDeg) + ", 180]");
  return p;
}

CaseOptions options_with_overrides(const GrooveSuite& suite, std::optional<long> rays,
                                   const std::optional<std::string>& sampling,
                                   const std::optional<std::string>& eq6_form, std::optional<long long> seed,
                                   const OptionNames& names) {
  CaseOptions o = suite.options;
  if (rays) check_rays(*rays, names.rays), o.rays = *rays;
  if (sampling) o.sampling = parse_sampling(*sampling, names.sampling, true);
  if (eq6_form) o.form = parse_form(*eq6_form, names.eq6_form);
  if (seed) check_seed(*seed, names.seed), o.seed = static_cast<std::uint64_t>(*seed);
  return o;
}

}  // namespace vgroove::validation
