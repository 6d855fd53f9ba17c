#include "analytic/brdf_3d.h"

#include <gtest/gtest.h>

#include <cmath>

namespace va = vgroove::analytic;

TEST(Brdf3d, Smoke) {
  const va::Lobe3d L = va::vgroove_lobe_3d(va::NdfKind::ggx, 0.5, 0.5, 45, 36, 16);
  EXPECT_NEAR(L.albedo, 1.0, 1e-9);
}
