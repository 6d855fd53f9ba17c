// PlaneCut: the plane of incidence out of flatland and 3D lobes, checked by hand.
#include "vgroove/validation/plane_cut.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::validation {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(PlaneCut, FlatlandIsEveryBinPerRadian) {
  const PlaneCut p = PlaneCut::flatland(4);
  EXPECT_EQ(p.bins(), 4);
  const std::vector<double> want_deg = {-67.5, -22.5, 22.5, 67.5};
  EXPECT_EQ(p.angles_deg(), want_deg);
  // A quarter of the flux in each bin of pi/4 radians: 1/pi per radian.
  const std::vector<double> d = p.cut([](std::size_t) { return 0.25; });
  ASSERT_EQ(d.size(), 4u);
  for (double v : d) EXPECT_NEAR(v, 1.0 / kPi, 1e-15);
  // Bin order is kept.
  const std::vector<double> n = p.cut([](std::size_t b) { return static_cast<double>(b); });
  EXPECT_NEAR(n[3], 3.0 * 4.0 / kPi, 1e-15);
}

// theta_bins 2 x phi_bins 4: the mirror side is phi bin 0 (bins 4 then 0, from the horizon), the
// light's side phi bin 2 (bins 2 then 6). Each bin's solid angle (pi/2)(cos t0 - cos t1).
TEST(PlaneCut, ThreeDIsTwoPhiBinsPerSteradian) {
  const PlaneCut p = PlaneCut::three_d(2, 4);
  EXPECT_EQ(p.bins(), 8);
  const std::vector<double> want_deg = {-67.5, -22.5, 22.5, 67.5};
  EXPECT_EQ(p.angles_deg(), want_deg);
  const std::vector<double> which = p.cut([](std::size_t n) { return static_cast<double>(n) + 1.0; });
  const double w0 = 0.5 * kPi * (1.0 - std::cos(kPi / 4)), w1 = 0.5 * kPi * std::cos(kPi / 4);
  ASSERT_EQ(which.size(), 4u);
  EXPECT_NEAR(which[0], 5.0 / w1, 1e-13);
  EXPECT_NEAR(which[1], 1.0 / w0, 1e-13);
  EXPECT_NEAR(which[2], 3.0 / w0, 1e-13);
  EXPECT_NEAR(which[3], 7.0 / w1, 1e-13);
  // A lobe uniform per steradian over the hemisphere (flux 1 over 2 pi sr) reads 1 / (2 pi) everywhere.
  const std::vector<double> uniform = p.cut([&](std::size_t n) { return (n < 4 ? w0 : w1) / (2.0 * kPi); });
  for (double v : uniform) EXPECT_NEAR(v, 1.0 / (2.0 * kPi), 1e-15);
}

}  // namespace
}  // namespace vgroove::validation
