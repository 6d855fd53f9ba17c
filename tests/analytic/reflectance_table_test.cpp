// Tests of analytic/reflectance_table.h: the interpolated reflectance against the exact curves it
// samples (the conductors of data/reference/metals.json as printed there, Schlick's F, a
// dielectric), at 10^6 cosines including both ends; a cubic is reproduced to rounding.
#include "vgroove/analytic/reflectance_table.h"

#include "vgroove/optics/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <vector>

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
  // The twelve rows of data/reference/metals.json (Au, Ag, Cu at 450.9, 548.6, 659.5 nm; Al at
  // 442.8, 563.57, 652.25 nm), Schlick's F and glass.
  const double eta[12] = {1.38, 0.43, 0.14, 0.04, 0.06, 0.05, 1.24, 1.02, 0.22, 0.6079, 1.0728, 1.5724};
  const double kappa[12] = {1.914, 2.455, 3.697, 2.657, 3.586, 4.483, 2.397, 2.577, 3.747, 5.3676, 6.7839, 7.7354};
  std::vector<Curve> curves;
  for (int j = 0; j < 12; ++j)
    curves.push_back(
        {"metals.json row", [&eta, &kappa, j](double c) { return optics::fresnel_conductor(c, eta[j], kappa[j]); }});
  curves.push_back({"Schlick 0.04", [](double c) { return optics::fresnel_schlick(c, 0.04); }});
  curves.push_back({"glass 1.5", [](double c) { return optics::fresnel_dielectric(c, 1.5); }});
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
