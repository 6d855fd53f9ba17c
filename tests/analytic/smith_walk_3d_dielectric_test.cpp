// Tests of analytic/smith_walk_3d_dielectric.h: the conductor limit against the 3D conductor walk
// bit for bit (and from below its mirror image), eta = 1, the k = 1 energies against Walter's BSDF
// with Smith's height-correlated G2 integrated by analytic/albedo_glass.h (an independent
// quadrature), with a deliberately broken law (Fresnel with eta inverted) rejected by the same
// check, the reciprocity of the transmitted averages (the wrong power of eta rejected by the same
// counts), and hard cases. Statistics: binomial counts, 5 standard deviations.
#include "vgroove/analytic/smith_walk_3d_dielectric.h"

#include "tests/stats.h"
#include "vgroove/analytic/albedo_glass.h"
#include "vgroove/optics/fresnel.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <vector>

namespace vgroove::analytic {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

// A uniform stream for the walk (SplitMix64; (0, 1) open), as the other walks' tests.
using vgroove::test_stats::Uniforms;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The direction towards the light at theta from the normal of `from`'s side, azimuth phi.
Dir3 light(double theta, double phi, WalkMedium from) {
  const Dir3 d = dir3(theta, phi);
  return from == WalkMedium::above ? d : Dir3{d.x, d.y, -d.z};
}

TEST(SmithWalk3dDielectric, ConductorLimitIsTheConductorWalk) {
  DielectricWalkOptions opt;
  opt.conductor_limit = true;
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.1, 0.5, 1.5})
      for (double th : {0.0, 30.0, 70.0, 89.9}) {
        Uniforms a{17}, b{17};
        const Dir3 i = dir3(deg(th), 0.7);
        for (int n = 0; n < 1000; ++n) {
          Uniforms c{b.state};
          const Walk3d w = smith_walk_3d(ndf, alpha, i, a);
          const DielectricWalk3d d = smith_walk_3d_dielectric(ndf, alpha, i, WalkMedium::above, opt, b);
          ASSERT_EQ(w.left, d.left);
          ASSERT_EQ(w.k, d.k);
          ASSERT_TRUE(same_bits(w.o.x, d.o.x) && same_bits(w.o.y, d.o.y) && same_bits(w.o.z, d.o.z));
          ASSERT_EQ(d.side, WalkMedium::above);
          ASSERT_EQ(d.path, 0u);
          // From below: the mirror image (z -> -z) of the walk from above.
          const DielectricWalk3d e =
              smith_walk_3d_dielectric(ndf, alpha, Dir3{i.x, i.y, -i.z}, WalkMedium::below, opt, c);
          ASSERT_EQ(e.side, WalkMedium::below);
          ASSERT_EQ(e.k, w.k);
          ASSERT_TRUE(same_bits(e.o.x, w.o.x) && same_bits(e.o.y, w.o.y) && same_bits(e.o.z, -w.o.z));
        }
      }
}

TEST(SmithWalk3dDielectric, EtaOnePassesStraightThrough) {
  DielectricWalkOptions opt;
  opt.eta = 1.0;
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (WalkMedium from : {WalkMedium::above, WalkMedium::below})
      for (double th : {0.0, 45.0, 80.0}) {
        Uniforms u{5};
        const Dir3 i = light(deg(th), 2.0, from);
        int recrossed = 0;
        for (int n = 0; n < 2000; ++n) {
          const DielectricWalk3d w = smith_walk_3d_dielectric(ndf, 0.8, i, from, opt, u);
          ASSERT_TRUE(w.left);
          ASSERT_NE(w.side, from);
          // The incident direction, on the far side: o = -i.
          ASSERT_NEAR(w.o.x, -i.x, 1e-13);
          ASSERT_NEAR(w.o.y, -i.y, 1e-13);
          ASSERT_NEAR(w.o.z, -i.z, 1e-13);
          ASSERT_EQ(w.k % 2, 1);
          ASSERT_EQ(w.path, w.k >= 64 ? ~0ULL : (std::uint64_t{1} << w.k) - 1);
          recrossed += w.k >= 3;
        }
        // Straight down, Lambda = 0: a vertical line crosses the interface once; slanted, the walk
        // re-crosses.
        if (th == 0.0)
          EXPECT_EQ(recrossed, 0);
        else
          EXPECT_GT(recrossed, 0);
      }
}

// Fresnel with eta inverted where Snell transmits: a deliberately wrong law.
struct InvertedEtaLaw {
  double operator()(double cos_i, double eta_rel) const { return optics::fresnel_dielectric(cos_i, 1.0 / eta_rel); }
};

struct Case {
  NdfKind ndf;
  double alpha, theta_deg;
  WalkMedium from;
};

// The largest |z| of the walk's k = 1 reflected and transmitted shares against Walter's single
// scattering with Smith's height-correlated G2 (E_R, E_T of albedo_glass.h at eta_rel, the
// relative index the light meets).
template <class Law>
double worst_z(const Case& c, int walks, const Law& law) {
  DielectricWalkOptions opt;
  opt.eta = 1.5;
  const double eta_rel = c.from == WalkMedium::above ? opt.eta : 1.0 / opt.eta;
  const double theta = deg(c.theta_deg);
  AlbedoOptions q;
  q.tol = 1e-5;
  const GlassAlbedo e =
      albedo_glass({c.ndf, MaskingKind::smith_height_correlated}, c.alpha, std::cos(theta), eta_rel, q);
  Uniforms u{99};
  const Dir3 i = light(theta, 0.3, c.from);
  long r1 = 0, t1 = 0;
  for (int n = 0; n < walks; ++n) {
    const DielectricWalk3d w = smith_walk_3d_dielectric(c.ndf, c.alpha, i, c.from, opt, u, law);
    if (w.k == 1) (w.side == c.from ? r1 : t1) += 1;
  }
  auto z = [&](long count, double p) {
    return (static_cast<double>(count) / walks - p) / std::sqrt(p * (1.0 - p) / walks);
  };
  return std::max(std::abs(z(r1, e.R.value)), std::abs(z(t1, e.T.value)));
}

TEST(SmithWalk3dDielectric, SingleScatteringIsWaltersWithTheHeightCorrelatedG2) {
  // 5 standard deviations of the binomial counts of 60,000 walks per case.
  const std::vector<Case> cases = {{NdfKind::ggx, 0.3, 0.0, WalkMedium::above},
                                   {NdfKind::ggx, 1.0, 60.0, WalkMedium::above},
                                   {NdfKind::beckmann, 0.5, 30.0, WalkMedium::below},
                                   {NdfKind::ggx, 0.6, 50.0, WalkMedium::below}};
  for (const Case& c : cases) {
    const double right = worst_z(c, 60000, DielectricFresnelLaw{});
    const double broken = worst_z(c, 60000, InvertedEtaLaw{});
    std::printf("%s alpha %.1f theta %.0f %s: |z| %.2f, broken law %.1f\n", ndf_name(c.ndf), c.alpha, c.theta_deg,
                c.from == WalkMedium::above ? "above" : "below", right, broken);
    EXPECT_LE(right, 5.0) << c.alpha << " " << c.theta_deg;
    EXPECT_GT(broken, 5.0) << c.alpha << " " << c.theta_deg;
  }
}

// T_avg = 2 int E_T mu dmu from each side by walks from cosine-weighted directions (mu = sqrt(u),
// azimuth uniform): r = T_avg(above) / (eta^p T_avg(below)) - 1, with its standard error from the
// two binomial shares. Reciprocity with energy conservation says p = 2.
struct Averages {
  double t[2], var[2];  // T_avg from above and from below, and the variances of their estimates
  // r for the power p, and its standard error.
  double r(double eta, double p) const { return t[0] / (std::pow(eta, p) * t[1]) - 1.0; }
  double se(double eta, double p) const {
    return (1.0 + r(eta, p)) * std::sqrt(var[0] / (t[0] * t[0]) + var[1] / (t[1] * t[1]));
  }
};
Averages transmitted_averages(NdfKind ndf, double alpha, double eta, int walks) {
  DielectricWalkOptions opt;
  opt.eta = eta;
  Averages a{};
  for (int s = 0; s < 2; ++s) {
    const WalkMedium from = s == 0 ? WalkMedium::above : WalkMedium::below;
    Uniforms dir{1234u + static_cast<unsigned>(s)}, u{777u + static_cast<unsigned>(s)};
    long through = 0;
    for (int n = 0; n < walks; ++n) {
      const double mu = std::sqrt(dir()), phi = 2.0 * std::numbers::pi * dir();
      through += smith_walk_3d_dielectric(ndf, alpha, light(std::acos(mu), phi, from), from, opt, u).side != from;
    }
    a.t[s] = static_cast<double>(through) / walks;
    a.var[s] = a.t[s] * (1.0 - a.t[s]) / walks;
  }
  return a;
}

// Every order together: the walk conserves energy (every walk leaves) and is reciprocal, so the
// averages obey T_avg(eta) = eta^2 T_avg(1 / eta) (1 - F_avg(1 / eta) = (1 - F_avg(eta)) / eta^2 for
// a flat interface). The same counts with the power 1 (a deliberately wrong identity) are rejected.
// 10^6 walks a side: r = -0.0007, -0.0010, -0.0005 (se 0.0012) for the three cases.
TEST(SmithWalk3dDielectric, TransmittedAveragesAreReciprocal) {
  for (const auto& [ndf, alpha] :
       {std::pair{NdfKind::ggx, 0.3}, std::pair{NdfKind::ggx, 1.0}, std::pair{NdfKind::beckmann, 0.6}}) {
    const Averages a = transmitted_averages(ndf, alpha, 1.5, 60000);
    std::printf("%s alpha %.1f: r = %+.4f +- %.4f (power 1: %+.3f)\n", ndf_name(ndf), alpha, a.r(1.5, 2.0),
                a.se(1.5, 2.0), a.r(1.5, 1.0));
    EXPECT_LE(std::abs(a.r(1.5, 2.0)), 5.0 * a.se(1.5, 2.0));
    EXPECT_GT(std::abs(a.r(1.5, 1.0)), 5.0 * a.se(1.5, 1.0));
  }
}

TEST(SmithWalk3dDielectric, EveryWalkLeavesAndHardCasesStayFinite) {
  for (double eta : {1.5, 1.0 / 1.5, 2.4, 1.0001})
    for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
      for (double alpha : {0.01, 0.3, 2.0})
        for (WalkMedium from : {WalkMedium::above, WalkMedium::below})
          for (double th : {0.0, 89.99}) {
            DielectricWalkOptions opt;
            opt.eta = eta;
            Uniforms u{3};
            const Dir3 i = light(deg(th), 1.0, from);
            for (int n = 0; n < 200; ++n) {
              const DielectricWalk3d w = smith_walk_3d_dielectric(ndf, alpha, i, from, opt, u);
              ASSERT_TRUE(w.left) << eta << " " << alpha << " " << th;
              ASSERT_TRUE(std::isfinite(w.o.x) && std::isfinite(w.o.y) && std::isfinite(w.o.z));
              ASSERT_NEAR(std::hypot(w.o.x, w.o.y, w.o.z), 1.0, 1e-12);
              ASSERT_TRUE(w.side == WalkMedium::above ? w.o.z > 0.0 : w.o.z < 0.0);
            }
          }
}

}  // namespace
}  // namespace vgroove::analytic
