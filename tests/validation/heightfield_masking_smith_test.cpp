// Traced masking on Gaussian (Beckmann) heightfields (sim/heightfield_masking.h) against Smith's
// G1 = 1 / (1 + Lambda(o)) (analytic/ndf.h; Heitz 2014, Eq. 10), anisotropic through the
// roughness projected on the view azimuth, alpha_o = sqrt(alpha_x^2 cos^2 phi_o + alpha_y^2
// sin^2 phi_o) (Heitz 2014, the anisotropic shape-invariant distributions, by stretching).
//
// Errors come from independent surfaces: each of `seeds` fields (its own seed) gives one G1 from
// its own points; the mean over fields is compared with Smith with the fields' standard error,
// Student t with seeds - 1 degrees of freedom, Bonferroni over the comparisons of a test (so a
// field's own departure from Beckmann, not only the points' noise, is in the threshold).
// - The overall G1 (the projected-area average over the facets) at moderate view.
// - Per facet-normal bin Smith's G1(o, m) is one number for every facing m; on the surface G1
//   rises as the facet turns towards the viewer (as on the 1D Gaussian profiles of
//   tests/validation/profile_masking_test.cpp): measured, with sizes.
// - HeightfieldMaskingSmithLong: 70-85 deg for alpha 0.2, 0.5, 1, and GGX fields against Smith's
//   GGX G1, printed as figures (ctest -L long).
#include "vgroove/analytic/ndf.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/heightfield_masking.h"

#include <gtest/gtest.h>
#include <boost/math/distributions/students_t.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace vgroove::validation {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct FieldCase {
  double alpha_x, alpha_y, phi_o;
};

double smith_g1(const FieldCase& c, double theta_o) {
  const double a = std::sqrt(c.alpha_x * c.alpha_x * std::cos(c.phi_o) * std::cos(c.phi_o) +
                             c.alpha_y * c.alpha_y * std::sin(c.phi_o) * std::sin(c.phi_o));
  return 1.0 / (1.0 + analytic::Lambda_beckmann(theta_o, a));
}

// Mean and standard error over fields.
struct Spread {
  double sum = 0.0, sum2 = 0.0;
  int count = 0;
  void add(double v) { sum += v, sum2 += v * v, ++count; }
  double mean() const { return sum / count; }
  double se() const { return std::sqrt(std::max(0.0, sum2 - count * mean() * mean()) / (count - 1) / count); }
};

// Per view angle: the overall G1 and each bin's over the fields (bins with points on every field).
struct Measured {
  Spread overall;
  std::vector<Spread> bin;
  std::int64_t lost = 0;
};

std::vector<sim::HeightfieldSurface> fields(const FieldCase& c, int n, int seeds, bool ggx = false) {
  std::vector<sim::HeightfieldSurface> s;
  for (int k = 0; k < seeds; ++k) {
    const sim::GaussianHeightfieldOptions opt{n, c.alpha_x, c.alpha_y, 8.0, 500u + static_cast<std::uint64_t>(k)};
    s.push_back(
        sim::make_heightfield_surface(ggx ? sim::make_ggx_heightfield(opt) : sim::make_gaussian_heightfield(opt)));
  }
  return s;
}

Measured measure(const std::vector<sim::HeightfieldSurface>& surfaces, const FieldCase& c, double theta_o,
                 std::int64_t points, int theta_m_bins, int phi_m_bins) {
  Measured m;
  m.bin.resize(static_cast<std::size_t>(theta_m_bins * phi_m_bins));
  std::uint64_t seed = 0;
  for (const sim::HeightfieldSurface& s : surfaces) {
    sim::HeightfieldMaskingOptions opt;
    opt.theta_o = theta_o;
    opt.phi_o = c.phi_o;
    opt.points = points;
    opt.seed = seed++;
    opt.theta_m_bins = theta_m_bins;
    opt.phi_m_bins = phi_m_bins;
    const sim::HeightfieldMaskingTally t = sim::heightfield_masking(s, opt);
    m.lost += t.lost;
    m.overall.add(t.g1());
    for (std::size_t b = 0; b < m.bin.size(); ++b)
      if (t.count[b] >= 100) m.bin[b].add(t.g1(static_cast<int>(b)));
  }
  return m;
}

double t_max(int seeds, int comparisons) {
  const boost::math::students_t t(seeds - 1);
  return boost::math::quantile(boost::math::complement(t, 0.001 / (2.0 * comparisons)));
}

TEST(HeightfieldMaskingSmith, OverallG1IsSmithsAtModerateView) {
  const int seeds = 8;
  const std::vector<double> thetas_deg = {45.0, 60.0, 70.0};
  const std::vector<FieldCase> cases = {{0.5, 0.5, 0.3}, {0.4, 0.8, 1.0}};
  const double z = t_max(seeds, static_cast<int>(thetas_deg.size() * cases.size()));
  for (const FieldCase& c : cases) {
    const auto surfaces = fields(c, 256, seeds);
    for (double theta_deg : thetas_deg) {
      const Measured m = measure(surfaces, c, theta_deg * kDeg, 30000, 1, 1);
      const double smith = smith_g1(c, theta_deg * kDeg);
      EXPECT_EQ(m.lost, 0);
      EXPECT_NEAR(m.overall.mean(), smith, z * m.overall.se())
          << "alpha (" << c.alpha_x << ", " << c.alpha_y << ") phi_o " << c.phi_o << " theta_o " << theta_deg
          << ": traced " << m.overall.mean() << " +- " << m.overall.se() << ", Smith " << smith;
      // The comparison resolves 1% of 1 - G1 or better where masking is visible.
      EXPECT_LT(z * m.overall.se(), std::max(0.01, 0.3 * (1.0 - smith)));
    }
  }
}

// theta_m bins 0-30, 30-60, 60-90 deg; azimuth bins of the normal relative to phi_o centred on 0
// (tilted towards o), 90, 180 (away), 270 deg. Asserted: the facets tilted towards o are more
// visible than those tilted away (the m-dependence Smith's G1 does not have), and Smith
// overestimates the visibility of the facets tilted away; the sizes are printed (60 deg, alpha
// 0.5: away 0.957 and 0.819 in the two bins against Smith's 0.987).
TEST(HeightfieldMaskingSmith, PerNormalG1RisesAsTheFacetTurnsTowardsTheViewer) {
  const int seeds = 8, theta_m_bins = 3, phi_m_bins = 4;
  const FieldCase c{0.5, 0.5, 0.3};
  const auto surfaces = fields(c, 256, seeds);
  const double theta_o = 60.0 * kDeg;
  const Measured m = measure(surfaces, c, theta_o, 40000, theta_m_bins, phi_m_bins);
  const double smith = smith_g1(c, theta_o);
  const double z = t_max(seeds, 4);
  for (int tb = 0; tb < 2; ++tb) {
    const Spread& towards = m.bin[static_cast<std::size_t>(tb * phi_m_bins + 0)];
    const Spread& away = m.bin[static_cast<std::size_t>(tb * phi_m_bins + 2)];
    ASSERT_EQ(towards.count, seeds);
    ASSERT_EQ(away.count, seeds);
    std::printf("theta_o 60, theta_m %d-%d deg: towards %.4f +- %.4f, away %.4f +- %.4f, Smith %.4f\n", 30 * tb,
                30 * tb + 30, towards.mean(), towards.se(), away.mean(), away.se(), smith);
    EXPECT_GT(towards.mean() - away.mean(), z * std::hypot(towards.se(), away.se()))
        << "theta_m bin " << tb << ": towards " << towards.mean() << ", away " << away.mean();
    EXPECT_GT(smith - away.mean(), z * away.se()) << "theta_m bin " << tb << ": " << away.mean();
  }
}

// GGX fields (sim/heightfield.h: GGX slopes, heights and slopes dependent) against Smith's GGX
// G1, printed: how far Smith is on this surface; asserted: no ray lost.
TEST(HeightfieldMaskingSmithLong, GgxFieldFigures) {
  const int seeds = 8, theta_m_bins = 3, phi_m_bins = 4;
  const FieldCase c{0.5, 0.5, 0.3};
  const auto surfaces = fields(c, 256, seeds, true);
  for (double theta_deg : {45.0, 60.0, 70.0, 80.0, 85.0}) {
    const Measured m = measure(surfaces, c, theta_deg * kDeg, 100000, theta_m_bins, phi_m_bins);
    const double smith = analytic::G1_smith_ggx(theta_deg * kDeg, c.alpha_x);
    EXPECT_EQ(m.lost, 0);
    std::printf("ggx alpha 0.5 theta_o %.0f: traced G1 %.4f +- %.4f, Smith %.4f (traced / Smith - 1 = %+.4f)\n",
                theta_deg, m.overall.mean(), m.overall.se(), smith, m.overall.mean() / smith - 1.0);
    for (int tb = 0; tb < theta_m_bins; ++tb)
      for (int pb = 0; pb < phi_m_bins; ++pb) {
        const Spread& s = m.bin[static_cast<std::size_t>(tb * phi_m_bins + pb)];
        if (s.count == seeds)
          std::printf("    theta_m %2d-%2d deg, azimuth %3d deg: G1 %.4f +- %.4f (/ Smith - 1 = %+.3f)\n", 30 * tb,
                      30 * tb + 30, 90 * pb, s.mean(), s.se(), s.mean() / smith - 1.0);
      }
  }
}

// 70-85 deg: how far Smith is, per alpha, overall and per bin (printed); asserted: no ray lost.
TEST(HeightfieldMaskingSmithLong, GrazingFigures) {
  const int seeds = 8, theta_m_bins = 3, phi_m_bins = 4;
  for (double alpha : {0.2, 0.5, 1.0}) {
    const FieldCase c{alpha, alpha, 0.3};
    const auto surfaces = fields(c, 256, seeds);
    for (double theta_deg : {70.0, 75.0, 80.0, 85.0}) {
      const Measured m = measure(surfaces, c, theta_deg * kDeg, 100000, theta_m_bins, phi_m_bins);
      const double smith = smith_g1(c, theta_deg * kDeg);
      EXPECT_EQ(m.lost, 0);
      std::printf("alpha %.1f theta_o %.0f: traced G1 %.4f +- %.4f, Smith %.4f (traced / Smith - 1 = %+.4f)\n", alpha,
                  theta_deg, m.overall.mean(), m.overall.se(), smith, m.overall.mean() / smith - 1.0);
      for (int tb = 0; tb < theta_m_bins; ++tb)
        for (int pb = 0; pb < phi_m_bins; ++pb) {
          const Spread& s = m.bin[static_cast<std::size_t>(tb * phi_m_bins + pb)];
          if (s.count == seeds)
            std::printf("    theta_m %2d-%2d deg, azimuth %3d deg: G1 %.4f +- %.4f (/ Smith - 1 = %+.3f)\n", 30 * tb,
                        30 * tb + 30, 90 * pb, s.mean(), s.se(), s.mean() / smith - 1.0);
        }
    }
  }
}

}  // namespace
}  // namespace vgroove::validation
