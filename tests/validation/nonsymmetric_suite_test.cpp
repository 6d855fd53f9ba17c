// The nonsymmetric suite (Lee et al. 2018, Sec. 5.2-5.3, Fig. 7-8): a strict spec, small runs that
// pass with thresholds from the sample count, a wrong model (the symmetric one against the
// nonsymmetric surface) rejected by the same thresholds, and results that do not depend on the
// thread count.
#include "vgroove/validation/nonsymmetric_suite.h"

#include "tests/test_files.h"
#include "tests/user_error_of.h"
#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;

// The one-line refusal of a suite (a test failure if it is read).
std::string refusal(const json& j) {
  return testing_files::user_error_of([&] { parse_nonsymmetric_suite(j, "n.json"); });
}

json shipped() {
  return json::parse(testing_files::read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/nonsymmetric_brdf.json"));
}

TEST(NonsymmetricSuite, ShippedSuiteParses) {
  const NonsymmetricSuite s = parse_nonsymmetric_suite(shipped(), "nonsymmetric_brdf.json");
  // The grid (3 NDFs x 4 alphas x 5 theta_i x 2 dimensions) and the anisotropic block
  // (2 NDFs x alpha_y 0.1, 0.3, 1.0 x light along and across x 2 partner laws).
  EXPECT_EQ(s.cases().size(), 3u * 4u * 5u * 2u + 2u * 3u * 2u * 2u);
  const NonsymmetricCase last = s.cases().back();
  EXPECT_TRUE(last.anisotropic && last.symmetric);
  EXPECT_EQ(last.dim, SurfaceDim::three_d);
  EXPECT_NEAR(last.phi_i, 0.5 * std::numbers::pi, 1e-15);
}

TEST(NonsymmetricSuite, BadSpecsNameTheFieldAndRange) {
  json j = shipped();
  j["roughnes"] = 0.5;
  EXPECT_NE(refusal(j).find("n.json: /roughnes is not a known key"), std::string::npos) << refusal(j);
  j = shipped();
  j["alpha"] = {0.5, 1.5};
  EXPECT_NE(refusal(j).find("no partner law for phong"), std::string::npos) << refusal(j);
  j = shipped();
  j["anisotropic"]["ndf"] = {"phong"};
  EXPECT_NE(refusal(j).find("/anisotropic/ndf/0"), std::string::npos) << refusal(j);
  j = shipped();
  j["anisotropic"]["partners"] = {"both"};
  EXPECT_NE(refusal(j).find("/anisotropic/partners/0"), std::string::npos) << refusal(j);
  j = shipped();
  j["phi_bins"] = 13;
  EXPECT_NE(refusal(j).find("must be even"), std::string::npos) << refusal(j);
}

NonsymmetricSuite small_suite() {
  json j = shipped();
  j["ndf"] = {"ggx"};
  j["alpha"] = {0.7};
  j["theta_i_deg"] = {60};
  j["anisotropic"]["ndf"] = {"beckmann"};
  j["anisotropic"]["alpha_y"] = {1.0};
  j["anisotropic"]["phi_i_deg"] = {90};
  j["anisotropic"]["partners"] = {"independent"};
  j["rays"] = 60000;
  j["grooves"] = 60000;
  j["reciprocity_pairs"] = 3;
  return parse_nonsymmetric_suite(j, "small.json");
}

// A flatland, a 3D and an anisotropic case pass; the symmetric model is rejected against the
// nonsymmetric surfaces at this grazing light (the power of the thresholds); the report and the
// thread count.
TEST(NonsymmetricSuite, SmallRunPassesAndRejectsTheSymmetricModel) {
  const NonsymmetricSuite s = small_suite();
  ASSERT_EQ(s.cases().size(), 3u);
  const NonsymmetricRun one = run_nonsymmetric_suite(s, 0, 1);
  for (const NonsymmetricOutcome& o : one.cases) {
    EXPECT_TRUE(o.pass) << surface_dim_name(o.c.dim) << " L1 " << o.l1 << " / " << o.l1_threshold << ", by k " << o.l1_k
                        << " / " << o.l1_k_threshold << ", albedo " << o.albedo_sim << " vs " << o.albedo_model;
    EXPECT_TRUE(o.other_rejected) << surface_dim_name(o.c.dim) << " symmetric model L1 " << o.l1_other;
    EXPECT_EQ(o.escaped, o.rays);
  }
  for (const ReciprocityRow& r : one.reciprocity) EXPECT_TRUE(r.pass) << r.worst;
  EXPECT_TRUE(one.pass);
  const NonsymmetricRun two = run_nonsymmetric_suite(s, 0, 2);
  for (std::size_t n = 0; n < one.cases.size(); ++n) {
    EXPECT_EQ(one.cases[n].l1, two.cases[n].l1);
    EXPECT_EQ(one.cases[n].by_k_sim, two.cases[n].by_k_sim);
  }
  const json r = nonsymmetric_report_json(s, one);
  EXPECT_EQ(r["cases"].size(), 3u);
  EXPECT_EQ(r["cases"][1]["plane"]["theta_deg"].size(), 2u * static_cast<std::size_t>(s.theta_bins));
  EXPECT_EQ(r["cases"][1]["plane"]["model_by_k"].size(), 4u);
  EXPECT_TRUE(r.contains("reciprocity"));
}

}  // namespace
}  // namespace vgroove::validation
