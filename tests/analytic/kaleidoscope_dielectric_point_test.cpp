// Tests of analytic/kaleidoscope_dielectric_point.h: the kaleidoscopic dielectric model's BSDF at a point.
// Against the model's own binned lobe (kaleidoscope_dielectric_lobe.h, a separate code path: cuts and
// Gauss-Legendre over the groove slope) by integrating the point BSDF over each bin (flatland: adaptive
// Gauss-Legendre that also refines every support edge, since the transmitted lobes' folds are 1/sqrt
// singularities at an edge; 3D: composite Gauss-Legendre, its error stated as 3 x the change when the
// panels double); F = 1 against the conductor BRDFs (brdf_flatland.h, brdf_3d.h: Eq. 16, an independent
// derivation); reciprocity of reflection; finiteness at hard points; broken Jacobians must fail; the
// sampler's draws against the pdf by chi-square.
#include "vgroove/analytic/kaleidoscope_dielectric_point.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/sampling_dielectric.h"
#include "vgroove/validation/chi_square.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove::analytic {
namespace {

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

struct Case {
  NdfKind ndf;
  double alpha, eta, theta_i_deg;
  DielectricLightFrom from = DielectricLightFrom::above;
};

std::string describe(const Case& c) {
  std::ostringstream os;
  os << ndf_name(c.ndf) << " alpha=" << c.alpha << " eta=" << c.eta << " theta_i=" << c.theta_i_deg
     << (c.from == DielectricLightFrom::below ? " from below" : " from above");
  return os.str();
}

// ---- Flatland -----------------------------------------------------------------------------------

constexpr int kFlatBins = 30, kFlatMaxK = 3;

// int over [a, b] of f cos (per row k) by adaptive Gauss-Legendre (8 nodes): a panel is accepted when
// its halves change no row by more than tol, and f is zero at all or none of its nodes and ends (else
// some row holds a support edge: the fold of a transmitted lobe, where f has a 1/sqrt singularity that nodes
// on the far side never see); at depth 45 (width ~1e-16) it is accepted with max |f| x width added
// (the singular mass 2 C sqrt(h) of a 1/sqrt edge is below it). `err` sums the accepted changes.
struct Panel {
  std::vector<double> v;
  double fmax = 0.0;
  bool mixed = false;  // zero at some of its nodes and ends, not at all
};

Panel panel_flatland(const Case& c, bool reflected, const DielectricPointOptions& o, double a, double b) {
  const GaussLegendre& gl = gauss_legendre_cached(8);
  Panel p;
  p.v.assign(kFlatMaxK + 2, 0.0);
  std::vector<int> zeros(kFlatMaxK + 2, 0);
  int n = 0;
  auto f = [&](double t) {
    return kaleidoscope_dielectric_bsdf_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), t, reflected, kFlatMaxK, o);
  };
  for (double t : {a, b}) {
    ++n;
    const DielectricPointValue v = f(std::clamp(t, -0.5 * kPi + 1e-12, 0.5 * kPi - 1e-12));
    for (std::size_t k = 0; k < zeros.size(); ++k) zeros[k] += v.by_k[k] == 0.0;
  }
  for (std::size_t q = 0; q < gl.size(); ++q) {
    const double t = 0.5 * (a + b) + 0.5 * (b - a) * gl.x[q];
    const DielectricPointValue v = f(t);
    ++n;
    for (std::size_t k = 0; k < zeros.size(); ++k) zeros[k] += v.by_k[k] == 0.0;
    p.fmax = std::max(p.fmax, v.f);
    for (std::size_t k = 0; k < p.v.size(); ++k) p.v[k] += 0.5 * (b - a) * gl.w[q] * v.by_k[k] * std::cos(t);
  }
  for (int z : zeros) p.mixed = p.mixed || (z > 0 && z < n);
  return p;
}

void adaptive_flatland(const Case& c, bool reflected, const DielectricPointOptions& o, double a, double b,
                       const Panel& whole, double tol, int depth, std::vector<double>& sum, double& err) {
  const double m = 0.5 * (a + b);
  const Panel l = panel_flatland(c, reflected, o, a, m), r = panel_flatland(c, reflected, o, m, b);
  double change = 0.0;
  for (std::size_t k = 0; k < whole.v.size(); ++k) change = std::max(change, std::abs(l.v[k] + r.v[k] - whole.v[k]));
  const bool edge = l.mixed || r.mixed;
  if ((change <= tol && !edge) || depth >= 45) {
    for (std::size_t k = 0; k < whole.v.size(); ++k) sum[k] += l.v[k] + r.v[k];
    err += change + (edge ? std::max(l.fmax, r.fmax) * (b - a) : 0.0);
    return;
  }
  adaptive_flatland(c, reflected, o, a, m, l, tol, depth + 1, sum, err);
  adaptive_flatland(c, reflected, o, m, b, r, tol, depth + 1, sum, err);
}

std::vector<double> bin_integral_flatland(const Case& c, bool reflected, double a, double b,
                                          const DielectricPointOptions& o, double& err) {
  std::vector<double> sum(kFlatMaxK + 2, 0.0);
  err = 0.0;
  constexpr int panels = 4;
  for (int p = 0; p < panels; ++p) {
    const double x0 = a + (b - a) * p / panels, x1 = a + (b - a) * (p + 1) / panels;
    adaptive_flatland(c, reflected, o, x0, x1, panel_flatland(c, reflected, o, x0, x1), 1e-13, 0, sum, err);
  }
  return sum;
}

struct BinCheck {
  double worst_excess = -1e300;  // max over cells of |Q - lobe| - (lobe error + quadrature error)
  double worst_diff = 0.0, worst_allowed = 0.0;
  std::string where;
};

BinCheck check_flatland_bins(const Case& c, const DielectricPointOptions& o) {
  DielectricLobeOptions lo;
  lo.from = c.from;
  const DielectricLobe L =
      kaleidoscope_dielectric_lobe_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), kFlatBins, kFlatMaxK, lo);
  BinCheck r;
  const double w = kPi / kFlatBins;
  for (bool reflected : {true, false})
    for (int b = 0; b < kFlatBins; ++b) {
      const double a = -0.5 * kPi + b * w;
      double quad_err = 0.0;
      const std::vector<double> q = bin_integral_flatland(c, reflected, a, a + w, o, quad_err);
      double total = 0.0;
      for (int row = 0; row <= kFlatMaxK + 1; ++row) {
        const double lobe = (reflected ? L.reflected_by_k : L.transmitted_by_k)[row][b];
        const double diff = std::abs(q[row] - lobe), allowed = L.error_estimate + quad_err + 1e-14;
        total += q[row];
        if (diff - allowed > r.worst_excess) {
          r.worst_excess = diff - allowed, r.worst_diff = diff, r.worst_allowed = allowed;
          r.where = describe(c) + (reflected ? " reflected" : " transmitted") + " bin " + std::to_string(b) + " k " +
                    std::to_string(row) + " point " + std::to_string(q[row]) + " lobe " + std::to_string(lobe);
        }
      }
      const double lobe = (reflected ? L.reflected : L.transmitted)[b];
      const double diff = std::abs(total - lobe), allowed = L.error_estimate + 5.0 * quad_err + 1e-14;
      if (diff - allowed > r.worst_excess) {
        r.worst_excess = diff - allowed, r.worst_diff = diff, r.worst_allowed = allowed;
        r.where = describe(c) + (reflected ? " reflected" : " transmitted") + " bin " + std::to_string(b) + " all k";
      }
    }
  return r;
}

const std::vector<Case>& flat_cases() {
  static const std::vector<Case> c{
      {NdfKind::ggx, 0.3, 1.5, 30.0},       {NdfKind::beckmann, 0.5, 1.5, -45.0},
      {NdfKind::ggx, 0.5, 1.0 / 1.5, 20.0}, {NdfKind::beckmann, 0.3, 1.5, 40.0, DielectricLightFrom::below},
      {NdfKind::ggx, 0.2, 2.4, 70.0},
  };
  return c;
}

TEST(KaleidoscopeDielectricPointLong, FlatlandBinIntegralIsTheLobe) {
  for (const Case& c : flat_cases()) {
    DielectricPointOptions o;
    o.from = c.from;
    const BinCheck r = check_flatland_bins(c, o);
    std::printf("%s: worst |point - lobe| - allowed %.3g (diff %.3g, allowed %.3g) at %s\n", describe(c).c_str(),
                r.worst_excess, r.worst_diff, r.worst_allowed, r.where.c_str());
    EXPECT_LE(r.worst_excess, 0.0) << r.where;
  }
}

TEST(KaleidoscopeDielectricPointLong, FlatlandBrokenJacobiansFailTheBins) {
  const Case c{NdfKind::ggx, 0.3, 1.5, 30.0};
  for (DielectricPointBreak b : {DielectricPointBreak::no_cosine, DielectricPointBreak::no_index_jacobian}) {
    DielectricPointOptions o;
    o.broken = b;
    const BinCheck r = check_flatland_bins(c, o);
    std::printf("broken %d: worst excess %.3g (diff %.3g, allowed %.3g) at %s\n", static_cast<int>(b), r.worst_excess,
                r.worst_diff, r.worst_allowed, r.where.c_str());
    EXPECT_GT(r.worst_excess, 1e-3) << static_cast<int>(b);
  }
}

// F = 1: the model's reflected lobes are G_kaleidoscopic's (KD-3), so the point BSDF per k is
// brdf_flatland.h's rho2 (Eq. 10-17 in flatland, solved there by kaleidoscope_solutions.h).
TEST(KaleidoscopeDielectricPoint, FlatlandConductorLimitIsFlatlandBrdf) {
  DielectricPointOptions o;
  o.reflectance = [](double) { return 1.0; };
  double worst = 0.0;
  int nonzero = 0;
  for (const Case& c : {Case{NdfKind::ggx, 0.3, 1.5, 30.0}, Case{NdfKind::beckmann, 0.6, 1.5, -50.0},
                        Case{NdfKind::phong, 0.2, 0.6, 0.0}, Case{NdfKind::ggx, 1.0, 2.4, 75.0}})
    for (int j = -17; j <= 17; ++j) {
      const double to = deg(5.0 * j + 0.37);
      const DielectricPointValue v =
          kaleidoscope_dielectric_bsdf_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), to, true, 6, o);
      for (int k = 1; k <= 6; ++k) {
        const double ref = flatland_brdf_k(c.ndf, c.alpha, deg(c.theta_i_deg), to, k);
        const double err = std::abs(v.by_k[k] - ref) / std::max(ref, 1e-300);
        if (ref > 1e-200) ++nonzero, worst = std::max(worst, err);
        EXPECT_NEAR(v.by_k[k], ref, 1e-9 * ref + 1e-300) << describe(c) << " theta_o=" << to << " k=" << k;
      }
    }
  std::printf("F = 1 against flatland_brdf_k: worst relative %.3g over %d nonzero values\n", worst, nonzero);
  EXPECT_GT(nonzero, 300);
}

// Reflection keeps every path in medium 1: the reversed chain meets the same local angles, so the
// dielectric factor prod F is the same both ways and rho2's reciprocity carries over per k.
TEST(KaleidoscopeDielectricPoint, FlatlandReflectionIsReciprocal) {
  double worst = 0.0;
  for (const Case& c : {Case{NdfKind::ggx, 0.3, 1.5, 0.0}, Case{NdfKind::beckmann, 0.5, 1.0 / 1.5, 0.0}})
    for (double ti : {-60.0, -20.0, 10.0, 45.0, 80.0})
      for (double to : {-70.0, -35.0, 5.0, 25.0, 62.0}) {
        const auto x = kaleidoscope_dielectric_bsdf_flatland(c.ndf, c.alpha, c.eta, deg(ti), deg(to), true, 4);
        const auto y = kaleidoscope_dielectric_bsdf_flatland(c.ndf, c.alpha, c.eta, deg(to), deg(ti), true, 4);
        for (int k = 1; k <= 5; ++k) {
          const double e = std::abs(x.by_k[k] - y.by_k[k]) / std::max(1e-300, std::max(x.f, y.f));
          worst = std::max(worst, e);
          EXPECT_LE(e, 1e-9) << describe(c) << " " << ti << " -> " << to << " k=" << k;
        }
      }
  std::printf("flatland reflection reciprocity: worst relative %.3g\n", worst);
}

TEST(KaleidoscopeDielectricPoint, FlatlandFiniteAtHardPoints) {
  int n = 0;
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann, NdfKind::phong})
    for (double alpha : {0.01, 0.1, 0.5, 2.0})
      for (double eta : {1.5, 1.0 / 1.5, 1.0, 2.4})
        for (double ti : {0.0, 30.0, -60.0, 89.99, -89.999})
          for (double to : {0.0, -ti, ti, 89.999, -89.99, 41.8, -41.81, 48.6})
            for (bool refl : {true, false})
              for (DielectricLightFrom from : {DielectricLightFrom::above, DielectricLightFrom::below}) {
                if (std::abs(to) >= 90.0) continue;
                DielectricPointOptions o;
                o.from = from;
                const auto v = kaleidoscope_dielectric_bsdf_flatland(ndf, alpha, eta, deg(ti), deg(to), refl, 3, o);
                ++n;
                ASSERT_TRUE(std::isfinite(v.f) && v.f >= 0.0)
                    << ndf_name(ndf) << " alpha " << alpha << " eta " << eta << " " << ti << " -> " << to << " " << refl
                    << " f " << v.f;
                for (double x : v.by_k) ASSERT_TRUE(std::isfinite(x) && x >= 0.0);
              }
  EXPECT_GT(n, 1000);
}

// ---- 3D ---------------------------------------------------------------------------------------------

constexpr int kThetaBins = 6, kPhiBins = 8, k3dMaxK = 2;

Dir3 light_dir(const Case& c) {
  const double t = deg(c.theta_i_deg);
  const double z = c.from == DielectricLightFrom::below ? -std::cos(t) : std::cos(t);
  return {-std::sin(t), 0.0, z};
}

// The exit direction of Lobe3d's bin convention: theta from the exit side's normal; `up` above.
Dir3 exit_dir(double theta, double phi, bool up) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), up ? std::cos(theta) : -std::cos(theta)};
}

// int over the bin of f |cos| d omega (per row) by panels x panels panels of 6 x 6 Gauss-Legendre nodes.
std::vector<double> bin_integral_3d(const Case& c, bool up, double t0, double t1, double p0, double p1, int panels,
                                    const DielectricPointOptions& o) {
  const GaussLegendre& gl = gauss_legendre_cached(6);
  std::vector<double> s(k3dMaxK + 2, 0.0);
  const Dir3 i = light_dir(c);
  for (int a = 0; a < panels; ++a)
    for (int b = 0; b < panels; ++b) {
      const double ta = t0 + (t1 - t0) * a / panels, tb = t0 + (t1 - t0) * (a + 1) / panels;
      const double pa = p0 + (p1 - p0) * b / panels, pb = p0 + (p1 - p0) * (b + 1) / panels;
      for (std::size_t q = 0; q < gl.size(); ++q)
        for (std::size_t r = 0; r < gl.size(); ++r) {
          const double t = 0.5 * (ta + tb) + 0.5 * (tb - ta) * gl.x[q];
          const double p = 0.5 * (pa + pb) + 0.5 * (pb - pa) * gl.x[r];
          const double w = 0.25 * (tb - ta) * (pb - pa) * gl.w[q] * gl.w[r] * std::sin(t) * std::cos(t);
          const DielectricPointValue v =
              kaleidoscope_dielectric_bsdf_3d(c.ndf, c.alpha, c.eta, i, exit_dir(t, p, up), k3dMaxK, o);
          for (std::size_t k = 0; k < s.size(); ++k) s[k] += w * v.by_k[k];
        }
    }
  return s;
}

BinCheck check_3d_bins(const Case& c, const DielectricPointOptions& o) {
  DielectricLobeOptions lo;
  lo.from = c.from;
  const DielectricLobe L =
      kaleidoscope_dielectric_lobe_3d(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), kThetaBins, kPhiBins, k3dMaxK, lo);
  BinCheck r;
  const double dt = 0.5 * kPi / kThetaBins, dp = 2.0 * kPi / kPhiBins;
  const bool from_above = c.from == DielectricLightFrom::above;
  for (bool reflected : {true, false})
    for (int t = 0; t < kThetaBins; ++t)
      for (int p = 0; p < kPhiBins; ++p) {
        const bool up = reflected == from_above;
        const double p0 = (p - 0.5) * dp;
        const std::vector<double> q1 = bin_integral_3d(c, up, t * dt, (t + 1) * dt, p0, p0 + dp, 2, o);
        const std::vector<double> q2 = bin_integral_3d(c, up, t * dt, (t + 1) * dt, p0, p0 + dp, 4, o);
        const int bin = t * kPhiBins + p;
        for (int row = 0; row <= k3dMaxK + 1; ++row) {
          const double lobe = (reflected ? L.reflected_by_k : L.transmitted_by_k)[row][bin];
          const double quad_err = 3.0 * std::abs(q2[row] - q1[row]);
          const double diff = std::abs(q2[row] - lobe), allowed = L.error_estimate + quad_err + 1e-12;
          if (diff - allowed > r.worst_excess) {
            r.worst_excess = diff - allowed, r.worst_diff = diff, r.worst_allowed = allowed;
            r.where = describe(c) + (reflected ? " reflected" : " transmitted") + " bin " + std::to_string(t) + "," +
                      std::to_string(p) + " k " + std::to_string(row) + " point " + std::to_string(q2[row]) + " lobe " +
                      std::to_string(lobe);
          }
        }
      }
  return r;
}

TEST(KaleidoscopeDielectricPointLong, ThreeDBinIntegralIsTheLobe) {
  for (const Case& c : {Case{NdfKind::beckmann, 0.3, 1.5, 40.0}, Case{NdfKind::ggx, 0.4, 1.0 / 1.5, 25.0},
                        Case{NdfKind::ggx, 0.3, 1.5, 30.0, DielectricLightFrom::below}}) {
    const BinCheck r = check_3d_bins(c, {});
    std::printf("%s: worst |point - lobe| - allowed %.3g (diff %.3g, allowed %.3g) at %s\n", describe(c).c_str(),
                r.worst_excess, r.worst_diff, r.worst_allowed, r.where.c_str());
    EXPECT_LE(r.worst_excess, 0.0) << r.where;
  }
}

TEST(KaleidoscopeDielectricPointLong, ThreeDBrokenJacobianFailsTheBins) {
  for (DielectricPointBreak b : {DielectricPointBreak::section_jacobian, DielectricPointBreak::no_cosine}) {
    DielectricPointOptions o;
    o.broken = b;
    const BinCheck r = check_3d_bins(Case{NdfKind::beckmann, 0.3, 1.5, 40.0}, o);
    std::printf("broken %d: worst excess %.3g (diff %.3g, allowed %.3g) at %s\n", static_cast<int>(b), r.worst_excess,
                r.worst_diff, r.worst_allowed, r.where.c_str());
    EXPECT_GT(r.worst_excess, 1e-3) << static_cast<int>(b);
  }
}

// F = 1: Eq. (16) of brdf_3d.h (the groove frame of the half vector, Eq. 5-6 at the projected angles),
// derived without lifting a cross-section's exit.
TEST(KaleidoscopeDielectricPoint, ThreeDConductorLimitIsVgrooveBrdf) {
  DielectricPointOptions o;
  o.reflectance = [](double) { return 1.0; };
  double worst = 0.0;
  int nonzero = 0;
  for (const Case& c :
       {Case{NdfKind::ggx, 0.3, 1.5, 30.0}, Case{NdfKind::beckmann, 0.6, 1.5, 65.0}, Case{NdfKind::ggx, 1.0, 0.6, 0.0}})
    for (double to : {3.0, 17.0, 38.0, 55.0, 71.0, 86.0})
      for (double po : {-170.0, -120.0, -61.0, 0.5, 44.0, 93.0, 150.0}) {
        const Dir3 i = light_dir(c), out = exit_dir(deg(to), deg(po), true);
        const DielectricPointValue v = kaleidoscope_dielectric_bsdf_3d(c.ndf, c.alpha, c.eta, i, out, 4, o);
        for (int k = 1; k <= 4; ++k) {
          const double ref = vgroove_brdf_k(i, out, k, c.ndf, c.alpha);
          if (ref > 1e-200) ++nonzero, worst = std::max(worst, std::abs(v.by_k[k] - ref) / ref);
          EXPECT_NEAR(v.by_k[k], ref, 1e-8 * ref + 1e-300) << describe(c) << " " << to << "," << po << " k=" << k;
        }
      }
  std::printf("3D F = 1 against vgroove_brdf_k: worst relative %.3g over %d nonzero values\n", worst, nonzero);
  EXPECT_GT(nonzero, 100);
}

TEST(KaleidoscopeDielectricPoint, ThreeDReflectionIsReciprocal) {
  double worst = 0.0;
  for (const Case& c : {Case{NdfKind::ggx, 0.3, 1.5, 0.0}, Case{NdfKind::beckmann, 0.5, 1.0 / 1.5, 0.0}})
    for (double ti : {10.0, 45.0, 80.0})
      for (double pi : {0.0, 100.0})
        for (double to : {5.0, 33.0, 62.0})
          for (double po : {-150.0, 20.0, 170.0}) {
            const Dir3 i = exit_dir(deg(ti), deg(pi), true), out = exit_dir(deg(to), deg(po), true);
            const auto x = kaleidoscope_dielectric_bsdf_3d(c.ndf, c.alpha, c.eta, i, out, 3);
            const auto y = kaleidoscope_dielectric_bsdf_3d(c.ndf, c.alpha, c.eta, out, i, 3);
            for (int k = 1; k <= 4; ++k) {
              const double e = std::abs(x.by_k[k] - y.by_k[k]) / std::max(1e-300, std::max(x.f, y.f));
              worst = std::max(worst, e);
              EXPECT_LE(e, 1e-8) << describe(c) << " " << ti << "," << pi << " -> " << to << "," << po << " k=" << k;
            }
          }
  std::printf("3D reflection reciprocity: worst relative %.3g\n", worst);
}

TEST(KaleidoscopeDielectricPoint, ThreeDFiniteAtHardPoints) {
  int n = 0;
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.01, 0.5, 2.0})
      for (double eta : {1.5, 1.0 / 1.5, 1.0})
        for (double ti : {0.0, 30.0, 89.99})
          for (bool below : {false, true}) {
            const double z = below ? -std::cos(deg(ti)) : std::cos(deg(ti));
            const Dir3 i{-std::sin(deg(ti)), 0.0, z};
            const double st = std::sin(deg(ti));
            // o = n, the mirror direction, straight through, grazing, TIR-side directions.
            std::vector<Dir3> outs{{0, 0, 1},
                                   {0, 0, -1},
                                   {st, 0, std::cos(deg(ti))},
                                   {-st, 0, -std::cos(deg(ti))},
                                   {st / eta, 0, -std::sqrt(std::max(0.0, 1 - st * st / (eta * eta)))}};
            for (double to : {89.999, 45.0, 60.0})
              for (double po : {0.0, 90.0, 180.0})
                for (bool up : {true, false}) outs.push_back(exit_dir(deg(to), deg(po), up));
            for (const Dir3& o : outs) {
              if (std::abs(std::sqrt(o.x * o.x + o.y * o.y + o.z * o.z) - 1.0) > 1e-9) continue;
              const auto v = kaleidoscope_dielectric_bsdf_3d(ndf, alpha, eta, i, o, 3);
              ++n;
              ASSERT_TRUE(std::isfinite(v.f) && v.f >= 0.0) << ndf_name(ndf) << " alpha " << alpha << " eta " << eta
                                                            << " ti " << ti << " o " << o.x << "," << o.y << "," << o.z;
            }
          }
  EXPECT_GT(n, 500);
}

// ---- The sampler's pdf ---------------------------------------------------------------------------

using test_stats::Uniforms;  // uniforms in (0, 1), not the code's own RNG

// Flatland: the draws' histogram against n x the pdf integrated over each bin (Gauss-Legendre, 16 x 8
// nodes a bin), failures in a last cell expecting n (1 - int pdf); and the mean of f |cos| / pdf over
// the draws (0 on failure) against the lobe's albedo_r + albedo_t within 4 standard errors.
TEST(KaleidoscopeDielectricPdfLong, FlatlandHistogramAndEstimator) {
  const std::vector<Case> cs{{NdfKind::ggx, 0.3, 1.5, 30.0},
                             {NdfKind::beckmann, 0.5, 1.0 / 1.5, -20.0},
                             {NdfKind::ggx, 0.5, 1.5, 40.0, DielectricLightFrom::below}};
  constexpr int bins = 36;
  constexpr long n = 100000;
  std::uint64_t seed = 71;
  for (const Case& c : cs) {
    DielectricPointOptions po;
    po.from = c.from;
    std::vector<double> expected(2 * bins + 1, 0.0), observed(2 * bins + 1, 0.0);
    const GaussLegendre& gl = gauss_legendre_cached(8);
    double mass = 0.0;
    const double w = kPi / bins;
    for (int side = 0; side < 2; ++side)
      for (int b = 0; b < bins; ++b) {
        double s = 0.0;
        for (int p = 0; p < 16; ++p) {
          const double x0 = -0.5 * kPi + b * w + p * w / 16, x1 = x0 + w / 16;
          for (std::size_t q = 0; q < gl.size(); ++q) {
            const double t = 0.5 * (x0 + x1) + 0.5 * (x1 - x0) * gl.x[q];
            s += 0.5 * (x1 - x0) * gl.w[q] *
                 kaleidoscope_dielectric_pdf_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), t, side == 0, po);
          }
        }
        expected[side * bins + b] = n * s;
        mass += s;
      }
    expected.back() = n * (1.0 - mass);
    DielectricSamplerOptions so;
    so.from = c.from;
    Uniforms rng{++seed};
    double sum = 0.0, sum2 = 0.0;
    int zero_pdf = 0;
    for (long s = 0; s < n; ++s) {
      const std::array<double, 4> u{rng(), rng(), rng(), rng()};
      const DielectricSampleFlatland d =
          sample_vgroove_dielectric_flatland(deg(c.theta_i_deg), u, c.ndf, c.alpha, c.eta, so);
      if (d.weight == 0.0) {
        observed.back() += 1.0;
        continue;
      }
      const int b = std::clamp(static_cast<int>(std::floor((d.theta_o + 0.5 * kPi) / w)), 0, bins - 1);
      observed[(d.reflected ? 0 : 1) * bins + b] += 1.0;
      const DielectricPointValue f = kaleidoscope_dielectric_bsdf_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg),
                                                                           d.theta_o, d.reflected, 0, po);
      const double pdf =
          kaleidoscope_dielectric_pdf_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), d.theta_o, d.reflected, po);
      if (!(pdf > 0.0)) {
        ++zero_pdf;
        continue;
      }
      const double x = f.f * std::cos(d.theta_o) / pdf;
      sum += x, sum2 += x * x;
    }
    const validation::ChiSquareResult t = validation::chi_square_test(observed, expected, 0.01, 2 * 3);
    DielectricLobeOptions lo;
    lo.from = c.from;
    const DielectricLobe L =
        kaleidoscope_dielectric_lobe_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), bins, 0, lo);
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
    const double albedo = L.albedo_r + L.albedo_t;
    std::printf("%s: chi2 %.1f dof %d p %.3g; E[f cos / pdf] %.6f +- %.6f, R + T %.6f (int pdf %.6f); zero pdf %d\n",
                describe(c).c_str(), t.statistic, t.dof, t.p_value, mean, se, albedo, mass, zero_pdf);
    EXPECT_FALSE(t.reject) << describe(c);
    EXPECT_EQ(zero_pdf, 0) << describe(c);
    EXPECT_LE(std::abs(mean - albedo), 4.0 * se + L.error_estimate) << describe(c);
  }
}

// 3D: the draws' histogram over (side, theta, phi) cells against n x the pdf integrated over each cell.
TEST(KaleidoscopeDielectricPdfLong, ThreeDHistogram) {
  const std::vector<Case> cs{{NdfKind::beckmann, 0.3, 1.5, 40.0},
                             {NdfKind::ggx, 0.4, 1.0 / 1.5, 25.0, DielectricLightFrom::below}};
  constexpr long n = 100000;
  constexpr int tb = 6, pb = 8;
  std::uint64_t seed = 91;
  const double dt = 0.5 * kPi / tb, dp = 2.0 * kPi / pb;
  for (const Case& c : cs) {
    DielectricPointOptions po;
    const bool from_above = c.from == DielectricLightFrom::above;
    std::vector<double> expected(2 * tb * pb + 1, 0.0), observed(2 * tb * pb + 1, 0.0);
    double mass = 0.0;
    for (int side = 0; side < 2; ++side)
      for (int t = 0; t < tb; ++t)
        for (int p = 0; p < pb; ++p) {
          const bool up = (side == 0) == from_above;
          const std::vector<double> s =
              bin_integral_3d(c, up, t * dt, (t + 1) * dt, (p - 0.5) * dp, (p + 0.5) * dp, 4, po);
          double v = 0.0;
          for (double x : s) v += x;
          expected[(side * tb + t) * pb + p] = n * v;
          mass += v;
        }
    expected.back() = n * (1.0 - mass);
    DielectricSamplerOptions so;
    so.from = c.from;
    Uniforms rng{++seed};
    const Dir3 i = light_dir(c);
    int zero_pdf = 0;
    for (long s = 0; s < n; ++s) {
      const std::array<double, 5> u{rng(), rng(), rng(), rng(), rng()};
      const DielectricSample3d d = sample_vgroove_dielectric_3d(deg(c.theta_i_deg), u, c.ndf, c.alpha, c.eta, so);
      if (d.weight == 0.0) {
        observed.back() += 1.0;
        continue;
      }
      const double th = std::atan2(std::hypot(d.o.x, d.o.y), std::abs(d.o.z));
      const int t = std::min(tb - 1, static_cast<int>(th / dt));
      int p = static_cast<int>(std::floor((std::atan2(d.o.y, d.o.x) + 0.5 * dp) / dp));
      p = ((p % pb) + pb) % pb;
      observed[((d.reflected ? 0 : 1) * tb + t) * pb + p] += 1.0;
      if (s % 20 == 0 && !(kaleidoscope_dielectric_pdf_3d(c.ndf, c.alpha, c.eta, i, d.o) > 0.0)) ++zero_pdf;
    }
    const validation::ChiSquareResult t = validation::chi_square_test(observed, expected, 0.01, 2);
    std::printf("%s: chi2 %.1f dof %d p %.3g; int pdf %.6f; zero pdf %d\n", describe(c).c_str(), t.statistic, t.dof,
                t.p_value, mass, zero_pdf);
    EXPECT_FALSE(t.reject) << describe(c);
    EXPECT_EQ(zero_pdf, 0) << describe(c);
  }
}

}  // namespace
}  // namespace vgroove::analytic
