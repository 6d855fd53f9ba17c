#include "vgroove/app/commands.h"
#include "vgroove/common/angles.h"

#include <cstdio>
#include <iostream>
#include <map>
#include <numbers>
#include "vgroove/app/bounce_rows.h"
#include "vgroove/app/options.h"
#include "vgroove/validation/groove_case.h"
#include "vgroove/validation/report.h"

namespace vgroove::app {

using namespace validation;

int cmd_analytic(const AnalyticArgs& a) {
  const GrooveParams params = groove_from(a.groove);
  check_theta_i(a.theta_i_deg, "--theta-i-deg");
  const analytic::Eq6Form form = parse_form(a.eq6_form, "--eq6-form");
  if (a.dry_run) return 0;
  const double theta_i = a.theta_i_deg * kRadPerDeg;
  nlohmann::json rows = nlohmann::json::array();
  nlohmann::json facets = nlohmann::json::object();
  // G is normalized by each facet's projected width f_a; the beam entering the opening is as wide
  // as the two facets' unshadowed parts together, f_a - f_b summed.
  ModelShares m[2];
  for (sim::Side side : {sim::Side::left, sim::Side::right})
    m[static_cast<int>(side)] = model_shares(params, theta_i, side, form);
  const double width = entering_width(m);
  for (sim::Side side : {sim::Side::left, sim::Side::right}) {
    const ModelShares& p = m[static_cast<int>(side)];
    const char* name = sim::side_name(side);
    if (!p.lit) {
      facets[name] = nullptr;
      continue;
    }
    // Zones that share a bounce count (k_b - 1 = 1 when k_b = 2) are one row.
    std::map<int, std::pair<double, double>> by_n;  // n -> (G, theta_o)
    for (int z = 0; z < p.shares; ++z) {
      auto& e = by_n[p.share[z].n];
      e.first += p.share[z].G;
      e.second = p.share[z].theta_o;
    }
    nlohmann::json G = nlohmann::json::object();
    for (const auto& [n, e] : by_n) {
      G[std::to_string(n)] = e.first;
      if (e.first != 0.0) rows.push_back(bounce_row(name, n, e.first * p.f_a / width, e.second));
    }
    facets[name] = {{"k", p.k}, {"f_a", p.f_a}, {"G", G}, {"shadow", p.shadow}};
  }
  nlohmann::json j = provenance();
  j["inputs"] = groove_json(params);
  j["inputs"].update({{"theta_i_deg", a.theta_i_deg}, {"eq6_form", a.eq6_form}});
  j["bounces"] = rows;
  j["facets"] = facets;
  if (a.json) {
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("analytic (Lee et al. 2018, %s): %s, theta_i %g deg; fractions of the beam entering the opening\n",
                params.symmetric ? (a.eq6_form == "printed" ? "Eq. 4-6 as printed" : "Eq. 4-6") : "Eq. 7-9",
                groove_text(params).c_str(), a.theta_i_deg);
    print_rows(rows);
  }
  return 0;
}

}  // namespace vgroove::app
