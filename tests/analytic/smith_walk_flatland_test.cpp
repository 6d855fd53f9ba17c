// Tests of analytic/smith_walk_flatland.h: the flatland Smith random walk (Heitz et al. 2016).
//
// - The visible projected length A(v) against its quadrature and against the projected-area
//   constraint: cos theta (1 + Lambda) for an upward view, |cos theta| Lambda(-v) downward.
// - Matched pair: the visible-normal pdf integrates to 1 and the sampler inverts its
//   distribution function (quadrature of the pdf up to sample(u) is u), for views up, down,
//   level and grazing, Beckmann and GGX.
// - Free paths by hand: the escape threshold xi = C1^Lambda, heights that move the right way.
// - The walk: every path leaves (F = 1: albedo 1), finite; its single-scattering lobe (k = 1)
//   follows the flatland microfacet BRDF with the height-correlated G2 (chi-square over bins,
//   pooled, p above 1e-3 / tests) and not the separable G2 (power).
#include "vgroove/analytic/smith_walk_flatland.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace vgroove::analytic {
namespace {

using namespace vgroove::test_stats;

double deg(double d) { return d * std::numbers::pi / 180.0; }
constexpr double kHalfPi = 0.5 * std::numbers::pi;

// A uniform stream for the walk (SplitMix64; (0, 1) open).
using vgroove::test_stats::Uniforms;

// The support of D_v within (-pi/2, pi/2): where cos(theta_v - m) > 0, split at its ends and at
// the NDF's peak m = 0.
std::vector<double> support_breaks(double theta_v) {
  std::vector<double> b{-kHalfPi, 0.0};
  for (double e :
       {theta_v - kHalfPi, theta_v + kHalfPi, theta_v - 1.5 * std::numbers::pi, theta_v + 1.5 * std::numbers::pi})
    if (e > -kHalfPi && e < kHalfPi) b.push_back(e);
  b.push_back(kHalfPi);
  std::sort(b.begin(), b.end());
  return b;
}
double integrate_pdf(NdfKind ndf, double alpha, double theta_v, double lo, double hi) {
  double sum = 0.0;
  const std::vector<double> b = support_breaks(theta_v);
  for (std::size_t j = 0; j + 1 < b.size(); ++j) {
    const double a = std::max(lo, b[j]), c = std::min(hi, b[j + 1]);
    if (c > a) sum += tanh_sinh([&](double m) { return visible_normal_pdf(ndf, alpha, theta_v, m); }, a, c);
  }
  return sum;
}

const double kViewsDeg[] = {-179.0, -135.0, -91.0, -89.99, -60.0, -1e-6, 0.0, 30.0, 75.0, 90.0, 120.0, 178.0, 180.0};

TEST(SmithWalkFlatland, VisibleProjectedLengthIsTheProjectedAreaConstraint) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.1, 0.5, 1.0, 2.0})
      for (double vd : kViewsDeg) {
        const double t = deg(vd);
        const double A = visible_projected_length(ndf, alpha, t);
        double quad = 0.0;
        const std::vector<double> b = support_breaks(t);
        for (std::size_t j = 0; j + 1 < b.size(); ++j)
          quad +=
              tanh_sinh([&](double m) { return std::max(0.0, std::cos(t - m)) * D2(ndf, m, alpha); }, b[j], b[j + 1]);
        EXPECT_NEAR(A, quad, 1e-10 * std::max(1.0, quad)) << ndf_name(ndf) << " alpha=" << alpha << " view=" << vd;
        const double c = std::cos(t);
        const double constraint = c > 0.0 ? c * (1.0 + Lambda(ndf, t, alpha)) : -c * Lambda(ndf, t, alpha);
        EXPECT_NEAR(A, constraint, 1e-12 * std::max(1.0, constraint))
            << ndf_name(ndf) << " alpha=" << alpha << " view=" << vd;
      }
}

TEST(SmithWalkFlatland, VisibleNormalSamplerInvertsItsDistribution) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.1, 0.5, 1.0, 2.0})
      for (double vd : kViewsDeg) {
        const double t = deg(vd);
        // A view within rounding of straight down sees a sliver of normals at the edge that no
        // quadrature resolves (the walk never asks: a ray going straight up leaves).
        if (!(visible_projected_length(ndf, alpha, t) > 1e-6)) continue;
        EXPECT_NEAR(integrate_pdf(ndf, alpha, t, -kHalfPi, kHalfPi), 1.0, 1e-9)
            << ndf_name(ndf) << " alpha=" << alpha << " view=" << vd;
        double prev = -kHalfPi;
        for (double u : {1e-9, 0.01, 0.2, 0.5, 0.77, 0.99, 1.0 - 1e-9}) {
          const double m = sample_visible_normal(ndf, alpha, t, u);
          ASSERT_TRUE(std::isfinite(m));
          EXPECT_GE(m, prev) << "monotone";
          prev = m;
          EXPECT_GT(std::cos(t - m), -1e-12) << "visible";
          EXPECT_NEAR(integrate_pdf(ndf, alpha, t, -kHalfPi, m), u, 2e-9)
              << ndf_name(ndf) << " alpha=" << alpha << " view=" << vd << " u=" << u;
        }
      }
}

TEST(SmithWalkFlatland, FreePathsByHand) {
  const double alpha = 0.6, up = deg(50), down = deg(-130);
  const double lambda = Lambda(NdfKind::ggx, up, alpha);
  const double lc = std::log(0.3);
  // Up: leaves exactly when xi < C1^Lambda.
  const double threshold = std::pow(0.3, lambda);
  EXPECT_TRUE(std::isinf(walk_free_path(NdfKind::ggx, alpha, lc, up, 0.999 * threshold)));
  const double h = walk_free_path(NdfKind::ggx, alpha, lc, up, 1.001 * threshold);
  EXPECT_GT(h, lc);  // met higher up
  EXPECT_LE(h, 0.0);
  // Up from above the whole surface (C1 = 1): always leaves.
  EXPECT_TRUE(std::isinf(walk_free_path(NdfKind::ggx, alpha, 0.0, up, 0.999999)));
  // Straight up: Lambda = 0, leaves from any height.
  EXPECT_TRUE(std::isinf(walk_free_path(NdfKind::beckmann, alpha, lc, 0.0, 0.999999)));
  // Down: always meets the surface below: C1' = C1 xi^(1 / (1 + Lambda)).
  EXPECT_NEAR(walk_free_path(NdfKind::ggx, alpha, lc, down, 0.25), lc + std::log(0.25) / (1.0 + lambda), 1e-15);
  // Straight down: C1' = C1 xi.
  EXPECT_NEAR(walk_free_path(NdfKind::beckmann, alpha, lc, std::numbers::pi, 0.25), lc + std::log(0.25), 1e-15);
}

// The single-scattering share of the flux into each theta_o bin.
std::vector<double> single_bins(NdfKind ndf, double alpha, double theta_i, int bins, bool correlated) {
  const double li = Lambda(ndf, theta_i, alpha), w = std::numbers::pi / bins;
  std::vector<double> p;
  for (int b = 0; b < bins; ++b)
    p.push_back(tanh_sinh(
        [&](double to) {
          const double h = 0.5 * (theta_i + to), lo = Lambda(ndf, to, alpha);
          const double g2 = correlated ? 1.0 / (1.0 + li + lo) : 1.0 / ((1.0 + li) * (1.0 + lo));
          return D2(ndf, h, alpha) * std::cos(theta_i - h) * g2 / (2.0 * std::cos(theta_i));
        },
        -kHalfPi + b * w, -kHalfPi + (b + 1) * w));
  return p;
}

TEST(SmithWalkFlatland, SingleScatteringIsTheHeightCorrelatedMicrofacetBrdf) {
  constexpr int kBins = 36, kPaths = 100000;
  struct Case {
    NdfKind ndf;
    double alpha, theta_i_deg;
  };
  const Case cases[] = {{NdfKind::beckmann, 0.3, 0.0},
                        {NdfKind::beckmann, 1.0, 60.0},
                        {NdfKind::ggx, 0.5, 30.0},
                        {NdfKind::ggx, 1.0, 80.0}};
  for (const Case& c : cases) {
    const double ti = deg(c.theta_i_deg);
    Uniforms u{static_cast<std::uint64_t>(c.alpha * 1000 + c.theta_i_deg)};
    std::vector<std::int64_t> k1(kBins, 0);
    std::int64_t left = 0, bounces = 0;
    for (int n = 0; n < kPaths; ++n) {
      const FlatlandWalk w = smith_walk_flatland(c.ndf, c.alpha, ti, u);
      ASSERT_TRUE(w.left);
      ASSERT_TRUE(std::isfinite(w.theta_o));
      ASSERT_LT(std::abs(w.theta_o), kHalfPi + 1e-15);
      ++left, bounces += w.k;
      if (w.k == 1)
        ++k1[static_cast<std::size_t>(
            std::clamp(static_cast<int>((w.theta_o + kHalfPi) / (std::numbers::pi / kBins)), 0, kBins - 1))];
    }
    EXPECT_EQ(left, kPaths);  // F = 1: albedo 1
    EXPECT_GE(bounces, kPaths);
    std::vector<double> edges;
    for (int b = 0; b <= kBins; ++b) edges.push_back(-kHalfPi + b * std::numbers::pi / kBins);
    // Cells: the k = 1 bins and one cell for k >= 2 (the rest of the unit flux).
    auto fit_of = [&](bool correlated) {
      std::vector<double> e = single_bins(c.ndf, c.alpha, ti, kBins, correlated);
      double s = 0.0;
      for (double& x : e) s += x, x *= kPaths;
      std::vector<std::int64_t> o(k1);
      std::int64_t rest = kPaths;
      for (auto x : k1) rest -= x;
      e.push_back(kPaths * (1.0 - s));
      o.push_back(rest);
      edges.push_back(edges.back() + 1.0);
      const ChiSquare f = chi_square_gof(edges, e, o);
      edges.pop_back();
      return f;
    };
    const ChiSquare fit = fit_of(true);
    EXPECT_GT(fit.p, 1e-3 / 4) << ndf_name(c.ndf) << " alpha=" << c.alpha << " theta_i=" << c.theta_i_deg
                               << " chi2=" << fit.stat << "/" << fit.dof << "\n"
                               << fit.table;
    // Power: where Lambda(i) Lambda(o) is large the separable G2 is rejected at the same level.
    if (c.alpha >= 1.0) {
      EXPECT_LT(fit_of(false).p, 1e-3 / 4) << "power: the separable G2 " << ndf_name(c.ndf) << " alpha=" << c.alpha;
    }
  }
}

TEST(SmithWalkFlatland, HardCasesStayFinite) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.01, 2.0})
      for (double ti : {0.0, 89.9, 89.99}) {
        Uniforms u{7};
        for (int n = 0; n < 2000; ++n) {
          const FlatlandWalk w = smith_walk_flatland(ndf, alpha, deg(ti), u);
          ASSERT_TRUE(w.left) << ndf_name(ndf) << " " << alpha << " " << ti;
          ASSERT_TRUE(std::isfinite(w.theta_o)) << ndf_name(ndf) << " " << alpha << " " << ti;
          ASSERT_LE(std::abs(w.theta_o), kHalfPi);
        }
      }
}

}  // namespace
}  // namespace vgroove::analytic
