// Cross test: the facet normals of sim/random_profile.h's profiles against analytic D2 (the
// flatland Beckmann and GGX NDFs of analytic/ndf.h; the two sides share no code).
//
// A segment's normal angle theta_m = atan(slope); segments have equal widths dx, so counting
// segments is the projected-length measure D2(theta) cos(theta) d theta. Samples: every 48th
// segment (3 correlation lengths: Gaussian slope correlation -0.002 there; GGX's slopes are a
// monotone transform of those, no more correlated; of a GGX profile only its first half, the
// second being its mirror) of 16 independent profiles; chi-square over 40 bins equal in
// slope / alpha, pooled to >= 5 expected, p above 1e-3 / 6 (Bonferroni over the six cases).
// Power: the same samples reject the NDF of roughness 1.06 alpha (Beckmann), 1.1 alpha (GGX).
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/sim/random_profile.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vgroove {
namespace {

using namespace vgroove::test_stats;

std::vector<double> expected_counts(NdfKind ndf, double alpha, const std::vector<double>& edges, double n) {
  const analytic::GaussLegendre gl = analytic::gauss_legendre(64);
  std::vector<double> e;
  for (std::size_t b = 0; b + 1 < edges.size(); ++b)
    e.push_back(n *
                analytic::integrate(
                    gl, [&](double t) { return analytic::D2(ndf, t, alpha) * std::cos(t); }, edges[b], edges[b + 1]));
  return e;
}

TEST(ProfileNdf, SegmentNormalsFollowD2) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.1, 0.5, 1.0}) {
      const std::vector<double> edges = slope_bin_edges(alpha, 40);
      std::vector<std::int64_t> counts(40, 0);
      std::int64_t n = 0;
      for (std::uint64_t seed = 0; seed < 16; ++seed) {
        sim::RandomProfileOptions o;
        o.ndf = ndf, o.alpha = alpha, o.segments = 1 << 15, o.samples_per_length = 16, o.seed = 1000 + seed;
        const sim::Polyline p = sim::make_random_profile(o);
        const int used = ndf == NdfKind::ggx ? p.segments() / 2 : p.segments();
        for (int j = 0; j < used; j += 48) {
          const double t = p.normal_angle(j);
          const int b = static_cast<int>(std::upper_bound(edges.begin(), edges.end(), t) - edges.begin()) - 1;
          ++counts[static_cast<std::size_t>(std::clamp(b, 0, 39))];
          ++n;
        }
      }
      const ChiSquare fit = chi_square_gof(edges, expected_counts(ndf, alpha, edges, static_cast<double>(n)), counts);
      EXPECT_GT(fit.p, 1e-3 / 6) << ndf_name(ndf) << " alpha=" << alpha << " n=" << n << " chi2=" << fit.stat
                                 << " dof=" << fit.dof << "\n"
                                 << fit.table;
      // GGX's heavy tails carry less information on its width (Fisher information for the scale
      // 0.8 / alpha^2 per sample against Gaussian's 2 / alpha^2) from half the samples.
      const double wrong_alpha = (ndf == NdfKind::ggx ? 1.1 : 1.06) * alpha;
      const ChiSquare wrong =
          chi_square_gof(edges, expected_counts(ndf, wrong_alpha, edges, static_cast<double>(n)), counts);
      EXPECT_LT(wrong.p, 1e-3 / 6) << ndf_name(ndf) << " alpha=" << alpha << " (power, alpha " << wrong_alpha << ")";
    }
}

}  // namespace
}  // namespace vgroove
