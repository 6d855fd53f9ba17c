// Tests of `vgroove brdf`: the numbers the library returns, to the last digit; the per-k terms sum
// to the total; bad input named with its range; a directions file read strictly.
#include "vgroove/analytic/brdf_model.h"
#include "vgroove/common/angles.h"

#include "tests/cli_run.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace vgroove::app {
namespace {

using nlohmann::json;
using testing_files::TempDir;
using testing_files::vgroove;
using testing_files::write_text;

double lib(analytic::BrdfModel m, double ti, double pi_, double to, double po, double alpha, NdfKind ndf) {
  analytic::BrdfEvalOptions o;
  o.ndf = ndf, o.alpha = alpha;
  return analytic::evaluate_brdf(m, analytic::dir3(deg_to_rad(ti), deg_to_rad(pi_)),
                                 analytic::dir3(deg_to_rad(to), deg_to_rad(po)), o)
      .value;
}

TEST(CmdBrdf, JsonEqualsTheLibraryToTheLastDigit) {
  for (const char* model : {"vgroove", "cook-torrance"})
    for (const char* ndf : {"ggx", "beckmann", "phong"}) {
      const auto r = vgroove(std::string("brdf --json --model ") + model + " --ndf " + ndf +
                             " --alpha 0.7 --theta-i-deg 30 --theta-o-deg 40 --phi-o-deg 170");
      ASSERT_EQ(r.status, 0) << r;
      const json j = json::parse(r.out);
      const double want = lib(*analytic::brdf_model_from_name(model), 30, 0, 40, 170, 0.7, *ndf_from_name(ndf));
      EXPECT_EQ(j["points"][0]["value"].get<double>(), want) << model << " " << ndf;
      EXPECT_GT(want, 0.0);
      EXPECT_EQ(j["unit"], "1/sr");
    }
}

TEST(CmdBrdf, TextPrintsEveryDigit) {
  const auto r = vgroove("brdf --theta-i-deg 20 --theta-o-deg 25 --phi-o-deg 180 --alpha 0.3");
  ASSERT_EQ(r.status, 0) << r;
  const double want = lib(analytic::BrdfModel::vgroove, 20, 0, 25, 180, 0.3, NdfKind::ggx);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", want);
  EXPECT_NE(r.out.find(buf), std::string::npos) << r << "\nwant " << buf;
}

// The orders resolved one by one add up to the total when nothing lies beyond them (a smooth
// surface far from grazing keeps its light within a few bounces).
TEST(CmdBrdf, PerKSumsToTheTotal) {
  const auto r = vgroove(
      "brdf --json --per-k --per-k-max 64 --max-k 64 --alpha 0.4 --theta-i-deg 10 "
      "--theta-o-deg 35 --phi-o-deg 150");
  ASSERT_EQ(r.status, 0) << r;
  const json p = json::parse(r.out)["points"][0];
  double s = 0.0;
  for (double v : p["by_k"]) s += v;
  EXPECT_NEAR(s, p["value"].get<double>(), 1e-13 * p["value"].get<double>());
  EXPECT_GT(p["by_k"][1].get<double>(), 0.0);  // k = 2 contributes off the mirror direction
}

TEST(CmdBrdf, DirectionsFile) {
  TempDir d;
  const std::string f = d.file("dirs.json");
  write_text(f, R"({"directions": [{"theta_i_deg": 30, "theta_o_deg": 40, "phi_o_deg": 180},
                                   {"theta_i_deg": 60, "theta_o_deg": 10, "phi_i_deg": 45, "phi_o_deg": 0}]})");
  const auto r = vgroove("brdf --json --directions '" + f + "'");
  ASSERT_EQ(r.status, 0) << r;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["points"].size(), 2u);
  EXPECT_EQ(j["points"][1]["value"].get<double>(), lib(analytic::BrdfModel::vgroove, 60, 45, 10, 0, 0.5, NdfKind::ggx));

  write_text(f, R"({"directions": [{"theta_i_deg": 30, "theta_o_deg": 40, "phi_o": 180}]})");
  const auto typo = vgroove("brdf --directions '" + f + "'");
  EXPECT_EQ(typo.status, 2) << typo;
  EXPECT_NE(typo.err.find("/directions/0/phi_o"), std::string::npos) << typo;

  write_text(f, R"({"directions": [{"theta_i_deg": 30, "theta_o_deg": 95}]})");
  const auto range = vgroove("brdf --directions '" + f + "'");
  EXPECT_EQ(range.status, 2) << range;
  EXPECT_NE(range.err.find("/directions/0/theta_o_deg = 95 is out of range [-90, 90]"), std::string::npos) << range;
}

TEST(CmdBrdf, BadInput) {
  struct Case {
    const char* args;
    const char* message;
  } cases[] = {
      {"brdf --theta-i-deg 30", "--theta-o-deg is required"},
      {"brdf --theta-o-deg 10 --alpha 0", "--alpha = 0 is out of range [0.01, 2]"},
      {"brdf --theta-o-deg 10 --alpha 2.5", "--alpha = 2.5 is out of range [0.01, 2]"},
      {"brdf --theta-o-deg 10 --theta-i-deg 90", "--theta-i-deg = 90 is out of range [0, 90)"},
      {"brdf --theta-o-deg 91", "--theta-o-deg = 91 is out of range [0, 90]"},
      {"brdf --theta-o-deg 10 --phi-o-deg 400", "--phi-o-deg = 400 is out of range [-360, 360]"},
      {"brdf --theta-o-deg 10 --model lambert", "--model = \"lambert\" is not one of"},
      {"brdf --theta-o-deg 10 --ndf cauchy", "--ndf = \"cauchy\" is not one of"},
      {"brdf --theta-o-deg 10 --dim 2d", "--dim = \"2d\" is not one of"},
      {"brdf --theta-o-deg 10 --max-k 0", "--max-k = 0 is out of range"},
      {"brdf --theta-o-deg 10 --dim flatland --max-k 5000", "--max-k = 5000 is out of range [1, 4096]"},
  };
  for (const Case& c : cases) {
    const auto r = vgroove(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r;
    EXPECT_EQ(r.out, "") << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r;
  }
}

TEST(CmdBrdf, FlatlandSignedAngles) {
  const auto r = vgroove("brdf --json --dim flatland --theta-i-deg 30 --theta-o-deg -35 --max-k 64");
  ASSERT_EQ(r.status, 0) << r;
  analytic::BrdfEvalOptions o;
  o.flatland = true, o.max_k = 64;
  const double t_i = deg_to_rad(30), t_o = deg_to_rad(-35);
  const double want = analytic::evaluate_brdf(analytic::BrdfModel::vgroove, {-std::sin(t_i), 0, std::cos(t_i)},
                                              {-std::sin(t_o), 0, std::cos(t_o)}, o)
                          .value;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["points"][0]["value"].get<double>(), want);
  EXPECT_EQ(j["unit"], "1/rad");
}

}  // namespace
}  // namespace vgroove::app
