// Tests of sim/microsurface3d.h: the 3D V-groove microsurface traced with the exact 2D tracer.
//
// Sampling (matched pairs): the groove polar-angle pdf 2 pi D cos sin integrates to one, the cdf is
// its integral, the sampler inverts the cdf, and the surface's grooves follow the pdf (chi-square
// against the pdf's quadrature, fixed seed, pooled low cells, Bonferroni over the grid); phi_a is
// uniform on [0, pi).
// Lift: |o| = 1, o.u = -i.u, and o equals the 3D mirror reflections of -i on the groove's facets
// in the order the 2D tracer reports. 2D reduction: a groove with phi_a = 0 lit in its plane gives
// the 2D tracer's bounce count and exit angle. A nearly flat surface returns the mirror bin. Every
// ray leaves (albedo 1, ridges coplanar). At theta_i = 0 the lobe is symmetric under phi -> phi + pi
// and phi -> -phi within statistics. Results do not depend on how chunks are merged.
//
// Conventions (sim/microsurface3d.h): n = (0, 0, 1), dir(theta, phi) = (sin theta cos phi,
// sin theta sin phi, cos theta), light at i = dir(theta_i, pi), mirror direction at phi = 0.
#include "vgroove/sim/microsurface3d.h"

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

using namespace vgroove::test_stats;  // tanh_sinh, gamma_q, ChiSquare, chi_square_gof

double deg(double d) { return d * std::numbers::pi / 180.0; }

const NdfKind kKinds[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};
// Student-T (microsurface3d.h) at a heavy tail near its limit 1.5, GGX's 2, and a light one.
const NdfKind kStudentTs[] = {student_t_ndf(1.6), student_t_ndf(2.0), student_t_ndf(8.0)};
const double kAlphas[] = {0.2, 0.6, 1.0};

class Sampling3d : public testing::TestWithParam<std::tuple<NdfKind, double>> {};

std::string kind_alpha_name(const testing::TestParamInfo<std::tuple<NdfKind, double>>& info) {
  const NdfKind kind = std::get<0>(info.param);
  std::string gamma;
  if (kind == NdfKind::student_t) gamma = "_g" + std::to_string(static_cast<int>(std::round(kind.gamma * 10)));
  return std::string(ndf_name(kind)) + gamma + "_alpha" +
         std::to_string(static_cast<int>(std::round(std::get<1>(info.param) * 100)));
}

TEST_P(Sampling3d, PdfIsNormalized) {
  const auto [kind, alpha] = GetParam();
  const double total = tanh_sinh([&](double t) { return theta_m_pdf_3d(kind, alpha, t); }, 0.0, 0.5 * std::numbers::pi);
  EXPECT_NEAR(total, 1.0, 1e-10) << ndf_name(kind) << " alpha=" << alpha;
}

TEST_P(Sampling3d, CdfIsTheIntegralOfThePdf) {
  const auto [kind, alpha] = GetParam();
  for (double t_deg : {1.0, 5.0, 15.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0}) {
    const double t = deg(t_deg);
    const double q = tanh_sinh([&](double x) { return theta_m_pdf_3d(kind, alpha, x); }, 0.0, t);
    EXPECT_NEAR(theta_m_cdf_3d(kind, alpha, t), q, 1e-11) << ndf_name(kind) << " alpha=" << alpha << " t=" << t_deg;
  }
  EXPECT_EQ(theta_m_cdf_3d(kind, alpha, 0.0), 0.0);
  EXPECT_EQ(theta_m_cdf_3d(kind, alpha, 0.5 * std::numbers::pi), 1.0);
}

TEST_P(Sampling3d, SampleInvertsTheCdf) {
  const auto [kind, alpha] = GetParam();
  double prev = 0.0;
  for (double u : {1e-12, 1e-6, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.999999}) {
    const double t = sample_theta_m_3d(kind, alpha, u);
    EXPECT_GT(t, prev) << ndf_name(kind) << " alpha=" << alpha << " u=" << u;
    EXPECT_LT(t, 0.5 * std::numbers::pi);
    // The cdf's condition number near u -> 1 is |d log(1-u)/d theta| * dtheta: relative in 1 - u.
    EXPECT_NEAR(theta_m_cdf_3d(kind, alpha, t), u, 1e-13 * u + 1e-11 * (1.0 - u) + 1e-15)
        << ndf_name(kind) << " alpha=" << alpha << " u=" << u;
    prev = t;
  }
}

// The surface's grooves against the pdf. Bins equal in atan(tan(theta) / alpha), which follows the
// law's scale; expected counts by quadrature of the pdf (not the cdf the sampler inverts). Level
// 1e-3 for the 9 cases, two tests each (theta_m, phi_a): 1e-3/18 each.
TEST_P(Sampling3d, GroovesFollowThePdf) {
  const auto [kind, alpha] = GetParam();
  constexpr int n = 100000, bins = 40;
  constexpr double level = 1e-3 / 18.0;
  const Microsurface3d m = make_microsurface3d({kind, alpha, n, 20180611});
  std::vector<double> edges(bins + 1);
  for (int j = 0; j <= bins; ++j) edges[j] = std::atan(alpha * std::tan(j * 0.5 * std::numbers::pi / bins));
  edges.back() = 0.5 * std::numbers::pi;
  std::vector<double> expected(bins);
  for (int j = 0; j < bins; ++j)
    expected[j] = n * tanh_sinh([&](double t) { return theta_m_pdf_3d(kind, alpha, t); }, edges[j], edges[j + 1]);
  std::vector<std::int64_t> observed(bins, 0);
  for (double t : m.theta_m) {
    ASSERT_TRUE(t >= 0.0 && t < 0.5 * std::numbers::pi) << t;
    const auto it = std::upper_bound(edges.begin(), edges.end(), t);
    ++observed[static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(it - edges.begin() - 1, 0, bins - 1))];
  }
  const ChiSquare c = chi_square_gof(edges, expected, observed);
  EXPECT_GE(c.p, level) << ndf_name(kind) << " alpha=" << alpha << ": chi2=" << c.stat << " dof=" << c.dof
                        << " p=" << c.p << "\n"
                        << c.table;

  constexpr int phi_bins = 36;
  std::vector<double> phi_edges(phi_bins + 1), phi_expected(phi_bins, static_cast<double>(n) / phi_bins);
  for (int j = 0; j <= phi_bins; ++j) phi_edges[j] = j * std::numbers::pi / phi_bins;
  std::vector<std::int64_t> phi_observed(phi_bins, 0);
  for (double p : m.phi_a) {
    ASSERT_TRUE(p >= 0.0 && p < std::numbers::pi) << p;
    ++phi_observed[static_cast<std::size_t>(std::min(phi_bins - 1, static_cast<int>(p / std::numbers::pi * phi_bins)))];
  }
  const ChiSquare cp = chi_square_gof(phi_edges, phi_expected, phi_observed);
  EXPECT_GE(cp.p, level) << "phi_a: chi2=" << cp.stat << " dof=" << cp.dof << "\n" << cp.table;
}

INSTANTIATE_TEST_SUITE_P(Grid, Sampling3d, testing::Combine(testing::ValuesIn(kKinds), testing::ValuesIn(kAlphas)),
                         kind_alpha_name);
// Student-T on its own (9 cases, two tests each at the level above: 1e-3 over them).
INSTANTIATE_TEST_SUITE_P(StudentT, Sampling3d,
                         testing::Combine(testing::ValuesIn(kStudentTs), testing::ValuesIn(kAlphas)), kind_alpha_name);

// gamma = 2 is GGX and gamma = 1 + 1/alpha^2 Phong (microsurface3d.h): pdf, cdf and the sampler.
TEST(Sampling3d, StudentTIsGgxAtTwoAndPhongAtOnePlusInverseAlphaSquared) {
  for (double alpha : {0.3, 0.8}) {
    const NdfKind p = student_t_ndf(1.0 + 1.0 / (alpha * alpha));
    for (double t_deg : {5.0, 30.0, 60.0, 85.0}) {
      const double t = deg(t_deg);
      EXPECT_NEAR(theta_m_pdf_3d(student_t_ndf(2.0), alpha, t) / theta_m_pdf_3d(NdfKind::ggx, alpha, t), 1.0, 1e-14);
      EXPECT_NEAR(theta_m_cdf_3d(student_t_ndf(2.0), alpha, t), theta_m_cdf_3d(NdfKind::ggx, alpha, t), 1e-14);
      EXPECT_NEAR(theta_m_pdf_3d(p, alpha, t) / theta_m_pdf_3d(NdfKind::phong, alpha, t), 1.0, 1e-13);
      EXPECT_NEAR(theta_m_cdf_3d(p, alpha, t), theta_m_cdf_3d(NdfKind::phong, alpha, t), 1e-14);
    }
    for (double u : {1e-9, 0.1, 0.5, 0.99}) {
      EXPECT_NEAR(sample_theta_m_3d(student_t_ndf(2.0), alpha, u), sample_theta_m_3d(NdfKind::ggx, alpha, u), 1e-14);
      EXPECT_NEAR(sample_theta_m_3d(p, alpha, u), sample_theta_m_3d(NdfKind::phong, alpha, u), 1e-14);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// One groove.

Vec3 reflect3(const Vec3& d, const Vec3& m) { return d - 2.0 * d.dot(m) * m; }

// The lift against brute-force 3D optics: the 2D tracer says which facet was hit first (they then
// alternate); reflecting -i on the 3D facet normals s = dir(theta_m, phi_a) (the 2D left facet, at
// -theta_m) and s' = dir(theta_m, phi_a + pi) in that order must give o. Also |o| = 1, o.u = -i.u
// and (i + o).u = 0: the half vector lies in the cross-section plane.
TEST(Microsurface3dLift, MatchesThreeDimensionalReflections) {
  Rng rng(7, 1, 2);
  int checked = 0, multi = 0;
  for (int n = 0; n < 20000; ++n) {
    Microsurface3d m;
    const double theta_m = 0.5 * std::numbers::pi * uniform_open(rng), phi_a = std::numbers::pi * uniform_open(rng);
    add_groove3d(m, theta_m, phi_a);
    const Vec3 i = direction3(deg(85.0) * rng.uniform(), 2.0 * std::numbers::pi * rng.uniform());
    const double f = uniform_open(rng);
    const Trace3dResult r = trace_groove3d(m.grooves[0], m.frames[0], i, f);
    if (r.trace.how != Termination::escaped) continue;
    ++checked;
    if (r.trace.bounces > 1) ++multi;
    const Vec3 u = m.frames[0].u();
    const std::string where = "theta_m=" + std::to_string(theta_m) + " phi_a=" + std::to_string(phi_a) +
                              " k=" + std::to_string(r.trace.bounces);
    // Each reflection rounds by ~1 ulp per component: k * 4e-16 for the norm, as for o itself.
    const double tol = 1e-15 * (4.0 + r.trace.bounces);
    EXPECT_NEAR(r.o.norm(), 1.0, tol) << where;
    EXPECT_NEAR(r.o.dot(u), -i.dot(u), tol) << where;
    EXPECT_NEAR((i + r.o).dot(u), 0.0, tol) << where;
    const Vec3 s[2] = {direction3(m.theta_m[0], phi_a), direction3(m.theta_m[0], phi_a + std::numbers::pi)};
    Vec3 d = -i;
    int side = static_cast<int>(r.trace.first);
    for (int k = 0; k < r.trace.bounces; ++k, side = 1 - side) d = reflect3(d, s[side]);
    EXPECT_NEAR((d - r.o).norm(), 0.0, 4.0 * tol) << where;
  }
  EXPECT_GT(checked, 19000);
  EXPECT_GT(multi, 5000);
}

// phi_a = 0 and i = (-sin theta_i, 0, cos theta_i): the cross-section is the plane of incidence, so
// the 3D trace is the 2D trace at t_i = theta_i: same bounce count, o = (e_x, 0, e_y) with the 2D
// exit angle atan2(-e_x, e_y). The only difference is the normalization of (i.a, i.n) (|i| = 1 up
// to an ulp), so angles agree to rounding times the bounce count.
TEST(Microsurface3dLift, ReducesToTheTwoDimensionalTracer) {
  int compared = 0;
  for (double theta_m_deg : {0.5, 10.0, 30.0, 45.0, 60.0, 75.0, 85.0, 89.0}) {
    Microsurface3d m;
    add_groove3d(m, deg(theta_m_deg), 0.0);
    const Groove& g = m.grooves[0];
    for (double theta_i_deg : {0.0, 20.0, 45.0, 70.0, 89.0}) {
      const double theta_i = deg(theta_i_deg);
      const Vec3 i(-std::sin(theta_i), 0.0, std::cos(theta_i));
      const Vec2 dir = beam_direction(theta_i);
      for (int j = 0; j < 101; ++j) {
        const double f = (j + 0.5) / 101.0;
        const Trace3dResult r3 = trace_groove3d(g, m.frames[0], i, f);
        const double x = g.rim_x(Side::left) + f * (g.rim_x(Side::right) - g.rim_x(Side::left));
        const TraceResult r2 = trace(g, beam_ray(g, dir, x));
        const std::string where = "theta_m=" + std::to_string(theta_m_deg) + " theta_i=" + std::to_string(theta_i_deg) +
                                  " f=" + std::to_string(f);
        ASSERT_EQ(r3.trace.how, r2.how) << where;
        if (r2.how != Termination::escaped) continue;
        ++compared;
        EXPECT_EQ(r3.trace.bounces, r2.bounces) << where;
        EXPECT_EQ(r3.o.y(), 0.0) << where;
        EXPECT_NEAR(std::atan2(-r3.o.x(), r3.o.z()), angle_from_normal(r2.exit_dir), 1e-15 * (8 + r2.bounces)) << where;
      }
    }
  }
  // All escape but the 8 rays at theta_i = 0 and f = 1/2, which hit the apex (vertex hits in both).
  EXPECT_EQ(compared, 8 * 5 * 101 - 8);
}

TEST(Microsurface3dTally, BinEdges) {
  const Microsurface3dTally t(90, 72, 4);
  const double d = t.phi_width();
  EXPECT_EQ(t.phi_bin_of(0.0), 0);
  EXPECT_EQ(t.phi_bin_of(-0.5 * d), 0);
  // Edges to 1e-12 relative: a bin's measure does not depend on which side owns an edge.
  EXPECT_EQ(t.phi_bin_of(0.5 * d * (1.0 - 1e-12)), 0);
  EXPECT_EQ(t.phi_bin_of(0.5 * d * (1.0 + 1e-12)), 1);
  EXPECT_EQ(t.phi_bin_of(-0.5 * d * (1.0 + 1e-12)), 71);
  EXPECT_EQ(t.phi_bin_of(std::numbers::pi), 36);
  EXPECT_EQ(t.phi_bin_of(-std::numbers::pi), 36);
  EXPECT_EQ(t.phi_bin_of(std::nextafter(-std::numbers::pi, 0.0)), 36);
  EXPECT_EQ(t.theta_bin_of(0.0), 0);
  EXPECT_EQ(t.theta_bin_of(deg(30.5)), 30);
  EXPECT_EQ(t.theta_bin_of(std::nextafter(0.5 * std::numbers::pi, 0.0)), 89);
  EXPECT_EQ(t.index(1, 2, 3), static_cast<std::size_t>((1 * 90 + 2) * 72 + 3));
}

// The block form counts as the ray-by-ray one: every fate, k past max_k, t at both ends and p over
// the whole range it wraps, [-phi_bins, 2 phi_bins).
TEST(Microsurface3dTally, BlockCountsAsRayByRay) {
  Microsurface3dTally one(6, 8, 3), block(6, 8, 3);
  std::vector<Termination> how;
  std::vector<int> k;
  std::vector<double> oz, t, p;
  const Termination fates[] = {Termination::escaped, Termination::vertex_hit, Termination::bounce_limit};
  for (int q = 0; q < 3 * 7 * 6 * 24; ++q) {
    const Termination h = q % 11 == 0 ? fates[(q / 11) % 3] : Termination::escaped;
    const int kq = 1 + q % 7, tq = (q / 7) % 6, pq = -8 + (q / 42) % 24;
    const bool up = q % 13 != 0;
    one.add_binned(h, kq, up, tq, pq);
    how.push_back(h), k.push_back(kq), oz.push_back(up ? 0.5 : -0.5), t.push_back(tq), p.push_back(pq);
  }
  block.add_binned_block(how.data(), k.data(), oz.data(), t.data(), p.data(), static_cast<int>(how.size()));
  EXPECT_EQ(block.rays, one.rays);
  EXPECT_EQ(block.escaped, one.escaped);
  EXPECT_EQ(block.vertex_hits, one.vertex_hits);
  EXPECT_EQ(block.bounce_limit, one.bounce_limit);
  EXPECT_EQ(block.not_upward, one.not_upward);
  EXPECT_EQ(block.bounces, one.bounces);
  EXPECT_EQ(block.max_k_seen, one.max_k_seen);
  EXPECT_EQ(block.by_k, one.by_k);
  EXPECT_EQ(block.hist, one.hist);
  EXPECT_EQ(block.hist_by_k, one.hist_by_k);
}

// ---------------------------------------------------------------------------------------------
// The surface.

// Every ray in exactly one bucket; every escaped ray in one k row and one bin; rows add up to hist.
void expect_accounted(const Microsurface3dTally& t, std::int64_t rays, const std::string& where) {
  EXPECT_EQ(t.rays, rays) << where;
  EXPECT_EQ(t.escaped + t.lost(), t.rays) << where;
  std::int64_t by_k = 0, hist = 0, bounces = 0;
  for (std::size_t k = 0; k < t.by_k.size(); ++k) by_k += t.by_k[k];
  for (int k = 0; k <= t.max_k; ++k) bounces += k * t.by_k[static_cast<std::size_t>(k)];
  for (int b = 0; b < t.theta_bins; ++b)
    for (int p = 0; p < t.phi_bins; ++p) {
      const std::int64_t h = t.hist[static_cast<std::size_t>(b) * t.phi_bins + p];
      hist += h;
      std::int64_t rows = 0;
      for (int k = 0; k <= t.max_k + 1; ++k) rows += t.hist_by_k[t.index(k, b, p)];
      EXPECT_EQ(rows, h) << where << " bin " << b << "," << p;
    }
  EXPECT_EQ(by_k, t.escaped) << where;
  EXPECT_EQ(hist, t.escaped) << where;
  EXPECT_EQ(t.by_k[0], 0) << where;  // a closed groove always reflects at least once
  if (t.by_k[static_cast<std::size_t>(t.max_k) + 1] == 0) {
    EXPECT_EQ(bounces, t.bounces) << where;
  }
}

// F = 1 and ridges coplanar: every ray that enters a groove leaves it upward. Lost rays (vertex
// hits have probability zero; the bounce limit of 1e5 is far above the ~pi/theta_v bound of these
// grooves except for apertures under ~3e-5 rad, probability ~1e-9 per groove) are counted: none.
TEST(Microsurface3d, AlbedoIsOneAndEveryRayIsAccounted) {
  for (const auto& [kind, alpha] :
       {std::pair{NdfKind::ggx, 1.0}, std::pair{NdfKind::beckmann, 0.5}, std::pair{NdfKind::phong, 0.5}}) {
    const Microsurface3d m = make_microsurface3d({kind, alpha, 10000, 11});
    for (double theta_i_deg : {0.0, 60.0}) {
      Microsurface3dTraceOptions opt;
      opt.theta_i = deg(theta_i_deg);
      opt.rays = 40000;
      opt.seed = 3;
      const Microsurface3dTally t = trace_microsurface3d(m, opt);
      const std::string where =
          std::string(ndf_name(kind)) + " alpha=" + std::to_string(alpha) + " theta_i=" + std::to_string(theta_i_deg);
      expect_accounted(t, opt.rays, where);
      EXPECT_EQ(t.lost(), 0) << where << ": blocked " << t.blocked << " vertex " << t.vertex_hits << " limit "
                             << t.bounce_limit << " not upward " << t.not_upward;
      EXPECT_EQ(t.albedo(), 1.0) << where;
      EXPECT_GT(t.max_k_seen, 2) << where;  // these roughnesses have grooves deep enough for k >= 3
    }
  }
}

// alpha = 1e-4: Beckmann and Phong put every groove under ~1e-3 rad (Beckmann: P(theta_m > 1e-3)
// = exp(-100) per groove; Phong, p + 2 = 2e8: (cos 1e-3)^(2e8) = exp(-100)), so every ray reflects
// once within 2e-3 rad of the mirror direction dir(30.5 deg, 0), the centre of bin (30, 0) of half
// widths 0.5 and 2.5 deg.
TEST(Microsurface3d, NearlyFlatSurfaceReturnsTheMirrorBin) {
  for (NdfKind kind : {NdfKind::beckmann, NdfKind::phong}) {
    const Microsurface3d m = make_microsurface3d({kind, 1e-4, 1000, 5});
    Microsurface3dTraceOptions opt;
    opt.theta_i = deg(30.5);
    opt.rays = 20000;
    const Microsurface3dTally t = trace_microsurface3d(m, opt);
    expect_accounted(t, opt.rays, ndf_name(kind));
    EXPECT_EQ(t.escaped, opt.rays) << ndf_name(kind);
    EXPECT_EQ(t.by_k[1], opt.rays) << ndf_name(kind);
    EXPECT_EQ(t.hist[30 * 72 + 0], opt.rays) << ndf_name(kind);
  }
}

// At theta_i = 0 (i = n, so i.u = 0 and o lies in the groove's cross-section, at phi_a or phi_a + pi):
// (1) phi -> phi + pi. A symmetric groove lit along its axis of symmetry sends each ray to
//     either side with equal probability (t_o -> -t_o), so for the fixed set of grooves the counts
//     a, b of the bins (t, p) and (t, p + n/2) are, given a + b, binomial(a + b, 1/2):
//     sum (a - b)^2 / (a + b) is chi-square with one dof per pair (pairs with a + b >= 10).
// (2) phi -> -phi holds only over the draw of the grooves (their phi_a are not mirror-symmetric).
//     With h_j, h'_j the fractions of groove j's rays in the two bins, (h - h')^2 <= h + h', so
//     Var(a - b) <= N (q + q') + N^2 (q + q') / G = (1 + N/G) E[a + b]: the statistic divided by
//     1 + N/G is at most chi-square (conservative).
// Level 1e-3 for the two.
TEST(Microsurface3d, NormalIncidenceLobeIsSymmetric) {
  constexpr int grooves = 400000;
  const Microsurface3d m = make_microsurface3d({NdfKind::ggx, 0.5, grooves, 21});
  Microsurface3dTraceOptions opt;
  opt.theta_i = 0.0;
  opt.rays = 200000;
  opt.seed = 8;
  opt.theta_bins = 18;
  opt.phi_bins = 36;
  const Microsurface3dTally t = trace_microsurface3d(m, opt);
  expect_accounted(t, opt.rays, "theta_i=0");
  const int np = opt.phi_bins;
  auto h = [&](int b, int p) { return static_cast<double>(t.hist[static_cast<std::size_t>(b) * np + p]); };
  auto pair_test = [&](auto mirror, int p_lo, int p_hi, double inflation, const char* what) {
    double stat = 0.0;
    int dof = 0;
    for (int b = 0; b < opt.theta_bins; ++b)
      for (int p = p_lo; p < p_hi; ++p) {
        const double a = h(b, p), c = h(b, mirror(p));
        if (a + c < 10.0) continue;
        stat += (a - c) * (a - c) / (a + c);
        ++dof;
      }
    stat /= inflation;
    const double pv = gamma_q(0.5 * dof, 0.5 * stat);
    EXPECT_GT(dof, 100) << what;
    EXPECT_GE(pv, 1e-3 / 2.0) << what << ": chi2=" << stat << " dof=" << dof;
    return pv;
  };
  pair_test([&](int p) { return p + np / 2; }, 0, np / 2, 1.0, "phi -> phi + pi");
  pair_test([&](int p) { return np - p; }, 1, np / 2, 1.0 + static_cast<double>(opt.rays) / grooves, "phi -> -phi");
}

// Chunks traced in any order and merged give bit-identical tallies (integer counts).
TEST(Microsurface3d, DeterministicAcrossChunkOrders) {
  const Microsurface3d m = make_microsurface3d({NdfKind::beckmann, 0.7, 5000, 13});
  Microsurface3dTraceOptions opt;
  opt.theta_i = deg(40.0);
  opt.rays = 3 * kRaysPerChunk + 1234;
  opt.seed = 99;
  const Microsurface3dTally forward = trace_microsurface3d(m, opt);
  Microsurface3dTally backward(opt.theta_bins, opt.phi_bins, opt.max_k);
  for (std::int64_t c = chunk_count(opt) - 1; c >= 0; --c) backward.merge(trace_microsurface3d_chunk(m, opt, c));
  Microsurface3dTally pairs(opt.theta_bins, opt.phi_bins, opt.max_k), a = pairs, b = pairs;
  a.merge(trace_microsurface3d_chunk(m, opt, 3));
  a.merge(trace_microsurface3d_chunk(m, opt, 1));
  b.merge(trace_microsurface3d_chunk(m, opt, 2));
  b.merge(trace_microsurface3d_chunk(m, opt, 0));
  pairs.merge(b);
  pairs.merge(a);
  for (const Microsurface3dTally* x : {&backward, &pairs}) {
    EXPECT_EQ(x->rays, forward.rays);
    EXPECT_EQ(x->escaped, forward.escaped);
    EXPECT_EQ(x->bounces, forward.bounces);
    EXPECT_EQ(x->max_k_seen, forward.max_k_seen);
    EXPECT_EQ(x->by_k, forward.by_k);
    EXPECT_EQ(x->hist, forward.hist);
    EXPECT_EQ(x->hist_by_k, forward.hist_by_k);
  }
  EXPECT_EQ(forward.rays, opt.rays);
  // A different ray seed gives a different (yet equally valid) tally: the seed is used.
  Microsurface3dTraceOptions other = opt;
  other.seed = 100;
  EXPECT_NE(trace_microsurface3d(m, other).hist_by_k, forward.hist_by_k);
  // The surface is a function of its options.
  const Microsurface3d m2 = make_microsurface3d({NdfKind::beckmann, 0.7, 5000, 13});
  EXPECT_EQ(m2.theta_m, m.theta_m);
  EXPECT_EQ(m2.phi_a, m.phi_a);
}

}  // namespace
}  // namespace vgroove::sim
