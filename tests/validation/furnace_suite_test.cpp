// The white furnace of the BRDF itself (validation/furnace_suite.h): Eq. (17) passes by both
// routes, a deliberately broken Eq. (16) (the Jacobian of Eq. 13 off by (k + 1)/k for k >= 2)
// fails by both, Cook-Torrance's two routes agree, and the spec is read strictly.
#include "vgroove/validation/furnace_suite.h"

#include "tests/test_files.h"
#include "vgroove/analytic/kaleidoscope_solutions.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <tuple>

namespace vgroove::validation {
namespace {

using nlohmann::json;

json furnace_spec() {
  return json::parse(testing_files::read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/furnace.json"));
}

FurnaceSuite small_suite() {
  FurnaceSuite s = parse_furnace_suite(furnace_spec(), "furnace.json");
  s.samples = 20000;
  s.rays = s.grooves = 2000;
  return s;
}

// Eq. (16) with |ds/do| multiplied by (k + 1)/k for k >= 2 (the error a wrong Eq. 13 would make):
// the term brdf_3d.cpp sums, written out here with the one change.
double broken_brdf_3d(const analytic::Dir3& i, const analytic::Dir3& o, analytic::NdfKind ndf, double alpha,
                      int max_k) {
  analytic::GrooveFrame f;
  if (!(i.z > 0.0 && o.z > 0.0) || !analytic::groove_frame(i, o, f)) return 0.0;
  double sum = 0.0;
  analytic::for_each_solution(f.x, 1, max_k, [&](const analytic::Solution& q) {
    double ratio = q.k == 1 ? 1.0 : q.C / (q.k * f.sin_h);
    if (q.k >= 2) ratio *= (q.k + 1.0) / q.k;  // the deliberate error
    sum += ratio * f.c * q.W * analytic::D_cs(ndf, q.S, q.C, alpha) / (4.0 * f.cos_d * i.z * o.z);
  });
  return sum;
}

double broken_brdf_flatland(double ti, double to, analytic::NdfKind ndf, double alpha, int max_k) {
  if (!(std::abs(ti) < 0.5 * std::numbers::pi && std::abs(to) < 0.5 * std::numbers::pi)) return 0.0;
  const double m = ti + to > 0.0 ? -1.0 : 1.0;
  double sum = 0.0;
  analytic::for_each_solution(analytic::cross_section(m * ti, m * to), 1, max_k, [&](const analytic::Solution& q) {
    double jac = 1.0 / (2.0 * q.k);
    if (q.k >= 2) jac *= (q.k + 1.0) / q.k;  // the deliberate error
    sum += analytic::D2_cs(ndf, q.S, q.C, alpha) * q.W * jac;
  });
  return sum / (std::cos(ti) * std::cos(to));
}

TEST(FurnaceSuite, ShippedSuiteParses) {
  const FurnaceSuite s = parse_furnace_suite(furnace_spec(), "furnace.json");
  EXPECT_EQ(s.cases(), 3u * 8u * 5u * 2u);
  EXPECT_EQ(s.strategy, analytic::FacetStrategy::vndf);
  EXPECT_EQ(s.tolerance_3d, 1e-6);
}

TEST(FurnaceSuite, BadSpecsNameTheField) {
  auto expect_error = [](const json& j, const std::string& part) {
    try {
      parse_furnace_suite(j, "f.json");
      ADD_FAILURE() << "no UserError";
    } catch (const support::UserError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  json j = furnace_spec();
  j["samlpes"] = 5;
  expect_error(j, "f.json: /samlpes is not a known key");
  j = furnace_spec();
  j["strategy"] = "bounded-vndf";
  expect_error(j, "f.json: /strategy = \"bounded-vndf\" does not exist for ggx in flatland");
  j = furnace_spec();
  j["max_k"] = 0;
  expect_error(j, "f.json: /max_k = 0 is out of range");
  j = furnace_spec();
  j["thresholds"]["quadrature_tolerance"].erase("3d");
  expect_error(j, "f.json: /thresholds/quadrature_tolerance/3d");
}

// Eq. (17) passes: energy by quadrature, the estimator, Cook-Torrance's two routes, the sanity line.
TEST(FurnaceSuite, Eq17PassesBothRoutes) {
  const FurnaceSuite s = small_suite();
  for (SurfaceDim dim : {SurfaceDim::flatland, SurfaceDim::three_d})
    for (const auto& [ndf, alpha, deg] :
         {std::tuple{analytic::NdfKind::ggx, 0.7, 30.0}, std::tuple{analytic::NdfKind::phong, 1.5, 60.0},
          std::tuple{analytic::NdfKind::beckmann, 0.1, 80.0}}) {
      const FurnaceOutcome o = run_furnace_case(s, BrdfCase{ndf, alpha, deg * kRadPerDeg, dim});
      EXPECT_TRUE(o.pass) << surface_dim_name(dim) << " " << analytic::ndf_name(ndf) << " alpha=" << alpha
                          << " theta_i=" << deg << ": energy " << o.albedo_quadrature + o.flux_beyond_max_k - 1.0
                          << ", estimate " << o.albedo_estimate + o.flux_beyond_max_k - 1.0 << " (se "
                          << o.standard_error << "), CT " << o.cook_torrance_quadrature << " vs "
                          << o.cook_torrance_estimate << " (se " << o.cook_torrance_standard_error << ")";
      EXPECT_LT(o.cook_torrance_quadrature, 0.97);  // what single scattering loses at these roughnesses
    }
}

// The broken variant fails by both routes: the quadrature's albedo is off by far more than the
// tolerance, and the estimator's by far more than its standard errors.
TEST(FurnaceSuite, BrokenJacobianFailsBothRoutes) {
  const FurnaceSuite s = small_suite();
  const analytic::NdfKind ndf = analytic::NdfKind::ggx;
  const double alpha = 0.7, ti = 30.0 * kRadPerDeg;
  BrdfUnderTest broken;
  broken.rho3 = [&](const analytic::Dir3& i, const analytic::Dir3& o) {
    return broken_brdf_3d(i, o, ndf, alpha, s.max_k);
  };
  broken.rho2 = [&](double a, double b) { return broken_brdf_flatland(a, b, ndf, alpha, s.max_k); };
  for (SurfaceDim dim : {SurfaceDim::flatland, SurfaceDim::three_d}) {
    const FurnaceOutcome o = run_furnace_case(s, BrdfCase{ndf, alpha, ti, dim}, broken);
    EXPECT_FALSE(o.energy_ok) << surface_dim_name(dim) << " energy " << o.albedo_quadrature + o.flux_beyond_max_k - 1.0;
    EXPECT_FALSE(o.estimate_ok) << surface_dim_name(dim) << " estimate "
                                << o.albedo_estimate + o.flux_beyond_max_k - 1.0 << " se " << o.standard_error;
    EXPECT_FALSE(o.pass);
    // The albedo is raised by the multiply scattered share, ~ (k+1)/k - 1 of the k >= 2 flux.
    EXPECT_GT(o.albedo_quadrature, 1.05) << surface_dim_name(dim);
  }
}

}  // namespace
}  // namespace vgroove::validation
