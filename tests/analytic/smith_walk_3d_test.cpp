// Tests of analytic/smith_walk_3d.h: the 3D Smith random walk (Heitz et al. 2016).
//
// - The slope across the view inverts its distribution function (written independently: GGX's
//   1/2 + (atan t + t / (1 + t^2)) / pi, Beckmann's (1 + erf(q / alpha)) / 2), tails included.
// - The visible-normal pdf integrates to 1 over the hemisphere (views up, grazing and down), and
//   for GGX and an upward view it is the Smith-GGX VNDF of analytic/vndf.h (Heitz 2018's closed
//   form, another derivation).
// - Matched pair: the sampler's moments (m_x, m_y, m_z, m_x m_y, m_z^2) against the pdf's by
//   quadrature, within 5 standard errors of the samples, views up and down.
// - The walk: its single-scattering share E_1 is the exact Smith albedo with the height-correlated
//   G2 (analytic/albedo_single.h, quadrature), not the separable one (power); with Schlick's F its
//   first bounce keeps F0 scale + bias (the exact split sum); every walk leaves (F = 1: the white
//   furnace); and the BRDF by next-event estimation, integrated over the exits, gives per order k
//   the share of walks that left after k reflections (two estimators of E_k, independent streams).
// - Hard cases (alpha 0.01 and 2, grazing light) stay finite.
// Tolerances: k standard errors of the samples (k = 5, with at most ~100 comparisons per test).
#include "vgroove/analytic/smith_walk_3d.h"

#include "tests/stats.h"
#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/vndf.h"
#include "vgroove/optics/fresnel.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace vgroove::analytic {
namespace {

using namespace vgroove::test_stats;

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

// A uniform stream for the walk (SplitMix64; (0, 1) open).
struct Uniforms {
  std::uint64_t state;
  double operator()() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;
  }
};

// Mean and standard error of a sample.
struct Mean {
  double sum = 0.0, sum2 = 0.0;
  long n = 0;
  void add(double x) { sum += x, sum2 += x * x, ++n; }
  double mean() const { return sum / n; }
  double se() const { return std::sqrt(std::max(0.0, sum2 / n - mean() * mean()) / n); }
};

TEST(SmithWalk3d, CrossSlopeInvertsItsDistribution) {
  const double us[] = {1e-16, 1e-9, 1e-3, 0.1, 0.3, 0.5, 0.7, 0.9, 0.999, 1.0 - 1e-9, 1.0 - 0x1.0p-53};
  for (double alpha : {0.01, 0.5, 2.0})
    for (double p : {0.0, 0.3, -4.0, 1e6}) {
      double prev = -INFINITY;
      for (double u : us) {
        const double tail = std::min(u, 1.0 - u);
        const double qg = sample_cross_slope(NdfKind::ggx, alpha, p, u);
        EXPECT_GE(qg, prev) << "monotone alpha=" << alpha << " p=" << p << " u=" << u;
        prev = qg;
        // GGX: t = q / (alpha c), F(t) = 1/2 + (atan t + t / (1 + t^2)) / pi; its tail for t < 0
        // from the same with |t| (F(-|t|) = 1 - F(|t|) = (pi/2 - atan|t| - |t| / (1 + t^2)) / pi,
        // written with atan(1/|t|) to keep the digits).
        const double t = std::abs(qg / (alpha * std::hypot(1.0, p / alpha)));
        double F_tail = (std::atan(1.0 / t) - t / (1.0 + t * t)) / kPi;
        if (t > 2.0) {
          // The two terms cancel for large t: their series, sum_{n >= 1} (-1)^(n+1) 2n / (2n + 1)
          // t^-(2n+1) / pi, terms falling by 1/t^2 <= 1/4.
          F_tail = 0.0;
          double power = 1.0 / (t * t * t);
          for (int n = 1; n <= 40; ++n, power /= t * t)
            F_tail += (n % 2 ? 1.0 : -1.0) * 2.0 * n / (2.0 * n + 1.0) * power;
          F_tail /= kPi;
        }
        EXPECT_NEAR(F_tail, tail, 1e-12 * tail) << "GGX alpha=" << alpha << " p=" << p << " u=" << u;
        // Beckmann: (1 + erf(q / alpha)) / 2, its tail erfc(|q| / alpha) / 2.
        const double qb = sample_cross_slope(NdfKind::beckmann, alpha, p, u);
        EXPECT_NEAR(0.5 * std::erfc(std::abs(qb) / alpha), tail, 1e-12 * tail)
            << "Beckmann alpha=" << alpha << " u=" << u;
        EXPECT_EQ(qb > 0.0, u > 0.5) << "u=" << u;
      }
    }
}

// int g(m) D_v(m) d omega_m by nested tanh-sinh over theta_m and the azimuth psi about v's own,
// each inner range the visible one (<v, m> > 0), the integrand smooth inside.
template <class G>
double vndf_integral(NdfKind ndf, double alpha, const Dir3& v, G&& g) {
  const double s = std::hypot(v.x, v.y), ex = s > 0.0 ? v.x / s : 1.0, ey = s > 0.0 ? v.y / s : 0.0;
  auto inner = [&](double th) {
    // <v, m> = v_z cos th + s sin th cos psi > 0 <=> cos psi > r.
    const double st = std::sin(th), ct = std::cos(th);
    double A = kPi;
    if (s * st > 0.0) {
      const double r = -v.z * ct / (s * st);
      if (r >= 1.0) return 0.0;
      if (r > -1.0) A = std::acos(r);
    } else if (v.z * ct <= 0.0) {
      return 0.0;
    }
    return tanh_sinh(
               [&](double psi) {
                 const double mx = st * std::cos(psi), my = st * std::sin(psi);
                 const Dir3 m{mx * ex - my * ey, mx * ey + my * ex, ct};
                 return g(m) * visible_normal_pdf_3d(ndf, alpha, v, m);
               },
               -A, A, 1.0 / 16.0) *
           st;
  };
  std::vector<double> cuts{0.0, 0.5 * kPi};
  for (double c : {std::atan(0.25 * alpha), std::atan(alpha), std::atan(4.0 * alpha)}) cuts.push_back(c);
  if (s > 0.0) {
    // Where the visible range starts or stops covering every azimuth: tan th = -+v_z / s.
    for (double c : {std::atan2(std::abs(v.z), s)}) cuts.push_back(c);
  }
  std::sort(cuts.begin(), cuts.end());
  double sum = 0.0;
  for (std::size_t j = 0; j + 1 < cuts.size(); ++j)
    if (cuts[j + 1] > cuts[j]) sum += tanh_sinh(inner, cuts[j], cuts[j + 1], 1.0 / 16.0);
  return sum;
}

const double kViews[][2] = {{0, 0}, {30, 40}, {75, 200}, {89.9, 10}, {100, 70}, {150, 300}, {175, 123}};

TEST(SmithWalk3d, VisibleNormalPdfIsNormalizedAndIsHeitzsGgxVndf) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.3, 1.0, 2.0})
      for (const auto& vd : kViews) {
        const Dir3 v = dir3(deg(vd[0]), deg(vd[1]));
        // Beckmann seen from 5 deg below the horizon at alpha 0.3: A(v) = e^{-1444}... underflows;
        // the walk never asks there (Lambda of the upward travel is 0 too: it leaves).
        if (visible_projected_area(ndf, alpha, v) == 0.0) {
          EXPECT_EQ(Lambda(ndf, kPi - polar_angle(v), alpha), 0.0);
          continue;
        }
        const double one = vndf_integral(ndf, alpha, v, [](const Dir3&) { return 1.0; });
        EXPECT_NEAR(one, 1.0, 1e-7) << ndf_name(ndf) << " alpha=" << alpha << " view " << vd[0] << "," << vd[1];
        if (ndf != NdfKind::ggx || !(v.z > 0.0)) continue;
        Uniforms U{7};
        for (int n = 0; n < 200; ++n) {
          const Dir3 m = dir3(0.5 * kPi * U(), 2.0 * kPi * U());
          const double a = visible_normal_pdf_3d(ndf, alpha, v, m), b = ggx_vndf_pdf(alpha, v, m);
          EXPECT_NEAR(a, b, 1e-12 * std::max(1.0, b)) << "alpha=" << alpha << " view " << vd[0];
        }
      }
}

TEST(SmithWalk3d, SamplerMomentsAreThePdfs) {
  using Moment = double (*)(const Dir3&);
  const Moment moments[] = {[](const Dir3& m) { return m.x; }, [](const Dir3& m) { return m.y; },
                            [](const Dir3& m) { return m.z; }, [](const Dir3& m) { return m.x * m.y; },
                            [](const Dir3& m) { return m.z * m.z; }};
  const long kSamples = 100000;
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.3, 1.5})
      for (const auto& vd : kViews) {
        const Dir3 v = dir3(deg(vd[0]), deg(vd[1]));
        if (visible_projected_area(ndf, alpha, v) == 0.0) continue;  // as above: no facet seen
        std::array<Mean, 5> got;
        Uniforms U{static_cast<std::uint64_t>(1000 * vd[0] + vd[1] + 17 * alpha)};
        for (long n = 0; n < kSamples; ++n) {
          const double u0 = U(), u1 = U();
          const Dir3 m = sample_visible_normal_3d(ndf, alpha, v, u0, u1);
          ASSERT_TRUE(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z));
          ASSERT_GT(m.x * v.x + m.y * v.y + m.z * v.z, -1e-12) << "a visible normal";
          for (std::size_t j = 0; j < got.size(); ++j) got[j].add(moments[j](m));
        }
        for (std::size_t j = 0; j < got.size(); ++j) {
          const double want = vndf_integral(ndf, alpha, v, moments[j]);
          EXPECT_NEAR(got[j].mean(), want, 5.0 * got[j].se() + 1e-9)
              << ndf_name(ndf) << " alpha=" << alpha << " view " << vd[0] << "," << vd[1] << " moment " << j;
        }
      }
}

// The share of walks leaving after one reflection, and the Schlick-weighted share, against the
// exact single-scattering albedo and split sum.
TEST(SmithWalk3d, SingleScatteringIsTheHeightCorrelatedAlbedo) {
  const long kPaths = 100000;
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.1, 0.5, 1.0, 2.0})
      for (double theta_deg : {0.0, 45.0, 80.0}) {
        const double mu = std::cos(deg(theta_deg));
        const Dir3 i = dir3(deg(theta_deg), 0.3);
        Uniforms U{static_cast<std::uint64_t>(31 * alpha + theta_deg)};
        const double F0 = 0.3;
        long k1 = 0, lost = 0;
        Mean schlick;
        for (long n = 0; n < kPaths; ++n) {
          double F = 1.0;
          const Walk3d w = smith_walk_3d(ndf, alpha, i, U, [&](double c) { F *= optics::fresnel_schlick(c, F0); });
          ASSERT_TRUE(std::isfinite(w.o.x) && std::isfinite(w.o.z));
          lost += !w.left;
          k1 += w.k == 1;
          schlick.add(w.k == 1 ? F : 0.0);
        }
        EXPECT_EQ(lost, 0) << "F = 1: every walk leaves";
        const double corr = albedo_single({ndf, MaskingKind::smith_height_correlated}, alpha, mu).value;
        // The binomial standard error at the expected share, floored at one path's worth (near
        // E = 1 the misses are Poisson with a mean below 1).
        const double E1 = static_cast<double>(k1) / kPaths, se = std::sqrt(corr * (1.0 - corr) / kPaths) + 1.0 / kPaths;
        const double sep = albedo_single({ndf, MaskingKind::smith_separable}, alpha, mu).value;
        EXPECT_NEAR(E1, corr, 5.0 * se) << ndf_name(ndf) << " alpha=" << alpha << " theta=" << theta_deg;
        if (alpha >= 1.0 && theta_deg == 80.0) {
          EXPECT_GT(std::abs(E1 - sep), 5.0 * se) << "power: the separable G2, alpha=" << alpha;
        }
        const SplitSum s = dfg_split_sum({ndf, MaskingKind::smith_height_correlated}, alpha, mu);
        EXPECT_NEAR(schlick.mean(), F0 * s.scale.value + s.bias.value, 5.0 * schlick.se())
            << ndf_name(ndf) << " alpha=" << alpha << " theta=" << theta_deg;
      }
}

// Two estimators of E_k: the share of sampled walks that left after k reflections, and the
// next-event estimates integrated over the exits (o uniform on the hemisphere, pdf 1 / (2 pi)).
TEST(SmithWalk3d, NextEventEstimatesIntegrateToTheSampledOrders) {
  const int kOrders = 4;
  const long kPaths = 200000;
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.5, 1.0})
      for (double theta_deg : {30.0, 70.0}) {
        const Dir3 i = dir3(deg(theta_deg), 0.0);
        Uniforms walks{static_cast<std::uint64_t>(100 * alpha + theta_deg)}, nee{~walks.state};
        std::vector<long> by_k(kOrders + 2, 0);
        std::vector<Mean> est(kOrders);
        for (long n = 0; n < kPaths; ++n) {
          const Walk3d w = smith_walk_3d(ndf, alpha, i, walks);
          ++by_k[std::min(w.k, kOrders + 1)];
          const Dir3 o = dir3(std::acos(nee()), 2.0 * kPi * nee());
          double e[kOrders] = {};
          smith_walk_3d_estimates(ndf, alpha, i, o, nee, e, kOrders);
          for (int k = 0; k < kOrders; ++k) est[k].add(2.0 * kPi * e[k]);
        }
        EXPECT_EQ(by_k[0], 0) << "every walk meets the surface once";
        for (int k = 1; k <= kOrders; ++k) {
          const double E = static_cast<double>(by_k[k]) / kPaths, se = std::sqrt(E * (1.0 - E) / kPaths);
          EXPECT_NEAR(est[k - 1].mean(), E, 5.0 * std::hypot(se, est[k - 1].se()))
              << ndf_name(ndf) << " alpha=" << alpha << " theta=" << theta_deg << " k=" << k;
        }
      }
}

TEST(SmithWalk3d, HardCasesStayFinite) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.01, 2.0})
      for (double theta_deg : {0.0, 89.9}) {
        Uniforms U{3};
        const Dir3 i = dir3(deg(theta_deg), 1.0);
        for (int n = 0; n < 20000; ++n) {
          double F = 1.0;
          const Walk3d w = smith_walk_3d(ndf, alpha, i, U, [&](double c) {
            ASSERT_TRUE(c >= 0.0 && c <= 1.0) << c;
            F *= optics::fresnel_conductor(c, 0.2, 3.0);
          });
          ASSERT_TRUE(w.left) << ndf_name(ndf) << " alpha=" << alpha << " theta=" << theta_deg;
          ASSERT_GT(w.o.z, 0.0);
          ASSERT_NEAR(w.o.x * w.o.x + w.o.y * w.o.y + w.o.z * w.o.z, 1.0, 1e-12);
          ASSERT_TRUE(F >= 0.0 && F <= 1.0);
        }
      }
}

}  // namespace
}  // namespace vgroove::analytic
