// Tests of Walter's sampler (analytic/walter_sampling.h): the directions it draws over the whole
// sphere against its own pdf by chi-square (cells of (cos theta_o, phi_o) on [-1, 1] x [-pi, pi),
// the pdf integrated over each cell by nested adaptive Gauss-Kronrod, one cell for the draws that
// give no direction, validation/chi_square.h pooling and testing at the family's level 0.01), a
// wrong Jacobian rejected on the same draws, and the weight with Smith's separable G2 equal to
// G1(o) on both sides (Walter Sec. 5.3 with visible normals; docs/derivations/walter.md).
// Figures (400,000 draws a case): chi-square 267-404 on 304-364 dof, p 0.07-0.99; the sampler
// reflecting with 1.1 F (its pdf unchanged) is rejected in all six cases (p 2e-5 to 6e-101), and the
// wrong Jacobian kept below gives 20,000-87,000 on about 300 dof.
#include "vgroove/analytic/walter_sampling.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/walter.h"
#include "vgroove/sim/rng.h"
#include "vgroove/validation/chi_square.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

namespace vgroove::analytic {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kCos = 32, kPhi = 16;

struct Case {
  NdfKind ndf;
  double alpha, eta, theta_i_deg;
};

std::string name(const Case& c) {
  return std::string(ndf_name(c.ndf)) + " alpha " + std::to_string(c.alpha) + " eta " + std::to_string(c.eta) +
         " theta_i " + std::to_string(c.theta_i_deg);
}

Dir3 light(const Case& c) { return dir3(c.theta_i_deg * kPi / 180.0, kPi); }

int cell_of(const Dir3& o) {
  const int a = std::min(kCos - 1, static_cast<int>((o.z + 1.0) * 0.5 * kCos));
  const int b = std::min(kPhi - 1, static_cast<int>((std::atan2(o.y, o.x) + kPi) / (2 * kPi) * kPhi));
  return a * kPhi + b;
}

// The draws' histogram (the last cell: no direction).
std::vector<double> histogram(const Case& c, long n, std::uint64_t seed) {
  std::vector<double> h(kCos * kPhi + 1, 0.0);
  const Dir3 i = light(c);
  for (long j = 0; j < n; ++j) {
    sim::Rng r(seed, 0, static_cast<std::uint64_t>(j));
    const double u0 = r.uniform(), u1 = r.uniform(), u2 = r.uniform();
    const WalterSample s = sample_walter(c.ndf, c.alpha, c.eta, MaskingKind::smith_separable, i, u0, u1, u2);
    h[s.ok ? cell_of(s.o) : kCos * kPhi] += 1.0;
  }
  return h;
}

// A density over the sphere integrated over the cells, times n (the last cell: n less their sum).
std::vector<double> expected(const std::function<double(const Dir3&)>& pdf, long n) {
  std::vector<double> e(kCos * kPhi + 1, 0.0);
  double sum = 0.0;
  AdaptiveOptions inner, outer;
  inner.abs_tol = outer.abs_tol = 1e-10;
  inner.rel_tol = outer.rel_tol = 1e-7;
  for (int a = 0; a < kCos; ++a)
    for (int b = 0; b < kPhi; ++b) {
      const double z0 = -1.0 + 2.0 * a / kCos, z1 = -1.0 + 2.0 * (a + 1) / kCos;
      const double p0 = -kPi + 2 * kPi * b / kPhi, p1 = -kPi + 2 * kPi * (b + 1) / kPhi;
      const double v = integrate_adaptive(
                           [&](double z) {
                             const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
                             return integrate_adaptive(
                                        [&](double p) {
                                          return pdf(Dir3{s * std::cos(p), s * std::sin(p), z});
                                        },
                                        p0, p1, inner)
                                 .value;
                           },
                           z0, z1, outer)
                           .value;
      e[a * kPhi + b] = n * v;
      sum += v;
    }
  e.back() = n * (1.0 - sum);
  return e;
}

const Case kCases[] = {
    {NdfKind::ggx, 0.3, 1.5, 40},     {NdfKind::ggx, 0.8, 1.5, 70},     {NdfKind::ggx, 0.5, 1 / 1.5, 30},
    {NdfKind::ggx, 0.5, 1 / 1.5, 60}, {NdfKind::beckmann, 0.4, 2.4, 0}, {NdfKind::beckmann, 1.0, 1 / 2.4, 50},
};
constexpr long kDraws = 400000;
constexpr int kTests = 6;

TEST(WalterSampling, ChiSquareAgainstItsPdf) {
  for (const Case& c : kCases) {
    const Dir3 i = light(c);
    const std::vector<double> obs = histogram(c, kDraws, 7);
    const std::vector<double> exp =
        expected([&](const Dir3& o) { return walter_pdf(c.ndf, c.alpha, c.eta, i, o); }, kDraws);
    const validation::ChiSquareResult r = validation::chi_square_test(obs, exp, 0.01, kTests);
    EXPECT_FALSE(r.reject) << name(c) << ": stat " << r.statistic << " dof " << r.dof << " p " << r.p_value;
    // Both lobes carry draws (a reflection-only or transmission-only sampler would pass the rest).
    double below = 0.0, above = 0.0;
    for (int a = 0; a < kCos; ++a)
      for (int b = 0; b < kPhi; ++b) (a < kCos / 2 ? below : above) += obs[a * kPhi + b];
    EXPECT_GT(above, 0.01 * kDraws) << name(c);
    if (c.eta > 1.0 || std::sin(c.theta_i_deg * kPi / 180) < c.eta) {
      EXPECT_GT(below, 0.1 * kDraws) << name(c);
    }
  }
}

// The same draws held to the transmission Jacobian with |i.h| for |o.h| (the density's shape wrong,
// its reflection right): rejected in every case that transmits.
TEST(WalterSampling, AWrongJacobianIsRejected) {
  for (const Case& c : {kCases[0], kCases[2], kCases[4]}) {
    const Dir3 i = light(c);
    const std::vector<double> obs = histogram(c, kDraws, 7);
    const auto wrong = [&](const Dir3& o) {
      const double p = walter_pdf(c.ndf, c.alpha, c.eta, i, o);
      if (o.z >= 0.0 || p == 0.0) return p;
      const Dir3 h = walter_half_vector(i, o, c.eta);
      const double ih = i.x * h.x + i.y * h.y + i.z * h.z, oh = o.x * h.x + o.y * h.y + o.z * h.z;
      return p * ih / std::abs(oh);
    };
    const validation::ChiSquareResult r = validation::chi_square_test(obs, expected(wrong, kDraws), 0.01, kTests);
    EXPECT_TRUE(r.reject) << name(c) << ": stat " << r.statistic << " dof " << r.dof;
  }
}

// f |o.n| / pdf = G2 / G1(i) for the Smith VNDF: G1(o) with the separable G2, on both sides.
TEST(WalterSampling, SmithWeightIsG1OfTheExit) {
  int reflected = 0, transmitted = 0;
  for (double eta : {1.5, 1 / 1.5, 2.4})
    for (double alpha : {0.1, 0.5, 1.2})
      for (double ti : {0.0, 45.0, 80.0}) {
        const Dir3 i = dir3(ti * kPi / 180.0, 0.3);
        for (int j = 0; j < 200; ++j) {
          sim::Rng r(3, 1, static_cast<std::uint64_t>(j));
          const double u0 = r.uniform(), u1 = r.uniform(), u2 = r.uniform();
          const WalterSample s = sample_walter(NdfKind::ggx, alpha, eta, MaskingKind::smith_separable, i, u0, u1, u2);
          if (!s.ok) continue;
          (s.transmitted ? transmitted : reflected) += 1;
          const double polar = std::atan2(std::hypot(s.o.x, s.o.y), std::abs(s.o.z));
          const double g1 = 1.0 / (1.0 + Lambda(NdfKind::ggx, polar, alpha));
          ASSERT_NEAR(s.weight, g1, 1e-12 * g1) << "eta " << eta << " alpha " << alpha << " ti " << ti;
        }
      }
  EXPECT_GT(reflected, 500);
  EXPECT_GT(transmitted, 2000);
}

TEST(WalterSampling, HardCasesAreFinite) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.01, 2.0})
      for (double eta : {1.0001, 1.5, 1 / 2.4})
        for (double ti : {0.0, 89.99}) {
          const Dir3 i = dir3(ti * kPi / 180.0, 1.0);
          for (int j = 0; j < 2000; ++j) {
            sim::Rng r(5, 2, static_cast<std::uint64_t>(j));
            const double u0 = r.uniform(), u1 = r.uniform(), u2 = r.uniform();
            const WalterSample s = sample_walter(ndf, alpha, eta, MaskingKind::smith_height_correlated, i, u0, u1, u2);
            if (!s.ok) continue;
            const double len = std::sqrt(s.o.x * s.o.x + s.o.y * s.o.y + s.o.z * s.o.z);
            ASSERT_NEAR(len, 1.0, 1e-12);
            ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0.0);
            ASSERT_TRUE(std::isfinite(s.weight) && s.weight >= 0.0) << s.weight;
            ASSERT_EQ(s.transmitted, s.o.z < 0.0);
          }
        }
}

}  // namespace
}  // namespace vgroove::analytic
