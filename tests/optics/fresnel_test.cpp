// Tests of optics/fresnel.h. Every expected value is derived by hand from the Fresnel equations
// at chosen points (derivations in the comments) or is an identity of those equations; the
// indices below are chosen values, not measured metals. Published constants (Johnson & Christy
// 1972, Rakic 1995) are checked in metals_reference_test.cpp against data/reference/metals.json.
#include "vgroove/optics/fresnel.h"
#include "vgroove/common/angles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace vgroove::optics {
namespace {

const std::vector<double> kEtas = {0.05, 0.2, 0.5, 0.9, 1.2, 1.5, 2.4, 4.0, 10.0};
const std::vector<double> kKappas = {0.0, 0.01, 0.5, 1.0, 3.0, 10.0};

std::vector<double> cos_grid() {  // 0 (grazing) to 1 (normal), denser near grazing
  std::vector<double> v;
  for (int a = 0; a <= 900; ++a) v.push_back(std::cos(a * 0.1 * kRadPerDeg));
  v.push_back(0.0);
  v.push_back(1e-9);
  return v;
}

TEST(Fresnel, NormalIncidenceIsTheClosedForm) {
  // At cos = 1: w = n, r_s = (1 - n)/(1 + n), r_p = (n^2 - n)/(n^2 + n) = (n - 1)/(n + 1), so
  // R_s = R_p = |n - 1|^2 / |n + 1|^2 = ((eta - 1)^2 + kappa^2) / ((eta + 1)^2 + kappa^2).
  for (double eta : kEtas)
    for (double kappa : kKappas) {
      const double expected = ((eta - 1) * (eta - 1) + kappa * kappa) / ((eta + 1) * (eta + 1) + kappa * kappa);
      const PolarizedReflectance r = fresnel_conductor_polarized(1.0, eta, kappa);
      EXPECT_NEAR(r.s, expected, 1e-15) << "eta=" << eta << " kappa=" << kappa;
      EXPECT_NEAR(r.p, expected, 1e-15) << "eta=" << eta << " kappa=" << kappa;
      EXPECT_NEAR(fresnel_conductor(1.0, eta, kappa), expected, 1e-15) << "eta=" << eta << " kappa=" << kappa;
      EXPECT_NEAR(fresnel_normal_incidence(eta, kappa), expected, 1e-15) << "eta=" << eta << " kappa=" << kappa;
      if (kappa == 0.0) {
        EXPECT_NEAR(fresnel_dielectric(1.0, eta), expected, 1e-15) << "eta=" << eta;
      }
    }
  // Two hand values: eta = 1.5 gives (0.5/2.5)^2 = 0.04; eta = kappa = 1 gives 1/5.
  EXPECT_NEAR(fresnel_dielectric(1.0, 1.5), 0.04, 1e-17);
  EXPECT_NEAR(fresnel_conductor(1.0, 1.0, 1.0), 0.2, 1e-16);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
  // At cos = 0: r_s = -w/w = -1 and r_p = -w/w = -1 (w != 0 unless n = 1).
  for (double eta : kEtas)
    for (double kappa : kKappas) {
      EXPECT_EQ(fresnel_conductor(0.0, eta, kappa), 1.0) << "eta=" << eta << " kappa=" << kappa;
      // Approaching grazing, F -> 1 continuously.
      EXPECT_NEAR(fresnel_conductor(1e-9, eta, kappa), 1.0, 1e-6) << "eta=" << eta << " kappa=" << kappa;
    }
  for (double eta : kEtas) EXPECT_EQ(fresnel_dielectric(0.0, eta), 1.0) << "eta=" << eta;
  for (double F0 : {0.0, 0.04, 0.5, 0.95}) EXPECT_DOUBLE_EQ(fresnel_schlick(0.0, F0), 1.0) << "F0=" << F0;
}

TEST(Fresnel, IndexMatchedInterfaceReflectsNothing) {
  for (double c : {0.0, 0.3, 1.0}) {
    EXPECT_EQ(fresnel_conductor(c, 1.0, 0.0), 0.0) << "cos=" << c;
    EXPECT_EQ(fresnel_dielectric(c, 1.0), 0.0) << "cos=" << c;
  }
}

TEST(Fresnel, ConductorWithoutAbsorptionIsTheDielectric) {
  // kappa = 0: w = sqrt(eta^2 - sin^2) = eta cos theta_t (or i|w| under total internal
  // reflection), and r_s, r_p reduce to the real dielectric amplitudes.
  for (double eta : kEtas)
    for (double c : cos_grid()) {
      const PolarizedReflectance a = fresnel_conductor_polarized(c, eta, 0.0);
      const PolarizedReflectance b = fresnel_dielectric_polarized(c, eta);
      EXPECT_NEAR(a.s, b.s, 1e-14) << "eta=" << eta << " cos=" << c;
      EXPECT_NEAR(a.p, b.p, 1e-14) << "eta=" << eta << " cos=" << c;
    }
}

TEST(Fresnel, TotalInternalReflectionBeyondTheCriticalAngle) {
  // From the denser side (eta < 1) every angle with sin theta_i >= eta reflects everything, in
  // both polarizations and through both code paths.
  for (double eta : {0.2, 1 / 1.5, 0.9}) {
    const double cos_critical = std::sqrt(1 - eta * eta);
    for (double f : {0.0, 0.3, 0.9, 0.999}) {
      const double c = f * cos_critical;
      EXPECT_EQ(fresnel_dielectric(c, eta), 1.0) << "eta=" << eta << " cos=" << c;
      const PolarizedReflectance r = fresnel_conductor_polarized(c, eta, 0.0);
      EXPECT_NEAR(r.s, 1.0, 1e-15) << "eta=" << eta << " cos=" << c;
      EXPECT_NEAR(r.p, 1.0, 1e-15) << "eta=" << eta << " cos=" << c;
    }
    EXPECT_LT(fresnel_dielectric(1.001 * cos_critical, eta), 1.0) << "eta=" << eta;
  }
}

TEST(Fresnel, BrewsterAngleZeroesThePPolarization) {
  // tan theta_B = eta: then sin theta_t = cos theta_B, so eta cos theta_B = cos theta_t and the
  // numerator of r_p vanishes. cos theta_B = 1 / sqrt(1 + eta^2). Holds from either side.
  for (double eta : {1.2, 1.5, 2.4, 4.0, 1 / 1.5, 0.5}) {
    const double cos_b = 1.0 / std::sqrt(1.0 + eta * eta);
    const PolarizedReflectance r = fresnel_dielectric_polarized(cos_b, eta);
    EXPECT_LT(r.p, 1e-30) << "eta=" << eta;  // r_p ~ 1e-16 at most: a rounding, squared
    EXPECT_GT(r.s, 1e-3) << "eta=" << eta;   // s light is still reflected there
    EXPECT_LT(fresnel_conductor_polarized(cos_b, eta, 0.0).p, 1e-30) << "eta=" << eta;
    // A minimum: R_p grows on both sides of it.
    for (double da : {-1.0, 1.0}) {
      const double c = std::cos(std::acos(cos_b) + da * kRadPerDeg);
      EXPECT_GT(fresnel_dielectric_polarized(c, eta).p, 1e-6) << "eta=" << eta << " da=" << da;
    }
  }
  // An absorbing medium has no angle of zero p reflectance: R_p stays positive on the grid.
  for (double c : cos_grid()) EXPECT_GT(fresnel_conductor_polarized(c, 1.5, 0.5).p, 1e-3) << "cos=" << c;
}

TEST(Fresnel, ReflectanceIsTheSameFromBothSidesOfAnInterface) {
  // Stokes relations: a ray refracted from angle theta_i (index ratio eta) to theta_t meets the
  // same interface from the other side at theta_t with ratio 1/eta, and both sides reflect the
  // same fraction, polarization by polarization.
  for (double eta : {1.2, 1.5, 2.4, 4.0})
    for (double a = 0.0; a < 89.95; a += 0.5) {
      const double ci = std::cos(a * kRadPerDeg);
      const double sin_t = std::sin(a * kRadPerDeg) / eta;
      const double ct = std::sqrt(1 - sin_t * sin_t);
      const PolarizedReflectance in = fresnel_dielectric_polarized(ci, eta);
      const PolarizedReflectance out = fresnel_dielectric_polarized(ct, 1 / eta);
      // The inside evaluation recomputes cos^2 theta_i = 1 - eta^2 (1 - cos^2 theta_t): an absolute
      // rounding of a few eta^2 x 1e-16, i.e. a relative one of eta^2 x 1e-16 / cos^2 theta_i, and
      // F is Lipschitz in cos^2 theta_i there (from the outside, no critical angle). Hence a
      // tolerance growing towards grazing (observed: 1.3e-14 at 86.5 deg, 8e-13 at 89.5 deg).
      const double tol = 1e-15 + 1e-15 * eta * eta / (ci * ci);
      EXPECT_NEAR(in.s, out.s, tol) << "eta=" << eta << " theta_i=" << a;
      EXPECT_NEAR(in.p, out.p, tol) << "eta=" << eta << " theta_i=" << a;
    }
}

TEST(Fresnel, AtFortyFiveDegreesRpIsRsSquared) {
  // Abeles' relation, for any complex n: at cos = sin = 1/sqrt(2), w^2 = n^2 - 1/2 and
  //   r_s^2 = (c^2 - 2cw + w^2) / (c^2 + 2cw + w^2) = (n^2 - 2cw) / (n^2 + 2cw),
  //   r_p = (n^2 c - w) / (n^2 c + w) = (2c^2 n^2 - 2cw) / (2c^2 n^2 + 2cw) = the same,
  // so r_p = r_s^2 and R_p = R_s^2.
  const double c = std::sqrt(0.5);
  for (double eta : kEtas)
    for (double kappa : kKappas) {
      const PolarizedReflectance r = fresnel_conductor_polarized(c, eta, kappa);
      EXPECT_NEAR(r.p, r.s * r.s, 1e-15) << "eta=" << eta << " kappa=" << kappa;
    }
}

TEST(Fresnel, HandDerivedValuesAtFortyFiveDegrees) {
  const double c = std::sqrt(0.5);
  // Dielectric eta = 1.5: sin^2 theta_t = (1/2) / 2.25 = 2/9, cos theta_t = sqrt(7)/3, so
  // r_s = (1/sqrt2 - sqrt7/2) / (1/sqrt2 + sqrt7/2) = (sqrt2 - sqrt7) / (sqrt2 + sqrt7) and
  // R_s = (9 - 2 sqrt14) / (9 + 2 sqrt14) = 0.0920134...; R_p = R_s^2 (Abeles); F = 0.0502398...
  {
    const double Rs = (9 - 2 * std::sqrt(14.0)) / (9 + 2 * std::sqrt(14.0));
    EXPECT_NEAR(Rs, 0.0920134, 1e-7);  // the radicals, evaluated by hand
    const PolarizedReflectance r = fresnel_dielectric_polarized(c, 1.5);
    EXPECT_NEAR(r.s, Rs, 1e-16);
    EXPECT_NEAR(r.p, Rs * Rs, 1e-16);
    EXPECT_NEAR(fresnel_dielectric(c, 1.5), 0.5 * (Rs + Rs * Rs), 1e-16);
    EXPECT_NEAR(fresnel_conductor(c, 1.5, 0.0), 0.5 * (Rs + Rs * Rs), 1e-16);
  }
  // Conductor n = 1 + i (n^2 = 2i): w^2 = 2i - 1/2, |w^2| = sqrt17 / 2, a = Re w with
  // a^2 = (|w^2| + Re w^2) / 2 = (sqrt17 - 1) / 4. Then
  //   R_s = |c - w|^2 / |c + w|^2 = (|w|^2 + c^2 - 2ac) / (|w|^2 + c^2 + 2ac)
  //       = (sqrt17 + 1 - sqrt(2 (sqrt17 - 1))) / (sqrt17 + 1 + sqrt(2 (sqrt17 - 1)))
  //       = (5.1231056 - 2.4992421) / (5.1231056 + 2.4992421) = 0.344233...,
  // R_p = R_s^2 = 0.118496..., F = 0.231365...
  {
    const double s17 = std::sqrt(17.0), q = std::sqrt(2 * (s17 - 1));
    const double Rs = (s17 + 1 - q) / (s17 + 1 + q);
    EXPECT_NEAR(Rs, 0.344233, 1e-6);
    const PolarizedReflectance r = fresnel_conductor_polarized(c, 1.0, 1.0);
    EXPECT_NEAR(r.s, Rs, 1e-15);
    EXPECT_NEAR(r.p, Rs * Rs, 1e-15);
    EXPECT_NEAR(fresnel_conductor(c, 1.0, 1.0), 0.5 * (Rs + Rs * Rs), 1e-15);
    EXPECT_NEAR(fresnel_conductor(c, 1.0, 1.0), 0.231365, 1e-6);
  }
}

// The same reflectances in real arithmetic, derived independently of the complex code: with
// w = a + ib = sqrt(n^2 - sin^2), a^2 + b^2 = |n^2 - sin^2| and a = sqrt((|.| + Re(.)) / 2), so
//   R_s = |c - w|^2 / |c + w|^2 = (a^2 + b^2 - 2ac + c^2) / (a^2 + b^2 + 2ac + c^2);
// and r_p / r_s simplifies (multiply out (n^2 c - w)(c + w) / ((n^2 c + w)(c - w)), using
// w^2 = n^2 - sin^2) to -(c w - sin^2) / (c w + sin^2), whence
//   R_p = R_s (c^2 (a^2 + b^2) - 2 a c sin^2 + sin^4) / (c^2 (a^2 + b^2) + 2 a c sin^2 + sin^4).
PolarizedReflectance conductor_real_form(double c, double eta, double kappa) {
  const double s2 = 1 - c * c;
  const double re = eta * eta - kappa * kappa - s2, im = 2 * eta * kappa;
  const double m = std::hypot(re, im);  // a^2 + b^2
  // a = sqrt((m + re)/2) cancels when re < 0 (total internal reflection, small eta): then take
  // b = sqrt((m - re)/2) and a = im / (2b), from 2ab = Im(n^2 - sin^2).
  const double a = re >= 0 ? std::sqrt(0.5 * (m + re)) : im / (2 * std::sqrt(0.5 * (m - re)));
  PolarizedReflectance r;
  r.s = (m - 2 * a * c + c * c) / (m + 2 * a * c + c * c);
  r.p = r.s * (c * c * m - 2 * a * c * s2 + s2 * s2) / (c * c * m + 2 * a * c * s2 + s2 * s2);
  return r;
}

TEST(Fresnel, ConductorAgreesWithTheRealArithmeticForm) {
  for (double eta : kEtas)
    for (double kappa : kKappas)
      for (double c : cos_grid()) {
        if (c == 0.0) continue;  // the real form's R_p is 0/0 x 1 there
        // At a critical angle (kappa = 0, sin theta_i = eta; cos 60 deg for eta = 0.5 is on the
        // grid) F has a square-root corner: w = sqrt(rounding), so any two correct evaluations
        // differ by ~1e-8 there. Not a comparison of the formulas.
        if (kappa == 0.0 && std::abs(eta * eta - (1 - c * c)) < 1e-9) continue;
        const PolarizedReflectance a = fresnel_conductor_polarized(c, eta, kappa);
        const PolarizedReflectance b = conductor_real_form(c, eta, kappa);
        EXPECT_NEAR(a.s, b.s, 1e-12 * b.s + 1e-15) << "eta=" << eta << " kappa=" << kappa << " cos=" << c;
        EXPECT_NEAR(a.p, b.p, 1e-12 * b.p + 1e-15) << "eta=" << eta << " kappa=" << kappa << " cos=" << c;
      }
}

TEST(Fresnel, ReflectanceIsAFraction) {
  for (double eta : kEtas)
    for (double kappa : kKappas)
      for (double c : cos_grid()) {
        const PolarizedReflectance r = fresnel_conductor_polarized(c, eta, kappa);
        EXPECT_GE(r.s, 0.0);
        EXPECT_LE(r.s, 1.0 + 1e-15) << "eta=" << eta << " kappa=" << kappa << " cos=" << c;
        EXPECT_GE(r.p, 0.0);
        EXPECT_LE(r.p, 1.0 + 1e-15) << "eta=" << eta << " kappa=" << kappa << " cos=" << c;
      }
  // |d . n| of unit vectors may exceed 1 by a rounding: clamped, not a NaN.
  EXPECT_EQ(fresnel_conductor(1.0 + 1e-16, 1.5, 2.0), fresnel_conductor(1.0, 1.5, 2.0));
  EXPECT_EQ(fresnel_dielectric(1.0 + 2e-16, 1.5), fresnel_dielectric(1.0, 1.5));
  EXPECT_EQ(fresnel_dielectric(-1e-17, 1.5), 1.0);
}

// The accepted extremes of a scene's conductor (eta in (0, 1000], kappa in [0, 1000]): every
// reflectance finite and a fraction. At eta = 1e-300 the squares of the tiny moduli underflow
// (0/0 gave NaN at normal incidence); the limit n -> 0 is the perfect conductor,
// |(n - 1)/(n + 1)|^2 -> 1, at normal incidence and, for kappa = 0, at every angle.
TEST(Fresnel, ExtremeIndicesGiveFiniteFractions) {
  for (double eta : {1e-300, 1e-200, 1e-160, 1e-12, 1e-3, 1000.0})
    for (double kappa : {0.0, 1e-300, 1e-160, 1e-3, 1000.0})
      for (double c : {0.0, 1e-300, 1e-9, 0.5, 1.0 - 1e-16, 1.0}) {
        const PolarizedReflectance r = fresnel_conductor_polarized(c, eta, kappa);
        EXPECT_TRUE(std::isfinite(r.s) && std::isfinite(r.p)) << "eta=" << eta << " kappa=" << kappa << " cos=" << c;
        EXPECT_GE(r.s, 0.0);
        EXPECT_LE(r.s, 1.0 + 1e-15) << "eta=" << eta << " kappa=" << kappa << " cos=" << c;
        EXPECT_GE(r.p, 0.0);
        EXPECT_LE(r.p, 1.0 + 1e-15) << "eta=" << eta << " kappa=" << kappa << " cos=" << c;
      }
  for (double c : {0.0, 0.3, 1.0}) EXPECT_NEAR(fresnel_conductor(c, 1e-300, 0.0), 1.0, 1e-15) << "cos=" << c;
  EXPECT_NEAR(fresnel_conductor(1.0, 1e-3, 0.0), fresnel_normal_incidence(1e-3, 0.0), 1e-15);
}

TEST(Fresnel, SchlickIsExactAtNormalIncidence) {
  for (double eta : kEtas)
    for (double kappa : kKappas) {
      const double F0 = fresnel_normal_incidence(eta, kappa);
      EXPECT_NEAR(fresnel_schlick(1.0, F0), fresnel_conductor(1.0, eta, kappa), 1e-15)
          << "eta=" << eta << " kappa=" << kappa;
    }
}

TEST(Fresnel, SchlickErrorForGlass) {
  // Schlick against the exact reflectance for eta = 1.5 (F0 = 0.04), on 10^5 + 1 cosines. The
  // bound is the measured maximum, not a guess: evaluating both (here and, independently, in
  // Python on 10^6 points) gives max |Schlick - exact| = 0.035693 near theta_i = 85.0 deg
  // (Schlick too low), so the assertion brackets it. Relative to the exact value the error is
  // larger, up to 23% near theta_i = 55.5 deg where F itself is only ~0.05.
  const double F0 = fresnel_normal_incidence(1.5);
  double max_abs = 0.0, at = 0.0, max_rel = 0.0;
  for (int i = 0; i <= 100000; ++i) {
    const double c = i / 100000.0;
    const double exact = fresnel_dielectric(c, 1.5), approx = fresnel_schlick(c, F0);
    if (std::abs(approx - exact) > max_abs) max_abs = std::abs(approx - exact), at = c;
    max_rel = std::max(max_rel, std::abs(approx - exact) / exact);
  }
  EXPECT_GT(max_abs, 0.0356);
  EXPECT_LT(max_abs, 0.0358);
  EXPECT_NEAR(std::acos(at) / kRadPerDeg, 85.0, 0.1);
  EXPECT_GT(max_rel, 0.23);
  EXPECT_LT(max_rel, 0.235);
}

}  // namespace
}  // namespace vgroove::optics
