// Tests of analytic/reflectance_table.h: the interpolated reflectance against the exact curves it
// samples (the conductors of data/reference/metals.json as printed there, Schlick's F, a
// dielectric), at 10^6 cosines including both ends; a cubic is reproduced to rounding.
#include "vgroove/analytic/reflectance_table.h"

#include "vgroove/optics/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace vgroove::analytic {
namespace {

TEST(ReflectanceTable, ReproducesACubic) {
  const ReflectanceTable t([](double c) { return 0.3 + c * (0.2 - c * (0.7 - 0.4 * c)); }, 16);
  for (int j = 0; j <= 1000; ++j) {
    const double c = j / 1000.0;
    EXPECT_NEAR(t(c), 0.3 + c * (0.2 - c * (0.7 - 0.4 * c)), 1e-15) << c;
  }
}

TEST(ReflectanceTable, MatchesTheExactCurvesBelow1e12) {
  struct Curve {
    const char* name;
    std::function<double(double)> F;
  };
  // Gold and silver at 450 nm, copper at 650 nm, aluminium at 443 nm (data/reference/metals.json).
  const Curve curves[] = {
      {"Au 450", [](double c) { return optics::fresnel_conductor(c, 1.38, 1.914); }},
      {"Ag 450", [](double c) { return optics::fresnel_conductor(c, 0.04, 2.657); }},
      {"Cu 650", [](double c) { return optics::fresnel_conductor(c, 0.22, 3.747); }},
      {"Al 443", [](double c) { return optics::fresnel_conductor(c, 0.6079, 5.3676); }},
      {"Schlick 0.04", [](double c) { return optics::fresnel_schlick(c, 0.04); }},
      {"glass 1.5", [](double c) { return optics::fresnel_dielectric(c, 1.5); }},
  };
  for (const Curve& cv : curves) {
    const ReflectanceTable t(cv.F);
    double worst = 0.0;
    for (int j = 0; j <= 1000000; ++j) {
      const double c = j / 1e6;
      worst = std::max(worst, std::abs(t(c) - cv.F(c)));
    }
    worst = std::max({worst, std::abs(t(1e-300) - cv.F(0.0)), std::abs(t(1.0) - cv.F(1.0))});
    EXPECT_LT(worst, 1e-12) << cv.name;
    std::printf("%s: largest |table - exact| = %.2e\n", cv.name, worst);
  }
}

}  // namespace
}  // namespace vgroove::analytic
