// Tests of analytic/walter.h: Walter et al. 2007's rough dielectric BSDF in 3D and flatland. Hand
// values at normal incidence, the Jacobians against finite differences of the half vector, the
// generalized reciprocity f_t(i, o) / n_o^2 = f_t(o, i) / n_i^2 (flatland n^1), the energy of the
// model at alpha = 0.01 against flat Fresnel R and T by quadrature over o (3D and flatland), grazing
// light and TIR, and the article's Eq. 21d as printed against its own reciprocity (ERRATA W1).
// Each check keeps a broken variant beside it that must fail.
#include "vgroove/analytic/walter.h"

#include "vgroove/analytic/ndf.h"
#include "vgroove/optics/fresnel.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace vgroove::analytic {
namespace {

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }
double dot(const Dir3& a, const Dir3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Dir3 neg(const Dir3& a) { return Dir3{-a.x, -a.y, -a.z}; }
constexpr MaskingKind kAll[] = {MaskingKind::vcavity, MaskingKind::smith_separable,
                                MaskingKind::smith_height_correlated};

// F0 = ((eta - 1) / (eta + 1))^2; GGX D(0) = 1 / (pi alpha^2); the flatland GGX slope law is the
// marginal of the 3D one, 1 / (2 alpha (1 + x^2 / alpha^2)^(3/2)), so D2(0) = 1 / (2 alpha); Beckmann's
// marginal exp(-x^2 / alpha^2) / (sqrt(pi) alpha), D2(0) = 1 / (sqrt(pi) alpha). At normal incidence
// and o = -+n, h = n, every G is 1, |i.h| = |o.h| = 1, and n_i i.h + n_o o.h = 1 - eta.
TEST(Walter, NormalIncidenceHandValues) {
  const Dir3 up{0, 0, 1}, down{0, 0, -1};
  for (double eta : {1.5, 2.4, 1.0 / 1.5})
    for (double a : {0.05, 0.3, 1.0})
      for (MaskingKind g : kAll) {
        const double F0 = (eta - 1) * (eta - 1) / ((eta + 1) * (eta + 1));
        const double D = 1.0 / (kPi * a * a), D2g = 1.0 / (2.0 * a), D2b = 1.0 / (std::sqrt(kPi) * a);
        EXPECT_NEAR(walter_brdf(up, up, NdfKind::ggx, a, eta, g), F0 * D / 4.0, 1e-13 * D) << eta << " " << a;
        const double t = eta * eta * (1 - F0) * D / ((1 - eta) * (1 - eta));
        EXPECT_NEAR(walter_btdf(up, down, NdfKind::ggx, a, eta, g), t, 1e-13 * t) << eta << " " << a;
        EXPECT_NEAR(walter_brdf2(0, 0, NdfKind::ggx, a, eta, g), F0 * D2g / 2.0, 1e-13 * D2g);
        EXPECT_NEAR(walter_brdf2(0, 0, NdfKind::beckmann, a, eta, g), F0 * D2b / 2.0, 1e-13 * D2b);
        const double t2 = eta * (1 - F0) * D2g / std::abs(1 - eta);
        EXPECT_NEAR(walter_btdf2(0, 0, NdfKind::ggx, a, eta, g), t2, 1e-13 * t2) << eta << " " << a;
      }
}

// The flatland Jacobian |d theta_h / d theta_t| = n_o |o.h| / |n_i i.h + n_o o.h| against a central
// difference of the half angle; the 3D one (Walter Eq. 17) against the solid angle of the image of a
// small cone of o (two tangent steps, cross product of the images of h).
TEST(Walter, JacobiansAreTheDerivatives) {
  double worst2 = 0.0, worst3 = 0.0;
  for (double eta : {1.5, 2.4, 1.0 / 1.5, 1.0 / 2.4})
    for (double ti : {-70.0, -20.0, 0.0, 35.0, 80.0})
      for (double tt : {-60.0, -10.0, 0.0, 25.0, 50.0}) {
        const double a = deg(ti), b = deg(tt), e = 1e-6;
        const double h0 = walter_half_angle_t2(a, b - e, eta), h1 = walter_half_angle_t2(a, b + e, eta);
        if (std::abs(h1 - h0) > 1.0) continue;  // the half vector flips side (not a refraction)
        const double fd = std::abs(h1 - h0) / (2 * e), j = walter_jacobian_t2(a, b, eta);
        worst2 = std::max(worst2, std::abs(fd - j) / j);
        // 3D, at azimuth 40 deg between i and o.
        const Dir3 i = dir3(a < 0 ? -a : a, a < 0 ? kPi : 0.0);
        const Dir3 o = neg(dir3(std::abs(b), deg(40.0)));
        const Dir3 u{-std::sin(deg(40.0)), std::cos(deg(40.0)), 0.0};                               // tangent 1
        const Dir3 v{o.z * std::cos(deg(40.0)), o.z * std::sin(deg(40.0)), std::sin(std::abs(b))};  // tangent 2
        auto at = [&](double s, double t) {
          Dir3 p{o.x + s * u.x + t * v.x, o.y + s * u.y + t * v.y, o.z + s * u.z + t * v.z};
          const double l = std::sqrt(dot(p, p));
          return walter_half_vector(i, Dir3{p.x / l, p.y / l, p.z / l}, eta);
        };
        const Dir3 hs0 = at(-e, 0), hs1 = at(e, 0), ht0 = at(0, -e), ht1 = at(0, e);
        const Dir3 ds{hs1.x - hs0.x, hs1.y - hs0.y, hs1.z - hs0.z}, dt{ht1.x - ht0.x, ht1.y - ht0.y, ht1.z - ht0.z};
        const Dir3 c{ds.y * dt.z - ds.z * dt.y, ds.z * dt.x - ds.x * dt.z, ds.x * dt.y - ds.y * dt.x};
        const double fd3 = std::sqrt(dot(c, c)) / (4 * e * e), j3 = walter_jacobian_t(i, o, eta);
        worst3 = std::max(worst3, std::abs(fd3 - j3) / j3);
      }
  EXPECT_LT(worst2, 1e-7);
  EXPECT_LT(worst3, 1e-6);
}

// Generalized reciprocity: light from o (the far side) to i is the model in the point-reflected
// frame (v -> -v: the far side becomes the near one, angles keep their labels) with eta -> 1 / eta:
//   3D:       f_t(i, o; eta) / eta^2 = f_t(-o, -i; 1 / eta),
//   flatland: f_t2(ti, tt; eta) / eta = f_t2(tt, ti; 1 / eta).
// Broken variant: the flatland form with the 3D power (eta^2) must fail.
TEST(Walter, GeneralizedReciprocity) {
  double worst = 0.0, worst_broken = 0.0;
  int n = 0;
  for (double eta : {1.5, 2.4, 1.0 / 1.33})
    for (double a : {0.1, 0.5, 1.2})
      for (MaskingKind g : kAll)
        for (double ti : {-60.0, 0.0, 20.0, 75.0})
          for (double tt : {-40.0, -5.0, 15.0, 50.0}) {
            const double f = walter_btdf2(deg(ti), deg(tt), NdfKind::ggx, a, eta, g) / eta;
            const double r = walter_btdf2(deg(tt), deg(ti), NdfKind::ggx, a, 1.0 / eta, g);
            const Dir3 i = dir3(deg(std::abs(ti)), ti < 0 ? kPi : 0.0), o = neg(dir3(deg(std::abs(tt)), deg(120.0)));
            const double f3 = walter_btdf(i, o, NdfKind::beckmann, a, eta, g) / (eta * eta);
            const double r3 = walter_btdf(neg(o), neg(i), NdfKind::beckmann, a, 1.0 / eta, g);
            if (f > 0.0) {
              ++n;
              worst = std::max(worst, std::abs(f - r) / f);
              worst_broken = std::max(worst_broken, std::abs(f * eta - r) / r);
            }
            if (f3 > 0.0) worst = std::max(worst, std::abs(f3 - r3) / f3);
            EXPECT_EQ(f > 0.0, r > 0.0) << ti << " " << tt;
            EXPECT_EQ(f3 > 0.0, r3 > 0.0) << ti << " " << tt;
          }
  EXPECT_GT(n, 100);
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(worst_broken, 0.2);  // eta^2 in flatland is not reciprocal
}

// Hemispherical shares of the model: int f |o.n| d omega_o over the reflected and the transmitted
// hemispheres, by quadrature over o around the lobe's centre c (mirror or Snell direction of i):
// o = cos(r) c + sin(r) (cos(p) e1 + sin(p) e2), r split at multiples of the width w (tanh-sinh),
// p by the trapezoid rule (periodic). `scale` multiplies f_t (1: the model; the tests' broken forms).
struct Shares {
  double R = 0.0, T = 0.0;
};
Shares shares3(const Dir3& i, NdfKind ndf, double a, double eta, MaskingKind g, double scale_t = 1.0) {
  Shares s;
  for (int side = 0; side < 2; ++side) {
    Dir3 c{-i.x, -i.y, i.z};  // mirror direction
    if (side == 1) {
      const double st2 = (1 - i.z * i.z) / (eta * eta);
      c = st2 < 1.0 ? Dir3{-i.x / eta, -i.y / eta, -std::sqrt(1 - st2)} : Dir3{0, 0, -1};
    }
    Dir3 e1 = std::abs(c.z) < 0.9 ? Dir3{0, 0, 1} : Dir3{1, 0, 0};
    const double d = dot(e1, c);
    e1 = Dir3{e1.x - d * c.x, e1.y - d * c.y, e1.z - d * c.z};
    const double l = std::sqrt(dot(e1, e1));
    e1 = Dir3{e1.x / l, e1.y / l, e1.z / l};
    const Dir3 e2{c.y * e1.z - c.z * e1.y, c.z * e1.x - c.x * e1.z, c.x * e1.y - c.y * e1.x};
    const int np = 96;
    auto ring = [&](double r) {
      double sum = 0.0;
      for (int q = 0; q < np; ++q) {
        const double p = 2 * kPi * (q + 0.5) / np;
        const Dir3 o{std::cos(r) * c.x + std::sin(r) * (std::cos(p) * e1.x + std::sin(p) * e2.x),
                     std::cos(r) * c.y + std::sin(r) * (std::cos(p) * e1.y + std::sin(p) * e2.y),
                     std::cos(r) * c.z + std::sin(r) * (std::cos(p) * e1.z + std::sin(p) * e2.z)};
        const double f = side == 0 ? walter_brdf(i, o, ndf, a, eta, g) : scale_t * walter_btdf(i, o, ndf, a, eta, g);
        if ((side == 0) == (o.z > 0.0)) sum += f * std::abs(o.z);
      }
      return sum * 2 * kPi / np * std::sin(r);
    };
    std::vector<double> cuts{0.0};
    for (double k : {0.25, 1.0, 3.0, 8.0, 25.0, 80.0})
      if (k * a < kPi) cuts.push_back(k * a);
    cuts.push_back(kPi);
    double v = 0.0;
    for (std::size_t q = 0; q + 1 < cuts.size(); ++q)
      v += test_stats::tanh_sinh(ring, cuts[q], cuts[q + 1], 1.0 / 16.0);
    (side == 0 ? s.R : s.T) = v;
  }
  return s;
}

Shares shares2(double ti, NdfKind ndf, double a, double eta, MaskingKind g, double scale_t = 1.0) {
  Shares s;
  const double st = std::sin(ti) / eta;
  const double centre[2] = {-ti, std::abs(st) < 1.0 ? std::asin(st) : 0.0};
  for (int side = 0; side < 2; ++side) {
    std::vector<double> cuts{-kPi / 2, kPi / 2};
    for (double k : {0.0, 0.25, 1.0, 3.0, 8.0, 25.0})
      for (double sg : {-1.0, 1.0}) {
        const double x = centre[side] + sg * k * a;
        if (std::abs(x) < kPi / 2) cuts.push_back(x);
      }
    std::sort(cuts.begin(), cuts.end());
    auto f = [&](double o) {
      return (side == 0 ? walter_brdf2(ti, o, ndf, a, eta, g) : scale_t * walter_btdf2(ti, o, ndf, a, eta, g)) *
             std::cos(o);
    };
    double v = 0.0;
    for (std::size_t q = 0; q + 1 < cuts.size(); ++q)
      if (cuts[q + 1] > cuts[q]) v += test_stats::tanh_sinh(f, cuts[q], cuts[q + 1], 1.0 / 32.0);
    (side == 0 ? s.R : s.T) = v;
  }
  return s;
}

// As alpha -> 0 the model is the flat interface: R -> F(theta_i), T -> 1 - F(theta_i), 3D and flatland,
// from either side (eta and 1 / eta; beyond the critical angle T -> 0). Beckmann at alpha = 0.01
// (GGX's tails, ~alpha^2 / tan^2 of the facets tilted past the critical angle, converge slowly): the
// spread of |i.h| and F over the lobe is O(alpha^2) (first order cancels by symmetry), measured at most
// 6.1e-5 (eta 1/1.5, 30 deg, near the critical angle); bound 2e-4. R + T = 1 to 1e-9 from 0 to
// 60 deg (G = 1 to rounding at alpha = 0.01: the projected area of the facets, all of the flux). Broken variants: f_t
// without its n_o^2 (3D) or n_o (flatland) factor, and with the article's extra (n_v / n_l)^2 (3D) or n_v / n_l
// (flatland), must miss 1 - F by more than 0.1.
TEST(Walter, SmallRoughnessIsFlatFresnel) {
  const double a = 0.01;
  for (double eta : {1.5, 2.4, 1.0 / 1.5})
    for (double ti : {0.0, 30.0, 60.0}) {
      const double F = optics::fresnel_dielectric(std::cos(deg(ti)), eta);
      const Dir3 i = dir3(deg(ti), 0.0);
      const Shares s3 = shares3(i, NdfKind::beckmann, a, eta, MaskingKind::smith_height_correlated);
      const Shares s2 = shares2(deg(ti), NdfKind::beckmann, a, eta, MaskingKind::smith_height_correlated);
      EXPECT_NEAR(s3.R, F, 2e-4) << "3D eta " << eta << " theta_i " << ti;
      EXPECT_NEAR(s3.T, 1 - F, 2e-4) << "3D eta " << eta << " theta_i " << ti;
      EXPECT_NEAR(s2.R, F, 2e-4) << "flatland eta " << eta << " theta_i " << ti;
      EXPECT_NEAR(s2.T, 1 - F, 2e-4) << "flatland eta " << eta << " theta_i " << ti;
      EXPECT_NEAR(s3.R + s3.T, 1.0, 1e-8) << "3D energy, eta " << eta << " theta_i " << ti;
      if (F < 0.9) {
        for (double scale : {1.0 / (eta * eta), eta * eta})
          EXPECT_GT(
              std::abs(shares3(i, NdfKind::beckmann, a, eta, MaskingKind::smith_height_correlated, scale).T - (1 - F)),
              0.1)
              << "broken 3D form passed: scale " << scale;
        for (double scale : {1.0 / eta, eta})
          EXPECT_GT(
              std::abs(shares2(deg(ti), NdfKind::beckmann, a, eta, MaskingKind::smith_height_correlated, scale).T -
                       (1 - F)),
              0.1)
              << "broken flatland form passed: scale " << scale;
      }
    }
}

// Light inside the denser medium (eta = 1 / 1.5, critical angle 41.8 deg) beyond the critical angle:
// every facet near n reflects all (F = 1), f_t is exactly 0 there and finite everywhere, and the
// smooth limit reflects everything.
TEST(Walter, TotalInternalReflection) {
  const double eta = 1.0 / 1.5;
  for (double ti : {50.0, 60.0, 80.0}) {
    const Dir3 i = dir3(deg(ti), 0.0);
    for (double tt = -89.0; tt <= 89.0; tt += 1.0) {
      const Dir3 o = neg(dir3(deg(std::abs(tt)), tt < 0 ? kPi : 0.0));
      const double f = walter_btdf(i, o, NdfKind::ggx, 0.01, eta, MaskingKind::smith_separable);
      ASSERT_TRUE(std::isfinite(f) && f >= 0.0) << ti << " " << tt;
      const Dir3 h = walter_half_vector(i, o, eta);
      if (std::abs(std::acos(std::min(1.0, h.z))) < deg(5.0)) {
        EXPECT_EQ(f, 0.0) << ti << " " << tt;  // i.h = cos(<= 5 deg off ti) > critical: TIR
      }
      ASSERT_TRUE(std::isfinite(walter_btdf2(deg(ti), deg(tt), NdfKind::ggx, 0.01, eta, MaskingKind::vcavity)));
    }
    const Shares s = shares3(i, NdfKind::beckmann, 0.01, eta, MaskingKind::smith_height_correlated);
    EXPECT_NEAR(s.R, 1.0, 1e-3) << ti;
    EXPECT_LT(s.T, 1e-12) << ti;
    const Shares s2 = shares2(deg(ti), NdfKind::beckmann, 0.01, eta, MaskingKind::smith_height_correlated);
    EXPECT_NEAR(s2.R, 1.0, 1e-3) << ti;
    EXPECT_LT(s2.T, 1e-12) << ti;
  }
}

// Grazing light and exits (89.9 deg), alpha 0.01..2, both sides, every NDF with a Lambda and every
// masking: finite and non-negative.
TEST(Walter, GrazingIsFinite) {
  int positive = 0;
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double a : {0.01, 0.1, 0.5, 1.0, 2.0})
      for (double eta : {1.5, 1.0 / 1.5, 2.4, 1.0})
        for (MaskingKind g : kAll)
          for (double ti : {-89.9, 0.0, 45.0, 89.9})
            for (double to : {-89.9, -45.0, -ti, 0.0, 30.0, 89.9}) {
              const double v[4] = {
                  walter_brdf2(deg(ti), deg(to), ndf, a, eta, g), walter_btdf2(deg(ti), deg(to), ndf, a, eta, g),
                  walter_brdf(dir3(deg(std::abs(ti)), ti < 0 ? kPi : 0), dir3(deg(std::abs(to)), 1.0), ndf, a, eta, g),
                  walter_btdf(dir3(deg(std::abs(ti)), ti < 0 ? kPi : 0), neg(dir3(deg(std::abs(to)), 1.0)), ndf, a, eta,
                              g)};
              for (double x : v) {
                ASSERT_TRUE(std::isfinite(x) && x >= 0.0) << ndf_name(ndf) << " a " << a << " eta " << eta << " "
                                                          << masking_name(g) << " ti " << ti << " to " << to;
                positive += x > 0.0;
              }
            }
  EXPECT_GT(positive, 1000);
}

// The article's Eq. 21d as printed (v the view/exit direction, l the light, m from Eq. 15b):
//   f_t(v, l) = (n_l^2 / n_v^2) (v.m)(l.m) / ((n_v / n_l) v + l)^2 (1 - F) G D / ((v.n)(l.n)),
// written out here from vectors, with Smith G1 G1 and GGX. Against the article's own Eq. 4c it fails
// reciprocity (f(v, l) / f(l, v) must be n_v^2 / n_l^2); with the prefactor n_v^2 / n_l^2 instead it
// is Walter's Eq. 21 with i = l (the light), which is what analytic/walter.h evaluates. ERRATA W1.
TEST(Walter, ArticleEq21dBreaksReciprocity) {
  const double a = 0.4;
  auto eq21d = [&](const Dir3& v, double nv, const Dir3& l, double nl, bool fixed) {
    Dir3 w{nv / nl * v.x + l.x, nv / nl * v.y + l.y, nv / nl * v.z + l.z};  // Eq. 15b, up to sign
    const double len = std::sqrt(dot(w, w));
    const double sg = (nv / nl + dot(v, l)) > 0 ? 1.0 : -1.0;
    const Dir3 m{sg * w.x / len, sg * w.y / len, sg * w.z / len};
    const double vm = dot(v, m), lm = dot(l, m);
    const double F = optics::fresnel_dielectric(std::abs(vm), nl / nv);
    const double G = G1_smith_ggx(std::acos(std::abs(v.z)), a) * G1_smith_ggx(std::acos(std::abs(l.z)), a);
    const double D = D_ggx(std::acos(std::abs(m.z)), a);
    const double pre = fixed ? nv * nv / (nl * nl) : nl * nl / (nv * nv);
    return pre * std::abs(vm * lm) / (len * len) * (1 - F) * G * D / std::abs(v.z * l.z);
  };
  const double eta = 1.5;
  for (double tl : {10.0, 40.0})
    for (double tv : {5.0, 30.0}) {
      const Dir3 l = dir3(deg(tl), 0.0);             // light above, n_l = 1
      const Dir3 v = neg(dir3(deg(tv), deg(10.0)));  // exit below, n_v = eta, near Snell's side
      const double walter = walter_btdf(l, v, NdfKind::ggx, a, eta, MaskingKind::smith_separable);
      ASSERT_GT(walter, 0.0);
      EXPECT_NEAR(eq21d(v, eta, l, 1.0, true), walter, 1e-12 * walter) << tl << " " << tv;
      // As printed: off by (n_l / n_v)^4, and f(v, l) / f(l, v) = (n_l / n_v)^6, not (n_v / n_l)^2.
      EXPECT_NEAR(eq21d(v, eta, l, 1.0, false), walter / std::pow(eta, 4), 1e-12 * walter);
      const double ratio = eq21d(v, eta, l, 1.0, false) / eq21d(l, 1.0, v, eta, false);
      EXPECT_NEAR(ratio, std::pow(1.0 / eta, 6), 1e-12) << "printed";
      const double ratio_fixed = eq21d(v, eta, l, 1.0, true) / eq21d(l, 1.0, v, eta, true);
      EXPECT_NEAR(ratio_fixed, eta * eta, 1e-12) << "fixed";
    }
}

}  // namespace
}  // namespace vgroove::analytic
