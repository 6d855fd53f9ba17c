#include "vgroove/app/bounce_rows.h"

#include "vgroove/validation/report.h"

#include <cstdio>
#include <string>

namespace vgroove::app {

nlohmann::json bounce_row(const char* facet, int k, double fraction, double theta_o) {
  return {{"first_facet", facet}, {"k", k}, {"fraction", fraction}, {"theta_o_deg", validation::output_deg(theta_o)}};
}

void print_rows(const nlohmann::json& rows) {
  std::printf("  first facet    k   fraction      theta_o (deg)\n");
  for (const auto& r : rows)
    std::printf("  %-11s %4d   %-12.6g  %.9g\n", r["first_facet"].get<std::string>().c_str(), r["k"].get<int>(),
                r["fraction"].get<double>(), r["theta_o_deg"].get<double>());
}

}  // namespace vgroove::app
