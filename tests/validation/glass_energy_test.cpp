// Tests of the rough-glass energy tables (validation/glass_energy.h): a nearly flat interface gives
// Fresnel's R by hand from either side; the hemispherical averages obey reciprocity,
// T_avg(above) = eta^2 T_avg(below) in 3D and eta T_avg(below) in flatland, within the sample
// count's noise (the other power, and the flat interface's identity by quadrature, beside it); the
// conductor limit gives the conductor tables' E_k; every ray is accounted; the counts do not depend
// on the thread count. With the Smith walk as the reference: its first order is Walter's BSDF with
// the height-correlated G2 (analytic/albedo_glass.h) and its averages are reciprocal.
#include "vgroove/validation/glass_energy.h"
#include "vgroove/analytic/albedo_glass.h"
#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/walter.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/validation/energy_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <numeric>

namespace vgroove::validation {
namespace {

double share(const std::vector<long long>& v, long long rays) {
  return static_cast<double>(std::accumulate(v.begin(), v.end(), 0LL)) / static_cast<double>(rays);
}

GlassTable run(const GlassGrid& g, int threads = 2) {
  auto t = run_glass_table(g, threads);
  EXPECT_TRUE(t.has_value());
  return t ? *t : GlassTable{};
}

// Beckmann alpha 0.01 (facets within a degree or two of the normal, no tail): E_R is the flat
// interface's F(mu, eta) from above and F(mu, 1/eta) from below (1 beyond the critical angle),
// within 5 standard errors plus 1e-3 for the facets' spread.
TEST(GlassEnergy, NearlyFlatIsFresnel) {
  GlassGrid g;
  g.ndfs = {NdfKind::beckmann};
  g.dims = {SurfaceDim::three_d, SurfaceDim::flatland};
  g.etas = {1.5};
  g.alphas = {0.01};
  g.mus = {1.0, 0.8, 0.5, 0.2};
  g.rays = 20000;
  g.grooves = 2000;
  const GlassTable t = run(g);
  for (std::size_t c = 0; c < g.cells(); ++c) {
    const GlassCell x = g.cell_at(c);
    const double F = optics::fresnel_dielectric(x.mu, x.from == sim::Medium::above ? x.eta : 1.0 / x.eta);
    const double R = share(t.cells[c].reflected, t.cells[c].rays);
    const double se = std::sqrt(std::max(F * (1 - F), 1e-4) / static_cast<double>(g.rays));
    EXPECT_NEAR(R, F, 5 * se + 1e-3) << surface_dim_name(x.dim) << " from "
                                     << (x.from == sim::Medium::above ? "above" : "below") << " mu " << x.mu;
  }
}

// The flat interface's identity, by quadrature of the project's Fresnel: 1 - F_avg(1/eta) =
// (1 - F_avg(eta)) / eta^2, F_avg = int_0^1 2 mu F(mu) d mu.
TEST(GlassEnergy, FlatInterfaceAveragesObeyTheIdentity) {
  for (double eta : {1.33, 1.5, 2.4}) {
    auto avg = [](double e) {
      return analytic::integrate_adaptive_parts([e](double mu) { return 2 * mu * optics::fresnel_dielectric(mu, e); },
                                                0.0, 1.0, 1e-12, 1e-14);
    };
    EXPECT_NEAR(1 - avg(1 / eta), (1 - avg(eta)) / (eta * eta), 1e-9) << eta;
    EXPECT_GT(std::abs(1 - avg(1 / eta) - (1 - avg(eta)) / eta), 0.05) << eta;  // the other power is wrong
  }
}

// Reciprocity of the exact rough surface, 3D (eta^2) and flatland (eta^1), GGX alpha 0.5 and
// Beckmann 1.0, eta 1.5 and 1/2.4: within 4 standard errors (8 tests). The other power misses by
// more than 20.
TEST(GlassEnergy, ReciprocityOfTheAverages) {
  GlassGrid g;
  g.ndfs = {NdfKind::ggx, NdfKind::beckmann};
  g.dims = {SurfaceDim::three_d, SurfaceDim::flatland};
  g.etas = {1.5, 1 / 2.4};
  g.alphas = {0.5};
  g.mus = {1.0};
  g.rays = 40000;
  g.grooves = 2000;
  const GlassTable t = run(g);
  const std::vector<GlassReciprocity> pairs = glass_reciprocity(t);
  ASSERT_EQ(pairs.size(), 8u);
  for (const GlassReciprocity& r : pairs) {
    const bool three_d = r.cell.dim == SurfaceDim::three_d;
    EXPECT_LT(std::abs(r.z()), 4.0) << ndf_name(r.cell.ndf) << " " << surface_dim_name(r.cell.dim) << " eta "
                                    << r.cell.eta << ": " << r.above << " vs " << r.scaled_below;
    const double wrong = (three_d ? r.cell.eta : r.cell.eta * r.cell.eta) * r.below;
    EXPECT_GT(std::abs(r.above - wrong) / r.se, 20.0) << surface_dim_name(r.cell.dim);
  }
}

// F = 1: every ray reflects, in the orders the conductor tables' fresh grooves give (sim/ndf_grooves.h:
// the same groove law, independent streams), per k = 1, 2, 3 and beyond within 5 standard errors.
TEST(GlassEnergy, ConductorLimitIsTheConductorTable) {
  GlassGrid g;
  g.dims = {SurfaceDim::three_d, SurfaceDim::flatland};
  g.sides = {sim::Medium::above};
  g.etas = {1.5};
  g.alphas = {0.8};
  g.mus = {0.6};
  g.rays = 40000;
  g.grooves = 4000;
  g.max_k = 3;
  g.conductor_limit = true;
  const GlassTable t = run(g);
  EnergyGrid e;
  e.ndfs = {NdfKind::ggx};
  e.dims = g.dims;
  e.alphas = g.alphas;
  e.mus = g.mus;
  e.rays = 40000;
  e.max_k = 3;
  const auto conductor = run_energy_table(e, 2);
  ASSERT_TRUE(conductor.has_value());
  for (std::size_t d = 0; d < 2; ++d) {
    const GlassCounts& glass = t.cells[d];
    const sim::BounceCounts& c = conductor->cells[d].counts;
    EXPECT_EQ(share(glass.transmitted, glass.rays), 0.0);
    for (int k = 1; k <= 4; ++k) {
      const double a = static_cast<double>(glass.reflected[static_cast<std::size_t>(k - 1)]) / glass.rays;
      const double b = static_cast<double>(c.by_k[static_cast<std::size_t>(k)]) / static_cast<double>(c.rays);
      const double se = std::sqrt(a * (1 - a) / glass.rays + b * (1 - b) / static_cast<double>(c.rays));
      EXPECT_NEAR(a, b, 5 * se + 1e-12) << surface_dim_name(g.dims[d]) << " k " << k;
    }
  }
}

// Walter's BSDF against the traced 3D surface (from above): the reflected albedo with the V-cavity
// G is the surface's first order exactly (a reflection at the first hit that leaves the groove),
// within 5 standard errors (a model 10 % off is not); the transmitted first order is reported beside
// Walter's with the V-cavity and Smith G (docs/derivations/walter.md, "In 3D").
TEST(GlassEnergy, WalterVcavityReflectionIsTheTracedFirstOrder) {
  GlassGrid g;
  g.sides = {sim::Medium::above};
  g.etas = {1.5};
  g.alphas = {0.3, 0.6};
  g.mus = {0.5};
  g.rays = 400000;
  g.grooves = 4000;
  g.max_k = 2;
  const GlassTable t = run(g);
  for (std::size_t c = 0; c < g.cells(); ++c) {
    const GlassCell x = g.cell_at(c);
    const double ti = std::acos(x.mu);
    const analytic::Dir3 i = analytic::dir3(ti, 0.0), mirror = analytic::dir3(ti, std::numbers::pi);
    const double st = std::sin(ti) / x.eta;
    // The Snell direction mirrored into the upper hemisphere (the transmitted lobe's pole).
    const analytic::Dir3 snell_up{-st, 0.0, std::sqrt(1 - st * st)};
    auto albedo = [&](analytic::MaskingKind m, bool transmitted) {
      analytic::HemisphereOptions o;
      o.scale = x.alpha;
      o.tol = 1e-7;
      return analytic::integrate_hemisphere(
                 transmitted ? snell_up : mirror,
                 [&](const analytic::Dir3& w) {
                   if (!transmitted) return analytic::walter_brdf(i, w, x.ndf, x.alpha, x.eta, m) * w.z;
                   const analytic::Dir3 down{w.x, w.y, -w.z};
                   return analytic::walter_btdf(i, down, x.ndf, x.alpha, x.eta, m) * w.z;
                 },
                 o)
          .value;
    };
    const double N = static_cast<double>(t.cells[c].rays);
    const double r1 = static_cast<double>(t.cells[c].reflected[0]) / N;
    const double t1 = static_cast<double>(t.cells[c].transmitted[0]) / N;
    const double model = albedo(analytic::MaskingKind::vcavity, false);
    EXPECT_NEAR(r1, model, 5 * std::sqrt(r1 * (1 - r1) / N)) << "alpha " << x.alpha << " mu " << x.mu;
    EXPECT_GT(std::abs(r1 - 1.1 * model), 5 * std::sqrt(r1 * (1 - r1) / N)) << "a model 10 % off passes";
    std::printf(
        "alpha %.1f mu %.1f: R1 traced %.5f Walter-vcavity %.5f | T1 traced %.5f (se %.5f) Walter-vcavity "
        "%.5f Walter-smith %.5f\n",
        x.alpha, x.mu, r1, model, t1, std::sqrt(t1 * (1 - t1) / N), albedo(analytic::MaskingKind::vcavity, true),
        albedo(analytic::MaskingKind::smith_separable, true));
  }
}

TEST(GlassEnergy, EnergyIsAccountedAndTheCountsDoNotDependOnThreads) {
  GlassGrid g;
  g.dims = {SurfaceDim::three_d, SurfaceDim::flatland};
  g.etas = {2.4, 1 / 1.33};
  g.alphas = {0.05, 1.5};
  g.mus = {0.999, 0.01};
  g.rays = 3000;
  g.grooves = 500;
  g.max_k = 4;
  const GlassTable one = run(g, 1), two = run(g, 2);
  ASSERT_EQ(one.cells.size(), g.cells() + g.average_cells());
  for (std::size_t c = 0; c < one.cells.size(); ++c) {
    const GlassCounts& x = one.cells[c];
    const long long left = std::accumulate(x.reflected.begin(), x.reflected.end(), 0LL) +
                           std::accumulate(x.transmitted.begin(), x.transmitted.end(), 0LL);
    EXPECT_EQ(left + x.bounce_limit + x.vertex, g.rays) << c;
    EXPECT_EQ(x.reflected, two.cells[c].reflected) << c;
    EXPECT_EQ(x.transmitted, two.cells[c].transmitted) << c;
    EXPECT_EQ(x.interactions, two.cells[c].interactions) << c;
  }
}

// The dielectric Smith walk's table: in 3D the k = 1 rows at mu = 0.7 are albedo_glass's E_R and E_T
// (Walter, GGX, height-correlated Smith G2) within 5 binomial standard errors from either side; the
// averages are reciprocal in 3D (eta^2) and flatland (eta) within 4 se, the other power 20 se off;
// every walk is accounted, and the counts do not depend on the thread count.
TEST(GlassEnergy, SmithWalkFirstOrderIsWaltersAndItsAveragesAreReciprocal) {
  GlassGrid g;
  g.reference = GlassReference::smith_walk;
  g.dims = {SurfaceDim::three_d, SurfaceDim::flatland};
  g.etas = {1.5};
  g.alphas = {0.5};
  g.mus = {0.7};
  g.rays = 40000;
  const GlassTable t = run(g), one = run(g, 1);
  for (std::size_t c = 0; c < g.cells(); ++c) {
    const GlassCell x = g.cell_at(c);
    const GlassCounts& n = t.cells[c];
    EXPECT_EQ(n.reflected, one.cells[c].reflected) << c;
    EXPECT_EQ(n.transmitted, one.cells[c].transmitted) << c;
    EXPECT_EQ(share(n.reflected, n.rays) + share(n.transmitted, n.rays) + static_cast<double>(n.bounce_limit) / n.rays,
              1.0);
    if (x.dim != SurfaceDim::three_d) continue;
    const double eta_rel = x.from == sim::Medium::above ? x.eta : 1.0 / x.eta;
    analytic::AlbedoOptions q;
    q.tol = 1e-6;
    const analytic::GlassAlbedo e =
        analytic::albedo_glass({x.ndf, analytic::MaskingKind::smith_height_correlated}, x.alpha, x.mu, eta_rel, q);
    const double N = static_cast<double>(n.rays);
    const double r1 = static_cast<double>(n.reflected[0]) / N, t1 = static_cast<double>(n.transmitted[0]) / N;
    std::printf("walk %s: E_R1 %.4f (Walter %.4f), E_T1 %.4f (Walter %.4f)\n",
                x.from == sim::Medium::above ? "above" : "below", r1, e.R.value, t1, e.T.value);
    EXPECT_LE(std::abs(r1 - e.R.value), 5.0 * std::sqrt(e.R.value * (1 - e.R.value) / N));
    EXPECT_LE(std::abs(t1 - e.T.value), 5.0 * std::sqrt(e.T.value * (1 - e.T.value) / N));
  }
  const std::vector<GlassReciprocity> pairs = glass_reciprocity(t);
  ASSERT_EQ(pairs.size(), 2u);
  for (const GlassReciprocity& r : pairs) {
    const bool three_d = r.cell.dim == SurfaceDim::three_d;
    std::printf("walk %s: T_avg above %.4f, scaled below %.4f (z %+.2f)\n", surface_dim_name(r.cell.dim), r.above,
                r.scaled_below, r.z());
    EXPECT_LT(std::abs(r.z()), 4.0) << surface_dim_name(r.cell.dim);
    const double wrong = (three_d ? r.cell.eta : r.cell.eta * r.cell.eta) * r.below;
    EXPECT_GT(std::abs(r.above - wrong) / r.se, 20.0) << surface_dim_name(r.cell.dim);
  }
}

// The Kulla-Conty glass audit columns beside the 3D Smith walk (eta 1.5, alpha 0.6, mu 0.5 and the
// hemispherical cells, both sides): the E fed to the form is the walk's first order (within 5 se;
// broken: the V-cavity model's E misses it by more); lit from above MoonRay's R' + T' = 1 and the
// walk keeps its energy too (R + T = 1 - limit), so dR + dT = 0 within 5 se and dT is the split's
// error alone (printed); lit from below MoonRay's sum falls short (loss > 0.01) and the scale-one
// form's is 1; the compensated averages: MoonRay's r = T'_avg(above) / (eta^2 T'_avg(below)) - 1
// is > 0.03 (0.058 in KullaContyGlass.InsideScaleBreaksTheTransmittedReciprocity), the scale-one
// form's below 1e-3 (the 8-point rule's error).
TEST(GlassEnergy, CompensationAuditBesideTheWalk) {
  GlassGrid g;
  g.reference = GlassReference::smith_walk;
  g.etas = {1.5};
  g.alphas = {0.6};
  g.mus = {0.5};
  g.rays = 20000;
  const GlassTable t = run(g);
  const std::vector<GlassCompensationRow> rows = glass_compensation_audit(t);
  ASSERT_EQ(rows.size(), 4u);
  double Tm[2] = {0.0, 0.0}, T1[2] = {0.0, 0.0};
  for (std::size_t c = 0; c < rows.size(); ++c) {
    const GlassCompensationRow& r = rows[c];
    const GlassCounts& n = t.cells[c];
    const double N = static_cast<double>(n.rays);
    const double r1 = static_cast<double>(n.reflected[0]) / N, t1 = static_cast<double>(n.transmitted[0]) / N;
    const bool above = r.cell.from == sim::Medium::above;
    const double eta_rel = above ? 1.5 : 1.0 / 1.5;
    EXPECT_LE(std::abs(r.E_R - r1), 5.0 * std::sqrt(r1 * (1 - r1) / N)) << c;
    EXPECT_LE(std::abs(r.E_T - t1), 5.0 * std::sqrt(t1 * (1 - t1) / N)) << c;
    if (r.cell.mu != kHemisphere) {
      analytic::AlbedoOptions o;
      o.tol = 1e-5;
      const analytic::GlassAlbedo v = analytic::albedo_glass(
          glass_single_scattering_model(GlassReference::vgroove, r.cell.ndf), r.cell.alpha, r.cell.mu, eta_rel, o);
      EXPECT_GT(std::abs(v.R.value + v.T.value - r1 - t1), 5.0 * std::sqrt((r1 + t1) * (1 - r1 - t1) / N)) << c;
    }
    const double dR = r.moonray.R - r.R, dT = r.moonray.T - r.T, limit = static_cast<double>(n.bounce_limit) / N;
    std::printf(
        "%s mu %s: E_ss %.4f + %.4f; traced R %.4f T %.4f (se %.4f); MoonRay dR %+.4f dT %+.4f; scale one "
        "dR %+.4f dT %+.4f\n",
        above ? "above" : "below", r.cell.mu == kHemisphere ? "avg" : "0.5", r.E_R, r.E_T, r.R, r.T,
        std::max(r.se_R, r.se_T), dR, dT, r.scale_one.R - r.R, r.scale_one.T - r.T);
    if (above) {
      EXPECT_NEAR(r.moonray.R + r.moonray.T, 1.0, 1e-12) << c;
      EXPECT_LE(std::abs(dR + dT - limit), 5.0 * std::max(r.se_R, r.se_T)) << c;
    } else {
      EXPECT_GT(1.0 - r.moonray.R - r.moonray.T, 0.01) << c;
      EXPECT_NEAR(r.scale_one.R + r.scale_one.T, 1.0, 1e-12) << c;
    }
    if (r.cell.mu == kHemisphere) Tm[above ? 0 : 1] = r.moonray.T, T1[above ? 0 : 1] = r.scale_one.T;
  }
  const double r_moon = Tm[0] / (1.5 * 1.5 * Tm[1]) - 1.0, r_one = T1[0] / (1.5 * 1.5 * T1[1]) - 1.0;
  std::printf("compensated averages: r MoonRay %+.4f, scale one %+.1e\n", r_moon, r_one);
  EXPECT_GT(r_moon, 0.03);
  EXPECT_LT(std::abs(r_one), 1e-3);
}

// The grid summary by hand on three synthetic rows (and a hemispherical one it must leave out):
// worst (signed), mean |error|, mean, z = error / sqrt(max(p (1 - p), 1 / n) / n), the regions
// (rough alpha >= 0.5, grazing mu <= 0.25, the conductor audit's) and sides, the Bonferroni
// threshold (m = 1: the two-sided 1 % point 2.5758293) and the closest form.
TEST(GlassEnergy, FormSummaryIsTheHandComputation) {
  const GlassRegions regions = glass_regions();
  EXPECT_EQ(regions.rough_alpha, 0.5);
  EXPECT_EQ(regions.grazing_mu, 0.25);
  EXPECT_NEAR(glass_noise_threshold(1), 2.5758293035489, 1e-9);
  EXPECT_NEAR(std::erfc(glass_noise_threshold(3) / std::numbers::sqrt2), 0.01 / 3.0, 1e-12);
  auto row = [](sim::Medium from, double alpha, double mu, double R, double T, long long left, double fR, double fT) {
    GlassCompensationRow r;
    r.cell.from = from, r.cell.alpha = alpha, r.cell.mu = mu;
    r.R = R, r.T = T, r.rays = 10000, r.left = left;
    r.moonray = {fR, fT};
    r.scale_one = {R, T};  // exact: errors 0
    return r;
  };
  const sim::Medium up = sim::Medium::above, down = sim::Medium::below;
  std::vector<GlassCompensationRow> rows = {
      row(up, 0.6, 0.2, 0.1, 0.8, 9000, 0.12, 0.85), row(down, 0.3, 0.8, 0.5, 0.5, 10000, 0.49, 0.5),
      row(up, 0.6, 0.8, 0.04, 0.96, 10000, 0.04, 0.93), row(up, 0.6, kHemisphere, 0.5, 0.5, 10000, 0.9, 0.9)};
  const std::vector<GlassForm> forms = {{"a", "", [](const GlassCompensationRow& r) { return r.moonray; }},
                                        {"b", "", [](const GlassCompensationRow& r) { return r.scale_one; }}};
  const GlassFormSummary s = glass_form_summary(rows, forms);
  const double eR[3] = {0.12 - 0.1, 0.49 - 0.5, 0.04 - 0.04}, eT[3] = {0.85 - 0.8, 0.5 - 0.5, 0.93 - 0.96},
               eS[3] = {0.97 - 0.9, 0.99 - 1.0, 0.97 - 1.0};
  const double seR[3] = {std::sqrt(0.1 * 0.9 / 1e4), std::sqrt(0.25 / 1e4), std::sqrt(0.04 * 0.96 / 1e4)};
  const double seS[3] = {std::sqrt(0.9 * 0.1 / 1e4), std::sqrt(1e-4 / 1e4), std::sqrt(1e-4 / 1e4)};
  // All cells, both sides: rows 0, 1, 2.
  const GlassErrorStat& R = s.at(0, 0, 0, 0);
  EXPECT_EQ(R.n, 3);
  EXPECT_NEAR(R.worst, eR[0], 1e-15);
  EXPECT_NEAR(R.mean_abs(), (std::abs(eR[0]) + std::abs(eR[1]) + std::abs(eR[2])) / 3.0, 1e-15);
  EXPECT_NEAR(R.mean(), (eR[0] + eR[1] + eR[2]) / 3.0, 1e-15);
  EXPECT_NEAR(R.worst_z, eR[0] / seR[0], 1e-9);
  EXPECT_NEAR(R.max_z, eR[0] / seR[0], 1e-9);
  EXPECT_NEAR(R.mean_abs_z(), (std::abs(eR[0] / seR[0]) + std::abs(eR[1] / seR[1])) / 3.0, 1e-9);
  EXPECT_EQ(R.at, "ggx above eta 1.5 alpha 0.6 mu 0.2");
  EXPECT_FALSE(R.within_noise());  // 6.7 se > 2.94
  const GlassErrorStat& T = s.at(0, 0, 0, 1);
  EXPECT_NEAR(T.worst, eT[0], 1e-15);
  EXPECT_NEAR(T.mean_abs(), (std::abs(eT[0]) + std::abs(eT[2])) / 3.0, 1e-15);
  const GlassErrorStat& S = s.at(0, 0, 0, 2);
  EXPECT_NEAR(S.worst, eS[0], 1e-15);
  EXPECT_NEAR(S.worst_z, eS[0] / seS[0], 1e-9);  // at the worst error, row 0: 0.07 / 0.003
  EXPECT_EQ(S.at, "ggx above eta 1.5 alpha 0.6 mu 0.2");
  EXPECT_NEAR(S.max_z, eS[2] / seS[2], 1e-6);  // -300 at row 2: R + T = 1 traced, its se one ray's worth
  EXPECT_EQ(S.z_at, "ggx above eta 1.5 alpha 0.6 mu 0.8");
  EXPECT_NEAR(S.mean_abs_z(), (std::abs(eS[0] / seS[0]) + std::abs(eS[1] / seS[1]) + std::abs(eS[2] / seS[2])) / 3.0,
              1e-6);
  // Rough (alpha >= 0.5): rows 0 and 2; grazing (mu <= 0.25): row 0; below: row 1.
  EXPECT_EQ(s.at(0, 0, 1, 1).n, 2);
  EXPECT_NEAR(s.at(0, 0, 1, 1).mean_abs(), (std::abs(eT[0]) + std::abs(eT[2])) / 2.0, 1e-15);
  EXPECT_EQ(s.at(0, 0, 2, 0).n, 1);
  EXPECT_NEAR(s.at(0, 0, 2, 0).worst, eR[0], 1e-15);
  EXPECT_EQ(s.at(0, 2, 0, 0).n, 1);
  EXPECT_NEAR(s.at(0, 2, 0, 0).worst, eR[1], 1e-15);
  EXPECT_NEAR(s.at(0, 2, 0, 0).worst_z, -2.0, 1e-9);
  EXPECT_NEAR(s.at(0, 2, 0, 0).max_z, -2.0, 1e-9);
  EXPECT_TRUE(s.at(0, 2, 0, 0).within_noise());  // |z| 2 <= 2.58 (m = 1)
  EXPECT_EQ(s.at(0, 1, 2, 0).n, 1);
  EXPECT_EQ(s.at(0, 2, 2, 0).n, 0);  // no grazing cell from below
  // Form b is exact: closest everywhere, within noise, a the farthest.
  for (int q = 0; q < 3; ++q) {
    EXPECT_EQ(s.closest(0, 0, q), 1);
    EXPECT_EQ(s.closest(0, 0, q, true), 0);
    EXPECT_TRUE(s.at(1, 0, 0, q).within_noise());
    EXPECT_EQ(s.at(1, 0, 0, q).worst, 0.0);
  }
}

namespace {
// A small 3D grid against the walk (both sides, eta 1.5, alpha 0.3 and 0.6, mu 0.2 and 0.8, 4000
// walks a cell: se <= 0.008), made once.
const GlassTable& small_walk_grid() {
  static const GlassTable t = [] {
    GlassGrid g;
    g.reference = GlassReference::smith_walk;
    g.etas = {1.5};
    g.alphas = {0.3, 0.6};
    g.mus = {0.2, 0.8};
    g.rays = 4000;
    return run(g);
  }();
  return t;
}
}  // namespace

// Over a real grid the summary and the JSON's error maps are the rows' errors (recomputed here
// cell by cell), and a deliberately broken form, each side fed the other side's Kulla-Conty
// weights (the swap compensation_glass_test keeps failing), is the farthest: its T' from either
// side and its R' + T' from above (it loses (1 - F_in)(1 - x)(1 - 1 / eta^2)(1 - E)). Physics:
// from above MoonRay's and Cycles' R' + T' are the walk's 1 within noise, from below Cycles' and the
// scale-one form's too, MoonRay's beyond it (its n^2).
TEST(GlassEnergy, BrokenFormIsTheWorstOverTheGrid) {
  const GlassTable& t = small_walk_grid();
  const std::vector<GlassCompensationRow> rows = glass_compensation_audit(t);
  ASSERT_EQ(rows.size(), 12u);  // 8 grid cells, 4 averages
  std::vector<GlassForm> forms = glass_forms();
  forms.push_back({"swapped_sides", "the other side's weights", [](const GlassCompensationRow& r) {
                     return analytic::kulla_conty_glass_albedo(
                         r.E_R, r.E_T, analytic::kulla_conty_glass_weights(1.0 / r.eta_rel, r.averages));
                   }});
  const GlassFormSummary s = glass_form_summary(rows, forms);
  print_glass_form_summary(std::cout, s, GlassReference::smith_walk);
  const std::size_t moon = 0, one = 1, cycles = 2, broken = 3;
  // Recomputed by hand: worst and mean |error| of every form, side and quantity (region all).
  for (std::size_t f = 0; f < forms.size(); ++f)
    for (int side = 0; side < 3; ++side)
      for (int q = 0; q < 3; ++q) {
        double worst = 0.0, sum = 0.0;
        int n = 0;
        for (const GlassCompensationRow& r : rows) {
          if (r.cell.mu == kHemisphere) continue;
          if (side == 1 && r.cell.from != sim::Medium::above) continue;
          if (side == 2 && r.cell.from != sim::Medium::below) continue;
          const analytic::CompensatedGlass v = forms[f].of(r);
          const double e = q == 0 ? v.R - r.R : q == 1 ? v.T - r.T : v.R + v.T - r.R - r.T;
          if (std::abs(e) > std::abs(worst)) worst = e;
          sum += std::abs(e), ++n;
        }
        const GlassErrorStat& st = s.at(f, side, 0, q);
        EXPECT_EQ(st.n, n);
        EXPECT_NEAR(st.worst, worst, 1e-14) << f << side << q;
        EXPECT_NEAR(st.mean_abs(), sum / n, 1e-14) << f << side << q;
      }
  EXPECT_EQ(s.closest(0, 0, 1, true), static_cast<int>(broken));
  EXPECT_EQ(s.closest(1, 0, 1, true), static_cast<int>(broken));
  EXPECT_EQ(s.closest(2, 0, 1, true), static_cast<int>(broken));
  EXPECT_EQ(s.closest(1, 0, 2, true), static_cast<int>(broken));
  EXPECT_FALSE(s.at(broken, 1, 0, 2).within_noise());
  EXPECT_TRUE(s.at(moon, 1, 0, 2).within_noise());
  EXPECT_TRUE(s.at(cycles, 1, 0, 2).within_noise());
  EXPECT_TRUE(s.at(cycles, 2, 0, 2).within_noise());
  EXPECT_TRUE(s.at(one, 2, 0, 2).within_noise());
  EXPECT_FALSE(s.at(moon, 2, 0, 2).within_noise());
  // The JSON: the shipped forms' summary lines and maps are the rows' values.
  const nlohmann::json j = glass_table_json(t)["kulla_conty_glass"];
  ASSERT_EQ(j["forms"].size(), 3u);
  const GlassFormSummary shipped = glass_form_summary(rows, glass_forms());
  for (const nlohmann::json& line : j["summary"]) {
    const auto f = static_cast<std::size_t>(
        std::find(shipped.forms.begin(), shipped.forms.end(), line["form"].get<std::string>()) - shipped.forms.begin());
    const auto pos = [](const auto& names, const std::string& x) {
      return static_cast<int>(std::find(std::begin(names), std::end(names), x) - std::begin(names));
    };
    const GlassErrorStat& st = shipped.at(f, pos(kGlassSides, line["side"]), pos(kGlassRegionNames, line["region"]),
                                          pos(kGlassQuantities, line["quantity"]));
    EXPECT_EQ(line["count"].get<long>(), st.n);
    EXPECT_EQ(line["worst"].get<double>(), st.worst);
    EXPECT_EQ(line["mean_abs"].get<double>(), st.mean_abs());
    EXPECT_EQ(line["within_noise"].get<bool>(), st.within_noise());
  }
  const nlohmann::json& maps = j["error_maps"];
  EXPECT_EQ(maps["shape"], nlohmann::json({1, 2, 1, 2, 2}));
  for (std::size_t c = 0; c < 8; ++c) {
    const GlassCompensationRow& r = rows[c];  // grid order: side, alpha, mu (innermost)
    EXPECT_EQ(maps["forms"]["moonray"]["R"]["error"][c].get<double>(), r.moonray.R - r.R) << c;
    EXPECT_EQ(maps["forms"]["cycles_glass"]["T"]["error"][c].get<double>(), r.cycles.T - r.T) << c;
    EXPECT_NEAR(maps["forms"]["scale_one"]["T"]["z"][c].get<double>(), (r.scale_one.T - r.T) / r.se_T, 1e-9) << c;
  }
}

// The issue's grid against the walk (GGX, eta 1.33, 1.5, 2.4 x alpha 0.1, 0.3, 0.6, 1 x 8 mu
// midpoints x both sides = 192 cells, 20000 walks a cell; ~11 s on 2 threads, label long): the
// walk loses nothing, so the forms that conserve energy (scale_one and cycles_glass from both
// sides, MoonRay from above) have R' + T' within noise over the whole grid, and MoonRay from below
// falls short beyond it; Kulla-Conty from above reflects too much in the rough region (the measured
// finding: mean error > 0, beyond noise). The summary is printed.
TEST(GlassEnergyLong, FormsOverTheIssueGrid) {
  GlassGrid g;
  g.reference = GlassReference::smith_walk;
  g.etas = {1.33, 1.5, 2.4};
  g.alphas = {0.1, 0.3, 0.6, 1.0};
  g.mus = midpoints(8);
  g.rays = 20000;
  const GlassTable t = run(g);
  const std::vector<GlassCompensationRow> rows = glass_compensation_audit(t);
  const GlassFormSummary s = glass_form_summary(rows, glass_forms());
  print_glass_form_summary(std::cout, s, g.reference);
  const std::size_t moon = 0, one = 1, cycles = 2;
  const int both = 0, above = 1, below = 2, all = 0, rough = 1, sum = 2;
  for (std::size_t f = 0; f < 3; ++f) EXPECT_EQ(s.at(f, both, all, sum).n, 192);
  EXPECT_TRUE(s.at(one, both, all, sum).within_noise());
  EXPECT_TRUE(s.at(cycles, both, all, sum).within_noise());
  EXPECT_TRUE(s.at(moon, above, all, sum).within_noise());
  EXPECT_FALSE(s.at(moon, below, all, sum).within_noise());
  EXPECT_LT(s.at(moon, below, all, sum).worst, 0.0);
  const GlassErrorStat& r = s.at(moon, above, rough, 0);
  EXPECT_GT(r.mean(), 0.0);
  EXPECT_FALSE(r.within_noise());
}

TEST(GlassEnergy, BadGridsAreNamed) {
  GlassGrid g;
  g.etas = {1.5};
  g.alphas = {0.5};
  g.mus = {0.5};
  auto message = [&](GlassGrid x) {
    try {
      check_glass_grid(x);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(g), "");
  GlassGrid x = g;
  x.etas = {1.0};
  EXPECT_NE(message(x).find("--eta = 1 is no interface"), std::string::npos);
  x.etas = {0.0};
  EXPECT_NE(message(x).find("--eta = 0 is out of range [0.1, 10]"), std::string::npos);
  x = g, x.ndfs = {NdfKind::phong};
  EXPECT_NE(message(x).find("--ndf = \"phong\""), std::string::npos);
  try {
    check_glass_grid(x, "");
  } catch (const std::exception& e) {
    EXPECT_EQ(std::string(e.what()).rfind("ndf = \"phong\"", 0), 0u) << e.what();  // Python's names
  }
  x = g, x.grooves = 0;
  EXPECT_NE(message(x).find("--grooves = 0 is out of range"), std::string::npos);
  try {
    glass_reference_from("walk");
    ADD_FAILURE() << "reference \"walk\" taken";
  } catch (const std::exception& e) {
    EXPECT_STREQ(e.what(), "--reference = \"walk\" is not one of \"vgroove\", \"smith_walk\"");
  }
  x = g, x.mus = {0.0};
  EXPECT_NE(message(x).find("--mu = 0 is out of range"), std::string::npos);
}

}  // namespace
}  // namespace vgroove::validation
