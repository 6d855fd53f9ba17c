// Tests of validation/groove_suite.h: the checked-in suite loads, and each spec error is a UserError
// whose message names the file, the JSON path, the value and the allowed range.
#include "vgroove/validation/groove_suite.h"

#include "vgroove/support/user_error.h"

#include "tests/test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;
using testing_files::TempDir;
using testing_files::write_text;

double deg(double d) { return d * std::numbers::pi / 180.0; }

// A small valid suite; each error test breaks one thing in it.
json valid_spec() {
  return json::parse(R"({
    "name": "small",
    "kind": "table1",
    "groove": {"type": "symmetric", "theta_v_deg": [30, 90]},
    "theta_i_deg": {"from": -60, "to": 60, "step": 30},
    "rays": 100,
    "thresholds": {"max_l1": 0.05, "mean_l1": 0.01, "max_theta_o_error_rad": 1e-9}
  })");
}

class GrooveSuiteSpec : public testing::Test {
 protected:
  // Writes the spec to a file of its own and loads it.
  GrooveSuite load(const json& spec) {
    write_text(file_, spec.dump(2));
    return load_groove_suite(file_);
  }
  GrooveSuite load_text(const std::string& text) {
    write_text(file_, text);
    return load_groove_suite(file_);
  }
  // The message of the UserError that loading `spec` throws.
  std::string error_of(const std::function<void()>& f) {
    try {
      f();
    } catch (const support::UserError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no support::UserError thrown";
    return "";
  }
  std::string error_of(const json& spec) {
    return error_of([&] { load(spec); });
  }

  TempDir dir_;
  std::string file_ = dir_.file("suite.json");
};

TEST_F(GrooveSuiteSpec, ValidSpecLoadsInRadians) {
  const GrooveSuite s = load(valid_spec());
  EXPECT_EQ(s.name, "small");
  EXPECT_EQ(s.file, file_);
  ASSERT_EQ(s.grooves.size(), 2u);
  EXPECT_TRUE(s.grooves[1].symmetric);
  EXPECT_DOUBLE_EQ(s.grooves[1].theta_v, deg(90));
  ASSERT_EQ(s.theta_i.size(), 5u);  // -60, -30, 0, 30, 60
  EXPECT_DOUBLE_EQ(s.theta_i.front(), deg(-60));
  EXPECT_DOUBLE_EQ(s.theta_i.back(), deg(60));
  EXPECT_EQ(s.cases(), 10u);
  EXPECT_EQ(s.options.rays, 100);
  // Defaults of the optional keys.
  EXPECT_EQ(s.options.sampling, sim::Sampling::stratified);
  EXPECT_EQ(s.options.seed, 1u);
  EXPECT_EQ(s.options.max_bounces, 100000);
  EXPECT_EQ(s.options.form, analytic::Eq6Form::corrected);
  EXPECT_FALSE(s.paper.has_value());
}

TEST_F(GrooveSuiteSpec, RangeStopsAtToWhenStepsDoNotLandOnIt) {
  json j = valid_spec();
  j["theta_i_deg"] = {{"from", 0}, {"to", 10}, {"step", 4}};
  const GrooveSuite s = load(j);
  ASSERT_EQ(s.theta_i.size(), 3u);  // 0, 4, 8
  EXPECT_DOUBLE_EQ(s.theta_i.back(), deg(8));
  // Steps that land on "to" up to rounding include it: -89 .. 89 by 0.1 is 1781 values.
  j["theta_i_deg"] = {{"from", -89}, {"to", 89}, {"step", 0.1}};
  const GrooveSuite t = load(j);
  EXPECT_EQ(t.theta_i.size(), 1781u);
  EXPECT_DOUBLE_EQ(t.theta_i.back(), deg(89));
}

TEST_F(GrooveSuiteSpec, TheCheckedInTable1SuiteLoads) {
  const GrooveSuite s = load_groove_suite(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table1_symmetric.json");
  EXPECT_EQ(s.grooves.size(), 36u);   // 1 .. 176 step 5
  EXPECT_EQ(s.theta_i.size(), 179u);  // -89 .. 89 step 1
  EXPECT_EQ(s.cases(), 6444u);
  EXPECT_DOUBLE_EQ(s.grooves.front().theta_v, deg(1));
  EXPECT_DOUBLE_EQ(s.grooves.back().theta_v, deg(176));
  for (const GrooveParams& g : s.grooves) EXPECT_TRUE(g.symmetric);
  EXPECT_DOUBLE_EQ(s.theta_i.front(), deg(-89));
  EXPECT_DOUBLE_EQ(s.theta_i.back(), deg(89));
  EXPECT_EQ(s.options.rays, 1000);
  EXPECT_EQ(s.options.seed, 2018u);
  ASSERT_TRUE(s.paper.has_value());
  EXPECT_EQ(s.paper->max_l1, 0.003);
}

TEST_F(GrooveSuiteSpec, ThetaVAboveTheRangeIsNamed) {
  json j = valid_spec();
  j["groove"]["theta_v_deg"] = {30, 195};
  const std::string m = error_of(j);
  EXPECT_CONTAINS(m, file_ + ": /groove/theta_v_deg/1 = 195 is out of range [0.001, 180]");
}

TEST_F(GrooveSuiteSpec, ThetaVZeroAndRangeEndsAreChecked) {
  json j = valid_spec();
  j["groove"]["theta_v_deg"] = {0};
  EXPECT_CONTAINS(error_of(j), file_ + ": /groove/theta_v_deg/0 = 0 is out of range [0.001, 180]");
  j["groove"]["theta_v_deg"] = {{"from", 5}, {"to", 195}, {"step", 5}};
  EXPECT_CONTAINS(error_of(j), file_ + ": /groove/theta_v_deg/to = 195 is out of range [0.001, 180]");
  j["groove"]["theta_v_deg"] = {{"from", -5}, {"to", 90}, {"step", 5}};
  EXPECT_CONTAINS(error_of(j), file_ + ": /groove/theta_v_deg/from = -5 is out of range [0.001, 180]");
}

TEST_F(GrooveSuiteSpec, GrazingThetaIIsNamed) {
  json j = valid_spec();
  j["theta_i_deg"] = {0, 90};
  EXPECT_CONTAINS(error_of(j), file_ + ": /theta_i_deg/1 = 90 is out of range [-89.999, 89.999]");
  j["theta_i_deg"] = {-90};
  EXPECT_CONTAINS(error_of(j), file_ + ": /theta_i_deg/0 = -90 is out of range [-89.999, 89.999]");
  j["theta_i_deg"] = {{"from", -90}, {"to", 0}, {"step", 1}};
  EXPECT_CONTAINS(error_of(j), file_ + ": /theta_i_deg/from = -90 is out of range [-89.999, 89.999]");
}

TEST_F(GrooveSuiteSpec, TooFewRaysIsNamed) {
  json j = valid_spec();
  j["rays"] = 0;
  EXPECT_CONTAINS(error_of(j), file_ + ": /rays = 0 is out of range [1, ");
  j["rays"] = -3;
  EXPECT_CONTAINS(error_of(j), file_ + ": /rays = -3 is out of range [1, ");
}

TEST_F(GrooveSuiteSpec, UnknownKeyIsNamed) {
  json j = valid_spec();
  j["roughnes"] = 0.1;
  const std::string m = error_of(j);
  EXPECT_CONTAINS(m, file_ + ": /roughnes is not a known key");
  json k = valid_spec();
  k["groove"]["thetav_deg"] = 10;
  EXPECT_CONTAINS(error_of(k), file_ + ": /groove/thetav_deg is not a known key");
  json t = valid_spec();
  t["thresholds"]["max_l2"] = 1;
  EXPECT_CONTAINS(error_of(t), file_ + ": /thresholds/max_l2 is not a known key");
}

TEST_F(GrooveSuiteSpec, WrongTypesAreNamed) {
  json j = valid_spec();
  j["rays"] = "many";
  EXPECT_CONTAINS(error_of(j), file_ + ": /rays = \"many\" must be an integer");
  j = valid_spec();
  j["rays"] = 100.5;
  EXPECT_CONTAINS(error_of(j), file_ + ": /rays = 100.5 must be an integer");
  j = valid_spec();
  j["groove"]["theta_v_deg"] = {30, "ninety"};
  EXPECT_CONTAINS(error_of(j), file_ + ": /groove/theta_v_deg/1 = \"ninety\" must be a number");
  j = valid_spec();
  j["groove"]["theta_v_deg"] = "90";
  EXPECT_CONTAINS(error_of(j), file_ + ": /groove/theta_v_deg = \"90\" must be a list of numbers");
  j = valid_spec();
  j["thresholds"] = 0.1;
  EXPECT_CONTAINS(error_of(j), file_ + ": /thresholds must be a JSON object");
}

TEST_F(GrooveSuiteSpec, BadChoicesAreNamed) {
  json j = valid_spec();
  j["sampling"] = "sobol";
  EXPECT_CONTAINS(error_of(j), file_ + ": /sampling = \"sobol\" is not one of \"stratified\", \"random\"");
  j = valid_spec();
  j["kind"] = "table2";
  EXPECT_CONTAINS(error_of(j), file_ + ": /kind = \"table2\" is not one of");
  j = valid_spec();
  j["eq6_form"] = "fixed";
  EXPECT_CONTAINS(error_of(j), file_ + ": /eq6_form = \"fixed\" is not one of \"corrected\", \"printed\"");
}

TEST_F(GrooveSuiteSpec, MissingRequiredKeysAreNamed) {
  for (const char* key : {"name", "kind", "groove", "theta_i_deg", "rays", "thresholds"}) {
    json j = valid_spec();
    j.erase(key);
    EXPECT_CONTAINS(error_of(j), file_ + ": /" + key + " is missing (required)") << "key=" << key;
  }
  json j = valid_spec();
  j["thresholds"].erase("mean_l1");
  EXPECT_CONTAINS(error_of(j), file_ + ": /thresholds/mean_l1 is missing (required)");
}

TEST_F(GrooveSuiteSpec, EmptyAndBackwardsRangesAreErrors) {
  json j = valid_spec();
  j["theta_i_deg"] = json::array();
  EXPECT_CONTAINS(error_of(j), file_ + ": /theta_i_deg is an empty list");
  j["theta_i_deg"] = {{"from", 10}, {"to", 0}, {"step", 1}};
  EXPECT_CONTAINS(error_of(j), file_ + ": /theta_i_deg/to = 0 is below from = 10");
  j["theta_i_deg"] = {{"from", 0}, {"to", 10}, {"step", 0}};
  EXPECT_CONTAINS(error_of(j), file_ + ": /theta_i_deg/step = 0 is out of range (0, inf)");
}

TEST_F(GrooveSuiteSpec, MissingFileIsNamed) {
  const std::string f = dir_.file("missing.json");
  EXPECT_CONTAINS(error_of([&] { load_groove_suite(f); }), f + ": cannot open the file");
}

TEST_F(GrooveSuiteSpec, InvalidJsonIsNamed) {
  EXPECT_CONTAINS(error_of([&] { load_text("{\"name\": \"small\", \"rays\": 10,"); }), file_ + ": not valid JSON");
  EXPECT_CONTAINS(error_of([&] { load_text("[1, 2]"); }), file_ + ": / must be a JSON object, found array");
}

TEST_F(GrooveSuiteSpec, TheCheckedInTable1SetHoldsBothColumns) {
  const std::string file = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table1.json";
  const GrooveSuiteSet set = load_groove_suite_set(file);
  ASSERT_EQ(set.suites.size(), 2u);
  EXPECT_EQ(set.suites[0].name, "table1_symmetric");
  EXPECT_EQ(set.suites[0].cases(), 6444u);
  // A set is not a suite: load_groove_suite says so, naming the file.
  EXPECT_CONTAINS(error_of([&] { load_groove_suite(file); }), file + ": is a set of suites");
}

TEST_F(GrooveSuiteSpec, ASingleSuiteIsASetOfOne) {
  write_text(file_, valid_spec().dump());
  const GrooveSuiteSet set = load_groove_suite_set(file_);
  ASSERT_EQ(set.suites.size(), 1u);
  EXPECT_EQ(set.name, "small");
}

TEST_F(GrooveSuiteSpec, SetWithAMissingMemberNamesIt) {
  write_text(file_, R"({"name": "set", "suites": ["nope.json"]})");
  EXPECT_CONTAINS(error_of([&] { load_groove_suite_set(file_); }), dir_.file("nope.json") + ": cannot open the file");
  write_text(file_, R"({"name": "set", "suites": []})");
  EXPECT_CONTAINS(error_of([&] { load_groove_suite_set(file_); }), file_ + ": /suites must be a non-empty list");
}

TEST(CheckAngles, CommandLineRangeMessages) {
  const auto msg = [](auto f) {
    try {
      f();
    } catch (const support::UserError& e) {
      return std::string(e.what());
    }
    return std::string("no support::UserError");
  };
  const std::string why =
      " (below 0.001 deg the tracer's rounding moves the bounce counts' boundaries: it and the model disagree)";
  // The note about narrow grooves is for values below the range only.
  EXPECT_EQ(msg([] { check_theta_v(195, "--theta-v-deg"); }), "--theta-v-deg = 195 is out of range [0.001, 180]");
  EXPECT_EQ(msg([] { check_theta_v(0, "--theta-v-deg"); }), "--theta-v-deg = 0 is out of range [0.001, 180]" + why);
  EXPECT_EQ(msg([] { check_theta_v(1e-8, "--theta-v-deg"); }),
            "--theta-v-deg = 1e-08 is out of range [0.001, 180]" + why);
  EXPECT_NO_THROW(check_theta_v(1e-3, "x"));
  EXPECT_THROW(check_theta_v(1e-6, "x"), support::UserError);
  EXPECT_EQ(msg([] { check_theta_i(90, "--theta-i-deg"); }), "--theta-i-deg = 90 is out of range [-89.999, 89.999]");
  EXPECT_EQ(msg([] { check_theta_i(-90, "--theta-i-deg"); }), "--theta-i-deg = -90 is out of range [-89.999, 89.999]");
  EXPECT_NO_THROW(check_theta_v(180, "x"));
  EXPECT_NO_THROW(check_theta_i(89.999, "x"));
  EXPECT_THROW(check_theta_v(std::nan(""), "x"), support::UserError);
}

}  // namespace
}  // namespace vgroove::validation
