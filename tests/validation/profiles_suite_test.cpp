// The "profiles" suite (validation/profiles_suite.h): a strict spec, a small run that passes and
// gives the same results on one thread as on two, and a report with what a plot needs.
#include "vgroove/validation/profiles_suite.h"

#include "tests/test_files.h"
#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;

#define EXPECT_USER_ERROR(stmt, part)                                           \
  try {                                                                         \
    stmt;                                                                       \
    ADD_FAILURE() << "no support::UserError";                                   \
  } catch (const support::UserError& e) {                                       \
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what(); \
  }

json shipped() {
  return json::parse(testing_files::read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/profiles.json"));
}

// A small suite: one NDF and roughness, normal and grazing, both surfaces.
json small(const std::string& ndf) {
  json j = shipped();
  j["ndf"] = {ndf};
  j["alpha"] = {0.5};
  j["theta_deg"] = {0, 70};
  j["realizations"] = 2;
  j["segments"] = 4096;
  j["rays"] = 20000;
  j["walk_paths"] = 20000;
  return j;
}

TEST(ProfilesSuite, ShippedSuiteParses) {
  const ProfilesSuite s = parse_profiles_suite(shipped(), "profiles.json");
  EXPECT_EQ(s.cases(), 2u * 4u * 5u);
  EXPECT_EQ(s.surfaces.size(), 2u);
  EXPECT_EQ(s.verdict_tests(), 40 * 2);
  const ProfilesCase last = s.case_at(s.cases() - 1);
  EXPECT_EQ(last.ndf, analytic::NdfKind::ggx);
  EXPECT_DOUBLE_EQ(last.alpha, 1.0);
  EXPECT_NEAR(last.theta, 80.0 * std::numbers::pi / 180.0, 1e-15);
}

TEST(ProfilesSuite, BadSpecsNameTheFieldAndRange) {
  json j = shipped();
  j["realisations"] = 3;
  EXPECT_USER_ERROR(parse_profiles_suite(j, "p.json"), "p.json: /realisations is not a known key");
  j = shipped();
  j["ndf"] = {"phong"};
  EXPECT_USER_ERROR(parse_profiles_suite(j, "p.json"),
                    "p.json: /ndf/0 = \"phong\" is not one of \"beckmann\", \"ggx\"");
  j = shipped();
  j["segments"] = 4097;
  EXPECT_USER_ERROR(parse_profiles_suite(j, "p.json"), "p.json: /segments = 4097 must be even");
  j = shipped();
  j["segments"] = 1024;
  j["samples_per_length"] = 64;
  EXPECT_USER_ERROR(parse_profiles_suite(j, "p.json"),
                    "p.json: /segments = 1024 must be at least 2 (8 samples_per_length + 1) = 1026");
  j = shipped();
  j["theta_deg"] = {0, 90};
  EXPECT_USER_ERROR(parse_profiles_suite(j, "p.json"), "p.json: /theta_deg/1 = 90 is out of range [0, 89]");
  j = shipped();
  j["surfaces"] = {"random", "flat"};
  EXPECT_USER_ERROR(parse_profiles_suite(j, "p.json"), "p.json: /surfaces/1 = \"flat\" is not one of");
  j = shipped();
  j["thresholds"].erase("p_min");
  EXPECT_USER_ERROR(parse_profiles_suite(j, "p.json"), "p.json: /thresholds/p_min");
}

TEST(ProfilesSuite, SmallRunPassesAndIsTheSameOnOneAndTwoThreads) {
  const ProfilesSuite s = parse_profiles_suite(small("ggx"), "small.json");
  const ProfilesRun one = run_profiles_suite(s, 0, 1), two = run_profiles_suite(s, 0, 2);
  ASSERT_TRUE(one.pass);
  json a = profiles_report_json(s, one), b = profiles_report_json(s, two);
  // Everything but the wall times and the thread count.
  for (json* r : {&a, &b}) {
    r->erase("wall_s"), r->erase("threads"), (*r)["summary"].erase("wall_s");
    for (json& c : (*r)["cases"]) {
      c["walk"].erase("wall_s");
      for (json& sf : c["surfaces"]) sf.erase("wall_s");
    }
  }
  EXPECT_EQ(a.dump(), b.dump());
  for (const ProfilesOutcome& o : one.cases)
    for (const SurfaceOutcome& so : o.surfaces) {
      EXPECT_EQ(so.lost, 0);
      EXPECT_TRUE(so.identity_holds);
      EXPECT_NEAR(so.albedo, 1.0, 0.0);  // F = 1: every ray leaves
    }
}

TEST(ProfilesSuite, ReportHasWhatAPlotNeeds) {
  const ProfilesSuite s = parse_profiles_suite(small("beckmann"), "small.json");
  const ProfilesRun run = run_profiles_suite(s, 0, 2);
  const json j = profiles_report_json(s, run);
  EXPECT_EQ(j["kind"], "profiles");
  EXPECT_EQ(j["bins"]["normal_deg_edges"].size(), 19u);
  EXPECT_EQ(j["bins"]["exit_deg_edges"].size(), 91u);
  const json& c = j["cases"][1];
  EXPECT_EQ(c["theta_deg"], 70.0);
  EXPECT_EQ(c["walk"]["lobe_by_k"].size(), 10u);  // k = 0..8 and > 8
  EXPECT_EQ(c["walk"]["lobe_by_k"][1].size(), 90u);
  EXPECT_EQ(c["vgroove_model"]["lobe_by_k"].size(), 10u);
  for (const json& sf : c["surfaces"]) {
    EXPECT_EQ(sf["g1"]["traced"].size(), 18u);
    EXPECT_EQ(sf["g1"]["vcavity"].size(), 18u);
    EXPECT_TRUE(sf["g1"]["smith"].is_number());
    EXPECT_EQ(sf["g2"]["traced"].size(), 18u);
    EXPECT_TRUE(sf["g2"]["smith_height_correlated"].is_number());
    EXPECT_EQ(sf["lobe"]["traced_by_k"].size(), 10u);
    EXPECT_EQ(sf["lobe"]["distance"]["walk"]["z_by_k"].size(), 10u);
    EXPECT_TRUE(sf["identity"]["holds"].get<bool>());
  }
  // On the V-groove profile the V-cavity is exact: its chi-squares pass.
  const json& vg = c["surfaces"][1];
  EXPECT_EQ(vg["surface"], "vgroove");
  EXPECT_GT(vg["g1"]["chi2_vcavity"]["p"].get<double>(), 1e-3 / 4);
  EXPECT_TRUE(vg["pass"].get<bool>());
  // At 70 deg on the Gaussian profile the V-cavity G1 is farther from the traced one than Smith's.
  const json& rd = c["surfaces"][0];
  EXPECT_GT(rd["g1"]["distance"]["vcavity"]["mean_abs"].get<double>(),
            2.0 * rd["g1"]["distance"]["smith"]["mean_abs"].get<double>());
}

}  // namespace
}  // namespace vgroove::validation
