// Tests of sim/partner_sampling.h: the laws of a nonsymmetric groove's second facet (densities
// normalized, distribution functions their integrals, draws that follow them by chi-square), and
// the claim of Lee et al. 2018, Eq. (18)-(19): a surface built from independent (theta_l,
// theta_r) pairs, theta_l from the NDF and theta_r from Eq. (20), with both rims on the
// macrosurface, has its facet normals distributed by the NDF in projected area.
//
// The claim's test builds the surface as the paper describes it: each groove's first facet has
// the projected width 1 and its tilt drawn from the NDF's tilt law q (a facet under a uniform point
// of the macrosurface), the second facet's tilt is drawn independently, and its width follows from
// the equal rim heights (tan a / tan b). Points drawn uniformly along the surface's length then
// land on facets whose tilts must follow q (the facets of either side). The surface has G = 50 N
// grooves, so the finite surface's own deviation from the law (of relative size ~ 1/sqrt(G), the
// widths having at most a logarithmically divergent variance) adds about N / G = 2 % to the
// chi-square statistic. The power test draws the second tilt from q itself (the naive
// independent surface): its second facets are flatter than q in projected area, and the same test
// rejects it.
#include "vgroove/sim/partner_sampling.h"

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/sim/slope_sampling.h"

#include "tests/param_names.h"
#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

namespace vgroove::sim {
namespace {

using vgroove::test_stats::chi_square_gof;
using vgroove::test_stats::tanh_sinh;
constexpr double kHalfPi = 0.5 * std::numbers::pi;

using KindAlpha = std::tuple<NdfKind, double>;
std::string kind_alpha_name(const testing::TestParamInfo<KindAlpha>& info) {
  return std::string(ndf_name(std::get<0>(info.param))) + "_a" +
         vgroove::test_names::name_text(std::get<1>(info.param));
}

// Edges of `bins` cells of equal probability under the distribution function F on [0, pi/2].
std::vector<double> equiprobable_edges(const std::function<double(double)>& F, int bins) {
  std::vector<double> edges{0.0};
  for (int j = 1; j < bins; ++j) {
    double lo = 0.0, hi = kHalfPi;
    for (int it = 0; it < 100; ++it) {
      const double mid = 0.5 * (lo + hi);
      (F(mid) < static_cast<double>(j) / bins ? lo : hi) = mid;
    }
    edges.push_back(0.5 * (lo + hi));
  }
  edges.push_back(kHalfPi);
  return edges;
}

std::vector<std::int64_t> histogram(const std::vector<double>& edges, const std::vector<double>& x) {
  std::vector<std::int64_t> h(edges.size() - 1, 0);
  for (double v : x) {
    const auto j = std::upper_bound(edges.begin(), edges.end(), v) - edges.begin() - 1;
    ++h[static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(j, 0, static_cast<std::ptrdiff_t>(h.size()) - 1))];
  }
  return h;
}

std::vector<double> expected_counts(const std::function<double(double)>& F, const std::vector<double>& edges,
                                    double n) {
  std::vector<double> e;
  for (std::size_t j = 0; j + 1 < edges.size(); ++j) e.push_back(n * (F(edges[j + 1]) - F(edges[j])));
  return e;
}

class PartnerSampling : public testing::TestWithParam<KindAlpha> {};

TEST_P(PartnerSampling, DensitiesIntegrateToTheirDistributionFunctions) {
  const auto [kind, alpha] = GetParam();
  for (double t : {0.05, 0.3, 0.8, 1.2, 1.5}) {
    const double F3 = tanh_sinh([&](double x) { return theta_r_pdf_3d(kind, alpha, x); }, 0.0, t);
    EXPECT_NEAR(F3, theta_r_cdf_3d(kind, alpha, t), 1e-10) << ndf_name(kind) << " alpha=" << alpha << " t=" << t;
    const double F2 = tanh_sinh([&](double x) { return theta_r_pdf(kind, alpha, x); }, 0.0, t);
    EXPECT_NEAR(F2, theta_r_cdf(kind, alpha, t), 1e-10) << ndf_name(kind) << " alpha=" << alpha << " t=" << t;
  }
  // The last ulp below pi/2 (6.1e-17 rad) holds the tail mass ~ (6.1e-17)^(p+1) of Phong's cos^p,
  // 3e-11 at alpha = 1.1 (p = -0.35).
  EXPECT_NEAR(theta_r_cdf_3d(kind, alpha, std::nextafter(kHalfPi, 0.0)), 1.0, 1e-10);
  EXPECT_NEAR(theta_r_cdf(kind, alpha, std::nextafter(kHalfPi, 0.0)), 1.0, 1e-10);
}

// Flatland's inverse is exact: cdf(sample(u)) = u.
TEST_P(PartnerSampling, FlatlandInverseInvertsTheDistributionFunction) {
  const auto [kind, alpha] = GetParam();
  for (double u : {1e-9, 0.01, 0.3, 0.5, 0.9, 0.999}) {
    const double t = sample_theta_r(kind, alpha, u);
    // The rounding of t (a few ulps) times the density, plus that of u.
    const double tol = 1e-14 + 4.0 * std::numeric_limits<double>::epsilon() * t * theta_r_pdf(kind, alpha, t);
    EXPECT_NEAR(theta_r_cdf(kind, alpha, t), u, tol) << ndf_name(kind) << " alpha=" << alpha << " u=" << u;
  }
}

// 20,000 draws in 40 cells of equal probability, both dimensions; 18 parameter sets x 2 tests:
// each passes above p = 1e-4.
TEST_P(PartnerSampling, DrawsFollowTheLawByChiSquare) {
  const auto [kind, alpha] = GetParam();
  const int n = 20000, bins = 40;
  std::vector<double> x3, x2;
  for (int j = 0; j < n; ++j) {
    Rng rng(7, 11, static_cast<std::uint64_t>(j));
    x3.push_back(sample_theta_r_3d(kind, alpha, rng));
    x2.push_back(sample_theta_r(kind, alpha, uniform_open(rng)));
  }
  auto F3 = [&](double t) { return theta_r_cdf_3d(kind, alpha, t); };
  auto F2 = [&](double t) { return theta_r_cdf(kind, alpha, t); };
  const auto e3 = equiprobable_edges(F3, bins), e2 = equiprobable_edges(F2, bins);
  const auto c3 = chi_square_gof(e3, expected_counts(F3, e3, n), histogram(e3, x3));
  const auto c2 = chi_square_gof(e2, expected_counts(F2, e2, n), histogram(e2, x2));
  EXPECT_GT(c3.p, 1e-4) << ndf_name(kind) << " alpha=" << alpha << " 3D chi2=" << c3.stat << "\n" << c3.table;
  EXPECT_GT(c2.p, 1e-4) << ndf_name(kind) << " alpha=" << alpha << " flatland chi2=" << c2.stat << "\n" << c2.table;
}

INSTANTIATE_TEST_SUITE_P(Grid, PartnerSampling,
                         testing::Combine(testing::Values(NdfKind::beckmann, NdfKind::ggx, NdfKind::phong),
                                          testing::Values(0.1, 0.5, 1.1)),
                         kind_alpha_name);

TEST(PartnerSampling, GammaVariatesHaveTheirMeanAndVariance) {
  for (double shape : {0.3, 1.5, 7.0}) {
    const int n = 200000;
    double s = 0.0, s2 = 0.0;
    Rng rng(3, 5, 0);
    for (int j = 0; j < n; ++j) {
      const double g = sample_gamma(shape, rng);
      s += g;
      s2 += g * g;
    }
    const double mean = s / n, var = s2 / n - mean * mean;
    // Gamma(k): mean k, variance k, fourth central moment 3k^2 + 6k.
    EXPECT_NEAR(mean, shape, 5.0 * std::sqrt(shape / n)) << "shape=" << shape;
    EXPECT_NEAR(var, shape, 5.0 * std::sqrt((3.0 * shape * shape + 6.0 * shape - shape * shape) / n))
        << "shape=" << shape;
  }
}

// ---------------------------------------------------------------------------------------------
// Eq. (18)-(19): independent pairs keep the NDF.

enum class Dim { flatland, three_d };

// Tilts of the facets under n points drawn uniformly along a surface of `grooves` grooves built
// from independent pairs: first facet of projected width 1, tilt from q; second facet tilt from
// `second`, width tan a / tan b. Flatland returns signed normal angles (first facet: -a, second:
// +b); 3D returns tilts (the azimuth is uniform for both by construction).
std::vector<double> facets_under_uniform_points(Dim dim, NdfKind kind, double alpha, int grooves, int n, bool naive) {
  std::vector<double> a(static_cast<std::size_t>(grooves)), b(a.size()), cum(a.size());
  double total = 0.0;
  for (int j = 0; j < grooves; ++j) {
    Rng rng(2018, 20, static_cast<std::uint64_t>(j));
    const auto s = static_cast<std::size_t>(j);
    if (dim == Dim::three_d) {
      a[s] = sample_theta_m_3d(kind, alpha, uniform_open(rng));
      b[s] = naive ? sample_theta_m_3d(kind, alpha, uniform_open(rng)) : sample_theta_r_3d(kind, alpha, rng);
    } else {
      a[s] = std::abs(sample_theta_m(kind, alpha, uniform_open(rng)));
      b[s] = naive ? std::abs(sample_theta_m(kind, alpha, uniform_open(rng)))
                   : sample_theta_r(kind, alpha, uniform_open(rng));
    }
    total += 1.0 + std::tan(a[s]) / std::tan(b[s]);
    cum[s] = total;
  }
  std::vector<double> out;
  Rng rng(2018, 21, 0);
  for (int j = 0; j < n; ++j) {
    const double x = uniform_open(rng) * total;
    const auto g = static_cast<std::size_t>(std::upper_bound(cum.begin(), cum.end(), x) - cum.begin());
    const double start = g == 0 ? 0.0 : cum[g - 1];
    const bool first = x - start < 1.0;
    if (dim == Dim::three_d)
      out.push_back(first ? a[g] : b[g]);
    else
      out.push_back(first ? -a[g] : b[g]);
  }
  return out;
}

double claim_p_value(Dim dim, NdfKind kind, double alpha, bool naive, std::string& table) {
  // The naive surface is rejected by far; it needs no large surface.
  const int n = 4000, grooves = (naive ? 10 : 50) * n, bins = 20;
  const std::vector<double> x = facets_under_uniform_points(dim, kind, alpha, grooves, n, naive);
  std::function<double(double)> F;
  std::vector<double> edges, xs = x;
  if (dim == Dim::three_d) {
    F = [kind, alpha](double t) { return theta_m_cdf_3d(kind, alpha, t); };
    edges = equiprobable_edges(F, bins);
  } else {
    // The signed angle over (-pi/2, pi/2), mapped to [0, pi/2] by theta -> (theta + pi/2) / 2 for
    // the edge finder; F in the original variable.
    F = [kind, alpha](double y) { return theta_m_cdf(kind, alpha, 2.0 * y - kHalfPi); };
    edges = equiprobable_edges(F, bins);
    for (double& v : xs) v = 0.5 * (v + kHalfPi);
  }
  const auto c = chi_square_gof(edges, expected_counts(F, edges, n), histogram(edges, xs));
  table = "chi2 = " + std::to_string(c.stat) + ", dof " + std::to_string(c.dof) + "\n" + c.table;
  return c.p;
}

class IndependentPairs : public testing::TestWithParam<KindAlpha> {};

// 12 sets (3 NDFs x 2 alphas x 2 dimensions): each must pass above p = 1e-3 / 12.
TEST_P(IndependentPairs, KeepTheNdfInProjectedArea) {
  const auto [kind, alpha] = GetParam();
  for (Dim dim : {Dim::flatland, Dim::three_d}) {
    std::string table;
    const double p = claim_p_value(dim, kind, alpha, false, table);
    EXPECT_GT(p, 1e-3 / 12.0) << ndf_name(kind) << " alpha=" << alpha << (dim == Dim::flatland ? " flatland" : " 3D")
                              << " p=" << p << "\n"
                              << table;
  }
}

// Power: the second tilt drawn from the NDF's own tilt law (not Eq. 20) is rejected.
TEST_P(IndependentPairs, NaiveIndependentTiltsAreRejected) {
  const auto [kind, alpha] = GetParam();
  for (Dim dim : {Dim::flatland, Dim::three_d}) {
    std::string table;
    const double p = claim_p_value(dim, kind, alpha, true, table);
    EXPECT_LT(p, 1e-6) << ndf_name(kind) << " alpha=" << alpha << (dim == Dim::flatland ? " flatland" : " 3D")
                       << " p=" << p << "\n"
                       << table;
  }
}

INSTANTIATE_TEST_SUITE_P(Grid, IndependentPairs,
                         testing::Combine(testing::Values(NdfKind::beckmann, NdfKind::ggx, NdfKind::phong),
                                          testing::Values(0.3, 1.0)),
                         kind_alpha_name);

}  // namespace
}  // namespace vgroove::sim
