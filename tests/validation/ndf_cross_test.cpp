// Cross tests: sim/slope_sampling.h and sim/microsurface.h (the slope-space derivation and the
// exact tracer) against analytic/ndf.h (the angle-space formulas). The two sides share no code.
//
//   - pdf: sim::theta_m_pdf = analytic::D2 cos, pointwise;
//   - cdf: sim::theta_m_cdf = the quadrature of analytic::D2 cos;
//   - sampler: sim::sample_theta_m follows analytic::D2 cos (chi-square);
//   - microsurface: at normal incidence the single-bounce exit angles of a procedural surface
//     follow D2 cos (chi-square over the grooves);
//   - masking: the fraction of a facet's projected width that the tracer finds lit is the V-cavity
//     G1 of Lee et al. 2018, Eq. (2).
//
// Conventions (sim/geometry.h, analytic/ndf.h): angles from the normal, counter-clockwise positive.
#include "vgroove/analytic/ndf.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/slope_sampling.h"
#include "vgroove/sim/tracer.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

analytic::NdfKind to_analytic(sim::NdfKind k) {
  switch (k) {
    case sim::NdfKind::beckmann:
      return analytic::NdfKind::beckmann;
    case sim::NdfKind::ggx:
      return analytic::NdfKind::ggx;
    case sim::NdfKind::phong:
      return analytic::NdfKind::phong;
  }
  return analytic::NdfKind::beckmann;
}

const sim::NdfKind kKinds[] = {sim::NdfKind::beckmann, sim::NdfKind::ggx, sim::NdfKind::phong};

// Projected-length density of theta_m by the analytic side.
double d2_cos(sim::NdfKind k, double alpha, double t) { return analytic::D2(to_analytic(k), t, alpha) * std::cos(t); }

// ---------------------------------------------------------------------------------------------
// Numerical helpers (as in tests/sim/microsurface_test.cpp).

using namespace vgroove::test_stats;  // tanh_sinh, gamma_q, ChiSquare, chi_square

// ---------------------------------------------------------------------------------------------
TEST(NdfCross, SimPdfIsAnalyticD2TimesCos) {
  // Two derivations of one density: sim in slope space, P(tan theta) / cos^2 theta, with Student-t
  // and Gaussian constants; analytic in angles, D2(theta) cos(theta). Relative 1e-12: the Phong
  // constants go through lgamma of arguments up to ~400 (alpha = 0.05) from different expressions.
  for (sim::NdfKind k : kKinds)
    for (double alpha : {0.05, 0.3, 0.5, 1.0, 2.0, 0.137})
      for (double t = -1.55; t <= 1.55; t += 0.05) {
        const double s = sim::theta_m_pdf(k, alpha, t), a = d2_cos(k, alpha, t);
        EXPECT_NEAR(s, a, 1e-12 * a + 1e-300) << sim::ndf_name(k) << " alpha=" << alpha << " theta=" << t;
      }
}

TEST(NdfCross, SimCdfIsTheIntegralOfAnalyticD2Cos) {
  // Tolerance: 1e-11 for the quadrature, 4e-8 where Phong (alpha > 1) is singular at -pi/2 (the
  // rounding of std::numbers::pi/2 hides the last 2 sqrt(6.1e-17) = 1.6e-8 of the integral; ndf_test.cpp).
  for (sim::NdfKind k : kKinds)
    for (double alpha : {0.05, 0.3, 1.0, 2.0})
      for (double x : {-6.0, -2.0, -0.5, 0.0, 0.4, 1.5, 4.0}) {
        const double t = std::atan(x * alpha);
        const double q = tanh_sinh([&](double v) { return d2_cos(k, alpha, v); }, -0.5 * std::numbers::pi, t);
        const double tol = k == sim::NdfKind::phong && alpha > 1.0 ? 4e-8 : 1e-11;
        EXPECT_NEAR(sim::theta_m_cdf(k, alpha, t), q, tol) << sim::ndf_name(k) << " alpha=" << alpha << " theta=" << t;
      }
}

TEST(NdfCross, SamplesFollowAnalyticD2Cos) {
  // Roughnesses off the sim test's grid; 3 x 3 cases at level 1e-3 / 9 each. Bins equal in
  // atan(tan(theta)/alpha); expected counts by quadrature of analytic::D2 cos.
  constexpr int n = 100000, bins = 40;
  constexpr double level = 1e-3 / 9.0;
  for (sim::NdfKind k : kKinds)
    for (double alpha : {0.1, 0.7, 1.5}) {
      const std::vector<double> edges = slope_bin_edges(alpha, bins);
      std::vector<double> expected(bins);
      for (int j = 0; j < bins; ++j)
        expected[j] = n * tanh_sinh([&](double v) { return d2_cos(k, alpha, v); }, edges[j], edges[j + 1]);
      std::vector<std::int64_t> observed(bins, 0);
      sim::Rng rng(424242, static_cast<std::uint64_t>(k.family), static_cast<std::uint64_t>(alpha * 1000));
      for (int i = 0; i < n; ++i) {
        const double t = sim::sample_theta_m(k, alpha, rng.uniform());
        const auto it = std::upper_bound(edges.begin(), edges.end(), t);
        ++observed[std::clamp<std::ptrdiff_t>(it - edges.begin() - 1, 0, bins - 1)];
      }
      const ChiSquare c = chi_square_gof(edges, expected, observed);
      EXPECT_GE(c.p, level) << sim::ndf_name(k) << " alpha=" << alpha << ": chi2=" << c.stat << " dof=" << c.dof
                            << " p=" << c.p << "\n"
                            << c.table;
    }
}

TEST(NdfCross, MicrosurfaceSingleBouncesAtNormalIncidenceFollowD2Cos) {
  // theta_i = 0: in a groove with theta_m < 30 deg every ray reflects once and leaves at
  // +-2 theta_m; a single bounce in a steeper groove leaves beyond 60 deg (microsurface_test.cpp).
  // With 8 stratified rays per groove, 4 on each facet, the k = 1 histogram folded onto |theta_o|
  // in [0, 60) deg, divided by 8, counts the grooves by |theta_m| = |theta_o|/2 in 1 deg bins: G
  // independent draws whose law is 2 D2 cos on [0, 30) deg, plus a cell for the rest.
  // 3 NDFs x 2 roughnesses at level 1e-3 / 6 each.
  constexpr int g = 20000;
  constexpr double level = 1e-3 / 6.0;
  for (sim::NdfKind k : kKinds)
    for (double alpha : {0.3, 0.7}) {
      const sim::Microsurface m = sim::make_microsurface({k, alpha, g, 99});
      sim::MicrosurfaceTraceOptions o;
      o.rays = 8 * g;
      o.sampling = sim::Sampling::stratified;
      o.theta_o_bins = 90;  // 2 deg
      const sim::MicrosurfaceTally t = sim::trace_microsurface(m, o);
      ASSERT_EQ(t.escaped, o.rays) << sim::ndf_name(k) << " alpha=" << alpha;
      std::vector<double> edges, expected;
      std::vector<std::int64_t> observed;
      std::int64_t total = 0;
      for (int j = 0; j < 30; ++j) {  // |theta_o| in [2j, 2j + 2) deg: bins 45 + j and 44 - j
        const std::int64_t rays = t.hist(1, 45 + j) + t.hist(1, 44 - j);
        ASSERT_EQ(rays % 8, 0) << sim::ndf_name(k) << " alpha=" << alpha << " bin " << j;
        const double lo = deg(j), hi = deg(j + 1);  // theta_m = theta_o / 2
        edges.push_back(lo);
        expected.push_back(2.0 * g * tanh_sinh([&](double v) { return d2_cos(k, alpha, v); }, lo, hi));
        observed.push_back(rays / 8);
        total += rays / 8;
      }
      edges.push_back(deg(30));
      edges.push_back(deg(90));
      expected.push_back(g * (1.0 - 2.0 * tanh_sinh([&](double v) { return d2_cos(k, alpha, v); }, 0.0, deg(30))));
      observed.push_back(g - total);
      const ChiSquare c = chi_square_gof(edges, expected, observed);
      EXPECT_GE(c.p, level) << sim::ndf_name(k) << " alpha=" << alpha << ": chi2=" << c.stat << " dof=" << c.dof
                            << " p=" << c.p << "\n"
                            << c.table;
    }
}

TEST(NdfCross, TracedLitFractionOfAFacetIsVCavityG1) {
  // Lee et al. 2018, Eq. (2) (Heitz 2014, Eq. (24)): G1(i, m) is the visible fraction of the
  // facets with normal m, seen from i. In a symmetric groove the left facet's normal is at
  // -(pi - theta_v)/2 and the right one's at +(pi - theta_v)/2. N stratified rays spread over a
  // facet's projected width (sim::aimed_at); those that cross the rim line outside the opening
  // are shadowed by the other rim (blocked), the rest hit the facet first. Each ray stands for
  // 1/N of the width and the lit part is one interval, so the traced fraction is within 1/N.
  constexpr long n = 20000;
  for (double tv = 10.0; tv <= 170.0; tv += 20.0)
    for (double ti = -85.0; ti <= 85.0; ti += 10.0) {
      const sim::Groove g = sim::make_symmetric_groove(deg(tv));
      const double theta_i = deg(ti);
      const sim::Vec2 dir = sim::beam_direction(theta_i);
      for (sim::Side side : {sim::Side::left, sim::Side::right}) {
        const double theta_n = (side == sim::Side::left ? -0.5 : 0.5) * (std::numbers::pi - deg(tv));
        // Light along the facet (theta_i = +-theta_v/2 on this grid): no projected width, and Eq. (2)
        // jumps there between 0 (H) and 1 (the limit from the lit side), with cos(pi/2) rounding
        // to 6e-17 choosing the side. No area to weigh: skipped.
        if (std::abs(std::cos(theta_i - theta_n)) < 1e-12) continue;
        const double g1 = analytic::G1_vcavity_inplane(theta_i, theta_n);
        const sim::Interval iv = sim::aimed_at(g, theta_i, side);
        if (!(iv.width() > 0.0)) {
          EXPECT_EQ(g1, 0.0) << "theta_v=" << tv << " theta_i=" << ti << " " << sim::side_name(side);
          continue;
        }
        sim::Rng unused(0, 0, 0);
        long lit = 0;
        for (long j = 0; j < n; ++j) {
          const sim::TraceResult r =
              sim::trace(g, sim::beam_ray(g, dir, sim::sample_position(sim::Sampling::stratified, iv, j, n, unused)));
          if (r.how == sim::Termination::blocked) continue;
          ++lit;
          ASSERT_GT(r.bounces, 0) << "theta_v=" << tv << " theta_i=" << ti << " ray " << j;
          ASSERT_EQ(r.first, side) << "theta_v=" << tv << " theta_i=" << ti << " ray " << j;
        }
        EXPECT_NEAR(static_cast<double>(lit) / n, g1, 1.0 / n + 1e-12)
            << "theta_v=" << tv << " deg, theta_i=" << ti << " deg, " << sim::side_name(side);
      }
    }
}

}  // namespace
}  // namespace vgroove
