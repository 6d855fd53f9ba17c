// Tests of analytic/masking_shadowing.h at values derived by hand: Smith's three joint forms from
// given Lambdas, their order (separable <= height-correlated <= height-direction-correlated, the
// last min(G1_i, G1_o) at the hotspot phi = 0 and nearly the height-correlated one at phi = pi),
// the V-cavity's G2 on a groove's cross-section, and the bin averages: 1 at normal incidence;
// over the whole hemisphere the V-cavity's G1 averages to Smith's 1 / (1 + Lambda) (both keep
// the projected area: int D (o.m)+ G1 dm = cos theta_o = int D (o.m)+ dm / (1 + Lambda), Heitz
// 2014 Eq. 25 and Sec. 3); a bin shrunk onto one normal gives the pointwise G2.
#include "vgroove/analytic/masking_shadowing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace vgroove::analytic {
namespace {

constexpr double kPi = std::numbers::pi, kDeg = kPi / 180.0;

TEST(MaskingShadowing, SmithFormsAtHandValues) {
  EXPECT_EQ(G2_smith_separable(0.0, 0.0), 1.0);
  EXPECT_EQ(G2_smith_height_correlated(0.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(G2_smith_separable(1.0, 0.5), 1.0 / 3.0);                   // (1/2) (2/3)
  EXPECT_DOUBLE_EQ(G2_smith_height_correlated(1.0, 0.5), 0.4);                 // 1 / 2.5
  EXPECT_DOUBLE_EQ(G2_smith_height_direction_correlated(1.0, 0.5, 0.0), 0.5);  // min(G1): 1 / (1 + 1)
  // phi = pi: lambda = 4.41 pi / (4.41 pi + 1) = 0.932680...
  const double l = 4.41 * kPi / (4.41 * kPi + 1.0);
  EXPECT_DOUBLE_EQ(van_ginneken_lambda(kPi), l);
  EXPECT_NEAR(l, 0.93268, 1e-5);  // 13.8544 / 14.8544
  EXPECT_DOUBLE_EQ(G2_smith_height_direction_correlated(1.0, 0.5, kPi), 1.0 / (2.0 + 0.5 * l));
  // Folded onto [0, pi]: the sign and whole turns of the difference do not matter.
  EXPECT_DOUBLE_EQ(van_ginneken_lambda(-0.7), van_ginneken_lambda(0.7));
  EXPECT_NEAR(van_ginneken_lambda(2.0 * kPi + 0.7), van_ginneken_lambda(0.7), 1e-15);
  EXPECT_DOUBLE_EQ(van_ginneken_lambda(2.0 * kPi - 0.7), van_ginneken_lambda(0.7));
  EXPECT_EQ(van_ginneken_lambda(0.0), 0.0);
  // The order of the forms, and the bounds of any joint probability: G1_i + G1_o - 1 <= G2 <= min.
  for (double li : {0.0, 0.05, 0.4, 2.0})
    for (double lo : {0.0, 0.3, 1.5})
      for (double phi : {0.0, 0.5, 1.5, kPi}) {
        const double gi = 1.0 / (1.0 + li), go = 1.0 / (1.0 + lo);
        const double sep = G2_smith_separable(li, lo), hc = G2_smith_height_correlated(li, lo),
                     hdc = G2_smith_height_direction_correlated(li, lo, phi);
        EXPECT_LE(sep, hc * (1.0 + 1e-15));
        EXPECT_LE(hc, hdc * (1.0 + 1e-15));
        EXPECT_LE(hdc, std::min(gi, go) * (1.0 + 1e-15));
        EXPECT_GE(sep, gi + go - 1.0 - 1e-15);
      }
}

// A 45 deg facet tilted towards o at 60 deg (in the plane of its cavity): visible 2 cos 45 cos 60
// / cos 15 = sqrt 3 - 1; the light opposite at 30 deg sees it whole; swapped, the same.
TEST(MaskingShadowing, VCavityG2OnACrossSection) {
  const double m = 45.0 * kDeg, to = 60.0 * kDeg, ti = 30.0 * kDeg;
  const double mx = std::sin(m), mz = std::cos(m);
  const double ox = std::sin(to), oz = std::cos(to), ix = -std::sin(ti), iz = std::cos(ti);
  EXPECT_NEAR(G2_vcavity(ix, 0, iz, ox, 0, oz, mx, 0, mz), std::sqrt(3.0) - 1.0, 1e-15);
  EXPECT_EQ(G2_vcavity(ox, 0, oz, ix, 0, iz, mx, 0, mz), G2_vcavity(ix, 0, iz, ox, 0, oz, mx, 0, mz));
  // The same direction twice: the V-cavity's G1.
  EXPECT_EQ(G2_vcavity(ox, 0, oz, ox, 0, oz, mx, 0, mz), G1_vcavity(ox * mx + oz * mz, oz, mz));
  // The macro normal is never hidden; a facet facing away from one direction carries nothing.
  EXPECT_EQ(G2_vcavity(ix, 0, iz, ox, 0, oz, 0, 0, 1), 1.0);
  EXPECT_EQ(G2_vcavity(-1, 0, 0.01, ox, 0, oz, mx, 0, mz), 0.0);
}

TEST(MaskingShadowing, BinAveragesAtNormalIncidenceAreOne) {
  const NormalBin all{0.0, 0.5 * kPi, -kPi, kPi};
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx}) {
    EXPECT_NEAR(vcavity_g1_bin_average(ndf, 0.6, 0.0, 0.0, all), 1.0, 1e-15);
    EXPECT_NEAR(vcavity_g2_bin_average(ndf, 0.6, 0.0, 0.0, 0.0, 1.0, all), 1.0, 1e-15);
  }
}

// Over the whole hemisphere the V-cavity's G1 averages to Smith's (the projected area, header).
// The quadrature's error: the kinks (min(1, .) and the facing cut) converge slowly; 8 panels of
// 16 nodes against 16 panels differ by < 2e-5 here (printed), so 1e-4 is four times that.
TEST(MaskingShadowing, WholeHemisphereVCavityG1IsSmiths) {
  const NormalBin all{0.0, 0.5 * kPi, -kPi, kPi};
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.3, 1.0})
      for (double theta_deg : {45.0, 70.0, 85.0}) {
        const double t = theta_deg * kDeg;
        const double v8 = vcavity_g1_bin_average(ndf, alpha, t, 0.3, all);
        const double v16 = vcavity_g1_bin_average(ndf, alpha, t, 0.3, all, 16);
        const double smith = 1.0 / (1.0 + Lambda(ndf, t, alpha));
        std::printf("%s alpha %.1f theta %.0f: V-cavity %.7f (16 panels %.7f), Smith %.7f\n", ndf_name(ndf), alpha,
                    theta_deg, v8, v16, smith);
        EXPECT_NEAR(v8, smith, 1e-4) << ndf_name(ndf) << " " << alpha << " " << theta_deg;
      }
}

// A bin shrunk onto one normal: the pointwise V-cavity G2.
TEST(MaskingShadowing, ANarrowBinGivesThePointwiseG2) {
  const double tm = 40.0 * kDeg, pm = 0.2, e = 1e-6;
  const NormalBin tiny{tm - e, tm + e, pm - e, pm + e};
  const double ti = 80.0 * kDeg, pi_ = 0.1, to = 65.0 * kDeg, po = 0.5;
  const double expected = G2_vcavity(std::sin(ti) * std::cos(pi_), std::sin(ti) * std::sin(pi_), std::cos(ti),
                                     std::sin(to) * std::cos(po), std::sin(to) * std::sin(po), std::cos(to),
                                     std::sin(tm) * std::cos(pm), std::sin(tm) * std::sin(pm), std::cos(tm));
  EXPECT_LT(expected, 0.9);  // masked: a value to see
  EXPECT_NEAR(vcavity_g2_bin_average(NdfKind::ggx, 0.5, ti, pi_, to, po, tiny, 1), expected, 1e-5);
}

}  // namespace
}  // namespace vgroove::analytic
