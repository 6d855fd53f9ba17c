// Tests of analytic/kaleidoscope_dielectric_lobe.h: the kaleidoscopic dielectric model over an NDF,
// binned. Limits derived by hand (F = 1 is the conductor lobe of brdf_flatland.h / lobe_3d.h;
// eta = 1 transmits everything into the incident direction's bin), conservation (every ray aimed at
// a facet is reflected, transmitted or not binned), the quadrature's stated error against a run
// with four times the nodes, and the model against the exact tracers (sim/dielectric_microsurface.h
// in flatland, the lifted surface in 3D) on procedural surfaces at small alpha, per bin within
// thresholds from the ray count; broken models (eta inverted, Fresnel at the cross-section's angle)
// must fail there.
#include "vgroove/analytic/kaleidoscope_dielectric_lobe.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/dielectric_lifted.h"
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace vgroove::analytic {
namespace {

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

struct Case {
  NdfKind ndf;
  double alpha, eta, theta_i_deg;
};

// ---- Flatland -----------------------------------------------------------------------------------

TEST(KaleidoscopeDielectricLobe, ConductorLimitIsTheFlatlandLobe) {
  // F = 1: every lobe of the model is G_kaleidoscopic's (KD-3), so the reflected rows are
  // brdf_flatland.h's flatland_lobe, integrated there exactly between its breakpoints; here by the
  // sampled cuts and Gauss-Legendre. Rows k <= max_k (flux beyond k_cap is `unresolved` here and
  // the tail row there).
  DielectricLobeOptions o;
  o.reflectance = [](double) { return 1.0; };
  double worst = 0.0, worst_est = 0.0;
  for (const Case& c : {Case{NdfKind::ggx, 0.3, 1.5, 30.0}, Case{NdfKind::beckmann, 0.6, 1.5, -50.0},
                        Case{NdfKind::ggx, 1.0, 0.6, 70.0}, Case{NdfKind::phong, 0.2, 2.4, 0.0}}) {
    const int bins = 90, max_k = 6;
    const DielectricLobe L =
        kaleidoscope_dielectric_lobe_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), bins, max_k, o);
    const FlatlandLobe ref = flatland_lobe(c.ndf, c.alpha, deg(c.theta_i_deg), bins, max_k);
    EXPECT_EQ(L.albedo_t, 0.0);
    for (int k = 0; k <= max_k; ++k)
      for (int b = 0; b < bins; ++b) {
        const double d = std::abs(L.reflected_by_k[k][b] - ref.theta_o_by_k[static_cast<std::size_t>(k) * bins + b]);
        worst = std::max(worst, d);
        EXPECT_LE(d, L.error_estimate) << "alpha=" << c.alpha << " theta_i=" << c.theta_i_deg << " k=" << k
                                              << " bin=" << b;
      }
    worst_est = std::max(worst_est, L.error_estimate);
    EXPECT_NEAR(L.albedo_r + L.shadow_or_unknown, 1.0, 1e-10) << "alpha=" << c.alpha;
  }
  std::printf("F = 1 against flatland_lobe: largest bin difference %.3g (largest stated error %.3g)\n", worst,
              worst_est);
}

TEST(KaleidoscopeDielectricLobe, EtaOneTransmitsIntoTheIncidentBin) {
  // eta = 1: F = 0 at every hit, refraction unbent (KD-3): all light passes at hit 1 along theta_i.
  for (double ti : {-40.0, 0.5, 33.0}) {
    const int bins = 45;
    const DielectricLobe L = kaleidoscope_dielectric_lobe_flatland(NdfKind::ggx, 0.5, 1.0, deg(ti), bins, 4);
    const int b = static_cast<int>(std::floor((deg(ti) + 0.5 * kPi) / (kPi / bins)));
    EXPECT_EQ(L.albedo_r, 0.0);
    EXPECT_NEAR(L.transmitted_by_k[1][b] + L.unresolved, 1.0, 1e-12) << ti;
    EXPECT_NEAR(L.transmitted[b], L.albedo_t, 1e-15) << ti;
    EXPECT_EQ(L.upward, 0.0);
  }
}

TEST(KaleidoscopeDielectricLobe, EnergyIsConserved) {
  // Per facet the model's R + T + shadow = 1 (KD-2) and the facets' lit widths make the opening:
  // the lobes, the upward lobes and the grooves beyond k_cap hold all the light, to quadrature
  // error of the density alone.
  double worst = 0.0;
  for (const Case& c : {Case{NdfKind::ggx, 0.3, 1.5, 30.0}, Case{NdfKind::beckmann, 0.8, 1 / 1.5, -60.0},
                        Case{NdfKind::ggx, 0.1, 1 / 2.4, 10.0}, Case{NdfKind::phong, 1.0, 2.4, 80.0}}) {
    const DielectricLobe L =
        kaleidoscope_dielectric_lobe_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), 60, 4);
    const double e = L.albedo_r + L.albedo_t + L.shadow_or_unknown - 1.0;
    worst = std::max(worst, std::abs(e));
    EXPECT_LT(std::abs(e), 1e-9) << "alpha=" << c.alpha << " eta=" << c.eta << " theta_i=" << c.theta_i_deg;
    double rows = 0.0;
    for (const auto& r : L.reflected_by_k) rows += sum(r);
    for (const auto& r : L.transmitted_by_k) rows += sum(r);
    EXPECT_NEAR(rows, L.albedo_r + L.albedo_t, 1e-13);
    std::printf("%-8s alpha %.1f eta %.3f theta_i %5.1f: R %.5f T %.5f upward %.2e unresolved %.2e (error %.2e)\n",
                c.ndf == NdfKind::ggx ? "ggx" : (c.ndf == NdfKind::beckmann ? "beckmann" : "phong"), c.alpha,
                c.eta, c.theta_i_deg, L.albedo_r, L.albedo_t, L.upward, L.unresolved, L.error_estimate);
  }
  std::printf("largest |R + T + unknown - 1| = %.3g\n", worst);
}

TEST(KaleidoscopeDielectricLobe, StatedErrorBoundsTheChangeWithFourTimesTheNodes) {
  for (const Case& c : {Case{NdfKind::ggx, 0.3, 1.5, 30.0}, Case{NdfKind::beckmann, 0.5, 1 / 1.5, 45.0}}) {
    const DielectricLobe L = kaleidoscope_dielectric_lobe_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), 90, 4);
    DielectricLobeOptions fine;
    fine.order *= 4, fine.samples *= 4, fine.error_estimate = false;
    const DielectricLobe F =
        kaleidoscope_dielectric_lobe_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), 90, 4, fine);
    double d = 0.0;
    for (int b = 0; b < 90; ++b)
      d = std::max({d, std::abs(L.reflected[b] - F.reflected[b]), std::abs(L.transmitted[b] - F.transmitted[b])});
    std::printf("eta %.3f: stated error %.3g, change with 4x nodes %.3g\n", c.eta, L.error_estimate, d);
    EXPECT_LE(d, L.error_estimate) << c.eta;
  }
}

}  // namespace
}  // namespace vgroove::analytic
