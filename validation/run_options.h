// vgroove validation: the values a run is given besides its spec (rays, threads, seed, ray
// placement, Eq. 6 form, a groove by its angles), checked the same way wherever they come from:
// the command line names them by its flags (--rays), the Python module by its keywords (rays).
// Each check throws support::UserError naming the value, its name and the allowed range.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/sim/beam.h"
#include "vgroove/validation/groove_suite.h"

#include <optional>
#include <string>

namespace vgroove::validation {

void check_seed(long long seed, const std::string& what);
void check_rays(long rays, const std::string& what);
// 0 means all cores.
void check_threads(int threads, const std::string& what);
// "stratified", "random", and with allow_breakpoints also "breakpoints" (sim/zones.h: a suite's
// single-groove cases, validate and bench accuracy; a beam's rays themselves are placed across the
// opening by the other two).
sim::Sampling parse_sampling(const std::string& s, const std::string& what, bool allow_breakpoints = false);
analytic::Eq6Form parse_form(const std::string& s, const std::string& what);

// The names of the values above and of a groove's angles in messages.
struct OptionNames {
  std::string rays = "--rays", threads = "--threads", sampling = "--sampling", eq6_form = "--eq6-form", seed = "--seed";
  std::string model_table = "--model-table";
  std::string theta_v = "--theta-v-deg", theta_l = "--theta-l-deg", theta_r = "--theta-r-deg",
              theta_i = "--theta-i-deg";
  static OptionNames flags() { return {}; }  // the command line's
  static OptionNames keywords();             // the Python module's: rays, theta_v_deg, ...
};

// A single groove given by its angles in degrees: theta_v (symmetric), or theta_l with theta_r
// (nonsymmetric, Lee et al. 2018, Fig. 5), checked; never both, never a zero aperture.
GrooveParams groove_from_degrees(std::optional<double> theta_v_deg, std::optional<double> theta_l_deg,
                                 std::optional<double> theta_r_deg, const OptionNames& names);

// A suite's case options with overrides (unset: the suite's).
CaseOptions options_with_overrides(const GrooveSuite& suite, std::optional<long> rays,
                                   const std::optional<std::string>& sampling,
                                   const std::optional<std::string>& eq6_form, std::optional<long long> seed,
                                   const OptionNames& names);

}  // namespace vgroove::validation
