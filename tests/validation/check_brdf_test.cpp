// Tests of the check-my-BRDF API: vgroove's own model passes, Cook-Torrance fails where it loses
// energy, a model a few percent off is caught, the thresholds do not depend on the thread count.
#include "vgroove/validation/check_brdf.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>

#include <limits>

#include <atomic>

#include <cmath>

namespace vgroove::validation {
namespace {

// The single pass visits only the orders Eq. (4) allows, so a huge max_k costs nothing and
// leaves no tail out (at alpha 1 a tenth of the flux is beyond k = 16).
constexpr int kAllOrders = 1'000'000;

CheckBrdfOptions small_3d(double alpha) {
  CheckBrdfOptions o;
  o.alpha = alpha;
  o.theta_i_deg = {0, 40, 80};
  o.rays = 200'000;
  o.grooves = 100'000;
  o.seed = 7;
  o.threads = 2;
  return o;
}

BrdfFn vgroove_model(const CheckBrdfOptions& o, double scale = 1.0) {
  return [=](const analytic::Dir3& wi, const analytic::Dir3& wo) {
    return scale * analytic::vgroove_brdf(wi, wo, o.ndf, o.alpha, kAllOrders);
  };
}

std::string dump(const CheckBrdfResult& r) { return r.to_json().dump(1); }

TEST(CheckBrdf, VgrooveModelPasses3d) {
  const CheckBrdfOptions o = small_3d(0.5);
  const CheckBrdfResult r = check_brdf(vgroove_model(o), o);
  ASSERT_EQ(r.cases.size(), 3u);
  EXPECT_TRUE(r.pass) << dump(r);
  for (const CheckBrdfCase& c : r.cases) {
    EXPECT_NEAR(c.albedo_model, 1.0, 2e-4) << "theta_i " << c.theta_i_deg;  // F = 1: nothing is lost
    EXPECT_LE(c.model_error, o.model_tolerance * 1.0001);
  }
}

// A value that is not a BRDF's (NaN, an infinity, a negative number) fails the check at the first
// rule that meets it: a UserError naming the value and its directions, before the surface is
// traced, not after the first rule over every bin (720 bins, 3,600 calls of a Python callback,
// 0.2 s) or the whole cubature (4 x 10^6 calls, 18-26 s per angle) as a failed case (non_finite). Seen failing with the
// check in BinIntegrator::rule removed.
TEST(CheckBrdf, AValueThatIsNotABrdfsFailsAtOnceNamingItsDirections) {
  CheckBrdfOptions o = small_3d(0.5);
  o.theta_i_deg = {40};
  o.rays = 20'000;
  o.grooves = 10'000;
  const double inf = std::numeric_limits<double>::infinity();
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), -1.0, inf, -inf, -1e-300}) {
    std::atomic<std::int64_t> calls{0};
    analytic::Dir3 at_i, at_o;
    const BrdfFn base = vgroove_model(o);
    const BrdfFn f = [&](const analytic::Dir3& wi, const analytic::Dir3& wo) {
      if (wo.z > 0.99 && calls.fetch_add(1) == 0) at_i = wi, at_o = wo;
      return wo.z > 0.99 ? bad : base(wi, wo);  // the first bins, around the normal
    };
    try {
      (void)check_brdf(f, o);
      FAIL() << bad << " accepted";
    } catch (const support::UserError& e) {
      auto v = [](const analytic::Dir3& d) {
        return "(" + support::number_text(d.x) + ", " + support::number_text(d.y) + ", " + support::number_text(d.z) +
               ")";
      };
      EXPECT_EQ(std::string(e.what()), "f(wi, wo) = " + support::number_text(bad) + " at wi = " + v(at_i) + ", wo = " +
                                           v(at_o) + " (theta_i_deg 40): a BRDF's values must be finite and >= 0");
    }
    // One rule's nodes: the first bin's first rule already holds the bad value.
    EXPECT_LE(calls.load(), o.quadrature_order * o.quadrature_order) << bad;
  }
  // -0 is 0: accepted (the check fails on its albedo instead).
  const CheckBrdfResult r = check_brdf([](const analytic::Dir3&, const analytic::Dir3&) { return -0.0; }, o);
  EXPECT_FALSE(r.pass);
  EXPECT_FALSE(r.cases[0].non_finite);
}

// With several incident angles, the first one (in the options' order) whose model meets a bad
// value is the one named, for any thread count: the angles after it stop, those before run on.
TEST(CheckBrdf, TheFirstAngleWithABadValueIsNamedForAnyThreadCount) {
  CheckBrdfOptions o = small_3d(0.5);
  o.theta_i_deg = {0, 40, 80};
  o.rays = 20'000;
  o.grooves = 10'000;
  o.max_model_evals = 200'000;
  for (int threads : {1, 2, 3}) {
    o.threads = threads;
    const BrdfFn base = vgroove_model(o);
    // Bad from theta_i 40 on, and late in theta_i 40's first pass (wo near the horizon).
    const BrdfFn f = [&](const analytic::Dir3& wi, const analytic::Dir3& wo) {
      return wi.z < 0.9 && wo.z < 0.05 ? std::numeric_limits<double>::quiet_NaN() : base(wi, wo);
    };
    try {
      (void)check_brdf(f, o);
      FAIL() << "accepted";
    } catch (const support::UserError& e) {
      EXPECT_NE(std::string(e.what()).find("(theta_i_deg 40): a BRDF's values"), std::string::npos)
          << threads << " threads: " << e.what();
    }
  }
}

TEST(CheckBrdf, CookTorranceFailsAtHighRoughness) {
  const CheckBrdfOptions o = small_3d(1.0);
  const CheckBrdfResult r =
      check_brdf([&](const analytic::Dir3& wi,
                     const analytic::Dir3& wo) { return analytic::cook_torrance(wi, wo, o.ndf, o.alpha); },
                 o);
  EXPECT_FALSE(r.pass);
  // The furnace's figure: Cook-Torrance with the V-cavity G keeps 0.375 of the light at normal
  // incidence on GGX alpha = 1 (3D); the traced surface keeps all of it.
  EXPECT_NEAR(r.cases[0].albedo_model, 0.375, 2e-3);
  EXPECT_NEAR(r.cases[0].albedo_sim, 1.0, 1e-12);
  EXPECT_FALSE(r.cases[0].pass);
}

// Power: the right lobe with 2 % of its energy missing fails on the albedo alone.
TEST(CheckBrdf, TwoPercentLessEnergyFails) {
  const CheckBrdfOptions o = small_3d(0.5);
  const CheckBrdfResult r = check_brdf(vgroove_model(o, 0.98), o);
  EXPECT_FALSE(r.pass);
  for (const CheckBrdfCase& c : r.cases) {
    EXPECT_FALSE(c.pass) << "theta_i " << c.theta_i_deg;
    EXPECT_GT(std::abs(c.albedo_sim - c.albedo_model), c.albedo_threshold);
  }
}

// Power: the right energy with the wrong shape (the model of a 20 % smoother surface) fails on L1.
TEST(CheckBrdf, WrongRoughnessFailsOnShape) {
  CheckBrdfOptions o = small_3d(0.5);
  CheckBrdfOptions other = o;
  other.alpha = 0.4;
  const CheckBrdfResult r = check_brdf(vgroove_model(other), o);
  EXPECT_FALSE(r.pass);
  for (const CheckBrdfCase& c : r.cases) EXPECT_GT(c.l1, c.l1_threshold) << "theta_i " << c.theta_i_deg;
}

TEST(CheckBrdf, VgrooveModelPassesFlatland) {
  CheckBrdfOptions o = small_3d(0.7);
  o.dim = SurfaceDim::flatland;
  const CheckBrdfResult r = check_brdf(
      [&](const analytic::Dir3& wi, const analytic::Dir3& wo) {
        // Flatland directions lie in y = 0: the signed 2D angle of (x, 0, z) is atan2(-x, z); k > 64
        // carries < 2e-4 of the flux here.
        return analytic::flatland_brdf(o.ndf, o.alpha, std::atan2(-wi.x, wi.z), std::atan2(-wo.x, wo.z), 64);
      },
      o);
  EXPECT_TRUE(r.pass) << dump(r);
}

TEST(CheckBrdf, ResultsDoNotDependOnThreads) {
  CheckBrdfOptions o = small_3d(0.3);
  o.theta_i_deg = {30};
  o.rays = 70'000;  // three chunks
  o.threads = 1;
  const CheckBrdfResult a = check_brdf(vgroove_model(o), o);
  o.threads = 2;
  const CheckBrdfResult b = check_brdf(vgroove_model(o), o);
  EXPECT_EQ(a.cases[0].albedo_sim, b.cases[0].albedo_sim);
  EXPECT_EQ(a.cases[0].l1, b.cases[0].l1);
  EXPECT_EQ(a.cases[0].l1_flux, b.cases[0].l1_flux);
  EXPECT_EQ(a.cases[0].albedo_model, b.cases[0].albedo_model);
}

TEST(CheckBrdf, BadOptionsNameTheField) {
  // The refusal's line, or "accepted".
  const auto refusal = [](const CheckBrdfOptions& opt) -> std::string {
    try {
      check_options(opt);
    } catch (const support::UserError& e) {
      return e.what();
    }
    return "accepted";
  };
  CheckBrdfOptions o;
  o.alpha = 3.0;
  EXPECT_EQ(refusal(o), "alpha = 3 is out of range [0.01, 2]");
  // The one alpha range of every face (validation/ranges.h), below as above.
  o.alpha = 0.005;
  EXPECT_EQ(refusal(o), "alpha = 0.005 is out of range [0.01, 2]");
  o = {};
  // The suites' range (validation::kMaxSurfaceThetaIDeg), as `validate` says it.
  o.theta_i_deg = {10, 89.95};
  try {
    check_options(o);
    FAIL() << "theta_i 89.95 accepted";
  } catch (const support::UserError& e) {
    EXPECT_STREQ(e.what(), "theta_i_deg = 89.95 is out of range [0, 89.9]");
  }
  o.theta_i_deg = {10, 89.9};
  EXPECT_NO_THROW(check_options(o));
  o = {};
  o.phi_bins = 7;
  EXPECT_THROW(check_options(o), support::UserError);
  o = {};
  o.rays = 0;
  EXPECT_THROW(check_options(o), support::UserError);
}

// check_lobes on hand-made histograms: equal lobes pass; a bin moved fails.
TEST(CheckBrdf, CompareLobesByHand) {
  const std::vector<double> p = {0.25, 0.25, 0.25, 0.25};
  const CheckBrdfCase same = check_lobes(p, p, 1e6, 1e6, 5.0, 0.0);
  EXPECT_TRUE(same.pass);
  EXPECT_EQ(same.l1, 0.0);
  const std::vector<double> moved = {0.35, 0.15, 0.25, 0.25};
  const CheckBrdfCase off = check_lobes(moved, p, 1e6, 1e6, 5.0, 0.0);
  EXPECT_NEAR(off.l1, 0.2, 1e-15);
  EXPECT_FALSE(off.pass);
}

}  // namespace
}  // namespace vgroove::validation
