#include "vgroove/app/bounce_rows.h"

#include <cstdio>
#include <string>

namespace vgroove::app {

void print_rows(const nlohmann::json& rows) {
  std::printf("  first facet    k   fraction      theta_o (deg)\n");
  for (const auto& r : rows)
    std::printf("  %-11s %4d   %-12.6g  %.9g\n", r["first_facet"].get<std::string>().c_str(), r["k"].get<int>(),
                r["fraction"].get<double>(), r["theta_o_deg"].get<double>());
}

}  // namespace vgroove::app
