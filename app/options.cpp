#include "vgroove/app/options.h"
#include "vgroove/common/angles.h"

#include "vgroove/support/user_error.h"

#include <limits>
#include <numbers>

namespace vgroove::app {

using namespace validation;

void check_seed(long long seed, const std::string& what) {
  if (seed < 0)
    throw support::UserError(what + " = " + std::to_string(seed) + " is out of range [0, " +
                             std::to_string(std::numeric_limits<long long>::max()) + "]");
}

void check_rays(long rays, const std::string& what) {
  if (rays < 1 || rays > kMaxRays)
    throw support::UserError(what + " = " + std::to_string(rays) + " is out of range [1, " + std::to_string(kMaxRays) +
                             "]");
}

sim::Sampling parse_sampling(const std::string& s, const std::string& what, bool breakpoints) {
  if (s == "stratified") return sim::Sampling::stratified;
  if (s == "random") return sim::Sampling::random;
  if (breakpoints && s == "breakpoints") return sim::Sampling::breakpoints;
  throw support::UserError(what + " = \"" + s + "\" is not one of \"stratified\", \"random\"" +
                           (breakpoints ? ", \"breakpoints\"" : ""));
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
  if (threads < 0 || threads > 1024)
    throw support::UserError("--threads = " + std::to_string(threads) + " is out of range [0, 1024] (0: all cores)");
}

}  // namespace vgroove::app
