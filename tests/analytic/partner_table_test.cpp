// Tests of the tabulated partner law (analytic/partner_table.h): the table is a density, its
// sampler draws it (chi-square against the cells' masses), and its error against P (Eq. 20) is
// bounded for every NDF and alpha the nonsymmetric model accepts.
#include "vgroove/analytic/partner_table.h"

#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/analytic/quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace vgroove::analytic {
namespace {

constexpr NdfKind kNdfs[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};
constexpr double kHalfPi = 0.5 * std::numbers::pi;

// int |P_tab - P| below 1e-5 (and the CDF at the nodes within it), 3D and flatland, alpha 0.01 to
// 2 (Phong up to 1: partner_table.h).
TEST(PartnerTable, ErrorIsBounded) {
  for (bool flat : {false, true})
    for (NdfKind ndf : kNdfs)
      for (double alpha : {0.01, 0.1, 0.5, 1.0, 2.0}) {
        if (ndf == NdfKind::phong && alpha > 1.0) continue;
        const PartnerTable t = make_partner_table(ndf, alpha, flat);
        const double l1 = partner_table_l1_error(t, ndf, alpha, flat);
        const double cdf = partner_table_cdf_error(t, ndf, alpha, flat);
        EXPECT_LT(l1, 1e-5) << ndf_name(ndf) << " alpha=" << alpha << " flat=" << flat;
        EXPECT_LE(cdf, l1 + 1e-12) << ndf_name(ndf) << " alpha=" << alpha << " flat=" << flat;
      }
}

// The bound has power: a table 16 times coarser is above it (the error is ~ h^2).
TEST(PartnerTable, CoarseTableExceedsTheBound) {
  const PartnerTable t = make_partner_table(NdfKind::ggx, 0.5, false, 64);
  EXPECT_GT(partner_table_l1_error(t, NdfKind::ggx, 0.5, false), 1e-5);
}

TEST(PartnerTable, IsADensity) {
  for (NdfKind ndf : kNdfs) {
    const PartnerTable t = make_partner_table(ndf, 0.5, false);
    const double total = integrate_adaptive_parts([&](double B) { return partner_table_pdf(t, B); }, 0.0, kHalfPi,
                                                  1e-12, 0.0, 1024, 4096);
    EXPECT_NEAR(total, 1.0, 1e-10) << ndf_name(ndf);
    EXPECT_EQ(partner_table_pdf(t, -0.1), 0.0);
    EXPECT_EQ(partner_table_pdf(t, 2.0), 0.0);
  }
}

// The sampler inverts the table's CDF: u -> B -> CDF(B) = u to rounding, at the ends too.
TEST(PartnerTable, SampleInvertsTheCdf) {
  const PartnerTable t = make_partner_table(NdfKind::beckmann, 0.3, false);
  auto cdf = [&](double B) {
    return integrate_adaptive_parts([&](double x) { return partner_table_pdf(t, x); }, 0.0, B, 1e-13, 0.0, 64, 4096);
  };
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int n = 0; n < 50; ++n) {
    const double u = U(g);
    EXPECT_NEAR(cdf(sample_partner(t, u)), u, 1e-9) << u;
  }
  for (double u : {0.0, 1.0 - std::ldexp(1.0, -53)}) {
    const double B = sample_partner(t, u);
    EXPECT_TRUE(std::isfinite(B) && B >= 0.0 && B <= kHalfPi) << u;
  }
  EXPECT_EQ(sample_partner(t, 0.0), 0.0);
}

// Chi-square of 10^5 draws against the table's cell masses (64 equal-mass groups of cells).
TEST(PartnerTable, DrawsTheTable) {
  for (bool flat : {false, true}) {
    const PartnerTable t = make_partner_table(NdfKind::phong, 0.9, flat);
    const int groups = 64;
    std::vector<double> edges{0.0};
    for (int j = 1; j < groups; ++j) edges.push_back(sample_partner(t, static_cast<double>(j) / groups));
    edges.push_back(kHalfPi);
    std::vector<double> count(groups, 0.0);
    std::mt19937_64 g(11);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const int n = 100000;
    for (int s = 0; s < n; ++s) {
      const double B = sample_partner(t, U(g));
      const auto it = std::upper_bound(edges.begin(), edges.end(), B);
      ++count[std::clamp(static_cast<int>(it - edges.begin()) - 1, 0, groups - 1)];
    }
    double chi2 = 0.0;
    const double e = static_cast<double>(n) / groups;
    for (double c : count) chi2 += (c - e) * (c - e) / e;
    // 63 dof: the 0.999 quantile is 103.4.
    EXPECT_LT(chi2, 103.4) << "flat=" << flat;
  }
}

TEST(PartnerTable, RefusesPhongWithoutAPartnerLaw) {
  EXPECT_THROW(make_partner_table(NdfKind::phong, 1.5, false), std::domain_error);
  EXPECT_THROW(make_partner_table(NdfKind::phong, 1.2, true), std::domain_error);
}

}  // namespace
}  // namespace vgroove::analytic
