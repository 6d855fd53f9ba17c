// The ranges of validation/ranges.h that are derived from others hold their definitions, and the
// energy tables hold their physics at the edge of theirs.
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/energy_table.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace vgroove::validation {
namespace {

TEST(Ranges, MinMuIsCosOfTheMostGrazingSurfaceLight) {
  // cos(89.9 deg) = sin(0.1 deg), in long double (89.9 as a double is 5.7e-15 deg off).
  EXPECT_EQ(kMaxSurfaceThetaIDeg, 89.9);
  EXPECT_EQ(kMinMu, static_cast<double>(std::sin(0.1L * std::numbers::pi_v<long double> / 180)));
  EXPECT_GE(0.5 / kMaxMuPoints, kMinMu);  // --mu-points' smallest midpoint
  EXPECT_LT(0.5 / (kMaxMuPoints + 1), kMinMu);
}

// At mu = cos 89.9 deg every model cell conserves energy (F = 1: its albedo within 1e-6 of 1,
// never above) with finite orders. Below the range it does not: at mu = 1e-16 (acos rounds to
// 90 deg) the same check fails, which is why the range stops where it does.
TEST(Ranges, EnergyModelConservesEnergyAtTheSmallestMu) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann, NdfKind::phong})
    for (SurfaceDim dim : {SurfaceDim::flatland, SurfaceDim::three_d})
      for (double alpha : {kMinAlpha, 0.5, kMaxAlpha}) {
        SCOPED_TRACE(std::string(ndf_name(ndf)) + (dim == SurfaceDim::flatland ? " flatland" : " 3d") + " alpha " +
                     std::to_string(alpha));
        const EnergyModel m = energy_model({ndf, dim, alpha, kMinMu}, 16);
        EXPECT_LE(m.albedo, 1.0 + 1e-12);
        EXPECT_GE(m.albedo, 1.0 - 1e-6);
        for (double e : m.by_k) EXPECT_TRUE(std::isfinite(e) && e >= -1e-15) << e;
        EXPECT_LE(m.cook_torrance, m.albedo + 1e-12);
      }
  int broken = 0;
  for (SurfaceDim dim : {SurfaceDim::flatland, SurfaceDim::three_d}) {
    const EnergyModel m = energy_model({NdfKind::ggx, dim, 0.5, 1e-16}, 16);
    broken += !(m.albedo <= 1.0 + 1e-12 && m.albedo >= 1.0 - 1e-6);
  }
  EXPECT_GT(broken, 0) << "mu = 1e-16 conserves energy: the check above cannot fail";
}

}  // namespace
}  // namespace vgroove::validation
