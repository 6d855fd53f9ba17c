// The "profiles" suite (validation/profiles_suite.h): a strict spec, a small run that passes and
// gives the same results on one thread as on two, and a report with what a plot needs.
#include "vgroove/validation/profiles_suite.h"

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
  return testing_files::user_error_of([&] { parse_profiles_suite(j, "p.json"); });
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
  EXPECT_NE(refusal(j).find("p.json: /realisations is not a known key"), std::string::npos) << refusal(j);
  j = shipped();
  j["ndf"] = {"phong"};
  EXPECT_NE(refusal(j).find("p.json: /ndf/0 = \"phong\" is not one of \"beckmann\", \"ggx\""), std::string::npos)
      << refusal(j);
  j = shipped();
  j["segments"] = 4097;
  EXPECT_NE(refusal(j).find("p.json: /segments = 4097 must be even"), std::string::npos) << refusal(j);
  j = shipped();
  j["segments"] = 1024;
  j["samples_per_length"] = 64;
  EXPECT_NE(refusal(j).find("p.json: /segments = 1024 must be at least 2 (8 samples_per_length + 1) = 1026"),
            std::string::npos)
      << refusal(j);
  j = shipped();
  j["theta_deg"] = {0, 90};
  EXPECT_NE(refusal(j).find("p.json: /theta_deg/1 = 90 is out of range [0, 89]"), std::string::npos) << refusal(j);
  j = shipped();
  j["surfaces"] = {"random", "flat"};
  EXPECT_NE(refusal(j).find("p.json: /surfaces/1 = \"flat\" is not one of"), std::string::npos) << refusal(j);
  j = shipped();
  j["thresholds"].erase("p_min");
  EXPECT_NE(refusal(j).find("p.json: /thresholds/p_min"), std::string::npos) << refusal(j);
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

// A reader's z from the report is the suite's: G1's and G2's traced_se per bin is the error the
// distances use (the realizations' spread, but at least the rays' binomial error: a spread of two
// realizations falls below it by chance), and the lit fractions' traced_se is their z_vcavity's
// (the ray counting: the predictions are each profile's own). On V-groove profiles V-cavity is
// exact, so both lit fractions (per macro length and per arc length) are within sigmas of it.
bool finite(const json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

TEST(ProfilesSuite, ReportedErrorsAreTheVerdicts) {
  const ProfilesSuite s = parse_profiles_suite(small("ggx"), "small.json");
  const ProfilesRun run = run_profiles_suite(s, 0, 2);
  const json j = profiles_report_json(s, run);
  for (const json& c : j["cases"])
    for (const json& sf : c["surfaces"]) {
      const std::string where = sf["surface"].get<std::string>() + " theta " + c["theta_deg"].dump();
      for (const char* g : {"g1", "g2"}) {
        const json& G = sf[g];
        double max_z = 0.0;
        for (std::size_t b = 0; b < G["traced"].size(); ++b) {
          // Bins no facet fell into (NaN in memory, null in a written report).
          if (!finite(G["traced"][b]) || !finite(G["vcavity"][b])) continue;
          const double se = G["traced_se"][b].get<double>(), counting = G["counting_se"][b].get<double>();
          EXPECT_GE(se, counting) << where << " " << g << " bin " << b;
          if (finite(G["realization_se"][b])) {
            EXPECT_GE(se, G["realization_se"][b].get<double>()) << where << " " << g << " bin " << b;
          }
          if (se > 0.0)
            max_z = std::max(max_z, std::abs(G["traced"][b].get<double>() - G["vcavity"][b].get<double>()) / se);
        }
        EXPECT_NEAR(max_z, G["distance"]["vcavity"]["max_abs_z"].get<double>(), 1e-12 * (1.0 + max_z))
            << where << " " << g;
      }
      for (const char* key : {"lit_fraction", "lit_fraction_arc_length"}) {
        const json& l = sf[key];
        const double z = (l["traced"].get<double>() - l["vcavity"].get<double>()) / l["traced_se"].get<double>();
        // The same z to the rounding of a difference of two means (traced = V-cavity to 1e-13 at 0 deg).
        EXPECT_NEAR(z, l["z_vcavity"].get<double>(), 1e-6 + 1e-9 * std::abs(z)) << where << " " << key;
        if (sf["surface"] == "vgroove") {
          EXPECT_LE(std::abs(z), s.sigmas) << where << " " << key;
        }
      }
      // Per macro length the steep facets count less: at 70 deg, where the steep grooves are the
      // shadowed ones, the macro fraction is the larger.
      if (c["theta_deg"] == 70.0) {
        EXPECT_GT(sf["lit_fraction"]["traced"].get<double>(), sf["lit_fraction_arc_length"]["traced"].get<double>())
            << where;
      }
    }
}

}  // namespace
}  // namespace vgroove::validation
