#include "vgroove/app/commands.h"

#include <cstdio>
#include <iostream>
#include "vgroove/app/bounce_rows.h"
#include "vgroove/app/options.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/single_groove.h"
#include "vgroove/support/json_text.h"

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

}  // namespace vgroove::app
