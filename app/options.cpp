#include "vgroove/app/options.h"

#include <optional>

namespace vgroove::app {

validation::GrooveParams groove_from(const GrooveArgs& g) {
  if (!g.nonsymmetric) return validation::groove_from_degrees(g.theta_v_deg, std::nullopt, std::nullopt, {});
  return validation::groove_from_degrees(g.theta_v_given ? std::optional<double>(g.theta_v_deg) : std::nullopt,
                                         g.theta_l_deg, g.theta_r_deg, {});
}

}  // namespace vgroove::app
