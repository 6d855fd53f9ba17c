// Tests of sim/microsurface_nonsymmetric.h: the surfaces hold the population of Lee et al. 2018's
// Eq. (21) (the facet under a uniform point of the macrosurface has its normal distributed by the
// NDF in projected area, and its partner's tilt by Eq. 20, independently; anisotropic: the slope
// law P22 and the partner law at alpha(phi)), every ray is accounted for, and the tallies do not
// depend on how the chunks are split.
//
// Each groove of a surface is an independent draw of the population and has the same macro width,
// so one uniform point per groove (the facet under it: the left one with probability
// tan(B) / (tan(A) + tan(B)), its share of the groove's width) gives independent samples of
// (facet, partner) under a uniform point of the surface.
#include "vgroove/sim/microsurface_nonsymmetric.h"

#include "vgroove/sim/partner_sampling.h"
#include "vgroove/sim/slope_sampling.h"

#include "tests/param_names.h"
#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

namespace vgroove::sim {
namespace {

using vgroove::test_stats::gamma_q;
constexpr double kHalfPi = 0.5 * std::numbers::pi;

// Chi-square of counts in cells that are equally likely under the hypothesis.
double uniform_cells_p(const std::vector<std::int64_t>& counts, std::int64_t n, std::string& table) {
  const double e = static_cast<double>(n) / static_cast<double>(counts.size());
  double stat = 0.0;
  table.clear();
  for (std::size_t c = 0; c < counts.size(); ++c) {
    stat += (counts[c] - e) * (counts[c] - e) / e;
    table += std::to_string(counts[c]) + (c % 8 == 7 ? "\n" : " ");
  }
  table += "expected " + std::to_string(e) + " each, chi2 " + std::to_string(stat);
  return gamma_q(0.5 * (static_cast<double>(counts.size()) - 1.0), 0.5 * stat);
}

int cell(double u, int cells) { return std::clamp(static_cast<int>(u * cells), 0, cells - 1); }

// The facet under a uniform point of groove j: (its tilt, its partner's tilt, whether it is left).
struct Under {
  double tilt, partner;
  bool left;
};
Under facet_under_point(double theta_l, double theta_r, double u) {
  const double ta = std::tan(-theta_l), tb = std::tan(theta_r);
  const bool left = u * (ta + tb) < tb;
  return left ? Under{-theta_l, theta_r, true} : Under{theta_r, -theta_l, false};
}

using KindAlpha = std::tuple<NdfKind, double>;
std::string kind_alpha_name(const testing::TestParamInfo<KindAlpha>& info) {
  return std::string(ndf_name(std::get<0>(info.param))) + "_a" +
         vgroove::test_names::name_text(std::get<1>(info.param));
}
class NonsymmetricPopulation : public testing::TestWithParam<KindAlpha> {};

// (facet tilt, partner tilt) through their distribution functions: 6 x 6 equally likely cells.
// 20,000 grooves; 9 parameter sets x 2 dimensions, each above p = 1e-3 / 18.
TEST_P(NonsymmetricPopulation, FacetFollowsTheNdfAndItsPartnerEq20Independently) {
  const auto [kind, alpha] = GetParam();
  const int n = 20000, cells = 6;
  NonsymmetricSurfaceOptions opt;
  opt.ndf = kind;
  opt.alpha_x = opt.alpha_y = alpha;
  opt.grooves = n;
  opt.seed = 5;
  const NonsymmetricMicrosurface flat = make_nonsymmetric_microsurface(opt);
  const NonsymmetricMicrosurface3d three = make_nonsymmetric_microsurface3d(opt);
  std::vector<std::int64_t> c2(cells * cells, 0), c3(cells * cells, 0), left2(2, 0);
  Rng rng(9, 9, 0);
  for (int j = 0; j < n; ++j) {
    const auto s = static_cast<std::size_t>(j);
    const Under f = facet_under_point(flat.theta_l[s], flat.theta_r[s], uniform_open(rng));
    // Flatland: the NDF's law of |theta_m| is 2 F(t) - 1 (F the signed law's distribution function).
    const double u_facet = 2.0 * theta_m_cdf(kind, alpha, f.tilt) - 1.0,
                 u_partner = theta_r_cdf(kind, alpha, f.partner);
    ++c2[static_cast<std::size_t>(cell(u_facet, cells) * cells + cell(u_partner, cells))];
    ++left2[f.left ? 0 : 1];
    const Under g = facet_under_point(three.theta_l[s], three.theta_r[s], uniform_open(rng));
    ++c3[static_cast<std::size_t>(cell(theta_m_cdf_3d(kind, alpha, g.tilt), cells) * cells +
                                  cell(theta_r_cdf_3d(kind, alpha, g.partner), cells))];
  }
  std::string table;
  const double p2 = uniform_cells_p(c2, n, table);
  EXPECT_GT(p2, 1e-3 / 18) << ndf_name(kind) << " alpha=" << alpha << " flatland\n" << table;
  const double p3 = uniform_cells_p(c3, n, table);
  EXPECT_GT(p3, 1e-3 / 18) << ndf_name(kind) << " alpha=" << alpha << " 3D\n" << table;
  // Left and right facets equally likely (the surface has no handedness).
  EXPECT_NEAR(static_cast<double>(left2[0]) / n, 0.5, 5.0 * 0.5 / std::sqrt(n));
}

INSTANTIATE_TEST_SUITE_P(Grid, NonsymmetricPopulation,
                         testing::Combine(testing::Values(NdfKind::beckmann, NdfKind::ggx, NdfKind::phong),
                                          testing::Values(0.2, 0.6, 1.0)),
                         kind_alpha_name);

// Power: with the partner drawn from the NDF's own tilt law instead, the same statistic rejects
// (the 3D surface built by hand from the symmetric sampler's tilts, reshuffled).
TEST(NonsymmetricPopulation, APartnerFromTheNdfIsRejected) {
  const int n = 20000, cells = 6;
  const NdfKind kind = NdfKind::ggx;
  const double alpha = 0.6;
  NonsymmetricMicrosurface3d m;
  for (int j = 0; j < n; ++j) {
    Rng rng(1, 2, static_cast<std::uint64_t>(j));
    const double a = sample_theta_m_3d(kind, alpha, uniform_open(rng)),
                 b = sample_theta_m_3d(kind, alpha, uniform_open(rng));
    add_nonsymmetric_groove3d(m, -a, b, 0.0);
  }
  std::vector<std::int64_t> c3(cells * cells, 0);
  Rng rng(9, 9, 1);
  for (int j = 0; j < n; ++j) {
    const auto s = static_cast<std::size_t>(j);
    const Under g = facet_under_point(m.theta_l[s], m.theta_r[s], uniform_open(rng));
    ++c3[static_cast<std::size_t>(cell(theta_m_cdf_3d(kind, alpha, g.tilt), cells) * cells +
                                  cell(theta_r_cdf_3d(kind, alpha, g.partner), cells))];
  }
  std::string table;
  EXPECT_LT(uniform_cells_p(c3, n, table), 1e-6) << table;
}

// Anisotropic: the facet under a uniform point has the slope -tan(theta) (cos phi, sin phi) of
// P22: scaled by the axes it is a unit isotropic slope (radius through its distribution function,
// angle uniform), and its partner's tilt follows Eq. (20) at alpha(phi). 4 x 4 x 4 cells, 20,000
// grooves, axes turned by 0.3 rad; alpha_x / alpha_y = 0.1 / 0.7 and 0.01 / 1 (ratio 100).
TEST(NonsymmetricPopulation, AnisotropicSlopesAndPartners) {
  for (NdfKind kind : {NdfKind::beckmann, NdfKind::ggx}) {
    for (auto [ax, ay] : {std::pair{0.1, 0.7}, std::pair{0.01, 1.0}}) {
      const int n = 20000, cells = 4;
      NonsymmetricSurfaceOptions opt;
      opt.ndf = kind;
      opt.alpha_x = ax;
      opt.alpha_y = ay;
      opt.axes_azimuth = 0.3;
      opt.grooves = n;
      opt.seed = 8;
      const NonsymmetricMicrosurface3d m = make_nonsymmetric_microsurface3d(opt);
      std::vector<std::int64_t> c(cells * cells * cells, 0);
      Rng rng(4, 4, 0);
      for (int j = 0; j < n; ++j) {
        const auto s = static_cast<std::size_t>(j);
        const Under g = facet_under_point(m.theta_l[s], m.theta_r[s], uniform_open(rng));
        // The facet's normal azimuth over the axes: phi_a for the left facet, phi_a + pi for the right.
        const double phi = m.phi_a[s] - opt.axes_azimuth + (g.left ? 0.0 : std::numbers::pi);
        const double t = std::tan(g.tilt);
        const double sx = -t * std::cos(phi) / ax, sy = -t * std::sin(phi) / ay;
        const double r2 = sx * sx + sy * sy;
        const double u_r = kind == NdfKind::ggx ? r2 / (1.0 + r2) : -std::expm1(-r2);
        const double u_w = (std::atan2(sy, sx) + std::numbers::pi) / (2.0 * std::numbers::pi);
        const double u_p = theta_r_cdf_3d(kind, alpha_along(ax, ay, phi), g.partner);
        ++c[static_cast<std::size_t>((cell(u_r, cells) * cells + cell(u_w, cells)) * cells + cell(u_p, cells))];
      }
      std::string table;
      EXPECT_GT(uniform_cells_p(c, n, table), 1e-3 / 4) << ndf_name(kind) << " " << ax << " x " << ay << "\n" << table;
    }
  }
}

TEST(NonsymmetricMicrosurface, AlphaAlongTheAxes) {
  EXPECT_DOUBLE_EQ(alpha_along(0.1, 0.7, 0.0), 0.1);
  EXPECT_DOUBLE_EQ(alpha_along(0.1, 0.7, 0.5 * std::numbers::pi), 0.7);
  EXPECT_NEAR(alpha_along(0.3, 0.3, 1.234), 0.3, 1e-15);
  // 1/alpha^2 = cos^2 / ax^2 + sin^2 / ay^2 at 45 deg: (1/0.01 + 1/0.49) / 2.
  EXPECT_NEAR(alpha_along(0.1, 0.7, 0.25 * std::numbers::pi), 1.0 / std::sqrt(0.5 * (100.0 + 1.0 / 0.49)), 1e-14);
}

// Every ray leaves (F = 1, peaks on one plane), in flatland and 3D, at grazing light too.
TEST(NonsymmetricMicrosurface, EveryRayLeavesAndIsCounted) {
  for (NdfKind kind : {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong}) {
    NonsymmetricSurfaceOptions opt;
    opt.ndf = kind;
    opt.alpha_x = opt.alpha_y = 0.7;
    opt.grooves = 2000;
    opt.seed = 3;
    const NonsymmetricMicrosurface flat = make_nonsymmetric_microsurface(opt);
    const NonsymmetricMicrosurface3d three = make_nonsymmetric_microsurface3d(opt);
    for (double theta_i : {0.0, 1.0, 1.55}) {
      MicrosurfaceTraceOptions to;
      to.theta_i = theta_i;
      to.rays = 40000;
      to.seed = 2;
      const MicrosurfaceTally t = trace_nonsymmetric_microsurface(flat, to);
      EXPECT_EQ(t.rays, to.rays);
      EXPECT_EQ(t.escaped, t.rays) << ndf_name(kind) << " theta_i=" << theta_i << " vertex " << t.vertex_hits;
      Microsurface3dTraceOptions t3;
      t3.theta_i = theta_i;
      t3.rays = 40000;
      t3.seed = 2;
      t3.theta_bins = 30;
      t3.phi_bins = 24;
      const Microsurface3dTally u = trace_nonsymmetric_microsurface3d(three, t3);
      EXPECT_EQ(u.rays, t3.rays);
      EXPECT_EQ(u.escaped, u.rays) << ndf_name(kind) << " theta_i=" << theta_i;
      std::int64_t s = 0;
      for (auto v : u.hist) s += v;
      EXPECT_EQ(s, u.escaped);
    }
  }
}

// Grooves with a facet near 0 deg (flat: the other facet has almost no length) or near 90 deg
// (vertical), and grazing light: every ray is counted, every exit upward and finite.
TEST(NonsymmetricMicrosurface, NearlyFlatAndNearlyVerticalFacets) {
  NonsymmetricMicrosurface3d m;
  const double h = 0.5 * std::numbers::pi;
  add_nonsymmetric_groove3d(m, -1e-9, 0.7, 0.1);
  add_nonsymmetric_groove3d(m, -0.7, 1e-9, 1.3);
  add_nonsymmetric_groove3d(m, -(h - 1e-9), 0.3, 2.0);
  add_nonsymmetric_groove3d(m, -0.3, h - 1e-9, 4.0);
  add_nonsymmetric_groove3d(m, -(h - 1e-3), h - 1e-3, 5.0);
  for (double theta_i : {0.0, 0.8, 1.5706}) {
    Microsurface3dTraceOptions t3;
    t3.theta_i = theta_i;
    t3.rays = 20000;
    t3.theta_bins = 9;
    t3.phi_bins = 8;
    const Microsurface3dTally t = trace_nonsymmetric_microsurface3d(m, t3);
    EXPECT_EQ(t.rays, t3.rays);
    EXPECT_EQ(t.escaped + t.lost(), t.rays);
    EXPECT_EQ(t.not_upward, 0) << "theta_i=" << theta_i;
    EXPECT_EQ(t.bounce_limit, 0) << "theta_i=" << theta_i;
  }
}

// Chunks merged in any order give the same tallies (integer counts): the thread count cannot matter.
TEST(NonsymmetricMicrosurface, ChunkOrderDoesNotMatter) {
  NonsymmetricSurfaceOptions opt;
  opt.ndf = NdfKind::ggx;
  opt.alpha_x = 0.2;
  opt.alpha_y = 0.9;
  opt.grooves = 1000;
  const NonsymmetricMicrosurface3d three = make_nonsymmetric_microsurface3d(opt);
  Microsurface3dTraceOptions t3;
  t3.theta_i = 0.7;
  t3.rays = 3 * kRaysPerChunk + 17;
  const Microsurface3dTally forward = trace_nonsymmetric_microsurface3d(three, t3);
  Microsurface3dTally backward(t3.theta_bins, t3.phi_bins, t3.max_k);
  for (std::int64_t c = chunk_count(t3) - 1; c >= 0; --c)
    backward.merge(trace_nonsymmetric_microsurface3d_chunk(three, t3, c));
  EXPECT_EQ(forward.hist_by_k, backward.hist_by_k);
  EXPECT_EQ(forward.by_k, backward.by_k);
  // Same options, same surface.
  EXPECT_EQ(make_nonsymmetric_microsurface3d(opt).theta_r, three.theta_r);

  NonsymmetricSurfaceOptions o2 = opt;
  o2.alpha_y = o2.alpha_x;
  const NonsymmetricMicrosurface flat = make_nonsymmetric_microsurface(o2);
  MicrosurfaceTraceOptions to;
  to.theta_i = -0.4;
  to.rays = 2 * kRaysPerChunk + 5;
  const MicrosurfaceTally f = trace_nonsymmetric_microsurface(flat, to);
  MicrosurfaceTally b(to.theta_o_bins, to.max_k);
  for (std::int64_t c = chunk_count(to) - 1; c >= 0; --c) b.merge(trace_nonsymmetric_microsurface_chunk(flat, to, c));
  EXPECT_EQ(f.theta_o_by_k, b.theta_o_by_k);
}

// Partner::symmetric is the symmetric surface of sim/microsurface3d.h in law: the bounce counts of
// 200,000 rays on each agree by a two-sample chi-square (GGX 0.8, theta_i = 50 deg).
TEST(NonsymmetricMicrosurface, SymmetricPartnerIsTheSymmetricSurface) {
  NonsymmetricSurfaceOptions opt;
  opt.ndf = NdfKind::ggx;
  opt.alpha_x = opt.alpha_y = 0.8;
  opt.partner = Partner::symmetric;
  opt.grooves = 100000;
  opt.seed = 11;
  const NonsymmetricMicrosurface3d a = make_nonsymmetric_microsurface3d(opt);
  Microsurface3dOptions so;
  so.ndf = NdfKind::ggx;
  so.alpha = 0.8;
  so.grooves = 100000;
  so.seed = 12;
  const Microsurface3d b = make_microsurface3d(so);
  Microsurface3dTraceOptions t3;
  t3.theta_i = 50.0 * std::numbers::pi / 180.0;
  t3.rays = 200000;
  t3.theta_bins = 6;
  t3.phi_bins = 4;
  t3.max_k = 6;
  const Microsurface3dTally ta = trace_nonsymmetric_microsurface3d(a, t3), tb = trace_microsurface3d(b, t3);
  double stat = 0.0;
  int cells = 0;
  for (std::size_t k = 0; k < ta.by_k.size(); ++k) {
    const double x = static_cast<double>(ta.by_k[k]), y = static_cast<double>(tb.by_k[k]);
    if (x + y < 10.0) continue;
    stat += (x - y) * (x - y) / (x + y);
    ++cells;
  }
  EXPECT_GT(gamma_q(0.5 * (cells - 1), 0.5 * stat), 1e-3) << "chi2 " << stat << " over " << cells << " cells";
}

}  // namespace
}  // namespace vgroove::sim
