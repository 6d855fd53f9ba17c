// Tests of the facet distributions (analytic/vndf.h): each density integrates to 1 over the
// normals, the V-cavity's visible normals are the grooves' lit widths, the bounded cap holds every
// reflection above the horizon and not every one below it. (Sampler against density: the
// chi-square tests, tests/analytic/sampling_chi2_test.cpp.)
#include "vgroove/analytic/vndf.h"

#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/common/angles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace vgroove::analytic {
namespace {

constexpr NdfKind kNdfs[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};

double over_normals(double alpha, const auto& pdf, double tol = 1e-9) {
  HemisphereOptions o;
  o.tol = tol;
  o.scale = alpha;
  o.max_pieces = 2000;
  return integrate_hemisphere(Dir3{0.0, 0.0, 1.0}, pdf, o).value;
}

// Normalization by quadrature over the hemisphere of normals (i in the (x, z) plane, so the
// mirror symmetry the quadrature uses holds): 1 to the quadrature's tolerance. The bounded VNDF
// jumps to 0 at its cap's edge, a curve the quadrature's cuts do not follow: 1e-5 there.
void check_normalization(NdfKind ndf, double alpha, double deg) {
  const Dir3 i = dir3(deg * kRadPerDeg, std::numbers::pi);
  EXPECT_NEAR(over_normals(alpha, [&](const Dir3& s) { return projected_ndf_pdf(ndf, alpha, s); }), 1.0, 1e-8)
      << ndf_name(ndf) << " alpha=" << alpha;
  EXPECT_NEAR(over_normals(alpha, [&](const Dir3& s) { return vcavity_vndf_pdf(ndf, alpha, i, s); }), 1.0, 1e-8)
      << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg;
  if (ndf != NdfKind::ggx) return;
  EXPECT_NEAR(over_normals(alpha, [&](const Dir3& m) { return ggx_vndf_pdf(alpha, i, m); }), 1.0, 1e-8)
      << "alpha=" << alpha << " theta_i=" << deg;
  EXPECT_NEAR(over_normals(
                  alpha, [&](const Dir3& m) { return ggx_bounded_vndf_pdf(alpha, i, m); }, 1e-7),
              1.0, 1e-5)
      << "alpha=" << alpha << " theta_i=" << deg;
}

TEST(Vndf, DensitiesIntegrateToOne) {
  for (NdfKind ndf : kNdfs) check_normalization(ndf, 0.5, 40.0);
  check_normalization(NdfKind::ggx, 1.5, 85.0);
}

// The grid (label long): every NDF, alpha 0.1..1.5, theta_i 0..85 deg.
TEST(VndfLong, DensitiesIntegrateToOne) {
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.1, 0.5, 1.0, 1.5})
      for (double deg : {0.0, 40.0, 85.0}) check_normalization(ndf, alpha, deg);
}

TEST(Vndf, FlatlandDensitiesIntegrateToOne) {
  for (NdfKind ndf : kNdfs)
    for (double alpha : {0.1, 0.5, 1.0, 1.5})
      for (double deg : {0.0, 40.0, 85.0}) {
        const double ti = deg * kRadPerDeg;
        auto integral = [&](const auto& f) { return integrate_half_circle(0.0, f, alpha, 1e-11).value; };
        EXPECT_NEAR(integral([&](double t) { return projected_ndf2_pdf(ndf, alpha, t); }), 1.0, 1e-9)
            << ndf_name(ndf) << " alpha=" << alpha;
        EXPECT_NEAR(integral([&](double t) { return vcavity_vndf2_pdf(ndf, alpha, ti, t); }), 1.0, 1e-9)
            << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << deg;
        if (ndf == NdfKind::ggx) {
          EXPECT_NEAR(integral([&](double t) { return ggx_vndf2_pdf(alpha, ti, t); }), 1.0, 1e-9)
              << "alpha=" << alpha << " theta_i=" << deg;
        }
      }
}

// The V-cavity's visible normals are where the light of a groove lands first: for the groove
// whose left facet is s, the share of the incident flux on s is (groove area share) x (lit width
// of s) / (opening width), with the lit width f_a - f_b of Eq. (6) at the projected angle t_i.
TEST(Vndf, VcavityVisibleNormalsAreTheLitWidths) {
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const NdfKind ndf = kNdfs[trial % 3];
    const double alpha = 0.1 + 1.4 * U(g);
    const Dir3 i = dir3(0.5 * std::numbers::pi * U(g), 2.0 * std::numbers::pi * U(g));
    const double theta_m = 0.5 * std::numbers::pi * U(g), phi = 2.0 * std::numbers::pi * U(g);
    const Dir3 s = dir3(theta_m, phi);
    const double ax = std::cos(phi), ay = std::sin(phi), ia = i.x * ax + i.y * ay;
    const double t_i = std::atan2(-ia, i.z), c = std::sqrt(ia * ia + i.z * i.z);
    const FacetPrediction p = G_kaleidoscopic(t_i, std::numbers::pi - 2.0 * theta_m, FacetSide::left);
    const double lit = p.lit ? p.f_a - p.f_b : 0.0;
    // D(s) <i.s> G1 / <i.n> with <i.s> G1 = c (f_a - f_b) (|i.s| = c f_a).
    const double expected = D(ndf, theta_m, alpha) * c * lit / i.z;
    EXPECT_NEAR(vcavity_vndf_pdf(ndf, alpha, i, s), expected, 1e-12 * std::max(1.0, expected))
        << "trial " << trial << " theta_m=" << theta_m;
  }
}

// Tokuyoshi and Eto 2024, Eq. (6) is the infimum over reflections above the horizon: the facet
// h(i, o) of every o above the horizon lies in the cap; for alpha < 1 some facets whose single
// reflection leaves below the horizon do not (the ones the V-groove needs for k >= 2 among them).
TEST(Vndf, BoundedCapHoldsEveryReflectionAboveTheHorizon) {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (double alpha : {0.05, 0.3, 0.7, 1.0, 1.3, 2.0}) {
    int outside_below = 0;
    for (int trial = 0; trial < 4000; ++trial) {
      const Dir3 i = dir3(0.5 * std::numbers::pi * 0.999 * U(g), 2.0 * std::numbers::pi * U(g));
      // (Not at the horizon itself, where the bound is reached and rounding decides.)
      const Dir3 o = dir3(0.5 * std::numbers::pi * 0.999 * U(g), 2.0 * std::numbers::pi * U(g));
      const double hx = i.x + o.x, hy = i.y + o.y, hz = i.z + o.z, l = std::sqrt(hx * hx + hy * hy + hz * hz);
      EXPECT_TRUE(ggx_bounded_vndf_covers(alpha, i, Dir3{hx / l, hy / l, hz / l}))
          << "alpha=" << alpha << " trial " << trial;
      // A facet whose reflection of i leaves below the horizon.
      const Dir3 m = dir3(0.5 * std::numbers::pi * U(g), 2.0 * std::numbers::pi * U(g));
      const double im = i.x * m.x + i.y * m.y + i.z * m.z;
      if (im > 0.0 && 2.0 * im * m.z - i.z < 0.0 && !ggx_bounded_vndf_covers(alpha, i, m)) ++outside_below;
    }
    if (alpha < 1.0) {
      EXPECT_GT(outside_below, 0) << "alpha=" << alpha;
    }
  }
}

// At alpha = 1 the bound is k = 0 for every i: the bounded VNDF cuts the cap at o_z = 0.
TEST(Vndf, BoundedLowerBoundHandValues) {
  const Dir3 n{0.0, 0.0, 1.0};
  EXPECT_EQ(ggx_bounded_vndf_lower_bound(1.0, n), 0.0);
  // Normal incidence, alpha < 1: s = 1, k = (1 - a^2) / (1 + a^2); the bound is -k.
  EXPECT_NEAR(ggx_bounded_vndf_lower_bound(0.5, n), -0.75 / 1.25, 1e-15);
  // alpha > 1: the bound is positive, (a^2 - 1) / (a^2 + 1) (the horizon maps above the equator).
  EXPECT_NEAR(ggx_bounded_vndf_lower_bound(1.5, n), 1.25 / 3.25, 1e-15);
  // The unbounded VNDF's cap at normal incidence is the whole sphere: lower bound -1.
  EXPECT_NEAR(ggx_vndf_norm(0.7, n), 2.0, 1e-15);
}

}  // namespace
}  // namespace vgroove::analytic
