#include "vgroove/app/cli_options.h"

#include "vgroove/app/options.h"
#include "vgroove/support/user_error.h"
#include "vgroove/support/work_plan.h"
#include "vgroove/validation/ranges.h"

namespace vgroove::app {

CLI::Validator strict_integer(const std::string& name, long long lo, long long hi, const std::string& note) {
  return CLI::Validator([=](std::string& s) { return s = integer_text(s, name, lo, hi, note), std::string(); }, "", "");
}
CLI::Validator strict_real(const std::string& name) {
  return CLI::Validator([=](std::string& s) { return s = real_text(s, name), std::string(); }, "", "");
}
CLI::Validator non_empty(const std::string& name) {
  return CLI::Validator(
      [=](std::string& s) {
        if (s.empty()) throw support::UserError(name + " = \"\" is empty");
        return std::string();
      },
      "", "");
}
std::string range_text(long long lo, long long hi) {
  std::string s(1, '[');  // appended piecewise: GCC 12 warns on "[" + std::string (bug 105651)
  s += std::to_string(lo);
  s += ", ";
  s += std::to_string(hi);
  return s + "]";
}

CLI::Option* add_threads(CLI::App* app, int& v) {
  return add_integer(app, "--threads", v, "worker threads (0: all cores); results do not depend on it", 0,
                     validation::kMaxThreads, " (0: all cores)")
      ->capture_default_str();
}
CLI::Option* add_seed(CLI::App* app, long long& v, const std::string& help) {
  return add_integer(app, "--seed", v, help, 0, validation::kMaxSeed);
}

CLI::Option* add_shard(CLI::App* app, std::string& v, const std::string& joined) {
  return add_text(app, "--shard", v,
                  "I/N, 1 <= I <= N <= " + std::to_string(support::kMaxShards) +
                      ": run only the I-th of N parts of the work and write it to --out as a partial report (" +
                      joined + ")");
}

void add_groove_options(CLI::App* app, GrooveArgs& g) {
  using validation::kMinApertureDeg;
  auto* v =
      add_real(app, "--theta-v-deg", g.theta_v_deg,
               "symmetric groove: aperture theta_v in degrees, [" + support::number_text(kMinApertureDeg) + ", 180]")
          ->capture_default_str();
  auto* l = add_real(app, "--theta-l-deg", g.theta_l_deg,
                     "nonsymmetric groove: angle of the left facet's normal from n, [-90, 0] (Lee et al. "
                     "2018, Fig. 5; counter-clockwise positive, so the left facet's normal leans right and "
                     "theta_l <= 0)");
  auto* r = add_real(app, "--theta-r-deg", g.theta_r_deg,
                     "nonsymmetric groove: angle of the right facet's normal, [0, 90]; aperture "
                     "theta_v = 180 + theta_l - theta_r >= " +
                         support::number_text(kMinApertureDeg) + "; a symmetric groove is theta_l = -theta_r");
  l->needs(r);
  r->needs(l);
  app->callback([&g, v, l]() {
    g.nonsymmetric = l->count() > 0;
    g.theta_v_given = v->count() > 0;
  });
}

}  // namespace vgroove::app
