// Tests of analytic/brdf_nonsymmetric.h (Lee et al. 2018, Eq. 21-25): the widths of Eq. (9) it
// integrates, the Jacobian printed after Eq. (23) against the exact groove map, the symmetric
// limit (Eq. 24: P = delta reproduces Eq. 16), k = 1 (Eq. 25: Cook-Torrance with the single-
// reflection share of Eq. 9 averaged over the partner), reciprocity, and the hard cases.
#include "vgroove/analytic/brdf_nonsymmetric.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/analytic/partner_distribution.h"

#include "vgroove/analytic/quadrature.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace va = vgroove::analytic;

namespace {

constexpr double kPi = std::numbers::pi;

va::Dir3 random_dir(std::mt19937_64& g) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  return va::dir3(std::acos(U(g)), 2.0 * kPi * U(g));
}

double rel(double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300}); }

va::NonsymmetricModel model(va::NdfKind ndf, double alpha, va::PartnerLaw law = va::PartnerLaw::independent) {
  va::NonsymmetricModel m;
  m.roughness = va::isotropic_roughness(ndf, alpha);
  m.partner = law;
  return m;
}

// The exact groove map, from the model's definition: the groove whose left facet (tilt A) leans
// towards a = (cos phi_a, sin phi_a, 0) and whose right facet has the tilt B, light i, left facet
// first, n reflections -> o.
va::Dir3 groove_exit(const va::Dir3& i, double A, double B, double phi_a, int n) {
  const double ax = std::cos(phi_a), ay = std::sin(phi_a);
  const double ia = i.x * ax + i.y * ay, iu = -i.x * ay + i.y * ax;
  const double t_i = std::atan2(-ia, i.z), c = std::sqrt(1.0 - iu * iu);
  const double t_o = va::exit_angle_nonsymmetric(t_i, -A, B, n);
  const double ex = -std::sin(t_o), ey = std::cos(t_o);
  return {c * ex * ax + iu * ay, c * ex * ay - iu * ax, c * ey};
}

TEST(NonsymmetricBrdf, CountWidthsAreEq9) {
  std::mt19937_64 g(3);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int n = 0; n < 2000; ++n) {
    const double tl = -0.5 * kPi * U(g), tr = 0.5 * kPi * U(g), ti = (U(g) - 0.5) * kPi;
    if (!(va::aperture(tl, tr) > 1e-3)) continue;
    const va::NonsymmetricPrediction p = va::G_nonsymmetric(ti, tl, tr, va::FacetSide::left);
    for (int k = 1; k <= 8; ++k) {
      double expect = 0.0;
      if (p.lit)
        for (const auto& s : p.share)
          if (s.n == k) expect += s.G * p.f_a;
      const va::CountWidth w = va::count_width(ti, tl, tr, k);
      EXPECT_NEAR(w.width, expect, 1e-14) << "ti=" << ti << " tl=" << tl << " tr=" << tr << " k=" << k;
      EXPECT_EQ(w.f_a, p.lit ? p.f_a : 0.0) << "ti=" << ti << " tl=" << tl << " tr=" << tr;
      if (p.lit) {
        EXPECT_EQ(w.f_b, p.f_b) << "ti=" << ti << " tl=" << tl << " tr=" << tr;
      }
    }
  }
}

// The Jacobian printed after Eq. (23): at fixed B the map (A, phi_a) -> o sweeps the solid angle
// d omega = 4 (i.h) sin(theta_h) |d t_h / d theta_l| dA d phi_a, |d t_h / d theta_l| =
// 0.5 |0.5 - (-1)^k (k + 0.5)|. Checked by central differences of the exact map.
TEST(NonsymmetricBrdf, Eq23JacobianMatchesTheExactGrooveMap) {
  std::mt19937_64 g(5);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int checked = 0;
  for (int n = 0; n < 400; ++n) {
    const va::Dir3 i = random_dir(g);
    const double A = 0.1 + 1.3 * U(g), B = 0.1 + 1.3 * U(g), phi = 2.0 * kPi * U(g);
    const int k = 1 + static_cast<int>(6 * U(g));
    const va::Dir3 o = groove_exit(i, A, B, phi, k);
    if (!(o.z > 0.05)) continue;
    const double h = 1e-6;
    auto d = [&](double dA, double dphi) { return groove_exit(i, A + dA, B, phi + dphi, k); };
    const va::Dir3 pa = d(h, 0), ma = d(-h, 0), pp = d(0, h), mp = d(0, -h);
    const double ax[3] = {(pa.x - ma.x) / (2 * h), (pa.y - ma.y) / (2 * h), (pa.z - ma.z) / (2 * h)};
    const double ap[3] = {(pp.x - mp.x) / (2 * h), (pp.y - mp.y) / (2 * h), (pp.z - mp.z) / (2 * h)};
    const double cx = ax[1] * ap[2] - ax[2] * ap[1], cy = ax[2] * ap[0] - ax[0] * ap[2],
                 cz = ax[0] * ap[1] - ax[1] * ap[0];
    const double swept = std::sqrt(cx * cx + cy * cy + cz * cz);
    va::Dir3 hv{i.x + o.x, i.y + o.y, i.z + o.z};
    const double len = std::sqrt(hv.x * hv.x + hv.y * hv.y + hv.z * hv.z);
    hv = {hv.x / len, hv.y / len, hv.z / len};
    const double cos_d = i.x * hv.x + i.y * hv.y + i.z * hv.z, sin_h = std::hypot(hv.x, hv.y);
    if (!(sin_h > 0.05)) continue;
    const double printed = 4.0 * cos_d * sin_h * std::abs(va::dtheta_h_dtheta_l(k));
    EXPECT_NEAR(swept / printed, 1.0, 1e-6) << "A=" << A << " B=" << B << " phi=" << phi << " k=" << k;
    ++checked;
  }
  EXPECT_GT(checked, 150);
}

// Eq. (24): with P = delta(B - A), Eq. (23) is Eq. (16) (3D) and its flatland analogue.
TEST(NonsymmetricBrdf, SymmetricLimitIsEq16) {
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (va::NdfKind ndf : {va::NdfKind::ggx, va::NdfKind::beckmann, va::NdfKind::phong}) {
    const va::NonsymmetricModel m = model(ndf, 0.6, va::PartnerLaw::symmetric);
    double worst = 0.0, worst_flat = 0.0;
    for (int n = 0; n < 400; ++n) {
      const va::Dir3 i = random_dir(g), o = random_dir(g);
      const double ti = (U(g) - 0.5) * 3.1, to = (U(g) - 0.5) * 3.1;
      for (int k = 1; k <= 6; ++k) {
        const double a = va::nonsymmetric_brdf_k(i, o, k, m), b = va::vgroove_brdf_k(i, o, k, ndf, 0.6);
        EXPECT_NEAR(a, b, 1e-10 * b + 1e-300) << va::ndf_name(ndf) << " n=" << n << " k=" << k;
        worst = std::max(worst, rel(a, b));
        const double c = va::flatland_nonsymmetric_brdf_k(ti, to, k, m), e = va::flatland_brdf_k(ndf, 0.6, ti, to, k);
        EXPECT_NEAR(c, e, 1e-10 * e + 1e-300) << va::ndf_name(ndf) << " flatland n=" << n << " k=" << k;
        worst_flat = std::max(worst_flat, rel(c, e));
      }
    }
    RecordProperty(std::string("worst_relative_") + va::ndf_name(ndf), std::to_string(worst));
  }
}

// A partner law narrowing onto B = A (uniform on [A - w, A + w]) tends to the symmetric model,
// integrated numerically this time: within O(w) of Eq. (16).
TEST(NonsymmetricBrdf, NarrowPartnerLawsTendToTheSymmetricModel) {
  std::mt19937_64 g(13);
  int compared = 0;
  for (int n = 0; n < 40; ++n) {
    const va::Dir3 i = random_dir(g), o = random_dir(g);
    for (int k = 1; k <= 4; ++k) {
      const double sym = va::vgroove_brdf_k(i, o, k, va::NdfKind::ggx, 0.5);
      if (!(sym > 1e-6)) continue;
      va::NonsymmetricModel m = model(va::NdfKind::ggx, 0.5);
      m.near_symmetric_halfwidth = 1e-4;
      const double narrow = va::nonsymmetric_brdf_k(i, o, k, m);
      m.near_symmetric_halfwidth = 1e-3;
      const double wider = va::nonsymmetric_brdf_k(i, o, k, m);
      // The difference shrinks with w (linearly near the edges of the support, quadratically inside).
      EXPECT_LE(std::abs(narrow - sym), std::max(2e-3 * sym, 0.2 * std::abs(wider - sym) + 1e-12))
          << "n=" << n << " k=" << k << " sym " << sym << " w=1e-4 " << narrow << " w=1e-3 " << wider;
      ++compared;
    }
  }
  EXPECT_GT(compared, 20);
}

// Eq. (25). With the independent partner, k = 1 is Cook-Torrance whose G is the single-reflection
// share of Eq. (9) averaged over P (the facet hit first is s = h at the projected angle t_i); with
// B = A it is Cook-Torrance with the V-cavity G.
TEST(NonsymmetricBrdf, SingleReflectionIsCookTorrance) {
  std::mt19937_64 g(17);
  for (va::NdfKind ndf : {va::NdfKind::ggx, va::NdfKind::beckmann}) {
    for (int n = 0; n < 40; ++n) {
      const va::Dir3 i = random_dir(g), o = random_dir(g);
      const double ct = va::cook_torrance(i, o, ndf, 0.7);
      EXPECT_NEAR(va::nonsymmetric_brdf_k(i, o, 1, model(ndf, 0.7, va::PartnerLaw::symmetric)), ct, 1e-10 * ct);
      // The cross-section through h and the 2D angles.
      va::Dir3 h{i.x + o.x, i.y + o.y, i.z + o.z};
      const double len = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
      h = {h.x / len, h.y / len, h.z / len};
      const double rho = std::hypot(h.x, h.y), ax = h.x / rho, ay = h.y / rho;
      const double t_i = std::atan2(-(i.x * ax + i.y * ay), i.z), theta_h = std::atan2(rho, h.z);
      // Split adaptively: the share has kinks in B (where the partner's rim starts to shadow).
      const double G1 = va::integrate_adaptive_parts(
          [&](double B) {
            const va::NonsymmetricPrediction p = va::G_nonsymmetric(t_i, -theta_h, B, va::FacetSide::left);
            double s = 0.0;
            for (const auto& z : p.share)
              if (z.n == 1) s += z.G;
            return va::P_theta_r(ndf, B, 0.7) * s;
          },
          0.0, 0.5 * kPi, 1e-12, 0.0, 16, 2000);
      const double expect = va::D(ndf, theta_h, 0.7) * G1 / (4.0 * i.z * o.z);
      EXPECT_NEAR(va::vgroove_nonsymmetric_brdf_k(i, o, 1, ndf, 0.7), expect, 1e-7 * expect + 1e-14)
          << va::ndf_name(ndf) << " n=" << n;
    }
  }
}

// Fresnel: a constant reflectance R scales the k-bounce term by R^k (every path makes k
// reflections); Schlick's is applied per bounce at the 3D cosine and stays within [R0^k, 1] x F = 1.
TEST(NonsymmetricBrdf, FresnelIsAppliedPerReflection) {
  std::mt19937_64 g(23);
  const va::FresnelFn constant = [](double) { return 0.8; };
  const va::FresnelFn schlick = [](double c) { return 0.5 + 0.5 * std::pow(1.0 - c, 5.0); };
  int nonzero = 0;
  for (int n = 0; n < 30; ++n) {
    const va::Dir3 i = random_dir(g), o = random_dir(g);
    for (int k = 1; k <= 4; ++k) {
      const double one = va::vgroove_nonsymmetric_brdf_k(i, o, k, va::NdfKind::ggx, 0.6);
      const double f = va::vgroove_nonsymmetric_brdf_k(i, o, k, va::NdfKind::ggx, 0.6, constant);
      EXPECT_NEAR(f, std::pow(0.8, k) * one, 1e-7 * one + 1e-300) << "n=" << n << " k=" << k;
      const double s = va::vgroove_nonsymmetric_brdf_k(i, o, k, va::NdfKind::ggx, 0.6, schlick);
      EXPECT_GE(s, std::pow(0.5, k) * one * (1.0 - 1e-7));
      EXPECT_LE(s, one * (1.0 + 1e-7));
      nonzero += one > 0.0;
    }
  }
  EXPECT_GT(nonzero, 40);
}

// Reciprocity, pointwise on random pairs, per k, 3D and flatland (the value is reported).
TEST(NonsymmetricBrdf, ReciprocalPerK) {
  std::mt19937_64 g(19);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  double worst = 0.0, worst_flat = 0.0;
  for (va::NdfKind ndf : {va::NdfKind::ggx, va::NdfKind::beckmann, va::NdfKind::phong}) {
    va::NonsymmetricModel m = model(ndf, 0.6);
    m.tolerance = 1e-10;
    for (int n = 0; n < 25; ++n) {
      const va::Dir3 i = random_dir(g), o = random_dir(g);
      const double ti = (U(g) - 0.5) * 3.0, to = (U(g) - 0.5) * 3.0;
      for (int k = 1; k <= 4; ++k) {
        const double a = va::nonsymmetric_brdf_k(i, o, k, m), b = va::nonsymmetric_brdf_k(o, i, k, m);
        if (a > 1e-200 || b > 1e-200) worst = std::max(worst, rel(a, b));
        const double c = va::flatland_nonsymmetric_brdf_k(ti, to, k, m),
                     d = va::flatland_nonsymmetric_brdf_k(to, ti, k, m);
        if (c > 1e-200 || d > 1e-200) worst_flat = std::max(worst_flat, rel(c, d));
      }
    }
  }
  RecordProperty("worst_relative_asymmetry_3d", std::to_string(worst));
  RecordProperty("worst_relative_asymmetry_flatland", std::to_string(worst_flat));
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_flat, 1e-9);
}

// Hard cases: alpha 0.01 to 2, grazing light, the mirror direction, h along n: finite and
// non-negative (or +inf at h = n exactly for k >= 2, the documented limit).
TEST(NonsymmetricBrdf, HardCasesAreFiniteOrTheDocumentedLimit) {
  for (va::NdfKind ndf : {va::NdfKind::ggx, va::NdfKind::beckmann}) {
    for (double alpha : {0.01, 0.1, 1.0, 2.0}) {
      for (double theta_i_deg : {0.0, 45.0, 89.9}) {
        const double ti = theta_i_deg * kPi / 180.0;
        const va::Dir3 i = va::dir3(ti, kPi);
        for (double to_deg : {0.0, 30.0, 89.9}) {
          for (double phi : {0.0, 1.0, kPi}) {
            // h = n exactly (o the mirror direction of i at the normal) is the limit checked below.
            if (theta_i_deg == 0.0 && to_deg == 0.0) continue;
            const va::Dir3 o = va::dir3(to_deg * kPi / 180.0, phi);
            const double v = va::vgroove_nonsymmetric_brdf(i, o, ndf, alpha, 6);
            EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << va::ndf_name(ndf) << " alpha=" << alpha << " " << v;
          }
        }
        // The mirror direction (h = n exactly when i is at the normal).
        const va::Dir3 mirror = va::dir3(ti, 0.0);
        const double v1 = va::vgroove_nonsymmetric_brdf_k(i, mirror, 1, ndf, alpha);
        EXPECT_TRUE(std::isfinite(v1) && v1 >= 0.0) << va::ndf_name(ndf) << " alpha=" << alpha;
        const double v2 = va::vgroove_nonsymmetric_brdf_k(i, mirror, 2, ndf, alpha);
        EXPECT_TRUE(v2 >= 0.0 && !std::isnan(v2)) << va::ndf_name(ndf) << " alpha=" << alpha;
        // Flatland: theta_o at the mirror and grazing.
        const va::NonsymmetricModel m = model(ndf, alpha);
        for (double to : {-ti, 0.0, 1.5706}) {
          const double f = va::flatland_nonsymmetric_brdf(ti, to, 6, m);
          EXPECT_TRUE(std::isfinite(f) && f >= 0.0) << va::ndf_name(ndf) << " alpha=" << alpha << " to=" << to;
        }
      }
    }
  }
  // Anisotropic, alpha_x / alpha_y = 100, along, across and between the axes.
  va::NonsymmetricModel an;
  an.roughness = va::Roughness{va::NdfKind::ggx, 0.01, 1.0};
  for (double phi : {0.0, 0.3, 0.5 * kPi})
    for (double to_deg : {10.0, 60.0, 89.9}) {
      const double v = va::nonsymmetric_brdf(va::dir3(0.7, kPi), va::dir3(to_deg * kPi / 180.0, phi), 6, an);
      EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << "phi=" << phi << " " << v;
    }
  // Below the horizon: 0.
  EXPECT_EQ(va::vgroove_nonsymmetric_brdf_k(va::dir3(0.3, 0.0), va::dir3(1.7, 1.0), 2, va::NdfKind::ggx, 0.5), 0.0);
  // Phong beyond its partner law's range is refused.
  EXPECT_THROW(va::vgroove_nonsymmetric_brdf_k(va::dir3(0.3, kPi), va::dir3(0.4, 0.5), 2, va::NdfKind::phong, 2.0),
               std::domain_error);
}

}  // namespace
