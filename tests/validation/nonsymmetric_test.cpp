// Nonsymmetric grooves, traced against the model (Lee et al. 2018, Eq. 7-9) off the paper's grid:
// random grooves and incident angles, grooves tilted so far that a facet faces away from the
// light, apertures under 5 deg; and the Jacobian's angular factor (after Eq. 23) from the tracer.
#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/rng.h"
#include "vgroove/validation/groove_case.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vgroove::validation {
namespace {

CaseOptions stratified(long rays) {
  CaseOptions o;
  o.rays = rays;
  o.sampling = sim::Sampling::stratified;
  return o;
}

// With N stratified rays per facet, each zone boundary inside (0, f_a) moves the count of the two
// zones it separates by at most 1/2 ray each: L1 <= (number of interior boundaries) / N. Eq. (9)
// has at most four (f_b, f_2, f_kb, f_ka).
double stratified_bound(long rays) { return 4.0 / static_cast<double>(rays) + 1e-12; }

void expect_agrees(const GrooveParams& g, double theta_i, long rays) {
  const CaseOutcome c = run_case(g, theta_i, stratified(rays), 0);
  const std::string where = "theta_l=" + std::to_string(g.theta_l / kRadPerDeg) +
                            " theta_r=" + std::to_string(g.theta_r / kRadPerDeg) +
                            " theta_i=" + std::to_string(theta_i / kRadPerDeg);
  ASSERT_TRUE(c.facet[0].compared || c.facet[1].compared) << where;
  EXPECT_LE(c.l1, stratified_bound(rays)) << where;
  EXPECT_LE(c.theta_o_error, 1e-9) << where;
  for (const FacetOutcome& f : c.facet) {
    EXPECT_EQ(f.vertex_hits, 0) << where;
    EXPECT_EQ(f.bounce_limit, 0) << where;
    EXPECT_EQ(f.wrong_first, 0) << where;
  }
}

TEST(NonsymmetricTrace, RandomGroovesOffTheGrid) {
  sim::Rng rng(20181106, 3, 0);
  int compared = 0;
  for (int n = 0; n < 300; ++n) {
    const double l = -(0.5 + 89.5 * rng.uniform()) * kRadPerDeg;
    const double r = (0.5 + 89.5 * rng.uniform()) * kRadPerDeg;
    const double ti = (-89.5 + 179.0 * rng.uniform()) * kRadPerDeg;
    const GrooveParams g = GrooveParams::make_nonsymmetric(l, r);
    if (g.degenerate() || g.theta_v < 0.5 * kRadPerDeg) continue;
    expect_agrees(g, ti, 1000);
    ++compared;
  }
  EXPECT_GT(compared, 250);
}

TEST(NonsymmetricTrace, FacetFacingAwayFromTheLight) {
  // theta_l = -85: the left facet is nearly vertical, its normal points almost along +x. Light from
  // theta_i = 40 deg meets it from behind (i . s_l = cos(125 deg) < 0): only the right facet is lit.
  const GrooveParams g = GrooveParams::make_nonsymmetric(-85 * kRadPerDeg, 10 * kRadPerDeg);
  const CaseOutcome c = run_case(g, 40 * kRadPerDeg, stratified(2000), 0);
  EXPECT_FALSE(c.facet[0].compared);
  EXPECT_TRUE(c.facet[1].compared);
  expect_agrees(g, 40 * kRadPerDeg, 2000);
  for (double ti : {-89.0, -60.0, 60.0, 89.0})
    for (auto [l, r] : {std::pair{-89.0, 5.0}, std::pair{-3.0, 80.0}, std::pair{-70.0, 70.0}})
      expect_agrees(GrooveParams::make_nonsymmetric(l * kRadPerDeg, r * kRadPerDeg), ti * kRadPerDeg, 2000);
}

TEST(NonsymmetricTrace, AperturesUnderFiveDegrees) {
  for (double v : {4.9, 2.0, 1.0, 0.5})
    for (double tilt : {-40.0, 0.0, 25.0})
      for (double ti : {-80.0, -30.0, 0.0, 45.0, 85.0}) {
        // theta_l + theta_r = 2 tilt, pi + theta_l - theta_r = v.
        const double l = tilt - 90.0 + 0.5 * v, r = tilt + 90.0 - 0.5 * v;
        if (l >= 0.0 || l < -90.0 || r <= 0.0 || r > 90.0) continue;
        expect_agrees(GrooveParams::make_nonsymmetric(l * kRadPerDeg, r * kRadPerDeg), ti * kRadPerDeg, 1000);
      }
}

TEST(NonsymmetricTrace, SymmetricGroovesThroughBothModels) {
  // The same groove as a symmetric one (Eq. 4-6) and as a nonsymmetric one (Eq. 7-9): the tracer
  // gives the same tally (the geometry is identical up to facet length, which is 1 for both), and
  // both models agree with it.
  for (double v : {3.0, 37.0, 90.0, 151.0})
    for (double ti : {-75.0, -10.0, 0.0, 33.0}) {
      const CaseOutcome a =
          run_case(GrooveParams::make_symmetric(v * kRadPerDeg), ti * kRadPerDeg, stratified(1000), 0);
      const CaseOutcome b =
          run_case(GrooveParams::make_nonsymmetric(-(90.0 - 0.5 * v) * kRadPerDeg, (90.0 - 0.5 * v) * kRadPerDeg),
                   ti * kRadPerDeg, stratified(1000), 0);
      EXPECT_LE(a.l1, stratified_bound(1000)) << "theta_v=" << v << " theta_i=" << ti;
      EXPECT_LE(b.l1, stratified_bound(1000)) << "theta_v=" << v << " theta_i=" << ti;
      EXPECT_NEAR(a.l1, b.l1, 2.0 / 1000) << "theta_v=" << v << " theta_i=" << ti;
    }
}

TEST(NonsymmetricTrace, JacobianAngularFactorFromTheTracer) {
  // Trace one ray through grooves theta_l - h and theta_l + h (theta_r fixed), aimed at the same
  // fraction of the left facet's beam; where it makes the same k reflections, the change of its
  // half-vector angle theta_h = (theta_i + theta_o)/2 per unit theta_l is the printed factor
  // 0.5 |0.5 - (-1)^k (k + 0.5)| (its inverse is |d theta_l / d theta_h| in |ds_l/do|).
  const double r = 40 * kRadPerDeg, h = 1e-7;
  int checked = 0;
  for (double l_deg : {-15.0, -35.0, -60.0, -80.0})
    for (double ti_deg : {-50.0, -10.0, 20.0})
      for (double u : {0.1, 0.35, 0.6, 0.85}) {
        const double l = l_deg * kRadPerDeg, ti = ti_deg * kRadPerDeg;
        double theta_o[2];
        int k[2];
        for (int s = 0; s < 2; ++s) {
          const sim::Groove g = sim::make_nonsymmetric_groove(l + (s ? h : -h), r);
          const sim::Interval aim = sim::aimed_at(g, ti, sim::Side::left);
          const double x = aim.lo + u * aim.width();
          const sim::TraceResult t = sim::trace(g, sim::beam_ray(g, sim::beam_direction(ti), x));
          k[s] = t.how == sim::Termination::escaped && t.first == sim::Side::left ? t.bounces : -1;
          theta_o[s] = sim::angle_from_normal(t.exit_dir);
        }
        if (k[0] < 1 || k[0] != k[1]) continue;  // shadowed, right facet first, or a transition in between
        const double dh = 0.5 * (theta_o[1] - theta_o[0]) / (2 * h);
        EXPECT_NEAR(std::abs(dh), std::abs(analytic::dtheta_h_dtheta_l(k[0])), 1e-6)
            << "k=" << k[0] << " theta_l=" << l_deg << " theta_i=" << ti_deg << " u=" << u;
        ++checked;
      }
  EXPECT_GT(checked, 20);
}

}  // namespace
}  // namespace vgroove::validation
