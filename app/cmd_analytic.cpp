#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"

#include <cstdio>
#include <iostream>
#include "vgroove/app/bounce_rows.h"
#include "vgroove/app/options.h"
#include "vgroove/support/json_text.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/single_groove.h"

namespace vgroove::app {

using namespace validation;

int cmd_analytic(const AnalyticArgs& a) {
  const GrooveParams params = groove_from(a.groove);
  check_theta_i(a.theta_i_deg, "--theta-i-deg");
  const analytic::Eq6Form form = parse_form(a.eq6_form, "--eq6-form");
  if (a.dry_run) return 0;
  const nlohmann::json j = analytic_json(params, a.theta_i_deg, form);
  if (a.json) {
    std::cout << support::json_text(j, 2) << "\n";
  } else {
    std::printf("analytic (Lee et al. 2018, %s): %s, theta_i %g deg; fractions of the beam entering the opening\n",
                params.symmetric ? (a.eq6_form == "printed" ? "Eq. 4-6 as printed" : "Eq. 4-6") : "Eq. 7-9",
                groove_text(params).c_str(), a.theta_i_deg);
    print_rows(j["bounces"]);
  }
  return 0;
}

void add_analytic_command(CLI::App& app, Commands& commands) {
  using validation::theta_i_range_text;
  auto* an = app.add_subcommand("analytic",
                                "Evaluate the kaleidoscopic model (Eq. 4-6 symmetric, Eq. 7-9 nonsymmetric) for one "
                                "V-groove; same output as trace.");
  AnalyticArgs& aa = commands.add(an, cmd_analytic);
  add_groove_options(an, aa.groove);
  add_real(an, "--theta-i-deg", aa.theta_i_deg, "incident angle theta_i in degrees, " + theta_i_range_text())
      ->capture_default_str();
  add_text(an, "--eq6-form", aa.eq6_form,
           "symmetric grooves: corrected (see docs/ERRATA.md) or printed (as in the paper)")
      ->capture_default_str();
  an->add_flag("--json", aa.json, "print JSON (the same shape as `trace --json`)");
}

}  // namespace vgroove::app
