#include "vgroove/analytic/smith_walk_flatland_dielectric.h"

#include <cmath>
#include <numbers>

namespace vgroove::analytic {

double log1m_exp(double lc) {
  // Maechler's rule: expm1 near 0, log1p far from it (each without cancellation on its side).
  return lc > -std::numbers::ln2 ? std::log(-std::expm1(lc)) : std::log1p(-std::exp(lc));
}

}  // namespace vgroove::analytic
