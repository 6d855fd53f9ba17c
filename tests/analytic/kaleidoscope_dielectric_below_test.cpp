// Tests of analytic/kaleidoscope_dielectric_below.h: one dielectric V-groove with flat rims lit from
// below. Conservation (every lobe, and a beam over facets and flat rims), eta = 1 (all light leaves
// up along theta_i), the flat groove (Fresnel and Snell by hand), F = 1 (everything reflected at
// hit 0), the chain's shares against Lee's Eq. (6) where a rim-line beam is unshadowed, and the model
// against exact split tracing (sim/dielectric_groove.h) per path signature by breakpoint search
// (validation/dielectric_grooves_case.h), with broken models that must fail.
//
// Tolerances. As tests/analytic/kaleidoscope_dielectric_test.cpp: the model's local angles are closed
// forms, the tracer's come from reflected direction vectors (~1e-15 per hit), each share a product of
// at most ~30 Fresnel factors times a zone width located to the ulp: the L1 over a facet's signatures
// is asserted below 1e-12 plus the model's own rounding bound (its change under a 64-ulp change of
// theta_i, validation::rounding_bound_below), directions likewise.
#include "vgroove/analytic/kaleidoscope_dielectric_below.h"

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/validation/dielectric_grooves_case.h"
#include "vgroove/validation/dielectric_grooves_suite.h"

#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

namespace vgroove::analytic {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

const double kEtas[] = {1.33, 1.5, 2.4, 1.0 / 1.33, 1.0 / 1.5, 1.0 / 2.4};

TEST(KaleidoscopeDielectricBelow, SharesSumToOne) {
  // Every ray aimed at a lit facet leaves, up or down, along one of the lobes: a telescoping sum
  // per hit (KD-7, KD-8). And a beam over a window: facets (R + T each) plus the flat rims
  // (F + (1 - F)) make all of it.
  double worst = 0.0, worst_beam = 0.0;
  long lit = 0;
  for (double eta : kEtas)
    for (double tv = 6.0; tv <= 180.0; tv += 7.0)
      for (double ti = -85.0; ti <= 85.0; ti += 5.0) {
        double facets = 0.0;
        const BelowBeamShares b = below_beam_shares(deg(ti), deg(tv), -3.0, 3.0);
        for (FacetSide side : {FacetSide::left, FacetSide::right}) {
          const DielectricBelowPrediction p = kaleidoscope_dielectric_below(deg(ti), deg(tv), eta, side);
          if (!p.lit) {
            EXPECT_EQ(b.facet[static_cast<int>(side)], 0.0);
            continue;
          }
          ++lit;
          const double sum = p.reflected_total() + p.transmitted_total();
          worst = std::max(worst, std::abs(sum - 1.0));
          for (const BelowLobe& l : p.lobes) EXPECT_GE(l.share, 0.0);
          facets += b.facet[static_cast<int>(side)] * sum;
        }
        const FlatBelowPrediction f = flat_rim_below(deg(ti), eta);
        const double flat = f.F + (f.tir ? 0.0 : 1.0 - f.F);
        worst_beam = std::max(worst_beam, std::abs(facets + b.flat * flat - 1.0));
      }
  std::printf("largest |R + T - 1| over %ld lit facets: %.3g; of a beam with the flat rims: %.3g\n", lit, worst,
              worst_beam);
  EXPECT_LT(worst, 1e-14);
  EXPECT_LT(worst_beam, 1e-14);
}

TEST(KaleidoscopeDielectricBelow, EtaOnePassesStraightThrough) {
  // eta = 1: F = 0 at every hit, nothing bends: all light leaves into medium 1 along theta_i (through
  // the opening, or across the other facet and the rim's underside).
  for (double tv : {20.0, 60.0, 90.0, 150.0, 180.0})
    for (double ti : {-70.0, -30.0, 0.0, 25.0, 60.0})
      for (FacetSide side : {FacetSide::left, FacetSide::right}) {
        const DielectricBelowPrediction p = kaleidoscope_dielectric_below(deg(ti), deg(tv), 1.0, side);
        if (!p.lit) continue;
        EXPECT_EQ(p.transmitted_total(), 1.0) << tv << " " << ti;
        for (const BelowLobe& l : p.lobes) {
          if (l.share == 0.0) continue;
          EXPECT_TRUE(l.up);
          EXPECT_NEAR(l.theta, deg(ti), 1e-14) << tv << " " << ti;
        }
      }
}

TEST(KaleidoscopeDielectricBelow, AFlatGrooveIsFresnelAndSnell) {
  // theta_v = pi: one hit, F(cos theta_i, 1/eta) back to -theta_i, the rest up along
  // asin(eta sin theta_i), as a flat rim.
  for (double eta : kEtas)
    for (double ti : {-75.0, -20.0, 0.0, 40.0, 70.0}) {
      const DielectricBelowPrediction p =
          kaleidoscope_dielectric_below(deg(ti), std::numbers::pi, eta, FacetSide::left);
      ASSERT_TRUE(p.lit);
      const double c = std::cos(deg(ti));
      const double s = std::sin(deg(ti));
      const bool tir = std::abs(eta * s) >= 1.0;
      const double F = tir ? 1.0 : optics::fresnel_dielectric(c, 1.0 / eta);
      EXPECT_NEAR(p.reflected_total(), F, 1e-15) << eta << " " << ti;
      EXPECT_EQ(p.n_max, 0);
      for (const BelowLobe& l : p.lobes)
        EXPECT_NEAR(l.theta, l.up ? std::asin(eta * s) : -deg(ti), 1e-15) << eta << " " << ti;
      const FlatBelowPrediction f = flat_rim_below(deg(ti), eta);
      EXPECT_NEAR(f.F, F, 1e-15);
      EXPECT_EQ(f.tir, tir);
    }
}

TEST(KaleidoscopeDielectricBelow, ConductorLimitReflectsAll) {
  // F = 1 at every hit: hit 0 reflects everything, once down or twice via the rim; the mirror image
  // of theta_i in the facet (2 (theta_v/2) - theta_i, as a downward exit angle).
  for (double tv : {30.0, 60.0, 90.0, 120.0})
    for (double ti : {-60.0, -10.0, 0.0, 10.0})
      for (FacetSide side : {FacetSide::left, FacetSide::right}) {
        const DielectricBelowPrediction p =
            kaleidoscope_dielectric_below_with(deg(ti), deg(tv), 1.5, side, [](double, double) { return 1.0; });
        if (!p.lit) continue;
        EXPECT_EQ(p.reflected_total(), 1.0);
        ASSERT_EQ(p.lobes.size(), 1u);
        const double t = side == FacetSide::left ? deg(ti) : -deg(ti);
        const double r = deg(tv) - t;  // hit 0's reflected direction (direction_at)
        const double down = std::cos(r) > 0.0 ? -r : std::remainder(r + std::numbers::pi, 2.0 * std::numbers::pi);
        EXPECT_NEAR(p.lobes[0].theta, side == FacetSide::left ? down : -down, 1e-15);
        EXPECT_EQ(p.lobes[0].k, std::cos(r) > 0.0 ? 2 : 1);
      }
}

TEST(KaleidoscopeDielectricBelow, ChainIsLeesWithoutTheShadow) {
  // KD-6: the chain's shares are Eq. (6)'s at the virtual angle theta' = theta_v/2 - pi/2 - alpha_t
  // (the beam whose reflection at the left facet is the refracted ray) with the whole facet lit: where
  // that beam is not shadowed (f_b = 0) they must be G_kaleidoscopic's, hit n + 1 of Lee's chain being
  // hit n of this one.
  long compared = 0;
  double worst = 0.0;
  for (double eta : kEtas)
    for (double tv = 20.0; tv <= 170.0; tv += 10.0)
      for (double ti = -80.0; ti <= 80.0; ti += 4.0) {
        const DielectricBelowPrediction p = kaleidoscope_dielectric_below(deg(ti), deg(tv), eta, FacetSide::left);
        if (!p.lit || p.tir0) continue;
        const double tp = 0.5 * deg(tv) - 0.5 * std::numbers::pi - p.alpha_t;
        if (!(std::abs(tp) < 0.5 * std::numbers::pi)) continue;
        const FacetPrediction g = G_kaleidoscopic(tp, deg(tv), FacetSide::left);
        if (!g.lit || g.shadow != 0.0) continue;
        ++compared;
        // G_n = A_n - A_{n+1} of this model.
        auto reach = [&](int n) {
          if (n == 0) return 1.0;
          return n <= p.n_max ? p.hits[static_cast<std::size_t>(n - 1)].reaching : 0.0;
        };
        for (const BounceShare& b : {g.fewer, g.more}) {
          const int n = b.n - 1;
          if (n < 0) continue;
          worst = std::max(worst, std::abs(reach(n) - reach(n + 1) - b.G));
        }
        EXPECT_LE(p.n_max, g.k) << eta << " " << tv << " " << ti;
      }
  std::printf("chain shares against Eq. (6) unshadowed: %ld cases, largest difference %.3g\n", compared, worst);
  EXPECT_GT(compared, 100);
  EXPECT_LT(worst, 1e-14);
}

// The model against the tracer over a grid, per facet: the largest L1 / (1e-12 + bound) and
// direction error / (1e-12 + bound) (pass: below 1); l1 and dir over the facets whose rounding bound
// is below 1e-9 (`boundary` counts the others: a lobe's fate flips within 64 ulps of theta_i, e.g.
// hit 0's reflection exactly horizontal at theta_i = theta_v - 90 deg, which the grid avoids).
struct GridResult {
  double l1 = 0.0, dir = 0.0, ratio = 0.0;
  long facets = 0, rays = 0, lobes = 0, boundary = 0;
};

template <class Model>
GridResult against_tracer(const std::vector<double>& etas, const std::vector<double>& tvs,
                          const std::vector<double>& tis, long grid, const Model& model) {
  GridResult out;
  for (double eta : etas)
    for (double tv : tvs)
      for (double ti : tis)
        for (Side side : {Side::left, Side::right}) {
          validation::DielectricGrooveCase c{deg(tv), deg(ti), eta, true};
          const DielectricBelowPrediction m = model(c, side);
          const validation::TracedBelowEnergy t = validation::trace_facet_energy_below(c, side, grid, 100000);
          const validation::DielectricFacetOutcome o = validation::compare_facet_below(m, t);
          if (!o.compared) continue;
          ++out.facets;
          out.rays += t.traced;
          out.lobes += static_cast<long>(m.lobes.size());
          double dir_bound = 0.0;
          const double bound = validation::rounding_bound_below(c, side, dir_bound);
          EXPECT_EQ(t.uncertified_cells, 0);
          EXPECT_LT(t.conservation, 1e-13);
          if (bound < 1e-9 && dir_bound < 1e-9) {
            out.l1 = std::max(out.l1, o.l1);
            out.dir = std::max(out.dir, o.direction_error);
          } else {
            ++out.boundary;
          }
          out.ratio = std::max(out.ratio, o.l1 / (1e-12 + bound));
          out.ratio = std::max(out.ratio, o.direction_error / (1e-12 + dir_bound));
        }
  return out;
}

DielectricBelowPrediction the_model(const validation::DielectricGrooveCase& c, Side side) {
  return kaleidoscope_dielectric_below(c.theta_i, c.theta_v, c.eta, side);
}

const std::vector<double> kGridEtas = {1.33, 1.5, 2.4, 1.0 / 1.33, 1.0 / 1.5, 1.0 / 2.4};
const std::vector<double> kGridApertures = {12.0, 20.0, 40.0, 60.0, 75.0, 90.0, 105.0, 120.0, 150.0, 180.0};
const std::vector<double> kGridAngles = {-85.0, -62.0, -37.0, -12.0, 3.0, 17.0, 33.0, 57.0, 80.0};

TEST(KaleidoscopeDielectricBelowTracer, MatchesSplitTracingToRounding) {
  const auto t0 = std::chrono::steady_clock::now();
  const GridResult r = against_tracer(kGridEtas, kGridApertures, kGridAngles, 16, the_model);
  const double ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf(
      "from below: %ld lit facets (%ld at a boundary), %ld lobes, %ld rays: largest L1 %.3g, direction "
      "%.3g rad; largest ratio to 1e-12 + the rounding bound %.3g (%.0f ms)\n",
      r.facets, r.boundary, r.lobes, r.rays, r.l1, r.dir, r.ratio, ms);
  EXPECT_GT(r.facets, 500);
  EXPECT_LT(r.ratio, 1.0);
}

TEST(KaleidoscopeDielectricBelowTracer, BrokenModelsFail) {
  // 1. The chain started as a parallel beam at the rim line (the from-above construction, its
  //    shadowed part dropped): wrong wherever that beam is shadowed.
  const GridResult rim = against_tracer(
      kGridEtas, kGridApertures, kGridAngles, 16, [](const validation::DielectricGrooveCase& c, Side side) {
        return kaleidoscope_dielectric_below_with(
            c.theta_i, c.theta_v, c.eta, side, [](double x, double e) { return optics::fresnel_dielectric(x, e); },
            BelowChainSource::rim_line_beam);
      });
  // 2. Hit 0 refracted with Snell's eta instead of 1/eta (sin alpha_t = sin alpha_i / eta).
  const GridResult snell =
      against_tracer({1.5}, {60.0, 90.0}, {0.0, 30.0}, 16, [](const validation::DielectricGrooveCase& c, Side side) {
        return kaleidoscope_dielectric_below(c.theta_i, c.theta_v, 1.0 / c.eta, side);
      });
  std::printf(
      "broken (largest L1 off boundaries, ratio to the bound): rim-line beam %.3g (%.3g); eta for 1/eta %.3g "
      "(%.3g)\n",
      rim.l1, rim.ratio, snell.l1, snell.ratio);
  EXPECT_GT(rim.ratio, 1e6);
  EXPECT_GT(snell.ratio, 1e6);
}

TEST(KaleidoscopeDielectricBelowLong, DenseGridMatchesSplitTracingToRounding) {
  // The same check over a dense grid: eight etas (1.05 and 1/1.05 near the critical angle's corner
  // besides the six), theta_v 6-180 deg in 5.1 deg steps, theta_i -89..89 deg in 2.3 deg steps.
  std::vector<double> tvs, tis;
  for (double tv = 6.0; tv <= 180.0; tv += 5.1) tvs.push_back(tv);
  for (double ti = -89.0; ti <= 89.0; ti += 2.3) tis.push_back(ti);
  std::vector<double> etas = kGridEtas;
  etas.push_back(1.05);
  etas.push_back(1.0 / 1.05);
  const GridResult r = against_tracer(etas, tvs, tis, 16, the_model);
  std::printf(
      "dense grid from below: %ld lit facets (%ld at a boundary), %ld lobes, %ld rays: largest L1 %.3g, "
      "direction %.3g rad; largest ratio to 1e-12 + the rounding bound %.3g\n",
      r.facets, r.boundary, r.lobes, r.rays, r.l1, r.dir, r.ratio);
  EXPECT_GT(r.facets, 30000);
  EXPECT_LT(r.ratio, 1.0);
}

nlohmann::json shipped_suite() {
  std::ifstream in(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/dielectric_grooves.json");
  return nlohmann::json::parse(in);
}

TEST(DielectricGroovesSuiteBelow, FromBelowCasesRunAfterTheOthersAndPassToRounding) {
  nlohmann::json j = shipped_suite();
  const validation::DielectricGroovesSuite full =
      validation::parse_dielectric_grooves_suite(j, "dielectric_grooves.json");
  EXPECT_EQ(full.cases(), full.above_cases() + 6u * full.below_theta_v.size() * full.below_theta_i.size());
  EXPECT_FALSE(full.case_at(full.above_cases() - 1).below);
  EXPECT_TRUE(full.case_at(full.above_cases()).below);
  j["theta_v_deg"] = {90};
  j["theta_i_deg"] = {10};
  j["surface_rays"] = 0;
  j["from_below"] = {{"theta_v_deg", {20, 75, 130}}, {"theta_i_deg", {-50, 8, 62}}};
  const validation::DielectricGroovesSuite s = validation::parse_dielectric_grooves_suite(j, "small.json");
  ASSERT_EQ(s.cases(), 6u + 54u);
  double largest = 0.0;
  for (std::size_t c = s.above_cases(); c < s.cases(); ++c) {
    const validation::DielectricGroovesOutcome o = validation::run_dielectric_grooves_case(s, s.case_at(c));
    EXPECT_TRUE(o.pass) << "case " << c << " l1 " << o.l1 << " dir " << o.direction_error;
    EXPECT_NEAR(o.reflected + o.transmitted, 1.0, 1e-14);
    largest = std::max(largest, o.l1);
  }
  ASSERT_GT(largest, 0.0);  // rounding shows: a threshold of 0 must fail somewhere
  j["thresholds"]["max_l1"] = 0.0;
  const validation::DielectricGroovesSuite strict = validation::parse_dielectric_grooves_suite(j, "small.json");
  int failed = 0;
  for (std::size_t c = strict.above_cases(); c < strict.cases(); ++c)
    failed += !validation::run_dielectric_grooves_case(strict, strict.case_at(c)).pass;
  EXPECT_GT(failed, 0);
}

TEST(DielectricGroovesSuiteBelow, BadInputNamesTheField) {
  const auto message = [](const nlohmann::json& below) {
    nlohmann::json j = shipped_suite();
    j["from_below"] = below;
    try {
      (void)validation::parse_dielectric_grooves_suite(j, "bad.json");
    } catch (const support::UserError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message({{"theta_v_deg", {0.5}}, {"theta_i_deg", {0}}}),
            "bad.json: /from_below/theta_v_deg/0 = 0.5 is out of range [6, 180]");
  EXPECT_EQ(message({{"theta_v_deg", {60}}, {"theta_i_deg", {90}}}),
            "bad.json: /from_below/theta_i_deg/0 = 90 is out of range [-89.999, 89.999]");
  EXPECT_NE(message({{"theta_v_deg", {60}}, {"theta_i_deg", {0}}, {"eta", {1.5}}}).find("/from_below/eta"),
            std::string::npos);
  EXPECT_NE(message({{"theta_v_deg", {60}}}).find("/from_below/theta_i_deg"), std::string::npos);
}

}  // namespace
}  // namespace vgroove::analytic
