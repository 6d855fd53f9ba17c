// Tests of validation/profile_masking.h over sim/profile_visibility.h: masking and shadowing
// traced on polyline profiles against Smith and V-cavity (Heitz 2014, Sec. 2, 5, 6).
//
// - V-groove profiles (the procedural microsurface of sim/microsurface.h as a polyline): the
//   V-cavity G1(o, m) and G2 = min(G1(o, m), G1(i, m)) and the lit length are exact, so the traced
//   counts pass the chi-square against them (p above 1e-3 over the number of tests); Smith's
//   G1 is rejected by the same counts at grazing view (the power of the test).
// - Every profile: the projected-area identity (every ray's first hit is a front-facing segment,
//   so the traced average G1 is exactly 1 / (1 + Lambda) of the profile's own normals).
// - Gaussian (Beckmann) profiles: what Heitz 2014 says of correlated surfaces, measured: the
//   V-cavity G1 is rejected, and G1(o, m) grows as the facet turns towards the viewer (Sec. 6.2:
//   "the normals oriented toward the view direction are the most visible"), which Smith's
//   m-independent G1 (Eq. 10) does not have.
#include "vgroove/validation/profile_masking.h"

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/random_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace vgroove::validation {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

struct Traced {
  sim::VisibilityTally from_o, from_i;
};
Traced trace_both(const sim::Polyline& p, double theta_i, double theta_o, std::int64_t rays) {
  sim::VisibilityOptions vo;
  vo.theta_view = theta_o, vo.theta_light = theta_i, vo.rays = rays, vo.seed = 11;
  sim::VisibilityOptions vi;
  vi.theta_view = theta_i, vi.rays = rays, vi.seed = 12;
  return {sim::trace_visibility(p, vo), sim::trace_visibility(p, vi)};
}

sim::Polyline vgroove_profile(NdfKind ndf, double alpha, int grooves) {
  sim::MicrosurfaceOptions mo;
  mo.ndf = ndf, mo.alpha = alpha, mo.grooves = grooves, mo.seed = 5;
  return sim::vgroove_polyline(sim::make_microsurface(mo).theta_m);
}

sim::Polyline gaussian_profile(double alpha, int segments) {
  sim::RandomProfileOptions o;
  o.ndf = NdfKind::beckmann, o.alpha = alpha, o.segments = segments, o.seed = 6;
  return sim::make_random_profile(o);
}

struct Pair {
  double theta_i_deg, theta_o_deg;
};
constexpr Pair kPairs[] = {{0, 0}, {-40, 40}, {30, 60}, {-70, 85}, {70, 70}};
constexpr int kTests = 2 * 2 * 5 * 4;  // ndf x alpha x pairs x (G1, G2, lit, lit per arc length)

TEST(ProfileMasking, VCavityIsExactOnVGrooveProfiles) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.3, 1.0}) {
      const sim::Polyline p = vgroove_profile(ndf, alpha, 2000);
      for (const Pair& pr : kPairs) {
        const MaskingCase c{ndf, alpha, deg(pr.theta_i_deg), deg(pr.theta_o_deg), 18};
        const Traced t = trace_both(p, c.theta_i, c.theta_o, 100000);
        const MaskingMeasure m = measure_masking(p, c, t.from_o, t.from_i);
        std::ostringstream where;
        where << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << pr.theta_i_deg << " theta_o=" << pr.theta_o_deg;
        EXPECT_EQ(m.lost, 0) << where.str();
        EXPECT_GT(m.g1_chi2.p, 1e-3 / kTests) << where.str() << " chi2=" << m.g1_chi2.stat << "/" << m.g1_chi2.dof;
        EXPECT_GT(m.g2_chi2.p, 1e-3 / kTests) << where.str() << " chi2=" << m.g2_chi2.stat << "/" << m.g2_chi2.dof;
        EXPECT_NEAR(m.lit_traced, m.lit_vcavity, 4.5 * m.lit_traced_sd + 1e-12) << where.str();
        EXPECT_NEAR(m.lit_arc_traced, m.lit_arc_vcavity, 4.5 * m.lit_arc_traced_sd + 1e-12) << where.str();
        // The V-cavity average is the identity on V-grooves (its Eq. 5), to rounding.
        EXPECT_NEAR(m.g1_average_vcavity, m.g1_identity, 1e-12) << where.str();
      }
    }
}

// Smith's illuminated fraction is per unit macro length (Smith 1967; Heitz 2014, Sec. 5). On a
// profile of grooves of half-angles 20 and 60 deg (equal widths) lit from -45 deg, by hand:
// the 20 deg groove is lit whole (20 + 45 <= 90: no facet turns its back to the light); of the
// 60 deg one only the facet turned towards the light, cut by the shadow of the near rim, to
// cos 60 cos 45 / cos(60 - 45) of the groove's width (Heitz 2014, Eq. 24). Per macro length
// (1 + 0.36603) / 2 = 0.68301; per arc length the 60 deg groove's facets are longer by
// cos 20 / cos 60, (1/cos 20 + 0.36603/cos 60) / (1/cos 20 + 1/cos 60) = 0.58620.
TEST(ProfileMasking, LitFractionIsPerMacroLengthAndPerArcLengthByHand) {
  const double t20 = deg(20), t60 = deg(60), ti = deg(-45);
  std::vector<double> theta_m;
  for (int g = 0; g < 500; ++g) theta_m.push_back(g % 2 == 0 ? t20 : t60);
  const sim::Polyline p = sim::vgroove_polyline(theta_m);
  const double lit60 = std::cos(t60) * std::cos(ti) / std::cos(t60 + ti);
  const double macro = 0.5 * (1.0 + lit60);
  const double arc = (1.0 / std::cos(t20) + lit60 / std::cos(t60)) / (1.0 / std::cos(t20) + 1.0 / std::cos(t60));
  ASSERT_NEAR(macro, 0.68301, 1e-5);
  ASSERT_NEAR(arc, 0.58620, 1e-5);
  const MaskingCase c{NdfKind::ggx, 0.7, ti, -ti, 18};
  const Traced t = trace_both(p, c.theta_i, c.theta_o, 200000);
  const MaskingMeasure m = measure_masking(p, c, t.from_o, t.from_i);
  EXPECT_EQ(m.lost, 0);
  EXPECT_NEAR(m.lit_traced, macro, 5.0 * m.lit_traced_sd) << "sd " << m.lit_traced_sd;
  EXPECT_NEAR(m.lit_arc_traced, arc, 5.0 * m.lit_arc_traced_sd) << "sd " << m.lit_arc_traced_sd;
  EXPECT_NEAR(m.lit_vcavity, macro, 1e-12);
  EXPECT_NEAR(m.lit_arc_vcavity, arc, 1e-12);
  // Smith: a facing point is lit with probability 1 / (1 + Lambda) (Eq. 10); three of the four
  // facets (the 60 deg groove's far one turns its back) face the light, each a quarter of the width.
  const double g1 = 1.0 / (1.0 + analytic::Lambda(c.ndf, ti, c.alpha));
  EXPECT_NEAR(m.lit_smith, 0.75 * g1, 1e-12);
  EXPECT_NEAR(m.lit_arc_smith,
              (2.0 / std::cos(t20) + 1.0 / std::cos(t60)) / (2.0 / std::cos(t20) + 2.0 / std::cos(t60)) * g1, 1e-12);
}

// A flat profile (grooves of half-angle 0) is lit whole per macro length at any angle below 90.
TEST(ProfileMasking, FlatProfileIsLitWhole) {
  const sim::Polyline p = sim::vgroove_polyline(std::vector<double>(64, 0.0));
  for (double theta : {0.0, 40.0, 80.0, 89.0}) {
    const MaskingCase c{NdfKind::beckmann, 0.5, deg(-theta), deg(theta), 18};
    const Traced t = trace_both(p, c.theta_i, c.theta_o, 20000);
    const MaskingMeasure m = measure_masking(p, c, t.from_o, t.from_i);
    EXPECT_NEAR(m.lit_traced, 1.0, 1e-12) << theta;
    EXPECT_NEAR(m.lit_arc_traced, 1.0, 1e-12) << theta;
    EXPECT_NEAR(m.lit_vcavity, 1.0, 1e-12) << theta;
  }
}

TEST(ProfileMasking, SmithIsRejectedOnVGrooveProfilesAtGrazingView) {
  // The power of the chi-square above: the same kind of counts against Smith's G1 per bin.
  const sim::Polyline p = vgroove_profile(NdfKind::beckmann, 1.0, 2000);
  const MaskingCase c{NdfKind::beckmann, 1.0, deg(-70), deg(70), 18};
  const Traced t = trace_both(p, c.theta_i, c.theta_o, 100000);
  const MaskingMeasure m = measure_masking(p, c, t.from_o, t.from_i);
  std::vector<double> expected, observed;
  for (int b = 0; b < m.bins; ++b) {
    const std::size_t bb = static_cast<std::size_t>(b);
    expected.push_back(100000.0 * m.g1_smith * m.g1_weight[bb]);
    observed.push_back(m.g1_weight[bb] > 0.0 ? 100000.0 * m.g1_traced[bb] * m.g1_weight[bb] : 0.0);
  }
  EXPECT_LT(chi_square(expected, observed).p, 1e-10);
  EXPECT_GT(m.g1_chi2.p, 1e-3);
}

TEST(ProfileMasking, ProjectedAreaIdentityHoldsOnEveryProfile) {
  sim::RandomProfileOptions g;
  g.ndf = NdfKind::ggx, g.alpha = 0.8, g.segments = 1 << 13, g.seed = 2;
  const sim::Polyline profiles[] = {gaussian_profile(0.5, 1 << 13), sim::make_random_profile(g),
                                    vgroove_profile(NdfKind::ggx, 0.8, 1000)};
  for (const sim::Polyline& p : profiles)
    for (double theta : {0.0, 45.0, 80.0, 89.0}) {
      const MaskingCase c{analytic::NdfKind::beckmann, 0.5, deg(-theta), deg(theta), 18};
      const Traced t = trace_both(p, c.theta_i, c.theta_o, 20000);
      const MaskingMeasure m = measure_masking(p, c, t.from_o, t.from_i);
      EXPECT_EQ(m.lost, 0) << theta;
      EXPECT_NEAR(m.g1_average_traced, m.g1_identity, 1e-12 * m.g1_identity) << theta;
      EXPECT_LE(m.g1_identity, 1.0 + 1e-15);
    }
}

TEST(ProfileMasking, GaussianProfilesSeeFacetsTurnedTowardsTheViewerMore) {
  const sim::Polyline p = gaussian_profile(0.5, 1 << 15);
  const MaskingCase c{analytic::NdfKind::beckmann, 0.5, deg(-70), deg(70), 18};
  const Traced t = trace_both(p, c.theta_i, c.theta_o, 200000);
  const MaskingMeasure m = measure_masking(p, c, t.from_o, t.from_i);
  EXPECT_EQ(m.lost, 0);
  EXPECT_LT(m.g1_chi2.p, 1e-10);  // the V-cavity G1 does not describe this surface
  // Bins of 10 deg: [-20, -10) (facing the viewer at 80-90 deg from it) against [30, 40)
  // (30-40 deg from it). Binomial standard deviations from the counts.
  auto sd = [&](int b) {
    const double w = m.g1_weight[static_cast<std::size_t>(b)], g = m.g1_traced[static_cast<std::size_t>(b)];
    return std::sqrt(g * w * (1.0 - g * w) / 200000.0) / w;
  };
  const int turned_away = 7, turned_towards = 12;
  const double diff = m.g1_traced[turned_towards] - m.g1_traced[turned_away];
  EXPECT_GT(diff, 10.0 * std::hypot(sd(turned_away), sd(turned_towards)))
      << m.g1_traced[turned_away] << " vs " << m.g1_traced[turned_towards];
}

}  // namespace
}  // namespace vgroove::validation
