// Tests of analytic/smith_walk_flatland_dielectric.h: the conductor limit against the conductor
// walk bit for bit (and from below its mirror image), eta = 1, the k = 1 energies against their
// quadratures (Fresnel over the visible normals with the height-correlated escape from either
// side, derived in docs/derivations/smith_walk_dielectric.md), with a deliberately broken law
// (Fresnel with eta inverted) rejected by the same check, and hard cases.
#include "vgroove/analytic/smith_walk_flatland_dielectric.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/optics/snell.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <vector>

namespace vgroove::analytic {
namespace {

using namespace vgroove::test_stats;

double deg(double d) { return d * std::numbers::pi / 180.0; }
constexpr double kHalfPi = 0.5 * std::numbers::pi;

// A uniform stream for the walk (SplitMix64; (0, 1) open), as the conductor walk's tests.
using vgroove::test_stats::Uniforms;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(SmithWalkDielectric, ConductorLimitIsTheConductorWalk) {
  DielectricWalkOptions opt;
  opt.conductor_limit = true;
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.1, 0.5, 1.5})
      for (double th : {0.0, 30.0, -70.0, 89.9}) {
        Uniforms a{17}, b{17}, c{17};
        for (int n = 0; n < 3000; ++n) {
          const FlatlandWalk w = smith_walk_flatland(ndf, alpha, deg(th), a);
          const FlatlandDielectricWalk d =
              smith_walk_flatland_dielectric(ndf, alpha, deg(th), WalkMedium::above, opt, b);
          ASSERT_EQ(w.left, d.left);
          ASSERT_EQ(w.k, d.k);
          ASSERT_TRUE(same_bits(w.theta_o, d.theta_o)) << w.theta_o << " " << d.theta_o;
          ASSERT_EQ(d.side, WalkMedium::above);
          ASSERT_EQ(d.path, 0u);
          // From below: the mirror image of the walk from above at -theta_i.
          Uniforms c2{c.state};
          const FlatlandWalk m = smith_walk_flatland(ndf, alpha, -deg(th), c2);
          const FlatlandDielectricWalk e =
              smith_walk_flatland_dielectric(ndf, alpha, deg(th), WalkMedium::below, opt, c);
          ASSERT_EQ(e.side, WalkMedium::below);
          ASSERT_EQ(e.k, m.k);
          ASSERT_TRUE(same_bits(e.theta_o, -m.theta_o));
        }
      }
}

TEST(SmithWalkDielectric, EtaOnePassesStraightThrough) {
  DielectricWalkOptions opt;
  opt.eta = 1.0;
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (WalkMedium from : {WalkMedium::above, WalkMedium::below})
      for (double th : {0.0, 45.0, -80.0}) {
        Uniforms u{5};
        int recrossed = 0;
        for (int n = 0; n < 3000; ++n) {
          const FlatlandDielectricWalk w = smith_walk_flatland_dielectric(ndf, 0.8, deg(th), from, opt, u);
          ASSERT_TRUE(w.left);
          ASSERT_NE(w.side, from);
          ASSERT_NEAR(w.theta_o, deg(th), 1e-13);  // the incident direction, on the far side
          ASSERT_EQ(w.k % 2, 1);
          ASSERT_EQ(w.path, w.k >= 64 ? ~0ULL : (std::uint64_t{1} << w.k) - 1);
          recrossed += w.k >= 3;
        }
        // Straight down, Lambda = 0: a vertical line crosses the interface once (as it crosses a
        // height profile once); slanted, the walk re-crosses.
        if (th == 0.0)
          EXPECT_EQ(recrossed, 0);
        else
          EXPECT_GT(recrossed, 0);
      }
}

// The k = 1 energies of light from `from` at theta_i (docs/derivations/smith_walk_dielectric.md):
//   E_R1 = int D_v(m) F a / (a + Lambda(o_r)) dm,  E_T1 = int D_v(m) (1 - F) a B(a, 1 + Lambda(o_t)) dm,
// a = 1 + Lambda(i), over the normals visible from i, o_r and o_t the reflected and refracted
// directions (0 where they point back into the surface). eta_rel_f inverts eta for the broken law.
struct SingleScattering {
  double reflected, transmitted;
};
SingleScattering single_scattering(NdfKind ndf, double alpha, double theta_v, double eta_rel, double eta_rel_f) {
  const double a = 1.0 + Lambda(ndf, theta_v, alpha);
  auto F_of = [&](double phi) {
    const double c = std::cos(phi);
    return optics::snell_cos_transmitted(c, eta_rel) < 0.0 ? 1.0 : optics::fresnel_dielectric(c, eta_rel_f);
  };
  auto refl = [&](double m) {
    const double o = wrap_angle(2.0 * m - theta_v);
    if (!(std::cos(o) > 0.0)) return 0.0;
    return visible_normal_pdf(ndf, alpha, theta_v, m) * F_of(theta_v - m) * a / (a + Lambda(ndf, o, alpha));
  };
  auto trans = [&](double m) {
    const double phi = theta_v - m, c = std::cos(phi);
    const double ct = optics::snell_cos_transmitted(c, eta_rel);
    if (ct < 0.0) return 0.0;
    const double o = wrap_angle(-m - std::atan2(std::sin(phi) / eta_rel, ct));
    if (!(std::cos(o) > 0.0)) return 0.0;
    return visible_normal_pdf(ndf, alpha, theta_v, m) * (1.0 - F_of(phi)) * a *
           std::beta(a, 1.0 + Lambda(ndf, o, alpha));
  };
  // Breaks: the visible support's ends, the NDF's peak, the critical angle's normals.
  std::vector<double> br = {std::max(-kHalfPi, theta_v - kHalfPi), std::min(kHalfPi, theta_v + kHalfPi), 0.0};
  if (eta_rel < 1.0)
    for (double s : {-1.0, 1.0}) br.push_back(theta_v + s * std::asin(eta_rel));
  std::sort(br.begin(), br.end());
  SingleScattering out{0.0, 0.0};
  for (std::size_t i = 0; i + 1 < br.size(); ++i) {
    const double lo = std::max(br[i], br.front()), hi = std::min(br[i + 1], br.back());
    if (!(hi > lo)) continue;
    out.reflected += tanh_sinh(refl, lo, hi);
    out.transmitted += tanh_sinh(trans, lo, hi);
  }
  return out;
}

// Fresnel with eta inverted where Snell transmits: a deliberately wrong law (the test below must
// reject it).
struct InvertedEtaLaw {
  double operator()(double cos_i, double eta_rel) const { return optics::fresnel_dielectric(cos_i, 1.0 / eta_rel); }
};

struct Case {
  NdfKind ndf;
  double alpha, theta_deg;
  WalkMedium from;
};

template <class Law>
double worst_z(const Case& c, int walks, const Law& law, bool inverted) {
  DielectricWalkOptions opt;
  opt.eta = 1.5;
  const double eta_rel = c.from == WalkMedium::above ? opt.eta : 1.0 / opt.eta;
  // In the frame of the incident medium the view is at +-theta_i (the below side's frame mirrors).
  const double theta_v = c.from == WalkMedium::above ? deg(c.theta_deg) : -deg(c.theta_deg);
  const SingleScattering e = single_scattering(c.ndf, c.alpha, theta_v, eta_rel, inverted ? 1.0 / eta_rel : eta_rel);
  Uniforms u{99};
  long r1 = 0, t1 = 0;
  for (int n = 0; n < walks; ++n) {
    const FlatlandDielectricWalk w =
        smith_walk_flatland_dielectric(c.ndf, c.alpha, deg(c.theta_deg), c.from, opt, u, law);
    if (w.k == 1) (w.side == c.from ? r1 : t1) += 1;
  }
  auto z = [&](long count, double p) {
    return (static_cast<double>(count) / walks - p) / std::sqrt(p * (1.0 - p) / walks);
  };
  return std::max(std::abs(z(r1, e.reflected)), std::abs(z(t1, e.transmitted)));
}

TEST(SmithWalkDielectric, SingleScatteringIsFresnelWithTheHeightCorrelatedEscape) {
  // 5 standard deviations of the binomial counts of 100,000 walks per case.
  const std::vector<Case> cases = {{NdfKind::ggx, 0.3, 0.0, WalkMedium::above},
                                   {NdfKind::ggx, 1.0, 60.0, WalkMedium::above},
                                   {NdfKind::beckmann, 0.5, 30.0, WalkMedium::below},
                                   {NdfKind::beckmann, 1.0, 0.0, WalkMedium::below},
                                   {NdfKind::ggx, 0.5, -50.0, WalkMedium::below}};
  for (const Case& c : cases) {
    EXPECT_LE(worst_z(c, 100000, DielectricFresnelLaw{}, false), 5.0) << c.alpha << " " << c.theta_deg;
    // The broken law against its own quadrature holds (the walk draws what its law says) ...
    EXPECT_LE(worst_z(c, 100000, InvertedEtaLaw{}, true), 5.0) << c.alpha << " " << c.theta_deg;
    // ... and against the right one it is rejected.
    EXPECT_GT(worst_z(c, 100000, InvertedEtaLaw{}, false), 5.0) << c.alpha << " " << c.theta_deg;
  }
}

TEST(SmithWalkDielectric, EveryWalkLeavesAndHardCasesStayFinite) {
  for (double eta : {1.5, 1.0 / 1.5, 2.4, 1.0001})
    for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
      for (double alpha : {0.01, 0.3, 2.0})
        for (WalkMedium from : {WalkMedium::above, WalkMedium::below})
          for (double th : {0.0, 89.99, -89.99}) {
            DielectricWalkOptions opt;
            opt.eta = eta;
            Uniforms u{3};
            for (int n = 0; n < 300; ++n) {
              const FlatlandDielectricWalk w = smith_walk_flatland_dielectric(ndf, alpha, deg(th), from, opt, u);
              ASSERT_TRUE(w.left) << eta << " " << alpha << " " << th;
              ASSERT_TRUE(std::isfinite(w.theta_o) && std::abs(w.theta_o) <= kHalfPi);
            }
          }
  EXPECT_EQ(log1m_exp(-std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_EQ(log1m_exp(0.0), -std::numeric_limits<double>::infinity());
  EXPECT_NEAR(log1m_exp(-1e-20), std::log(1e-20), 1e-12);
  EXPECT_NEAR(log1m_exp(-50.0), -std::exp(-50.0), 1e-35);
}

}  // namespace
}  // namespace vgroove::analytic
