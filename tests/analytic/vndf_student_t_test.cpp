// Tests of the Student-T Smith visible normals (analytic/detail/vndf_student_t.h): the density
// integrates to 1 (tanh-sinh quadrature, tests/stats.h, with the visibility crease as a cut); at
// gamma = 2 the density is GGX's and the samples are the GGX visible-slope sampler's for the same
// uniforms (smith_walk_3d.h's closed form, the same method); at gamma -> infinity both tend to
// Beckmann's at the rate 1/gamma; the samples follow the density by chi-square with fixed seeds
// (and a density of another gamma is rejected by the same test); no NaN over the hard cases.
#include "vgroove/analytic/detail/vndf_student_t.h"

#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/analytic/smith_walk_flatland.h"
#include "vgroove/analytic/vndf.h"
#include "vgroove/common/angles.h"

#include "../stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

namespace vgroove::analytic {
namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

// The incident direction at theta_i (degrees) in the (x, z) plane, its horizontal part along -x
// (vndf.h's flatland direction).
Dir3 incident(double deg) { return {-std::sin(deg * kRadPerDeg), 0.0, std::cos(deg * kRadPerDeg)}; }

// The normal at cos(theta) = c and azimuth phi.
Dir3 normal_at(double c, double phi) {
  const double sn = std::sqrt((1.0 - c) * (1.0 + c));
  return {sn * std::cos(phi), sn * std::sin(phi), c};
}

// int f(m) dm over theta_m in [t0, t1] and phi in [p0, p1] for the density of tail gamma: tanh-sinh in
// phi and in c = cos(theta) (dm = dc dphi), c cut where <i, m> = 0 (the density's crease; i = (-sin
// ti, 0, cos ti): <i, m> = cos(ti) c - sin(ti) sqrt(1 - c^2) cos(phi)) and at every decade below 0.1.
// Below c = eps = 1e-6, where D ~ c^(2 gamma - 4) is nearly not integrable for gamma near 1.5 (the
// mass below c falls as c^(2 gamma - 3): at gamma = 1.51, alpha = 0.2, theta_i = 60 deg, 61 % of the
// samples have c < 1e-6 and 5 % c < 1e-61, beyond tanh-sinh's last node), the share from the density's form there: f ~
// K c^(2 gamma - 4) (sigma + c cos(ti)), sigma = -sin(ti) cos(phi) (relative error O(c^2)), K from f at eps.
template <class F>
double over_normals(const Dir3& i, double gamma, F&& f, double t0, double t1, double p0, double p1,
                    double h = 1.0 / 32.0) {
  const double sin_i = -i.x, cos_i = i.z;
  const double c_lo = t1 >= kHalfPi ? 0.0 : std::cos(t1), c_hi = std::cos(t0);
  // The crease reaches the horizon at phi = pi/2 (a kink of the inner integral in phi): cut there.
  if (p0 < kHalfPi && p1 > kHalfPi && sin_i > 0.0)
    return over_normals(i, gamma, f, t0, t1, p0, kHalfPi, h) + over_normals(i, gamma, f, t0, t1, kHalfPi, p1, h);
  constexpr double eps = 1e-6;
  return test_stats::tanh_sinh(
      [&](double phi) {
        auto g = [&](double c) { return f(normal_at(c, phi)); };
        double sum = 0.0, lo = c_lo;
        if (c_lo == 0.0) {
          const double sigma = -sin_i * std::cos(phi), c0 = std::max(0.0, -sigma / cos_i);
          const double at = g(eps);
          if (c0 < eps && at > 0.0) {
            const double K = at / (std::pow(eps, 2.0 * gamma - 4.0) * (sigma + eps * cos_i));
            sum += K *
                   (sigma * (std::pow(eps, 2.0 * gamma - 3.0) - std::pow(c0, 2.0 * gamma - 3.0)) / (2.0 * gamma - 3.0) +
                    cos_i * (std::pow(eps, 2.0 * gamma - 2.0) - std::pow(c0, 2.0 * gamma - 2.0)) / (2.0 * gamma - 2.0));
          }
          lo = eps;
        }
        std::vector<double> cuts{lo};
        for (double d = 1e-5; d < 0.1; d *= 10.0)
          if (d > lo && d < c_hi) cuts.push_back(d);
        const double cp = std::cos(phi);
        const double crease = cp > 0.0 && sin_i > 0.0 ? sin_i * cp / std::hypot(cos_i, sin_i * cp) : 0.0;
        if (crease > lo && crease < c_hi) cuts.push_back(crease);
        cuts.push_back(c_hi);
        std::sort(cuts.begin(), cuts.end());
        for (std::size_t j = 0; j + 1 < cuts.size(); ++j) sum += test_stats::tanh_sinh(g, cuts[j], cuts[j + 1], h);
        return sum;
      },
      p0, p1, h);
}

// The share of pdf(theta_s) within eps of the end side pi/2 (side = +-1), from the density's form
// there: pdf ~ K delta^(2 gamma - 4) (sigma + delta cos(theta_i)) at theta_s = side (pi/2 - delta),
// sigma = side sin(theta_i) (D2 ~ delta^(2 gamma - 4), <i.s> linear; the next terms are O(delta^2)
// relative), K from the pdf at delta = eps. (theta_s itself cannot resolve the last 1e-16 rad, which
// carry (1e-16)^0.2 of the mass at gamma = 1.6.)
constexpr double kEndEps = 1e-4;
template <class F>
double end_share(F&& pdf, double gamma, double theta_i, double side) {
  const double ci = std::cos(theta_i), sigma = side * std::sin(theta_i), eps = kEndEps;
  if (sigma < 0.0) return 0.0;  // the end faces away from i
  const double at = pdf(side * (kHalfPi - eps));
  return at * eps * (sigma / (2.0 * gamma - 3.0) + eps * ci / (2.0 * gamma - 2.0)) / (sigma + eps * ci);
}

// int pdf(theta_s) d theta_s over [lo, hi] within (-pi/2, pi/2): tanh-sinh up to kEndEps from the ends
// (cut at the crease theta_i -+ pi/2), end_share beyond.
template <class F>
double over_facet_angles(F&& pdf, double gamma, double theta_i, double lo = -kHalfPi, double hi = kHalfPi) {
  double sum = 0.0;
  if (lo <= -kHalfPi) sum += end_share(pdf, gamma, theta_i, -1.0);
  if (hi >= kHalfPi) sum += end_share(pdf, gamma, theta_i, 1.0);
  lo = std::max(lo, -kHalfPi + kEndEps), hi = std::min(hi, kHalfPi - kEndEps);
  if (!(hi > lo)) return sum;
  const double crease = theta_i - std::copysign(kHalfPi, theta_i);
  if (crease > lo && crease < hi)
    return sum + test_stats::tanh_sinh(pdf, lo, crease, 1.0 / 128.0) +
           test_stats::tanh_sinh(pdf, crease, hi, 1.0 / 128.0);
  return sum + test_stats::tanh_sinh(pdf, lo, hi, 1.0 / 128.0);
}

// ---- Normalization --------------------------------------------------------------------------------

void check_normalization(double gamma, double alpha, double deg, double h) {
  const StudentT t{alpha, gamma};
  const Dir3 i = incident(deg);
  // Mirror symmetric about the (x, z) plane: phi in [0, pi], twice.
  const double total = 2.0 * over_normals(
                                 i, gamma, [&](const Dir3& m) { return student_t_vndf_pdf(t, i, m); }, 0.0, kHalfPi,
                                 0.0, std::numbers::pi, h);
  EXPECT_NEAR(total, 1.0, 1e-7) << "gamma=" << gamma << " alpha=" << alpha << " theta_i=" << deg;
  const double flat =
      over_facet_angles([&](double s) { return student_t_vndf2_pdf(t, deg * kRadPerDeg, s); }, gamma, deg * kRadPerDeg);
  EXPECT_NEAR(flat, 1.0, 1e-7) << "flatland gamma=" << gamma << " alpha=" << alpha << " theta_i=" << deg;
}

TEST(StudentTVndf, DensityIntegratesToOne) {
  for (double gamma : {1.51, 2.0, 50.0})
    for (double deg : {0.0, 75.0, 89.9}) check_normalization(gamma, 0.5, deg, 1.0 / 16.0);
}

// The grid (label long): gamma 1.51..50, alpha 0.1..2, theta_i 0..89.9 deg.
TEST(StudentTVndfLong, DensityIntegratesToOne) {
  for (double gamma : {1.51, 1.6, 2.0, 3.0, 8.0, 50.0})
    for (double alpha : {0.1, 0.5, 1.0, 2.0})
      for (double deg : {0.0, 30.0, 75.0, 89.9}) check_normalization(gamma, alpha, deg, 1.0 / 32.0);
}

// ---- gamma = 2 is GGX -------------------------------------------------------------------------------

TEST(StudentTVndf, Gamma2DensityIsGgx) {
  for (double alpha : {0.01, 0.3, 1.0, 2.0})
    for (double deg : {0.0, 20.0, 60.0, 89.9}) {
      const StudentT t{alpha, 2.0};
      const Dir3 i = dir3(deg * kRadPerDeg, 0.7);
      for (double tm : {0.0, 0.3, 0.9, 1.4, 1.55})
        for (double pm : {0.0, 1.0, 2.5, 3.1}) {
          const Dir3 m = dir3(tm, pm);
          const double ggx = ggx_vndf_pdf(alpha, i, m);
          EXPECT_NEAR(student_t_vndf_pdf(t, i, m), ggx, 1e-13 * ggx)
              << "alpha=" << alpha << " theta_i=" << deg << " m=(" << tm << ", " << pm << ")";
        }
      for (double ts : {-1.5, -0.7, -0.1, 0.0, 0.4, 1.2, 1.56}) {
        const double ggx = ggx_vndf2_pdf(alpha, deg * kRadPerDeg, ts);
        EXPECT_NEAR(student_t_vndf2_pdf(t, deg * kRadPerDeg, ts), ggx, 1e-13 * ggx) << "flatland";
      }
    }
}

// The same uniforms give the same normal as the GGX visible-slope sampler (smith_walk_3d.h: the slope
// along the view by the closed-form inverse of its CDF, the slope across by delta - sin(delta)): both
// are the increasing inverses of the same two CDFs.
TEST(StudentTVndf, Gamma2SamplesAreGgxForTheSameUniforms) {
  double worst = 0.0;
  for (double alpha : {0.01, 0.3, 1.0, 2.0})
    for (double deg : {0.0, 20.0, 60.0, 85.0, 89.9}) {
      const StudentT t{alpha, 2.0};
      const Dir3 i = dir3(deg * kRadPerDeg, 2.2);
      for (double u0 : {1e-3, 0.01, 0.2, 0.5, 0.77, 0.99, 0.999})
        for (double u1 : {1e-3, 0.03, 0.5, 0.61, 0.999}) {
          const Dir3 a = sample_student_t_vndf(t, i, u0, u1);
          const Dir3 b = sample_visible_normal_3d(NdfKind::ggx, alpha, i, u0, u1);
          const double d = std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)});
          worst = std::max(worst, d);
          EXPECT_LT(d, 1e-12) << "alpha=" << alpha << " theta_i=" << deg << " u=(" << u0 << ", " << u1 << ")";
        }
      // Flatland: the facet of the view at theta_i (i = (-sin, cos)), increasing in u as
      // smith_walk_flatland.h's for theta_i < 0; for theta_i >= 0 the mirror image at 1 - u.
      for (double u : {1.0 / 1024.0, 0.125, 0.5, 0.75, 1023.0 / 1024.0}) {
        const double ti = deg * kRadPerDeg;
        const double a = sample_student_t_vndf2(t, ti, u), b = -sample_visible_normal(NdfKind::ggx, alpha, -ti, u);
        EXPECT_NEAR(a, b, 1e-12) << "flatland alpha=" << alpha << " theta_i=" << deg << " u=" << u;
        if (deg == 0.0) continue;
        const double c = sample_student_t_vndf2(t, -ti, u), e = sample_visible_normal(NdfKind::ggx, alpha, -ti, u);
        EXPECT_NEAR(c, e, 1e-12) << "flatland alpha=" << alpha << " theta_i=-" << deg << " u=" << u;
      }
    }
  RecordProperty("worst_difference", std::to_string(worst));
}

// Beyond u in [1e-3, 0.999] the closed form above rounds to more than 1e-12 (asin near 1: 1.7e-12 at
// u0 = 1 - 1e-6, theta_i = 0, alpha = 0.01): the tails against 40-digit references instead (mpmath,
// bisection on F(v) = [(1 + tanh v) + s sech v] / 2 / (1 + Lambda) and on the cross slope's CDF
// [atan(sinh w) + sech w tanh w + pi / 2] / pi, gamma = 2's forms).
TEST(StudentTVndf, Gamma2TailsMatchHighPrecisionReferences) {
  struct Ref {
    double alpha, deg, phi, u0, u1;
    Dir3 m;
  };
  const Ref refs[] = {
      {0.01, 20, 2.2, 1e-06, 0.5, {-0.58772735700248963711, 0.80743339414380495896, 0.051262733562335584215}},
      {0.01, 20, 2.2, 0.999999, 0.5, {0.51259993271114598153, -0.70422160645670502205, 0.49123643796451652019}},
      {0.01, 0, 2.2, 0.999999, 0.3, {-0.93095274939216119592, 0.31410182032759081975, 0.18619082916746938039}},
      {1.0, 89.9, 2.2, 1e-09, 0.5, {-0.58850111725534585185, 0.80849640381959007936, 1.0017468541123451442e-9}},
      {2.0, 60, 2.2, 1e-06, 0.999, {0.69873169150871834627, 0.71538382934013325884, 1.111341434589315954e-7}},
      {0.3, 45, 2.2, 0.999999, 1e-07, {-0.80406750673479936253, -0.59449066995159305448, 0.0075025298259611564017}},
  };
  for (const Ref& r : refs) {
    const Dir3 m = sample_student_t_vndf(StudentT{r.alpha, 2.0}, dir3(r.deg * kRadPerDeg, r.phi), r.u0, r.u1);
    EXPECT_NEAR(m.x, r.m.x, 1e-14) << "alpha=" << r.alpha << " theta_i=" << r.deg << " u=(" << r.u0 << ", " << r.u1
                                   << ")";
    EXPECT_NEAR(m.y, r.m.y, 1e-14) << "alpha=" << r.alpha << " theta_i=" << r.deg << " u=(" << r.u0 << ", " << r.u1
                                   << ")";
    EXPECT_NEAR(m.z, r.m.z, 1e-14 * std::max(r.m.z, 1e-3))
        << "alpha=" << r.alpha << " theta_i=" << r.deg << " u=(" << r.u0 << ", " << r.u1 << ")";
  }
}

// ---- gamma -> infinity is Beckmann, at the rate 1/gamma ---------------------------------------------

// The largest relative difference of the densities, and of the sampled normals (same uniforms, the
// Beckmann visible-slope sampler of smith_walk_3d.h), from Beckmann's.
struct Distance {
  double pdf = 0.0, sample = 0.0;
};
Distance distance_to_beckmann(double gamma, double alpha, double deg) {
  const StudentT t{alpha, gamma};
  const Dir3 i = dir3(deg * kRadPerDeg, 0.4);
  Distance d;
  // Normals within 2.5 widths (where both densities carry mass; beyond, the tails differ in kind).
  for (double r : {0.0, 0.5, 1.0, 1.5, 2.5})
    for (double pm : {0.0, 1.3, 2.9}) {
      const Dir3 m = dir3(std::atan(alpha * r), pm);
      const double b = visible_normal_pdf_3d(NdfKind::beckmann, alpha, i, m);
      if (!(b > 0.0)) continue;
      d.pdf = std::max(d.pdf, std::abs(student_t_vndf_pdf(t, i, m) / b - 1.0));
    }
  for (double u0 : {0.02, 0.3, 0.5, 0.8, 0.98})
    for (double u1 : {0.05, 0.5, 0.9}) {
      const Dir3 a = sample_student_t_vndf(t, i, u0, u1);
      const Dir3 b = sample_visible_normal_3d(NdfKind::beckmann, alpha, i, u0, u1);
      d.sample = std::max(d.sample, std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(a.z - b.z)}) / alpha);
    }
  return d;
}

TEST(StudentTVndf, LargeGammaIsBeckmannAtRateOneOverGamma) {
  for (double alpha : {0.05, 0.5, 1.5})
    for (double deg : {0.0, 45.0, 80.0}) {
      const Distance d3 = distance_to_beckmann(1e3, alpha, deg), d4 = distance_to_beckmann(1e4, alpha, deg);
      // O(1/gamma), ten times closer at 1e4 than at 1e3. The first-order terms at gamma = 1e4: the
      // density's r^4 / (2 gamma) - 2 r^2 / gamma at r = 2.5 widths is 7e-4 (1.3e-3 with Lambda's
      // and the normalization's shares); the t quantile's (z^3 + z) / (4 nu), nu = 2 gamma - 2, at
      // u = 0.98 (z = 2.05) is 1.4e-4 of the slope's scale, moved out to 2e-4 by a grazing view.
      EXPECT_LT(d4.pdf, 2e-3) << "alpha=" << alpha << " theta_i=" << deg;
      EXPECT_LT(d4.sample, 4e-4) << "alpha=" << alpha << " theta_i=" << deg;
      EXPECT_NEAR(d3.pdf / d4.pdf, 10.0, 1.0) << "alpha=" << alpha << " theta_i=" << deg;
      if (d4.sample > 1e-9) {
        EXPECT_NEAR(d3.sample / d4.sample, 10.0, 1.0) << "alpha=" << alpha << " theta_i=" << deg;
      }
    }
}

// ---- Chi-square of the samples against the density --------------------------------------------------

// n samples of the 3D sampler binned in theta_m (edges equally spaced in slope / alpha, 12 bins) and
// |phi_m| (8 bins; the law is mirror symmetric about the plane of incidence), against the density's
// integral over each bin times n.
test_stats::ChiSquare chi_square_3d(const StudentT& t, double deg, const StudentT& density, long n,
                                    std::uint64_t seed) {
  const Dir3 i = incident(deg);
  constexpr int kT = 12, kP = 8;
  std::vector<double> te(kT + 1), pe(kP + 1);
  for (int j = 0; j <= kT; ++j) te[j] = j == kT ? kHalfPi : std::atan(t.alpha * std::tan(j * kHalfPi / kT));
  for (int j = 0; j <= kP; ++j) pe[j] = j * std::numbers::pi / kP;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<std::int64_t> observed(kT * kP, 0);
  for (long s = 0; s < n; ++s) {
    const double u0 = U(rng), u1 = U(rng);
    const Dir3 m = sample_student_t_vndf(t, i, u0, u1);
    const double th = std::atan2(std::hypot(m.x, m.y), m.z), ph = std::abs(std::atan2(m.y, m.x));
    const int a = std::clamp(static_cast<int>(std::upper_bound(te.begin(), te.end(), th) - te.begin()) - 1, 0, kT - 1);
    const int b = std::clamp(static_cast<int>(std::upper_bound(pe.begin(), pe.end(), ph) - pe.begin()) - 1, 0, kP - 1);
    ++observed[a * kP + b];
  }
  std::vector<double> expected(kT * kP), edges(kT * kP + 1);
  for (int a = 0; a < kT; ++a)
    for (int b = 0; b < kP; ++b)
      expected[a * kP + b] = 2.0 * static_cast<double>(n) *
                             over_normals(
                                 i, density.gamma, [&](const Dir3& m) { return student_t_vndf_pdf(density, i, m); },
                                 te[a], te[a + 1], pe[b], pe[b + 1], 1.0 / 16.0);
  for (int j = 0; j <= kT * kP; ++j) edges[j] = j;
  return test_stats::chi_square_gof(edges, expected, observed);
}

test_stats::ChiSquare chi_square_flatland(const StudentT& t, double deg, const StudentT& density, long n,
                                          std::uint64_t seed) {
  const double ti = deg * kRadPerDeg;
  const std::vector<double> edges = test_stats::slope_bin_edges(t.alpha, 48);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<std::int64_t> observed(edges.size() - 1, 0);
  for (long s = 0; s < n; ++s) {
    const double th = sample_student_t_vndf2(t, ti, U(rng));
    const auto j = std::upper_bound(edges.begin(), edges.end(), th) - edges.begin() - 1;
    ++observed[std::clamp<std::ptrdiff_t>(j, 0, static_cast<std::ptrdiff_t>(observed.size()) - 1)];
  }
  std::vector<double> expected(observed.size());
  for (std::size_t j = 0; j < expected.size(); ++j) {
    auto f = [&](double s) { return student_t_vndf2_pdf(density, ti, s); };
    expected[j] = static_cast<double>(n) * over_facet_angles(f, density.gamma, ti, edges[j], edges[j + 1]);
  }
  return test_stats::chi_square_gof(edges, expected, observed);
}

// A fixed seed per case and the level 1e-3: a correct sampler fails a case at a given seed with
// probability 1e-3. n = 30000 samples resolve a density error of about 6 % in a bin holding 1 % of
// the mass (its standard error 1.8 %), which the rejection of a nearby gamma below shows.
struct ChiCase {
  double gamma, alpha, deg;
};

void check_chi_square(const ChiCase& c, long n, std::uint64_t seed) {
  const StudentT t{c.alpha, c.gamma};
  const test_stats::ChiSquare r3 = chi_square_3d(t, c.deg, t, n, seed);
  EXPECT_GT(r3.p, 1e-3) << "3d gamma=" << c.gamma << " alpha=" << c.alpha << " theta_i=" << c.deg << " chi2=" << r3.stat
                        << " dof=" << r3.dof << "\n"
                        << r3.table;
  const test_stats::ChiSquare r2 = chi_square_flatland(t, c.deg, t, n, seed + 1000);
  std::printf(
      "gamma %g alpha %g theta_i %g, %ld samples: 3d chi2 %.1f dof %d p %.3g; flatland chi2 %.1f dof %d p %.3g\n",
      c.gamma, c.alpha, c.deg, n, r3.stat, r3.dof, r3.p, r2.stat, r2.dof, r2.p);
  EXPECT_GT(r2.p, 1e-3) << "flatland gamma=" << c.gamma << " alpha=" << c.alpha << " theta_i=" << c.deg
                        << " chi2=" << r2.stat << " dof=" << r2.dof << "\n"
                        << r2.table;
}

// A heavy tail at a moderate view: 30000 samples, about a second in all.
TEST(StudentTVndf, SamplesFollowTheDensityByChiSquare) { check_chi_square({1.6, 0.5, 30.0}, 30000, 31); }

// Label long: a light tail at a grazing view, and gamma near 1.5, where 61 % of the visible normals
// lie within 1e-6 rad of the vertical (alpha 0.2, theta_i 60 deg), 100000 samples each.
TEST(StudentTVndfLong, SamplesFollowTheDensityByChiSquareHardCases) {
  check_chi_square({8.0, 0.3, 75.0}, 100000, 32);
  check_chi_square({1.51, 0.2, 60.0}, 100000, 33);
}

// The grid (label long): 200000 samples, gamma 1.51..1e4, alpha 0.05..2, theta_i 0..89.9 deg.
TEST(StudentTVndfLong, SamplesFollowTheDensityByChiSquare) {
  constexpr ChiCase kCases[] = {{1.6, 0.5, 30.0}, {8.0, 0.3, 75.0}, {2.5, 1.0, 0.0},    {1.51, 0.2, 60.0},
                                {3.0, 2.0, 85.0}, {1e4, 0.5, 45.0}, {1.55, 0.05, 89.9}, {20.0, 0.1, 10.0}};
  std::uint64_t seed = 41;
  for (const ChiCase& c : kCases) check_chi_square(c, 200000, ++seed);
}

// The same test has the power to see a wrong law: the samples of gamma against the density of a
// nearby gamma (1.6 against 1.8 in 3D; 8 against 6 in flatland) are rejected.
TEST(StudentTVndf, ChiSquareRejectsTheDensityOfAnotherGamma) {
  const StudentT t16{0.5, 1.6}, t18{0.5, 1.8}, t8{0.3, 8.0}, t6{0.3, 6.0};
  const test_stats::ChiSquare r3 = chi_square_3d(t16, 30.0, t18, 30000, 7);
  const test_stats::ChiSquare r2 = chi_square_flatland(t8, 75.0, t6, 30000, 8);
  std::printf("rejected: 3d chi2 %.1f dof %d p %.3g; flatland chi2 %.1f dof %d p %.3g\n", r3.stat, r3.dof, r3.p,
              r2.stat, r2.dof, r2.p);
  EXPECT_LT(r3.p, 1e-6);
  EXPECT_LT(r2.p, 1e-6);
}

// ---- Hard cases -------------------------------------------------------------------------------------

// gamma just above 1.5 (visible normals pile up at the vertical), 1e4 (Beckmann), alpha 0.01..2,
// theta_i 0 (no tilt) to 89.9 deg, uniforms at 0 and next to 1: unit normals in the upper hemisphere
// (z >= 0; z = 0 only where the facet is vertical to double precision) that face i, finite densities,
// and monotone in u0.
TEST(StudentTVndf, NoNanOverTheHardCases) {
  const double us[] = {0.0, 1e-300, 1e-16, 1e-6, 0.3, 0.5, 0.9, 1.0 - 1e-12, std::nextafter(1.0, 0.0)};
  for (double gamma : {1.5 + 1e-9, 1.5 + 1e-4, 1.501, 1.6, 2.0, 5.0, 100.0, 1e4})
    for (double alpha : {0.01, 0.1, 1.0, 2.0})
      for (double deg : {0.0, 1e-6, 30.0, 80.0, 89.0, 89.9}) {
        const StudentT t{alpha, gamma};
        const Dir3 i = dir3(deg * kRadPerDeg, 1.0);
        const double ti = deg * kRadPerDeg;
        double last_x = -2.0, last_flat = 2.0;
        for (double u0 : us) {
          for (double u1 : {0.0, 0.5, std::nextafter(1.0, 0.0)}) {
            const Dir3 m = sample_student_t_vndf(t, i, u0, u1);
            const double len = std::sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
            ASSERT_TRUE(std::isfinite(len) && std::abs(len - 1.0) < 1e-14 && m.z >= 0.0)
                << "gamma=" << gamma << " alpha=" << alpha << " theta_i=" << deg << " u=(" << u0 << ", " << u1 << ")";
            EXPECT_GE(i.x * m.x + i.y * m.y + i.z * m.z, -1e-15)
                << "faces away: gamma=" << gamma << " alpha=" << alpha << " theta_i=" << deg << " u0=" << u0;
            const double pdf = student_t_vndf_pdf(t, i, m);
            ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0.0) << "pdf " << pdf;
          }
          // The component along i's horizontal direction falls as u0 grows (the slope towards -i_xy grows).
          const Dir3 m = sample_student_t_vndf(t, i, u0, 0.5);
          if (deg > 0.0) {
            const double along = -(m.x * std::cos(1.0) + m.y * std::sin(1.0));
            EXPECT_GE(along, last_x - 1e-15) << "gamma=" << gamma << " alpha=" << alpha << " theta_i=" << deg;
            last_x = along;
          }
          const double s = sample_student_t_vndf2(t, ti, u0);
          ASSERT_TRUE(std::isfinite(s) && std::abs(s) <= kHalfPi) << "flatland gamma=" << gamma << " u=" << u0;
          EXPECT_LE(s, last_flat + 1e-15) << "flatland gamma=" << gamma << " alpha=" << alpha << " theta_i=" << deg;
          last_flat = s;
          ASSERT_TRUE(std::isfinite(student_t_vndf2_pdf(t, ti, s)));
        }
      }
}

// The inversion returns F^-1(u) to the rounding of F: the law's CDF, computed here independently by
// tanh-sinh quadrature of the density N sech^(2a) v (1 - s k sinh v)+ from -infinity, meets u.
TEST(StudentTVndf, InversionMeetsTheCdfByQuadrature) {
  for (double gamma : {1.6, 2.0, 8.0, 300.0})
    for (double s : {0.0, 0.05, 1.0, 30.0}) {
      const double a = gamma - 1.0, k = std::sqrt(gamma - 1.0);
      auto density = [&](double v) {
        const double e = std::pow(1.0 / std::cosh(v), 2.0 * a);
        return e > 0.0 ? e * std::max(0.0, 1.0 - s * k * std::sinh(v)) : 0.0;
      };
      const double v_mu = s > 0.0 ? std::asinh(1.0 / (s * k)) : 60.0;
      // The density's integral from -infinity to v: below v0 = min(v, -16) by t = v0 - x / (1 - x),
      // x in [0, 1), then piecewise between -16, -4, -1, 0, 1, 4, 16 and 64 (the law's scales).
      auto from_left = [&](double v) {
        const double v0 = std::min(v, -16.0);
        double sum = test_stats::tanh_sinh(
            [&](double x) { return x < 1.0 ? density(v0 - x / (1.0 - x)) / ((1.0 - x) * (1.0 - x)) : 0.0; }, 0.0, 1.0,
            1.0 / 128.0);
        double lo = v0;
        for (double cut : {-4.0, -1.0, 0.0, 1.0, 4.0, 16.0, 64.0}) {
          const double hi = std::min(cut, v);
          if (hi > lo) sum += test_stats::tanh_sinh(density, lo, hi, 1.0 / 128.0);
          lo = std::max(lo, hi);
        }
        return sum;
      };
      const double total = from_left(v_mu);
      for (double u : {1e-4, 0.1, 0.5, 0.9, 0.999}) {
        const double v = student_t_visible_slope_inverse(a, k, s, u);
        EXPECT_NEAR(from_left(v) / total, u, 1e-10 * std::max(u, 1e-2))
            << "gamma=" << gamma << " s=" << s << " u=" << u << " v=" << v;
      }
    }
}

}  // namespace
}  // namespace vgroove::analytic
