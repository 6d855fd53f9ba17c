// The "dielectric_brdf" suite (validation/dielectric_brdf_suite.h): a tiny suite passes the
// tracer's own checks, energy is conserved per ray, the report does not depend on the thread
// count, the walk's control fails when it is broken on purpose, the kaleidoscopic model is wired
// from both sides, and bad specs name the field.
#include "vgroove/validation/dielectric_brdf_suite.h"

#include "tests/test_files.h"
#include "tests/user_error_of.h"
#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;

// The one-line refusal of a suite (a test failure if it is read).
std::string refusal(const json& j) {
  return testing_files::user_error_of([&] { parse_dielectric_brdf_suite(j, "x.json"); });
}

json shipped(const std::string& name) {
  return json::parse(testing_files::read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/" + name));
}

// One case per surface kind and dimension, light from both sides, few rays.
json tiny() {
  return json{{"name", "tiny"},
              {"kind", "dielectric_brdf"},
              {"surfaces", {"vgroove", "profiles"}},
              {"dimensions", {"flatland", "3d"}},
              {"ndf", {"ggx"}},
              {"alpha", {0.4}},
              {"theta_i_deg", {40}},
              {"eta", {1.5}},
              {"sides", {"above", "below"}},
              {"rays", 20000},
              {"walk_paths", 20000},
              {"grooves", 5000},
              {"realizations", 2},
              {"segments", 4096},
              {"flatland_bins", 18},
              {"theta_bins", 6},
              {"phi_bins", 8},
              {"max_k", 3},
              {"thresholds", {{"sigmas", 5}}}};
}

// Times apart, the report as text.
std::string without_times(json j) {
  j.erase("wall_s"), j.erase("threads");
  j["summary"].erase("wall_s");
  for (auto& c : j["cases"]) c.erase("wall_s");
  return j.dump();
}

TEST(DielectricBrdfSuite, TinySuitePassesItsChecks) {
  const DielectricBrdfSuite s = parse_dielectric_brdf_suite(tiny(), "tiny.json");
  ASSERT_EQ(s.cases(), 6u);  // vgroove flatland and 3D, profiles flatland; two sides each
  const DielectricBrdfRun run = run_dielectric_brdf_suite(s, 0, 2);
  for (const DielectricBrdfOutcome& o : run.cases) {
    ASSERT_TRUE(o.control.has_value());
    EXPECT_TRUE(o.control->holds) << dielectric_surface_name(o.c.surface) << " " << surface_dim_name(o.c.dim) << " R z "
                                  << o.control->z_reflected << " L1 " << o.control->l1_reflected << " / "
                                  << o.control->threshold_reflected << ", T z " << o.control->z_transmitted << " L1 "
                                  << o.control->l1_transmitted << " / " << o.control->threshold_transmitted;
    EXPECT_EQ(o.models.size(), 4u);
    // Both hemispheres receive light and every path signature's energy adds up to the lobes'.
    EXPECT_GT(o.reflected.energy, 0.0);
    EXPECT_GT(o.transmitted.energy, 0.0);
    double paths = 0.0, rows = 0.0;
    for (const PathShare& p : o.paths) paths += p.traced;
    for (int k = 0; k <= s.max_k; ++k) rows += o.reflected.by_k[k] + o.transmitted.by_k[k];
    EXPECT_NEAR(paths, rows, 1e-12);
    EXPECT_TRUE(o.pass);
  }
  EXPECT_TRUE(run.pass);
}

TEST(DielectricBrdfSuite, EnergyIsConservedPerRay) {
  json j = tiny();
  j["surfaces"] = {"vgroove"};
  j["alpha"] = {1.0};  // deep grooves: many interactions, TIR from below
  j["theta_i_deg"] = {80};
  j["rays"] = 10000;
  j["models"] = {"walter_vcavity"};
  j["max_interactions"] = 3;  // paths end at the limit too: their energy must be counted
  const DielectricBrdfSuite s = parse_dielectric_brdf_suite(j, "tiny.json");
  const DielectricBrdfRun run = run_dielectric_brdf_suite(s, 0, 2);
  for (const DielectricBrdfOutcome& o : run.cases) {
    EXPECT_EQ(o.unbalanced, 0);
    EXPECT_LE(o.largest_imbalance, 1e-12);
    // Random branching: every ray leaves whole, so the fractions add up to 1 to rounding.
    EXPECT_NEAR(o.reflected.energy + o.transmitted.energy + o.cut + o.bounce_limit + o.vertex, 1.0, 1e-12);
    EXPECT_GT(o.interactions, o.rays);
    EXPECT_GT(o.bounce_limit, 0.0);
  }
}

TEST(DielectricBrdfSuite, ThreadCountChangesNothing) {
  json j = tiny();
  j["rays"] = 5000, j["walk_paths"] = 5000;
  const DielectricBrdfSuite s = parse_dielectric_brdf_suite(j, "tiny.json");
  const std::string one = without_times(dielectric_brdf_report_json(s, run_dielectric_brdf_suite(s, 0, 1)));
  const std::string two = without_times(dielectric_brdf_report_json(s, run_dielectric_brdf_suite(s, 0, 2)));
  EXPECT_EQ(one, two);
}

// Walter-Smith with eta inverted is no control for the walk: the verdict must catch it.
TEST(DielectricBrdfSuite, ABrokenControlFails) {
  json j = tiny();
  j["surfaces"] = {"vgroove"};
  j["dimensions"] = {"flatland"};
  j["theta_i_deg"] = {20};
  j["models"] = {"smith_walk"};
  DielectricBrdfSuite s = parse_dielectric_brdf_suite(j, "tiny.json");
  s.break_control = true;
  const DielectricBrdfRun run = run_dielectric_brdf_suite(s, 0, 2);
  for (const DielectricBrdfOutcome& o : run.cases) {
    ASSERT_TRUE(o.control.has_value());
    EXPECT_FALSE(o.control->holds) << "T z " << o.control->z_transmitted;
    EXPECT_FALSE(o.pass);
  }
  EXPECT_FALSE(run.pass);
}

// The kaleidoscopic model (analytic/kaleidoscope_dielectric_lobe.h) in the suite's rows and bins:
// on flatland Beckmann grooves of alpha 0.1 it matches the traced lobes from either side (light
// from below is its model at 1 / eta mirrored: the lobes reversed would miss by many thresholds).
TEST(DielectricBrdfSuite, TheKaleidoscopicModelIsWiredFromBothSides) {
  json j = tiny();
  j["surfaces"] = {"vgroove"};
  j["dimensions"] = {"flatland"};
  j["ndf"] = {"beckmann"};
  j["alpha"] = {0.1};
  j["theta_i_deg"] = {30};
  j["models"] = {"kaleidoscopic"};
  const DielectricBrdfSuite s = parse_dielectric_brdf_suite(j, "tiny.json");
  const DielectricBrdfRun run = run_dielectric_brdf_suite(s, 0, 2);
  ASSERT_EQ(run.cases.size(), 2u);
  for (const DielectricBrdfOutcome& o : run.cases) {
    ASSERT_EQ(o.models.size(), 1u);
    const ModelOutcome& m = o.models[0];
    EXPECT_TRUE(m.matches_all) << sim::medium_name(o.c.side) << ": L1 R " << m.fit_reflected.l1_all << " / "
                               << m.fit_reflected.threshold_all << ", T " << m.fit_transmitted.l1_all << " / "
                               << m.fit_transmitted.threshold_all;
  }
}

TEST(DielectricBrdfSuite, BadSpecsNameTheFieldAndRange) {
  json j = tiny();
  j["eta"] = {0.0};
  EXPECT_NE(refusal(j).find("/eta"), std::string::npos) << refusal(j);
  j = tiny();
  j["sides"] = {"left"};
  EXPECT_NE(refusal(j).find("/sides"), std::string::npos) << refusal(j);
  j = tiny();
  j["theta_i_deg"] = {90};
  EXPECT_NE(refusal(j).find("/theta_i_deg"), std::string::npos) << refusal(j);
  j = tiny();
  j["models"] = {"walter"};
  EXPECT_NE(refusal(j).find("/models"), std::string::npos) << refusal(j);
  j = tiny();
  j["surfaces"] = {"profiles"};
  j["dimensions"] = {"3d"};
  EXPECT_NE(refusal(j).find("flatland only"), std::string::npos) << refusal(j);
  j = tiny();
  j["max_k"] = 0;
  EXPECT_NE(refusal(j).find("max_k"), std::string::npos) << refusal(j);
  j = tiny();
  j["extra"] = 1;
  EXPECT_NE(refusal(j).find("extra"), std::string::npos) << refusal(j);
}

TEST(DielectricBrdfSuite, ShippedSuitesParse) {
  const DielectricBrdfSuite b = parse_dielectric_brdf_suite(shipped("dielectric_brdf.json"), "dielectric_brdf.json");
  EXPECT_GT(b.cases(), 0u);
  EXPECT_EQ(b.case_list.front().surface, DielectricSurface::vgroove);
  const DielectricBrdfSuite p =
      parse_dielectric_brdf_suite(shipped("dielectric_profiles.json"), "dielectric_profiles.json");
  EXPECT_GT(p.cases(), 0u);
  for (const DielectricBrdfCase& c : p.case_list) EXPECT_EQ(c.surface, DielectricSurface::profiles);
}

}  // namespace
}  // namespace vgroove::validation
