// Tests of sim/slope_sampling.h and sim/microsurface.h.
//
// Sampling (matched pairs): the pdf integrates to one, the cdf is the integral of the pdf, the
// sampler inverts the cdf, and samples follow the pdf (chi-square against the pdf's quadrature
// over bins, fixed seed, pooled low cells, Bonferroni over the grid).
// Microsurface: every ray is accounted for and the albedo is one (F = 1); the bounce limit is
// counted, not dropped; mirror symmetry theta_i -> -theta_i within statistics; a very smooth
// surface reflects once, around -theta_i; at normal incidence the single-bounce rays are exactly
// those of the grooves with theta_m < 30 deg; results do not depend on how chunks are merged.
//
// Conventions (sim/geometry.h): angles from the normal, counter-clockwise positive; a flat mirror
// gives theta_o = -theta_i.
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/slope_sampling.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

// ---------------------------------------------------------------------------------------------
// Numerical helpers (independent of the code under test).

using namespace vgroove::test_stats;  // tanh_sinh, gamma_q, ChiSquare, chi_square

// Two samples, same bins: are they draws from one law? Cells pooled until a + b >= 10 (5 per
// sample); stat = sum (a sqrt(Nb/Na) - b sqrt(Na/Nb))^2 / (a + b), dof = cells - 1.
ChiSquare chi_square_two_sample(const std::vector<std::int64_t>& a, const std::vector<std::int64_t>& b) {
  double na = 0.0, nb = 0.0;
  for (auto v : a) na += static_cast<double>(v);
  for (auto v : b) nb += static_cast<double>(v);
  std::vector<std::pair<double, double>> cells;
  std::pair<double, double> acc{0.0, 0.0};
  for (std::size_t j = 0; j < a.size(); ++j) {
    acc.first += static_cast<double>(a[j]);
    acc.second += static_cast<double>(b[j]);
    if (acc.first + acc.second >= 10.0) {
      cells.push_back(acc);
      acc = {0.0, 0.0};
    }
  }
  if (acc.first + acc.second > 0.0) {
    if (cells.empty())
      cells.push_back(acc);
    else {
      cells.back().first += acc.first;
      cells.back().second += acc.second;
    }
  }
  ChiSquare r;
  std::ostringstream os;
  const double ka = std::sqrt(nb / na), kb = std::sqrt(na / nb);
  for (const auto& [x, y] : cells) {
    r.stat += (x * ka - y * kb) * (x * ka - y * kb) / (x + y);
    os << "  " << x << " | " << y << "\n";
  }
  r.dof = static_cast<int>(cells.size()) - 1;
  r.p = gamma_q(0.5 * r.dof, 0.5 * r.stat);
  r.table = os.str();
  return r;
}

TEST(TestHelpers, ChiSquareSurvivalFunction) {
  // dof 2: Q(1, x/2) = exp(-x/2); dof 1: Q(1/2, x/2) = erfc(sqrt(x/2)).
  for (double x : {0.1, 1.0, 3.0, 10.0, 40.0}) {
    EXPECT_NEAR(gamma_q(1.0, 0.5 * x), std::exp(-0.5 * x), 1e-14 * std::exp(-0.5 * x) + 1e-16) << "x=" << x;
    EXPECT_NEAR(gamma_q(0.5, 0.5 * x), std::erfc(std::sqrt(0.5 * x)), 1e-13 * std::erfc(std::sqrt(0.5 * x)) + 1e-16)
        << "x=" << x;
  }
  // Upper quantiles from the standard tables (4-5 digits): dof 10 at p = 0.001 is 29.588, dof 30
  // at p = 0.001 is 59.703, dof 1 at p = 0.05 is 1.959964^2 = 3.841459 (the normal 97.5% point squared).
  EXPECT_NEAR(gamma_q(5.0, 0.5 * 29.588), 1e-3, 1e-6);
  EXPECT_NEAR(gamma_q(15.0, 0.5 * 59.703), 1e-3, 1e-6);
  EXPECT_NEAR(gamma_q(0.5, 0.5 * 1.959964 * 1.959964), 0.05, 1e-6);
}

const NdfKind kKinds[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};
// Student-T (slope_sampling.h) at a heavy tail near its limit 1.5, GGX's 2, and a light one.
const NdfKind kStudentTs[] = {student_t_ndf(1.6), student_t_ndf(2.0), student_t_ndf(8.0)};
const double kAlphas[] = {0.05, 0.3, 0.5, 1.0, 2.0};

using KindAlpha = std::tuple<NdfKind, double>;
std::string kind_alpha_name(const testing::TestParamInfo<KindAlpha>& info) {
  std::ostringstream os;
  os << ndf_name(std::get<0>(info.param));
  if (std::get<0>(info.param) == NdfKind::student_t) os << "_g" << std::get<0>(info.param).gamma;
  os << "_a" << std::get<1>(info.param);
  std::string s = os.str();
  std::replace(s.begin(), s.end(), '.', 'p');
  return s;
}

// ---------------------------------------------------------------------------------------------
TEST(IncompleteBeta, ClosedForms) {
  for (double x : {1e-6, 0.01, 0.2, 0.5, 0.8, 0.999}) {
    const double y = 1.0 - x;
    EXPECT_NEAR(incomplete_beta(1.0, 1.0, x, y), x, 1e-15) << "x=" << x;
    EXPECT_NEAR(incomplete_beta(3.0, 1.0, x, y), x * x * x, 1e-15) << "x=" << x;
    EXPECT_NEAR(incomplete_beta(1.0, 2.5, x, y), 1.0 - std::pow(y, 2.5), 1e-14) << "x=" << x;
    // I_x(1/2, 1/2) = (2/pi) asin(sqrt(x)) (the arcsine law).
    EXPECT_NEAR(incomplete_beta(0.5, 0.5, x, y), 2.0 / std::numbers::pi * std::asin(std::sqrt(x)), 1e-14) << "x=" << x;
    // Symmetry I_x(a, b) = 1 - I_{1-x}(b, a), with large a (Phong at small alpha).
    EXPECT_NEAR(incomplete_beta(400.0, 0.5, x, y) + incomplete_beta(0.5, 400.0, y, x), 1.0, 1e-13) << "x=" << x;
  }
  EXPECT_EQ(incomplete_beta(2.0, 3.0, 0.0, 1.0), 0.0);
  EXPECT_EQ(incomplete_beta(2.0, 3.0, 1.0, 0.0), 1.0);
}

// ---------------------------------------------------------------------------------------------
// Tolerance of quadratures of the pdf: ~1e-12 for smooth integrands; Phong with alpha > 1 has an
// integrable singularity cos^(2/alpha^2 - 1) at +-pi/2, where theta stops approaching pi/2 at the
// rounding of std::numbers::pi/2 (6.1e-17): up to 2 sqrt(6.1e-17) = 1.6e-8 per end (ndf_test.cpp).
double quad_tol(NdfKind kind, double alpha) { return kind == NdfKind::phong && alpha > 1.0 ? 4e-8 : 1e-11; }

class SlopeSampling : public testing::TestWithParam<KindAlpha> {};

TEST_P(SlopeSampling, PdfIsNormalized) {
  const auto [kind, alpha] = GetParam();
  auto f = [&](double t) { return theta_m_pdf(kind, alpha, t); };
  EXPECT_NEAR(tanh_sinh(f, -0.5 * std::numbers::pi, 0.0) + tanh_sinh(f, 0.0, 0.5 * std::numbers::pi), 1.0,
              quad_tol(kind, alpha))
      << ndf_name(kind) << " alpha=" << alpha;
}

TEST_P(SlopeSampling, CdfIsTheIntegralOfThePdf) {
  const auto [kind, alpha] = GetParam();
  auto f = [&](double t) { return theta_m_pdf(kind, alpha, t); };
  for (double x : {0.01, 0.3, 1.0, 2.5, 8.0}) {
    const double t = std::atan(x * alpha);  // x in units of the slope scale alpha
    // The lower tail from -pi/2, and the central part from 0 (cdf(0) = 1/2 by symmetry).
    EXPECT_NEAR(theta_m_cdf(kind, alpha, -t), tanh_sinh(f, -0.5 * std::numbers::pi, -t), quad_tol(kind, alpha))
        << ndf_name(kind) << " alpha=" << alpha << " theta=" << -t;
    EXPECT_NEAR(theta_m_cdf(kind, alpha, t) - 0.5, tanh_sinh(f, 0.0, t), 1e-11)
        << ndf_name(kind) << " alpha=" << alpha << " theta=" << t;
  }
  EXPECT_EQ(theta_m_cdf(kind, alpha, 0.0), 0.5);
  EXPECT_EQ(theta_m_cdf(kind, alpha, -0.5 * std::numbers::pi), 0.0);
  EXPECT_EQ(theta_m_cdf(kind, alpha, 0.5 * std::numbers::pi), 1.0);
}

TEST_P(SlopeSampling, SampleInvertsTheCdf) {
  const auto [kind, alpha] = GetParam();
  // The sample is the inverse to the resolution of doubles: u lies between the cdf two ulps
  // below and two ulps above it (relative 1e-12 for the cdf's own rounding). Not |cdf(t) - u|
  // small: Phong at alpha = 2 (nu = 1/2) has tails so heavy that u = 1e-9 falls within one ulp
  // of -pi/2. Down to u = 1e-15 in both tails.
  for (double u : {1e-15, 1e-9, 1e-4, 0.01, 0.1, 0.3, 0.49, 0.5, 0.51, 0.7, 0.9, 0.999, 1.0 - 1e-9}) {
    const double t = sample_theta_m(kind, alpha, u);
    const double below = std::nextafter(std::nextafter(t, -4.0), -4.0);
    const double above = std::nextafter(std::nextafter(t, 4.0), 4.0);
    const double tail = std::min(u, 1.0 - u);
    EXPECT_LE(theta_m_cdf(kind, alpha, below), u + 1e-12 * tail)
        << ndf_name(kind) << " alpha=" << alpha << " u=" << u << " theta=" << t;
    EXPECT_GE(theta_m_cdf(kind, alpha, above), u - 1e-12 * tail)
        << ndf_name(kind) << " alpha=" << alpha << " u=" << u << " theta=" << t;
    // Where the cdf is steep enough for that to pin it down, the round trip is tight.
    if (alpha < 1.5) {
      EXPECT_NEAR(theta_m_cdf(kind, alpha, t), u, 1e-12 * tail + 1e-16)
          << ndf_name(kind) << " alpha=" << alpha << " u=" << u << " theta=" << t;
    }
    EXPECT_GE(t, -0.5 * std::numbers::pi);
    EXPECT_LE(t, 0.5 * std::numbers::pi);
  }
  EXPECT_EQ(sample_theta_m(kind, alpha, 0.5), 0.0) << ndf_name(kind) << " alpha=" << alpha;
}

TEST_P(SlopeSampling, SymmetricAndMonotone) {
  const auto [kind, alpha] = GetParam();
  double prev = -0.5 * std::numbers::pi;
  for (int j = 1; j < 1000; ++j) {
    const double u = j / 1000.0;
    const double t = sample_theta_m(kind, alpha, u);
    EXPECT_GT(t, prev) << ndf_name(kind) << " alpha=" << alpha << " u=" << u;
    EXPECT_NEAR(sample_theta_m(kind, alpha, 1.0 - u), -t, 1e-14 * (1.0 + std::abs(t)))
        << ndf_name(kind) << " alpha=" << alpha << " u=" << u;
    prev = t;
  }
}

// Samples against the pdf. Bins of equal width in phi = atan(tan(theta) / alpha), which follows
// the law's scale; expected counts by quadrature of the pdf (not by the cdf the sampler inverts).
// Level 1e-3 for the whole grid of 15, so 1e-3/15 for each case.
TEST_P(SlopeSampling, SamplesFollowThePdf) {
  const auto [kind, alpha] = GetParam();
  constexpr int n = 100000, bins = 40;
  constexpr double level = 1e-3 / 15.0;
  const std::vector<double> edges = slope_bin_edges(alpha, bins);
  std::vector<double> expected(bins);
  for (int j = 0; j < bins; ++j)
    expected[j] = n * tanh_sinh([&](double t) { return theta_m_pdf(kind, alpha, t); }, edges[j], edges[j + 1]);
  std::vector<std::int64_t> observed(bins, 0);
  // Student-T's tail in the stream (0 for the other NDFs: their streams are as without it).
  const std::uint64_t stream = static_cast<std::uint64_t>(kind.family) | static_cast<std::uint64_t>(kind.gamma * 10)
                                                                             << 8;
  Rng rng(20180611, stream, static_cast<std::uint64_t>(alpha * 1000));
  for (int i = 0; i < n; ++i) {
    const double t = sample_theta_m(kind, alpha, rng.uniform());
    const auto it = std::upper_bound(edges.begin(), edges.end(), t);
    ++observed[std::clamp<std::ptrdiff_t>(it - edges.begin() - 1, 0, bins - 1)];
  }
  const ChiSquare c = chi_square_gof(edges, expected, observed);
  EXPECT_GE(c.p, level) << ndf_name(kind) << " alpha=" << alpha << ": chi2=" << c.stat << " dof=" << c.dof
                        << " p=" << c.p << "\n"
                        << c.table;
}

INSTANTIATE_TEST_SUITE_P(Grid, SlopeSampling, testing::Combine(testing::ValuesIn(kKinds), testing::ValuesIn(kAlphas)),
                         kind_alpha_name);
// Student-T on its own (15 cases at the same level each: 1e-3 over them).
INSTANTIATE_TEST_SUITE_P(StudentT, SlopeSampling,
                         testing::Combine(testing::ValuesIn(kStudentTs), testing::ValuesIn(kAlphas)), kind_alpha_name);

// gamma = 2 is GGX, and gamma = 1 + 1/alpha^2 is Phong (the same slope laws, slope_sampling.h): the
// pdf, the cdf and the samples agree to rounding, the samples by another route (Newton on the
// t law's tail against GGX's closed form and Phong's Newton).
TEST(SlopeSampling, StudentTIsGgxAtTwoAndPhongAtOnePlusInverseAlphaSquared) {
  for (double alpha : {0.3, 0.8})
    for (double t_deg : {-80.0, -30.0, 0.0, 10.0, 60.0}) {
      const double t = t_deg * std::numbers::pi / 180.0;
      EXPECT_NEAR(theta_m_pdf(student_t_ndf(2.0), alpha, t) / theta_m_pdf(NdfKind::ggx, alpha, t), 1.0, 1e-14) << t_deg;
      EXPECT_NEAR(theta_m_cdf(student_t_ndf(2.0), alpha, t), theta_m_cdf(NdfKind::ggx, alpha, t), 1e-14) << t_deg;
      const NdfKind p = student_t_ndf(1.0 + 1.0 / (alpha * alpha));
      EXPECT_NEAR(theta_m_pdf(p, alpha, t) / theta_m_pdf(NdfKind::phong, alpha, t), 1.0, 1e-13) << t_deg;
      EXPECT_NEAR(theta_m_cdf(p, alpha, t), theta_m_cdf(NdfKind::phong, alpha, t), 1e-14) << t_deg;
    }
  for (double u : {1e-9, 0.02, 0.4, 0.6, 0.999})
    EXPECT_NEAR(sample_theta_m(student_t_ndf(2.0), 0.5, u), sample_theta_m(NdfKind::ggx, 0.5, u), 1e-14) << u;
}

// ---------------------------------------------------------------------------------------------
// Microsurface.

// Every ray in exactly one bucket; every escaped ray in one k row and one theta_o bin, per-k
// histograms adding up to the total.
void expect_accounted(const MicrosurfaceTally& t, std::int64_t rays, const std::string& where) {
  EXPECT_EQ(t.rays, rays) << where;
  EXPECT_EQ(t.escaped + t.lost(), t.rays) << where;
  std::int64_t by_k = 0, hist = 0, bounces = 0;
  for (std::size_t k = 0; k < t.by_k.size(); ++k) by_k += t.by_k[k];
  for (int k = 0; k <= t.max_k; ++k) bounces += k * t.by_k[static_cast<std::size_t>(k)];
  for (int j = 0; j < t.bins; ++j) {
    hist += t.theta_o[static_cast<std::size_t>(j)];
    std::int64_t rows = 0;
    for (int k = 0; k <= t.max_k + 1; ++k) rows += t.hist(k, j);
    EXPECT_EQ(rows, t.theta_o[static_cast<std::size_t>(j)]) << where << " bin " << j;
  }
  for (int k = 0; k <= t.max_k + 1; ++k) {
    std::int64_t row = 0;
    for (int j = 0; j < t.bins; ++j) row += t.hist(k, j);
    EXPECT_EQ(row, t.by_k[static_cast<std::size_t>(k)]) << where << " k row " << k;
  }
  EXPECT_EQ(by_k, t.escaped) << where;
  EXPECT_EQ(hist, t.escaped) << where;
  if (t.by_k.back() == 0) {
    EXPECT_EQ(bounces, t.bounces) << where;  // all k within the rows
  }
  EXPECT_NEAR(t.albedo(), 1.0 - static_cast<double>(t.lost()) / static_cast<double>(t.rays), 1e-15) << where;
}

std::string where(NdfKind kind, double alpha, double theta_i) {
  std::ostringstream os;
  os << ndf_name(kind) << " alpha=" << alpha << " theta_i=" << theta_i * 180.0 / std::numbers::pi << " deg";
  return os.str();
}

TEST(Microsurface, GroovesCoverTheLengthAsTheNdfSays) {
  // Equal widths: the fraction of the macrosurface under grooves with |theta_m| < t is the
  // fraction of grooves, expected cdf(t) - cdf(-t); binomial, 5 sigma.
  constexpr int g = 20000;
  std::vector<NdfKind> kinds(std::begin(kKinds), std::end(kKinds));
  kinds.insert(kinds.end(), std::begin(kStudentTs), std::end(kStudentTs));
  for (NdfKind kind : kinds) {
    const Microsurface m = make_microsurface({kind, 0.5, g, 7});
    ASSERT_EQ(m.grooves.size(), static_cast<std::size_t>(g));
    for (double x : {0.2, 0.7, 1.5, 3.0}) {
      const double t = std::atan(0.5 * x);
      const double p = theta_m_cdf(kind, 0.5, t) - theta_m_cdf(kind, 0.5, -t);
      const double frac =
          static_cast<double>(std::count_if(m.theta_m.begin(), m.theta_m.end(), [&](double v) { return v < t; })) / g;
      EXPECT_NEAR(frac, p, 5.0 * std::sqrt(p * (1.0 - p) / g)) << ndf_name(kind) << " t=" << t;
    }
    for (std::size_t j = 0; j < m.grooves.size(); ++j) {
      ASSERT_GE(m.theta_m[j], 0.0);
      ASSERT_LT(m.theta_m[j], 0.5 * std::numbers::pi);
      ASSERT_GT(m.grooves[j].theta_v, 0.0) << "groove " << j;
      ASSERT_NEAR(m.grooves[j].theta_v, std::numbers::pi - 2.0 * m.theta_m[j], 1e-15) << "groove " << j;
    }
  }
}

TEST(Microsurface, AlbedoIsOneAndEveryRayIsAccounted) {
  // F = 1 and no absorption: every ray leaves (the tracer always ends within ceil(pi/theta_v)
  // reflections); vertex hits have probability ~1e-16 per ray and no groove here needs more than
  // the bounce limit.
  constexpr std::int64_t rays = 50000;
  std::vector<NdfKind> kinds(std::begin(kKinds), std::end(kKinds));
  kinds.insert(kinds.end(), std::begin(kStudentTs), std::end(kStudentTs));
  for (NdfKind kind : kinds) {
    const Microsurface m = make_microsurface({kind, 0.5, 4000, 11});
    for (double ti : {0.0, 40.0, 80.0}) {
      MicrosurfaceTraceOptions o;
      o.theta_i = deg(ti);
      o.rays = rays;
      o.seed = 3;
      const MicrosurfaceTally t = trace_microsurface(m, o);
      const std::string w = where(kind, 0.5, o.theta_i);
      expect_accounted(t, rays, w);
      EXPECT_EQ(t.escaped, rays) << w;
      EXPECT_EQ(t.albedo(), 1.0) << w;
      EXPECT_EQ(t.blocked, 0) << w;
      EXPECT_EQ(t.not_upward, 0) << w;
      EXPECT_EQ(t.vertex_hits, 0) << w;
      EXPECT_EQ(t.bounce_limit, 0) << w;
      EXPECT_GT(t.max_k_seen, 1) << w;  // alpha = 0.5 has grooves deep enough for k >= 2
    }
  }
}

TEST(Microsurface, BounceLimitIsCountedNotDropped) {
  // The same rays (same seeds) with max_bounces = 2 and unlimited: the rays the first run stops
  // at the limit are exactly those the second sees with k > 2, and the others are unchanged.
  const Microsurface m = make_microsurface({NdfKind::ggx, 1.0, 2000, 5});
  MicrosurfaceTraceOptions o;
  o.theta_i = deg(30);
  o.rays = 40000;
  o.seed = 9;
  const MicrosurfaceTally full = trace_microsurface(m, o);
  o.trace.max_bounces = 2;
  const MicrosurfaceTally cut = trace_microsurface(m, o);
  expect_accounted(full, o.rays, "unlimited");
  expect_accounted(cut, o.rays, "max_bounces=2");
  std::int64_t deep = 0;
  for (std::size_t k = 3; k < full.by_k.size(); ++k) deep += full.by_k[k];
  EXPECT_GT(deep, 0);
  EXPECT_EQ(cut.bounce_limit, deep);
  EXPECT_NEAR(cut.albedo(), 1.0 - static_cast<double>(deep) / o.rays, 1e-15);
  for (int k = 0; k <= 2; ++k)
    EXPECT_EQ(cut.by_k[static_cast<std::size_t>(k)], full.by_k[static_cast<std::size_t>(k)]) << "k=" << k;
  EXPECT_EQ(cut.max_k_seen, 2);
}

TEST(Microsurface, MirrorSymmetry) {
  // Each groove is symmetric, so P(theta_o | theta_i) = P(-theta_o | -theta_i) on a given surface.
  // Rays from theta_i and -theta_i with different seeds; the second histogram reversed; two-sample
  // chi-square on the theta_o histogram and on the bounce counts. 3 NDFs x 2 angles x 2 statistics:
  // level 1e-3 / 12 each.
  constexpr double level = 1e-3 / 12.0;
  for (NdfKind kind : kKinds) {
    const Microsurface m = make_microsurface({kind, 0.5, 4000, 21});
    for (double ti : {20.0, 60.0}) {
      MicrosurfaceTraceOptions o;
      o.rays = 200000;
      o.theta_i = deg(ti);
      o.seed = 1;
      const MicrosurfaceTally a = trace_microsurface(m, o);
      o.theta_i = -deg(ti);
      o.seed = 2;
      const MicrosurfaceTally b = trace_microsurface(m, o);
      std::vector<std::int64_t> b_rev(b.theta_o.rbegin(), b.theta_o.rend());
      const ChiSquare h = chi_square_two_sample(a.theta_o, b_rev);
      EXPECT_GE(h.p, level) << where(kind, 0.5, deg(ti)) << ": theta_o chi2=" << h.stat << " dof=" << h.dof
                            << " p=" << h.p << "\n"
                            << h.table;
      const ChiSquare k = chi_square_two_sample(a.by_k, b.by_k);
      EXPECT_GE(k.p, level) << where(kind, 0.5, deg(ti)) << ": k chi2=" << k.stat << " dof=" << k.dof << " p=" << k.p
                            << "\n"
                            << k.table;
      // The test has power: the unreversed histogram differs (the lobe sits at -theta_i).
      EXPECT_LT(chi_square_two_sample(a.theta_o, b.theta_o).p, 1e-10) << where(kind, 0.5, deg(ti));
    }
  }
}

TEST(Microsurface, SmoothSurfaceReflectsOnceAroundTheMirrorDirection) {
  // alpha = 0.01. A first reflection off the facet at -+theta_m leaves at theta_o1 = -+2 theta_m -
  // theta_i, |theta_o1| <= |theta_i| + 2 theta_m; it meets the other facet only if it is shallower
  // than that facet, |theta_o1| > pi/2 - theta_m. So k >= 2 needs theta_m > (pi/2 - |theta_i|) / 3,
  // and the multiple-bounce fraction is at most the length fraction q of such grooves (+ 5 sigma
  // of the N rays). For Beckmann q = 0 here (8 sigma of its slopes); GGX's tails leave ~1.5% at 80 deg.
  constexpr std::int64_t rays = 100000;
  for (NdfKind kind : {NdfKind::beckmann, NdfKind::ggx}) {
    const Microsurface m = make_microsurface({kind, 0.01, 20000, 13});
    for (double ti : {0.0, 40.0, 80.0}) {
      MicrosurfaceTraceOptions o;
      o.theta_i = deg(ti);
      o.rays = rays;
      o.seed = 17;
      const MicrosurfaceTally t = trace_microsurface(m, o);
      const std::string w = where(kind, 0.01, o.theta_i);
      expect_accounted(t, rays, w);
      const double t_star = (0.5 * std::numbers::pi - o.theta_i) / 3.0;
      const double q =
          static_cast<double>(std::count_if(m.theta_m.begin(), m.theta_m.end(), [&](double v) { return v > t_star; })) /
          static_cast<double>(m.theta_m.size());
      const double single = static_cast<double>(t.by_k[1]) / rays;
      EXPECT_GE(single, 1.0 - q - 5.0 * std::sqrt(q * (1.0 - q) / rays)) << w << " q=" << q;
      EXPECT_GT(single, 0.98) << w;
      if (kind == NdfKind::beckmann) {
        EXPECT_EQ(t.by_k[1], rays) << w;
      }
      // The lobe's peak: -theta_i lies in the peak bin or on its edge.
      const int peak = static_cast<int>(std::max_element(t.theta_o.begin(), t.theta_o.end()) - t.theta_o.begin());
      EXPECT_LE(std::abs(t.bin_center(peak) + o.theta_i), t.bin_width()) << w << " peak bin " << peak;
      // Nearly all rays within 5 deg of it (2 theta_m < 5 deg is 6 sigma for Beckmann's slopes).
      std::int64_t near = 0;
      for (int j = 0; j < t.bins; ++j)
        if (std::abs(t.bin_center(j) + o.theta_i) < deg(5)) near += t.theta_o[static_cast<std::size_t>(j)];
      EXPECT_GT(static_cast<double>(near) / rays, 0.95) << w;
    }
  }
}

TEST(Microsurface, AtNormalIncidenceSingleBouncesComeFromGroovesUnder30Degrees) {
  // theta_i = 0: a ray reflected by a facet at theta_m leaves at 2 theta_m from the normal; it
  // clears the other facet when it rises more steeply than it, 90 - 2 theta_m > theta_m, i.e.
  // theta_m < 30 deg. So all rays in those grooves bounce once and leave with |theta_o| =
  // 2 theta_m < 60 deg, and a single bounce in a steeper groove leaves beyond 60 deg. With 8
  // stratified rays per groove (at f = (i + 0.5)/8, never the apex), the single-bounce rays
  // within 60 deg (30 bins of 2 deg) are exactly 8 x the number of grooves under 30 deg.
  for (NdfKind kind : kKinds) {
    const Microsurface m = make_microsurface({kind, 0.7, 3000, 23});
    MicrosurfaceTraceOptions o;
    o.rays = 8 * 3000;
    o.sampling = Sampling::stratified;
    const MicrosurfaceTally t = trace_microsurface(m, o);
    expect_accounted(t, o.rays, where(kind, 0.7, 0.0));
    std::int64_t central = 0;
    for (int j = 15; j < 75; ++j) central += t.hist(1, j);
    const auto shallow = std::count_if(m.theta_m.begin(), m.theta_m.end(), [](double v) { return v < deg(30); });
    EXPECT_EQ(central, 8 * shallow) << ndf_name(kind);
    EXPECT_LT(shallow, 3000) << ndf_name(kind);  // the case has steep grooves too
  }
}

// Stratified landing points are the midpoints of equal strata, exactly: never on a ridge (f in
// (0, 1)), in groove order, one groove's bit for bit (j + 1/2) / rays, and the strata's midpoints
// where those fall inside a groove.
TEST(Microsurface, StratifiedLandingPointsAreMidpointsOffTheRidges) {
  for (const auto& [grooves, rays] : {std::pair<std::int64_t, std::int64_t>{1, 7},
                                      {10000, 5000},
                                      {6, 4},
                                      {7, 7},
                                      {3, 1000},
                                      {10000000, 1000000000}}) {
    int last = 0;
    for (std::int64_t j : {std::int64_t{0}, std::int64_t{1}, rays / 3, rays / 2, rays - 2, rays - 1}) {
      if (j < 0 || j >= rays) continue;
      const Landing at = stratified_landing(j, rays, grooves);
      EXPECT_GT(at.f, 0.0) << grooves << " " << rays << " " << j;
      EXPECT_LT(at.f, 1.0) << grooves << " " << rays << " " << j;
      EXPECT_GE(at.groove, last);
      EXPECT_LT(at.groove, grooves);
      last = at.groove;
      const long double mid = (j + 0.5L) * grooves / rays;
      const long double got = at.groove + static_cast<long double>(at.f);
      EXPECT_LE(std::abs(got - mid), 0.25L / rays + 1e-15L * grooves) << grooves << " " << rays << " " << j;
      if (grooves == 1) {
        EXPECT_EQ(at.f, (static_cast<double>(j) + 0.5) / static_cast<double>(rays));
      }
    }
  }
}

TEST(Microsurface, StratifiedRaysNeverHitARidge) {
  // Two rays per groove land at f = 1/4 and 3/4 of each; one ray per two grooves would land on
  // every other left ridge (a vertex hit for 88 % of the rays).
  for (const auto& [grooves, rays] : {std::pair{4000, 2000}, std::pair{2000, 4000}, std::pair{3000, 3000}}) {
    const Microsurface m = make_microsurface({NdfKind::ggx, 0.5, grooves, 1});
    MicrosurfaceTraceOptions o;
    o.theta_i = deg(30);
    o.rays = rays;
    o.sampling = Sampling::stratified;
    const MicrosurfaceTally t = trace_microsurface(m, o);
    EXPECT_EQ(t.vertex_hits, 0) << grooves << " grooves, " << rays << " rays";
    EXPECT_EQ(t.escaped, rays) << grooves << " grooves, " << rays << " rays";
    const MicrosurfaceTally ref = trace_microsurface_chunk_reference(m, o, 0);
    EXPECT_EQ(ref.by_k, t.by_k);
    EXPECT_EQ(ref.theta_o_by_k, t.theta_o_by_k);
  }
}

TEST(Microsurface, ResultsDoNotDependOnHowChunksAreMerged) {
  const Microsurface m = make_microsurface({NdfKind::beckmann, 0.5, 1000, 31});
  MicrosurfaceTraceOptions o;
  o.theta_i = deg(35);
  o.rays = 5 * kRaysPerChunk + 123;  // a partial last chunk
  o.seed = 77;
  const MicrosurfaceTally serial = trace_microsurface(m, o);
  ASSERT_EQ(chunk_count(o), 6);
  // As two "threads" would: odd and even chunks apart, in reverse, merged at the end.
  MicrosurfaceTally odd(o.theta_o_bins, o.max_k), even(o.theta_o_bins, o.max_k);
  for (std::int64_t c = chunk_count(o) - 1; c >= 0; --c) (c % 2 ? odd : even).merge(trace_microsurface_chunk(m, o, c));
  odd.merge(even);
  EXPECT_EQ(odd.rays, serial.rays);
  EXPECT_EQ(odd.escaped, serial.escaped);
  EXPECT_EQ(odd.bounces, serial.bounces);
  EXPECT_EQ(odd.by_k, serial.by_k);
  EXPECT_EQ(odd.theta_o, serial.theta_o);
  EXPECT_EQ(odd.theta_o_by_k, serial.theta_o_by_k);
  EXPECT_EQ(trace_microsurface(m, o).theta_o_by_k, serial.theta_o_by_k);  // reproducible
  // The seeds matter: another ray seed, or another surface, gives other counts.
  o.seed = 78;
  EXPECT_NE(trace_microsurface(m, o).theta_o, serial.theta_o);
  o.seed = 77;
  EXPECT_NE(trace_microsurface(make_microsurface({NdfKind::beckmann, 0.5, 1000, 32}), o).theta_o, serial.theta_o);
  EXPECT_EQ(make_microsurface({NdfKind::beckmann, 0.5, 1000, 31}).theta_m, m.theta_m);
}

// Reciprocity of the traced surface itself (Helmholtz: each groove is a fixed mirror geometry, so
// the flux it carries from a into b equals that from b into a, per unit projected solid angle):
//   M(A, B) = int_A da int_B db rho(a, b) cos a cos b = int_A cos a frac(a -> B) da
// is symmetric in the two angular bins A, B. frac(a -> B) is the traced fraction of rays from a
// landing in B, and the integral over A is Gauss-Legendre on 4 nodes. The same surface (same
// grooves) serves both directions, so only the rays' multinomial noise separates M(A, B) from
// M(B, A): sd^2 = sum_j (w_j cos a_j)^2 f_j (1 - f_j) / N per side; the test allows 5 sd
// plus the 4-node quadrature error (frac is smooth within a 5 deg bin except at a few kinks of
// Eq. 4). Measured: the four pairs agree to 0.1-1 sd (sd 1.5e-5..3.8e-5 on M of 1e-3..3.5e-3);
// without the cos a weights (a non-reciprocal measure) they would differ by cos a / cos b.
TEST(MicrosurfaceReciprocity, TracedFlatlandSurfaceIsReciprocalWithinStatistics) {
  MicrosurfaceOptions mo;
  mo.ndf = NdfKind::ggx;
  mo.alpha = 0.7;
  mo.grooves = 20000;
  mo.seed = 3;
  const Microsurface surface = make_microsurface(mo);
  const long rays = 100000;
  const int bins = 36;  // 5 deg bins over (-90, 90)
  const double w = std::numbers::pi / bins;
  constexpr double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  constexpr double gw[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  // M(A -> B) and its variance, for bin indices A and B.
  auto M = [&](int A, int B, double& var) {
    double m = 0.0;
    var = 0.0;
    for (int j = 0; j < 4; ++j) {
      const double a = -0.5 * std::numbers::pi + (A + 0.5) * w + 0.5 * w * x[j];
      MicrosurfaceTraceOptions to;
      to.theta_i = a;
      to.rays = rays;
      to.seed = 11 + static_cast<std::uint64_t>(A * 8 + j);
      to.theta_o_bins = bins;
      to.max_k = 4;
      const MicrosurfaceTally t = trace_microsurface(surface, to);
      const double f = static_cast<double>(t.theta_o[static_cast<std::size_t>(B)]) / static_cast<double>(rays);
      const double c = 0.5 * w * gw[j] * std::cos(a);
      m += c * f;
      var += c * c * f * (1.0 - f) / static_cast<double>(rays);
    }
    return m;
  };
  // Pairs of bins: near-mirror, back-scattering and one grazing-to-steep pair.
  for (auto [A, B] : {std::pair{24, 11}, std::pair{22, 20}, std::pair{30, 14}, std::pair{33, 8}}) {
    double va = 0.0, vb = 0.0;
    const double ab = M(A, B, va), ba = M(B, A, vb);
    EXPECT_NEAR(ab, ba, 5.0 * std::sqrt(va + vb)) << "bins " << A << " and " << B;
    EXPECT_GT(ab, 0.0);
  }
}

}  // namespace
}  // namespace vgroove::sim
