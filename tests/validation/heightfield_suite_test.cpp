// The "heightfield" suite (validation/heightfield_suite.h): a strict spec, the memory refusal
// before any work, and a small run whose controls hold (Cook-Torrance with Smith's G and the
// Smith walk on smooth Beckmann fields at normal incidence, where masking and multiple scattering
// are nearly absent and heights are independent of slopes) while deliberately wrong models are
// caught by the same metric, with the same numbers on one thread as on two; "surface": the
// default Gaussian fields as before, and random-orientation V-groove fields; "walk_heights" and
// "aspect" lists; the full-size groove fields (HeightfieldSuiteLong, ctest -L long).
#include "vgroove/validation/heightfield_suite.h"

#include "tests/cli_run.h"
#include "tests/test_files.h"
#include "tests/user_error_of.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/check_brdf.h"
#include "vgroove/validation/energy_lobe_shape.h"
#include "vgroove/validation/heightfield_lobe.h"
#include "vgroove/validation/histogram_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;

// The one-line refusal of a suite read from `file`, and of a run's memory estimate (a test
// failure if there is none).
std::string refusal(const json& j, const std::string& file) {
  return testing_files::user_error_of([&] { parse_heightfield_suite(j, file); });
}
std::string memory_refusal(const HeightfieldSuite& s, int threads) {
  return testing_files::user_error_of([&] { heightfield_run_memory_bytes(s, threads); });
}

json shipped() {
  return json::parse(testing_files::read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/heightfield.json"));
}

// Beckmann alpha 0.3 at normal incidence on 64^2 fields (l = 4 cells): about 0.2 s.
json small() {
  json j = shipped();
  j["ndf"] = {"beckmann"};
  j["alpha"] = {0.3};
  j["theta_i_deg"] = {0};
  j["field_size"] = 64;
  j["correlation_length"] = 4;
  j["fields"] = 4;
  j["rays"] = 4000;
  j["walk_paths"] = 20000;
  j["controls"] = {{{"model", "cook_torrance_smith"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}},
                   {{"model", "smith_walk"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}}};
  j["masking"] = {{"theta_o_deg", {0, 75}}, {"phi_deg", {0, 180}}, {"points", 1500}};
  return j;
}

TEST(HeightfieldSuite, ShippedSuiteParses) {
  const HeightfieldSuite s = parse_heightfield_suite(shipped(), "heightfield.json");
  EXPECT_EQ(s.cases(), 2u * 3u * 3u);
  EXPECT_EQ(s.field_size, 256);
  EXPECT_EQ(s.fields, 8);
  ASSERT_EQ(s.controls.size(), 2u);
  const HeightfieldCase c = s.case_at(s.controls[0].case_index);
  EXPECT_EQ(c.ndf, analytic::NdfKind::beckmann);
  EXPECT_EQ(c.alpha, 0.3);
  EXPECT_EQ(c.theta_i_deg, 0.0);
  ASSERT_TRUE(s.masking.has_value());
  EXPECT_EQ(s.masking->theta_o_deg.back(), 85.0);  // grazing, where Smith is expected to err
  EXPECT_EQ(s.masking->pairs(), 9u);
  const HeightfieldCase last = s.case_at(s.cases() - 1);
  EXPECT_EQ(last.ndf, analytic::NdfKind::ggx);
  EXPECT_EQ(last.theta_i_deg, 70.0);
}

TEST(HeightfieldSuite, BadSpecsNameTheFieldAndRange) {
  const auto bad = [](const char* key, const json& value, const std::string& part) {
    json j = shipped();
    j[key] = value;
    EXPECT_NE(refusal(j, "h.json").find(part), std::string::npos) << refusal(j, "h.json");
  };
  bad("field_size", 100, "h.json: /field_size = 100 must be a power of two in [16, 65536]");
  bad("field_size", 8, "h.json: /field_size");
  bad("correlation_length", 40, "h.json: /correlation_length");  // > 256 / 8
  bad("correlation_length", 1, "h.json: /correlation_length");
  bad("fields", 1, "h.json: /fields");
  bad("phi_bins", 7, "h.json: /phi_bins = 7 must be even");
  bad("ndf", json{"phong"}, "h.json: /ndf");
  bad("theta_i_deg", json{90}, "h.json: /theta_i_deg");
  bad("feild_size", 64, "h.json: /feild_size is not a known key");
  bad("surface", "voronoi", "h.json: /surface");
  {
    json j = shipped();  // l = 24 fits a Gaussian 256^2 field (<= 32), not grooves 72 long (> 64)
    j["surface"] = "grooves";
    j["correlation_length"] = 24;
    EXPECT_NE(
        refusal(j, "h.json")
            .find("h.json: /correlation_length = 24 must be in [2, 21.3333] (field_size / 12) with surface grooves"),
        std::string::npos)
        << refusal(j, "h.json");
    j["correlation_length"] = 8;
    j["field_size"] = 8192;
    EXPECT_NE(refusal(j, "h.json")
                  .find("h.json: /field_size = 8192 must be a power of two in [16, 4096] with surface grooves"),
              std::string::npos)
        << refusal(j, "h.json");
    j["surface"] = "gaussian";
    j["field_size"] = 256;
    j["correlation_length"] = 24;
    EXPECT_EQ(parse_heightfield_suite(j, "h.json").correlation_length, 24.0);
  }
  bad("controls", json{{{"model", "smith_walk"}, {"ndf", "ggx"}, {"alpha", 0.4}, {"theta_i_deg", 0}}},
      "h.json: /controls/0 names no case of the suite");
  bad("controls", json{{{"model", "walter"}, {"ndf", "ggx"}, {"alpha", 0.3}, {"theta_i_deg", 0}}},
      "h.json: /controls/0/model");
  bad("masking", json{{"theta_o_deg", {90}}, {"phi_deg", {0}}, {"points", 10}}, "h.json: /masking/theta_o_deg");
  bad("masking", json{{"theta_o_deg", {0}}, {"phi_deg", {270}}, {"points", 10}}, "h.json: /masking/phi_deg");
  bad("masking", json{{"theta_o_deg", {0}}, {"phi_deg", {0}}, {"points", 0}}, "h.json: /masking/points");
  bad("masking", json{{"theta_o_deg", {0}}, {"phi_deg", {0}}, {"points", 10}, {"bins", 3}},
      "h.json: /masking/bins is not a known key");
}

TEST(HeightfieldSuite, AFieldTooLargeForMemoryIsRefusedBeforeAnyWork) {
  json j = shipped();
  j["field_size"] = 65536;  // 126 GB with its hierarchy
  const HeightfieldSuite s = parse_heightfield_suite(j, "h.json");
  if (support::memory_limit_bytes() >= sim::heightfield_bytes(65536)) GTEST_SKIP() << "this machine holds 126 GB";
  EXPECT_NE(memory_refusal(s, 1).find("h.json: /field_size = 65536 needs 126.0 GB"), std::string::npos)
      << memory_refusal(s, 1);
  EXPECT_NE(memory_refusal(s, 1).find("it must be a power of two in [16, "), std::string::npos) << memory_refusal(s, 1);
  // Groove fields (at most 4096^2, refused above by the spec): the same bytes per cell (their
  // synthesis holds 8 bytes per cell and the seeds, below the hierarchy), the same estimate.
  j["field_size"] = 4096;
  json jg = j;
  jg["surface"] = "grooves";
  const HeightfieldSuite g = parse_heightfield_suite(jg, "h.json");
  EXPECT_EQ(g.surface, HeightfieldSurfaceKind::grooves);
  EXPECT_EQ(heightfield_run_memory_bytes(g, 2), heightfield_run_memory_bytes(parse_heightfield_suite(j, "h.json"), 2));
  EXPECT_GE(heightfield_run_memory_bytes(g, 2), 2.0 * sim::heightfield_bytes(4096));
  // The shipped size fits, and the estimate counts the field with its hierarchy per worker.
  const HeightfieldSuite ok = parse_heightfield_suite(shipped(), "h.json");
  EXPECT_GE(heightfield_run_memory_bytes(ok, 2), 2.0 * sim::heightfield_bytes(256));
}

TEST(HeightfieldSuite, SmallRunControlsHoldWrongModelsAreCaughtAndThreadsDoNotMatter) {
  const HeightfieldSuite s = parse_heightfield_suite(small(), "small.json");
  const HeightfieldRun one = run_heightfield_suite(s, 0, 1);
  ASSERT_EQ(one.cases.size(), 1u);
  const HeightfieldOutcome& o = one.cases[0];
  EXPECT_TRUE(one.pass);
  EXPECT_EQ(o.rays, 4 * 4000);
  EXPECT_EQ(o.lost, 0);
  EXPECT_FALSE(o.non_finite);
  // F = 1: every ray leaves.
  EXPECT_NEAR(o.albedo, 1.0, 1e-15);
  ASSERT_EQ(one.controls_hold.size(), 2u);
  EXPECT_TRUE(one.controls_hold[0]) << "Cook-Torrance (Smith) k = 1: L1 " << o.cook_torrance.l1[0] << " threshold "
                                    << o.cook_torrance.l1_threshold[0];
  EXPECT_TRUE(one.controls_hold[1]);
  // The V-groove model puts 0.4% into k = 2 at normal incidence (the facets' partners), where the
  // field has almost none: a model of another surface, caught.
  EXPECT_FALSE(o.vgroove.within_noise);

  // Deliberately wrong models against the same traced lobe: Smith's k = 1 at 1.5 alpha (shape),
  // and the right one with 3% less energy.
  CheckBrdfOptions co;
  co.ndf = NdfKind::beckmann, co.alpha = 0.45, co.theta_bins = s.theta_bins, co.phi_bins = s.phi_bins;
  const analytic::MicrofacetModel smith{NdfKind::beckmann, analytic::MaskingKind::smith_height_correlated};
  const BrdfFn rough = [&](const analytic::Dir3& i, const analytic::Dir3& w) {
    return single_scattering_brdf(smith, 0.45, i, w);
  };
  const std::vector<double> wrong = integrate_model_lobe(batch_of(rough), 0.0, co).flux;
  const HeightfieldMiss m1 = heightfield_miss(o.lobe, o.lobe_se, o.energy, o.energy_se, wrong, {}, {sum(wrong)}, {}, 1,
                                              s.bins(), s.sigmas, s.model_tolerance);
  EXPECT_FALSE(m1.within_noise) << "L1 " << m1.l1[0] << " threshold " << m1.l1_threshold[0];
  std::vector<double> dim = o.ct_lobe;
  for (double& v : dim) v *= 0.97;
  const HeightfieldMiss m2 = heightfield_miss(o.lobe, o.lobe_se, o.energy, o.energy_se, dim, {}, {sum(dim)}, {}, 1,
                                              s.bins(), s.sigmas, s.model_tolerance);
  EXPECT_FALSE(m2.within_noise) << "E_1 diff " << m2.energy_diff[0] << " threshold " << m2.energy_threshold[0];

  // Two threads, the same outcome value for value (timings aside).
  const HeightfieldRun two = run_heightfield_suite(s, 0, 2);
  ASSERT_EQ(two.cases.size(), 1u);
  EXPECT_EQ(two.cases[0].lobe, o.lobe);
  EXPECT_EQ(two.cases[0].lobe_se, o.lobe_se);
  EXPECT_EQ(two.cases[0].walk_lobe, o.walk_lobe);
  EXPECT_EQ(two.cases[0].ct_lobe, o.ct_lobe);
  EXPECT_EQ(two.cases[0].vgroove_lobe, o.vgroove_lobe);
  EXPECT_EQ(two.cases[0].edge_hits, o.edge_hits);
}

TEST(HeightfieldSuite, ReportSaysWhichModelIsWithinNoise) {
  json j = small();
  j["ndf"] = {"ggx"};
  j["alpha"] = {0.6};
  j["theta_i_deg"] = {60};
  j.erase("controls");
  const HeightfieldSuite s = parse_heightfield_suite(j, "small.json");
  const HeightfieldRun run = run_heightfield_suite(s, 0, 2);
  const json r = heightfield_report_json(s, run);
  ASSERT_EQ(r["cases"].size(), 1u);
  const json& c = r["cases"][0];
  for (const char* m : {"smith_walk", "cook_torrance_smith", "vgroove"}) {
    ASSERT_TRUE(c[m]["against_traced"].contains("within_noise")) << m;
    for (const json& row : c[m]["against_traced"]["rows"]) {
      EXPECT_EQ(row["within_noise"].get<bool>(),
                row["l1"].get<double>() <= row["l1_threshold"].get<double>() &&
                    std::abs(row["energy_diff"].get<double>()) <= row["energy_threshold"].get<double>());
    }
  }
  EXPECT_EQ(c["cook_torrance_smith"]["against_traced"]["rows"].size(), 1u);
  EXPECT_EQ(c["smith_walk"]["against_traced"]["rows"].size(), 3u);
  std::ostringstream table;
  print_heightfield_table(table, s, run);
  EXPECT_NE(table.str().find("smith_walk"), std::string::npos);
  EXPECT_NE(table.str().find("rays, lost 0"), std::string::npos);
  EXPECT_NE(table.str().find("wall"), std::string::npos);
}

// The masking section on the small run (theta_i = 0, theta_o 0 and 75 deg, azimuth differences 0
// and 180): at theta_o = 0 every point is in view (a vertical line meets the field once), so G1 =
// G2 = 1 exactly and every model says 1; with the light at the normal G2 is G1 under G2's weight,
// and Smith's three forms are all 1 / (1 + Lambda_o). A deliberately wrong model, Smith's at 1.5
// alpha, is caught by the same rule.
TEST(HeightfieldSuite, MaskingSectionSaysWhichModelIsWithinNoise) {
  const HeightfieldSuite s = parse_heightfield_suite(small(), "small.json");
  const HeightfieldRun run = run_heightfield_suite(s, 0, 1);
  ASSERT_EQ(run.cases.size(), 1u);
  const HeightfieldOutcome& o = run.cases[0];
  EXPECT_TRUE(o.pass);
  EXPECT_EQ(o.masking_lost, 0);
  EXPECT_EQ(o.masking_points, 4 * 1500 * (2 + 4));
  ASSERT_EQ(o.g1.size(), 2u);
  ASSERT_EQ(o.g2.size(), 4u);
  for (const HeightfieldMaskingValue* v : {&o.g1[0], &o.g2[0], &o.g2[1]}) {
    EXPECT_EQ(v->theta_o_deg, 0.0);
    EXPECT_EQ(v->g, 1.0);
    for (const HeightfieldMaskingMiss& m : v->models) {
      EXPECT_NEAR(m.value, 1.0, 1e-12) << m.model;
      EXPECT_TRUE(m.within_noise) << m.model;
    }
  }
  const HeightfieldMaskingValue& g2 = o.g2[3];  // theta_o 75, dphi 180
  EXPECT_EQ(g2.theta_o_deg, 75.0);
  EXPECT_EQ(g2.phi_deg, 180.0);
  ASSERT_EQ(g2.models.size(), 4u);
  EXPECT_EQ(g2.g1_i, 1.0);
  EXPECT_EQ(g2.g, g2.g1_o);
  EXPECT_LT(g2.g, 1.0);
  const double smith = 1.0 / (1.0 + analytic::Lambda_beckmann(75.0 * std::numbers::pi / 180.0, 0.3));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(g2.models[static_cast<std::size_t>(k)].value, smith, 1e-15);
  // The overall G1 (weight (o.N)+, the projected area) is Smith's on any field whose D is
  // Beckmann's (docs/derivations/heightfield.md), and the V-cavity's too (it keeps the projected
  // area as well): both within noise.
  const HeightfieldMaskingValue& g1 = o.g1[1];
  ASSERT_EQ(g1.models.size(), 2u);
  EXPECT_NEAR(g1.models[0].value, smith, 1e-15);
  EXPECT_NEAR(g1.models[1].value, smith, 1e-4);
  EXPECT_TRUE(g1.models[0].overall_within_noise) << g1.g << " +- " << g1.g_se << " vs " << smith;
  EXPECT_TRUE(g1.models[1].overall_within_noise) << g1.g << " +- " << g1.g_se << " vs " << g1.models[1].value;
  const double rough = 1.0 / (1.0 + analytic::Lambda_beckmann(75.0 * std::numbers::pi / 180.0, 0.45));
  const HeightfieldMaskingMiss wrong = heightfield_masking_miss(
      "rough", g1, rough, std::vector<double>(g1.bins.size(), rough), s.sigmas, s.model_tolerance);
  EXPECT_FALSE(wrong.overall_within_noise) << wrong.diff << " (" << wrong.z << " se)";

  const json r = heightfield_report_json(s, run);
  const json& m = r["cases"][0]["masking"];
  ASSERT_EQ(m["g2"].size(), 4u);
  for (const json& v : m["g2"])
    for (const char* name :
         {"smith_separable", "smith_height_correlated", "smith_height_direction_correlated", "vcavity"}) {
      const json& mm = v["models"][name];
      EXPECT_EQ(mm["overall_within_noise"].get<bool>(),
                std::abs(mm["diff"].get<double>()) <= s.sigmas * v["traced_se"].get<double>() + s.model_tolerance)
          << name;
    }
  std::ostringstream table;
  print_heightfield_table(table, s, run);
  EXPECT_NE(table.str().find("G2 theta_o 75.0 dphi 180.0: "), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("within noise overall: "), std::string::npos);

  // Two threads: the same values.
  const HeightfieldRun two = run_heightfield_suite(s, 0, 2);
  EXPECT_EQ(two.cases[0].g2[3].g, g2.g);
  ASSERT_EQ(two.cases[0].g2[3].bins.size(), g2.bins.size());
  for (std::size_t b = 0; b < g2.bins.size(); ++b) {  // NaN in bins without points on every field
    const double x = two.cases[0].g2[3].bins[b];
    EXPECT_TRUE(x == g2.bins[b] || (std::isnan(x) && std::isnan(g2.bins[b]))) << b;
  }
}

// "surface" absent and "surface": "gaussian" are one suite, and its report is value for value
// what the suite gave before the key existed (main at b617e36, the small run: 6 of 16000 rays
// twice scattered, the walk's and the V-groove model's L1, the masking's G2 at 75 deg).
TEST(HeightfieldSuite, SurfaceGaussianIsTheDefaultValueForValue) {
  const HeightfieldSuite absent = parse_heightfield_suite(small(), "small.json");
  EXPECT_EQ(absent.surface, HeightfieldSurfaceKind::gaussian);
  json j = small();
  j["surface"] = "gaussian";
  const HeightfieldSuite s = parse_heightfield_suite(j, "small.json");
  ASSERT_EQ(s.surface, HeightfieldSurfaceKind::gaussian);
  const HeightfieldRun run = run_heightfield_suite(s, 0, 1);
  ASSERT_EQ(run.cases.size(), 1u);
  const HeightfieldOutcome& o = run.cases[0];
  EXPECT_EQ(o.energy, (std::vector<double>{0.999625, 0.000375, 0.0}));
  EXPECT_EQ(o.walk.l1_total, 0.09679999999999998);
  EXPECT_DOUBLE_EQ(o.vgroove.l1_total, 0.08901195469699476);
  ASSERT_EQ(o.g2.size(), 4u);
  EXPECT_EQ(o.g2[3].g, 0.9557577974481588);
  const json r = heightfield_report_json(s, run);
  EXPECT_EQ(r["inputs"]["surface"], "gaussian");
  EXPECT_TRUE(r["inputs"].contains("patches_per_field"));
  EXPECT_FALSE(r["inputs"].contains("grooves"));
}

// "surface": "grooves": random-orientation V-groove fields of the case's tilts (64^2 cells, l = 4:
// grooves 12 long and 12 apart, 28 per field). At normal incidence on Beckmann alpha 0.1 every
// groove's tilt is below 30 deg / sqrt(2) (a slope above 0.41 has probability 6e-8 per groove), so
// every triangle, a chord of an s-Lipschitz h, tilts less than 30 deg: a reflected ray climbs at
// more than 30 deg, faster than the surface can rise, and leaves after one bounce: E_1 = 1
// exactly. GGX alpha 0.6 at 45 deg (the broken variant of that bound: its steep grooves scatter
// twice) and every case: no ray lost, F = 1 gives albedo 1, the report names the surface and the
// grooves, and the fields are not the Gaussian ones.
TEST(HeightfieldSuite, GrooveFieldsAreTracedAndReported) {
  json j = small();
  j.erase("masking"), j.erase("controls");
  j["surface"] = "grooves";
  j["ndf"] = {"beckmann"};
  j["alpha"] = {0.1};
  const HeightfieldSuite flat = parse_heightfield_suite(j, "g.json");
  const HeightfieldRun a = run_heightfield_suite(flat, 0, 2);
  ASSERT_EQ(a.cases.size(), 1u);
  EXPECT_TRUE(a.pass);
  EXPECT_EQ(a.cases[0].energy, (std::vector<double>{1.0, 0.0, 0.0}));

  j["ndf"] = {"ggx"};
  j["alpha"] = {0.6};
  j["theta_i_deg"] = {45};
  const HeightfieldSuite s = parse_heightfield_suite(j, "g.json");
  const HeightfieldRun run = run_heightfield_suite(s, 0, 2);
  ASSERT_EQ(run.cases.size(), 1u);
  const HeightfieldOutcome& o = run.cases[0];
  EXPECT_TRUE(run.pass);
  EXPECT_EQ(o.lost, 0);
  EXPECT_FALSE(o.non_finite);
  EXPECT_NEAR(o.albedo, 1.0, 1e-15);
  EXPECT_GT(o.energy[1], s.sigmas * o.energy_se[1]) << "steep grooves scatter twice";
  j["surface"] = "gaussian";
  const HeightfieldRun gauss = run_heightfield_suite(parse_heightfield_suite(j, "g.json"), 0, 2);
  EXPECT_NE(gauss.cases[0].lobe, o.lobe);

  const json r = heightfield_report_json(s, run);
  EXPECT_EQ(r["inputs"]["surface"], "grooves");
  EXPECT_EQ(r["inputs"]["grooves"]["groove_length"], 12.0);
  EXPECT_EQ(r["inputs"]["grooves"]["groove_spacing"], 12.0);
  EXPECT_EQ(r["inputs"]["grooves"]["seed_step"], 2.0);
  EXPECT_EQ(r["inputs"]["grooves"]["grooves_per_field"], 28);
  EXPECT_FALSE(r["inputs"].contains("patches_per_field"));
  for (const char* m : {"smith_walk", "cook_torrance_smith", "vgroove"})
    EXPECT_TRUE(r["cases"][0][m]["against_traced"].contains("within_noise")) << m;
  std::ostringstream table;
  print_heightfield_table(table, s, run);
  EXPECT_NE(table.str().find("random-orientation V-groove fields of 64^2 cells"), std::string::npos) << table.str();
}

// "aspect": alpha_y = aspect alpha on Beckmann Gaussian fields (alpha_x = alpha along the mirror
// azimuth). The control: on mildly anisotropic smooth fields (alpha 0.3 x 0.45) at normal
// incidence the anisotropic walk is within noise (masking and multiple scattering nearly absent);
// the same walk with its axes swapped (0.45 x 0.3: the lobe turned a quarter) is caught by the
// same rule. Cook-Torrance and the V-groove model (isotropic here) are skipped, and say so. (With
// 80000 rays on 256^2 fields the walk's k = 2 row misses by 1.7x at 0.3 x 0.45, as the isotropic
// walk does at a like E_2, alpha 0.4: 1.5x; its k = 1 row stays within, 0.8x.)
TEST(HeightfieldSuite, AnisotropicWalkIsWithinNoiseAndItsSwappedAxesAreNot) {
  json j = small();
  j.erase("masking");
  j["aspect"] = 1.5;
  j["controls"] = {{{"model", "smith_walk"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}}};
  const HeightfieldSuite s = parse_heightfield_suite(j, "a.json");
  ASSERT_TRUE(s.anisotropic());
  const HeightfieldRun run = run_heightfield_suite(s, 0, 2);
  ASSERT_EQ(run.cases.size(), 1u);
  const HeightfieldOutcome& o = run.cases[0];
  EXPECT_TRUE(run.pass);
  EXPECT_EQ(o.lost, 0);
  ASSERT_EQ(run.controls_hold.size(), 1u);
  EXPECT_TRUE(run.controls_hold[0]) << "walk L1 " << o.walk.l1_total << " threshold " << o.walk.l1_total_threshold;
  EXPECT_TRUE(o.ct_lobe.empty());
  EXPECT_TRUE(o.vgroove_lobe.empty());

  const sim::HeightfieldTally w = walk_lobe(analytic::Roughness{NdfKind::beckmann, 0.45, 0.3}, 0.0, s.walk_paths, 7,
                                            s.theta_bins, s.phi_bins, kHeightfieldRows - 1);
  const std::vector<double> swapped = joint_fractions(w, 1);
  std::vector<double> e(kHeightfieldRows, 0.0), var;
  for (int r = 0; r < kHeightfieldRows; ++r)
    for (int b = 0; b < s.bins(); ++b)
      e[static_cast<std::size_t>(r)] += swapped[static_cast<std::size_t>(r * s.bins() + b)];
  for (double p : swapped) var.push_back(p * (1.0 - p) / static_cast<double>(s.walk_paths));
  const HeightfieldMiss m = heightfield_miss(o.lobe, o.lobe_se, o.energy, o.energy_se, swapped, var, e, {},
                                             kHeightfieldRows, s.bins(), s.sigmas, 0.0);
  EXPECT_FALSE(m.within_noise) << "swapped axes: L1 k=1 " << m.l1[0] << " threshold " << m.l1_threshold[0];

  const json r = heightfield_report_json(s, run);
  EXPECT_EQ(r["inputs"]["aspect"], 1.5);
  EXPECT_NE(r["cases"][0]["vgroove"]["skipped"].get<std::string>().find("anisotropic"), std::string::npos);
  EXPECT_TRUE(r["cases"][0]["cook_torrance_smith"].contains("skipped"));
  std::ostringstream table;
  print_heightfield_table(table, s, run);
  EXPECT_NE(table.str().find("skipped: anisotropic roughness (alpha_y = 1.5 alpha_x)"), std::string::npos)
      << table.str();

  // What aspect != 1 refuses, one line each.
  const auto bad = [&](json k, const std::string& part) {
    json b = j;
    for (auto& [key, v] : k.items()) b[key] = v;
    EXPECT_NE(refusal(b, "a.json").find(part), std::string::npos) << refusal(b, "a.json");
  };
  bad({{"aspect", 5}}, "a.json: /aspect");
  bad({{"ndf", {"ggx"}}, {"controls", json::array()}}, "a.json: /aspect = 1.5 (anisotropic) needs ndf [\"beckmann\"]");
  bad({{"surface", "grooves"}}, "a.json: /aspect = 1.5 (anisotropic) needs surface gaussian");
  bad({{"masking", {{"theta_o_deg", {45}}, {"phi_deg", {0}}, {"points", 10}}}}, "a.json: /masking is not measured");
  bad({{"controls", {{{"model", "vgroove"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}}}}},
      "a.json: /controls/0 model vgroove is skipped when aspect != 1");
  bad({{"aspect", 4}}, "a.json: /aspect = 4 (anisotropic) with alpha 0.3 and correlation_length 4: ");
}

// "walk_heights": the walk once per height distribution (Heitz et al. 2016, Sec. 4), each from
// its own stream, side by side. The walk meets heights only through C1(h) (analytic/smith_walk_3d.h),
// so the log C1, uniform and Gaussian walks are one random walk: independent samples of it agree
// within noise (the report's against_first), and each is within noise of the smooth field at
// normal incidence as the control is. The first is the walk before the key, value for value. The
// broken variant: a uniform walk of alpha 0.4 is caught by the same rule. A bad name is refused,
// naming the field and the allowed values.
TEST(HeightfieldSuite, WalkHeightDistributionsAgreeSideBySide) {
  json j = small();
  j.erase("masking");
  j["walk_heights"] = {"log_c1", "uniform", "gaussian"};
  const HeightfieldSuite s = parse_heightfield_suite(j, "w.json");
  ASSERT_EQ(s.walk_heights.size(), 3u);
  const HeightfieldRun run = run_heightfield_suite(s, 0, 2);
  ASSERT_EQ(run.cases.size(), 1u);
  const HeightfieldOutcome& o = run.cases[0];
  EXPECT_TRUE(run.pass);
  EXPECT_EQ(o.walk.l1_total, 0.09679999999999998);  // SurfaceGaussianIsTheDefaultValueForValue's
  ASSERT_EQ(o.other_walks.size(), 2u);
  const json r = heightfield_report_json(s, run);
  EXPECT_EQ(r["inputs"]["walk_heights"], json({"log_c1", "uniform", "gaussian"}));
  EXPECT_EQ(r["cases"][0]["smith_walk"]["heights"], "log_c1");
  const json& others = r["cases"][0]["smith_walk_other_heights"];
  ASSERT_EQ(others.size(), 2u);
  for (std::size_t h = 0; h < 2; ++h) {
    const HeightfieldOtherWalk& w = o.other_walks[h];
    EXPECT_EQ(others[h]["heights"], h == 0 ? "uniform" : "gaussian");
    EXPECT_EQ(w.paths, s.walk_paths);
    EXPECT_NE(w.lobe, o.walk_lobe) << "independent streams";
    EXPECT_TRUE(others[h]["against_first"]["within_noise"])
        << w.heights << ": L1 " << w.against_first.l1_total << " threshold " << w.against_first.l1_total_threshold;
    EXPECT_TRUE(others[h]["against_traced"]["within_noise"])
        << w.heights << ": L1 " << w.against_traced.l1_total << " threshold " << w.against_traced.l1_total_threshold;
  }
  std::ostringstream table;
  print_heightfield_table(table, s, run);
  EXPECT_NE(table.str().find("smith_walk gaussian  within noise; against log_c1: within noise"), std::string::npos)
      << table.str();

  // The broken variant: the uniform walk at alpha 0.4, against the first by the same rule.
  const double paths = static_cast<double>(s.walk_paths);
  const sim::HeightfieldTally wide =
      walk_lobe(analytic::Roughness{NdfKind::beckmann, 0.4, 0.4}, analytic::WalkHeights::uniform, 0.0, s.walk_paths, 11,
                s.theta_bins, s.phi_bins, kHeightfieldRows - 1);
  const std::vector<double> lobe = joint_fractions(wide, 1);
  std::vector<double> var, wide_e(kHeightfieldRows, 0.0), se, e_se;
  for (double p : lobe) var.push_back(p * (1.0 - p) / paths);
  for (double p : o.walk_lobe) se.push_back(std::sqrt(p * (1.0 - p) / paths));
  for (int q = 0; q < kHeightfieldRows; ++q) {
    for (int b = 0; b < s.bins(); ++b)
      wide_e[static_cast<std::size_t>(q)] += lobe[static_cast<std::size_t>(q * s.bins() + b)];
    const double p = o.walk_energy[static_cast<std::size_t>(q)];
    e_se.push_back(std::sqrt(p * (1.0 - p) / paths));
  }
  const HeightfieldMiss m = heightfield_miss(o.walk_lobe, se, o.walk_energy, e_se, lobe, var, wide_e, {},
                                             kHeightfieldRows, s.bins(), s.sigmas, 0.0);
  EXPECT_FALSE(m.within_noise) << "alpha 0.4: L1 k=1 " << m.l1[0] << " threshold " << m.l1_threshold[0];

  const auto bad = [&](const json& v, const std::string& part) {
    json b = j;
    b["walk_heights"] = v;
    EXPECT_NE(refusal(b, "w.json").find(part), std::string::npos) << refusal(b, "w.json");
  };
  bad({"uniform", "lognormal"},
      "w.json: /walk_heights/1 = \"lognormal\" is not one of \"log_c1\", \"uniform\", \"gaussian\"");
  bad({"uniform", "uniform"}, "w.json: /walk_heights/1 = \"uniform\" is given twice");
  bad(json::array(), "w.json: /walk_heights = [] must be a non-empty list");
  bad("uniform", "w.json: /walk_heights = \"uniform\" must be a non-empty list");
}

// "aspect" as a list: cases over its values (ndf, aspect, alpha, theta_i). One number is the
// suite before the list, value for value (main at 05b6ad5, the small anisotropic run: traced E_k,
// the walk's E_k and L1), and a list of one is that number. In a list the first aspect's cases are
// the suite of that aspect alone (the same fields, rays and walks); an isotropic case among them
// compares Cook-Torrance and the V-groove model, an anisotropic one skips them. Each value is
// checked as the number is (range, l_y, ndf, surface), and a control names its aspect.
// The other walks are held by the first walk's rule, model_tolerance included. On a nearly flat
// field at normal incidence (Beckmann 0.1) every path leaves after one bounce in the traced field
// and in every walk: E_1 = 1 with no spread, so without the tolerance the threshold is 0 and a
// difference of rounding fails ("misses: E1 +0.0000 (> 0.0000)", seen with model_tolerance 0).
TEST(HeightfieldSuite, OtherWalksOnANearlyFlatFieldAreHeldWithTheModelTolerance) {
  json j = small();
  j.erase("masking");
  j["alpha"] = {0.1};
  j["controls"] = json::array();
  j["walk_heights"] = {"log_c1", "uniform", "gaussian"};
  const HeightfieldSuite s = parse_heightfield_suite(j, "w.json");
  const HeightfieldRun run = run_heightfield_suite(s, 0, 2);
  ASSERT_EQ(run.cases.size(), 1u);
  const HeightfieldOutcome& o = run.cases[0];
  ASSERT_EQ(o.other_walks.size(), 2u);
  for (const HeightfieldOtherWalk& w : o.other_walks) {
    EXPECT_GT(w.against_first.energy_threshold[0], 0.0) << w.heights;  // row 0: k = 1
    EXPECT_TRUE(w.against_first.within_noise) << w.heights << ": L1 " << w.against_first.l1_total;
    EXPECT_TRUE(w.against_traced.within_noise) << w.heights << ": L1 " << w.against_traced.l1_total;
  }
}

TEST(HeightfieldSuite, AspectListIsCasesOverAspectsAndOneNumberIsAsBefore) {
  json j = small();
  j.erase("masking");
  j["aspect"] = 1.5;
  j["controls"] = {{{"model", "smith_walk"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}}};
  const HeightfieldSuite one = parse_heightfield_suite(j, "a.json");
  const HeightfieldRun a = run_heightfield_suite(one, 0, 2);
  ASSERT_EQ(a.cases.size(), 1u);
  EXPECT_EQ(a.cases[0].energy, (std::vector<double>{0.9929375, 0.007062500000000001, 0.0}));
  EXPECT_EQ(a.cases[0].walk_energy,
            (std::vector<double>{0.9896499999999997, 0.009899999999999997, 0.00045000000000000004}));
  EXPECT_EQ(a.cases[0].walk.l1_total, 0.102275);
  EXPECT_EQ(heightfield_report_json(one, a)["inputs"]["aspect"], 1.5);
  j["aspect"] = {1.5};
  const HeightfieldSuite listed = parse_heightfield_suite(j, "a.json");
  const HeightfieldRun b = run_heightfield_suite(listed, 0, 2);
  EXPECT_EQ(b.cases[0].lobe, a.cases[0].lobe);
  EXPECT_EQ(b.cases[0].walk_lobe, a.cases[0].walk_lobe);
  EXPECT_EQ(heightfield_report_json(listed, b)["inputs"]["aspect"], json({1.5}));

  j["aspect"] = {1, 1.5};
  j["controls"] = {
      {{"model", "cook_torrance_smith"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}, {"aspect", 1}},
      {{"model", "smith_walk"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}, {"aspect", 1.5}}};
  const HeightfieldSuite s = parse_heightfield_suite(j, "a.json");
  ASSERT_EQ(s.cases(), 2u);
  EXPECT_EQ(s.case_at(1).aspect, 1.5);
  EXPECT_EQ(s.controls[1].case_index, 1u);
  const HeightfieldRun run = run_heightfield_suite(s, 0, 2);
  ASSERT_EQ(run.cases.size(), 2u);
  EXPECT_TRUE(run.pass);
  json iso = small();
  iso.erase("masking");
  const HeightfieldRun alone = run_heightfield_suite(parse_heightfield_suite(iso, "a.json"), 0, 2);
  EXPECT_EQ(run.cases[0].lobe, alone.cases[0].lobe);
  EXPECT_EQ(run.cases[0].walk_lobe, alone.cases[0].walk_lobe);
  EXPECT_EQ(run.cases[0].ct_lobe, alone.cases[0].ct_lobe);
  EXPECT_NE(run.cases[1].lobe, a.cases[0].lobe) << "the second aspect's fields are its own";
  EXPECT_TRUE(run.cases[1].ct_lobe.empty());
  const json r = heightfield_report_json(s, run);
  EXPECT_EQ(r["inputs"]["aspect"], json({1, 1.5}));
  EXPECT_EQ(r["cases"][1]["aspect"], 1.5);
  EXPECT_TRUE(r["cases"][0]["vgroove"].contains("against_traced"));
  EXPECT_TRUE(r["cases"][1]["vgroove"].contains("skipped"));
  EXPECT_EQ(r["controls"][1]["aspect"], 1.5);
  std::ostringstream table;
  print_heightfield_table(table, s, run);
  EXPECT_NE(table.str().find("beckmann aspect 1.5 alpha 0.30"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("control: smith_walk on beckmann aspect 1.5 alpha 0.30"), std::string::npos)
      << table.str();

  const auto bad = [&](json k, const std::string& part) {
    json c = j;
    for (auto& [key, v] : k.items()) c[key] = v;
    EXPECT_NE(refusal(c, "a.json").find(part), std::string::npos) << refusal(c, "a.json");
  };
  bad({{"aspect", {1, 5}}}, "a.json: /aspect/1 = 5 is out of range");
  bad({{"aspect", json::array()}}, "a.json: /aspect = [] must be a non-empty list");
  bad({{"aspect", {1, 4}}}, "a.json: /aspect/1 = 4 (anisotropic) with alpha 0.3 and correlation_length 4: ");
  bad({{"ndf", {"ggx"}}, {"controls", json::array()}}, "a.json: /aspect/1 = 1.5 (anisotropic) needs ndf");
  bad({{"controls", {{{"model", "smith_walk"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}}}}},
      "a.json: /controls/0 needs an aspect: the suite has several");
  bad({{"controls",
        {{{"model", "vgroove"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}, {"aspect", 1.5}}}}},
      "a.json: /controls/0 model vgroove is skipped when aspect != 1");
  bad({{"controls",
        {{{"model", "smith_walk"}, {"ndf", "beckmann"}, {"alpha", 0.3}, {"theta_i_deg", 0}, {"aspect", 2}}}}},
      "a.json: /controls/0 names no case of the suite (ndf beckmann, alpha 0.3, theta_i_deg 0, aspect 2)");
  bad({{"masking", {{"theta_o_deg", {45}}, {"phi_deg", {0}}, {"points", 10}}}}, "a.json: /masking is not measured");
}

// The groove suite at full size (data/suites/heightfield_grooves_512.json: 512^2 fields, l = 16,
// 24 cases, 8 fields of 10,000 rays each): what physics says holds. Every ray leaves (F = 1: albedo
// 1, none lost) and, the control, Cook-Torrance with Smith's G is within noise on Beckmann 0.3 at
// normal incidence, where nothing is masked and the k = 1 lobe is the facets' (at 256^2, l = 8, it
// misses by 1.6 times: the triangles across the creases).
TEST(HeightfieldSuiteLong, FullSizeGrooveFieldsHoldTheControls) {
  const std::string file = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/heightfield_grooves_512.json";
  const HeightfieldSuite s = parse_heightfield_suite(json::parse(testing_files::read_text(file)), file);
  ASSERT_EQ(s.field_size, 512);
  ASSERT_EQ(s.controls.size(), 1u);
  const HeightfieldRun run = run_heightfield_suite(s, 0, 2);
  ASSERT_EQ(run.cases.size(), s.cases());
  for (const HeightfieldOutcome& o : run.cases) {
    SCOPED_TRACE(std::string(analytic::ndf_name(o.c.ndf)) + " alpha " + std::to_string(o.c.alpha) + " theta_i " +
                 std::to_string(o.c.theta_i_deg));
    EXPECT_EQ(o.lost, 0);
    EXPECT_FALSE(o.non_finite);
    EXPECT_NEAR(o.albedo, 1.0, 1e-12);
  }
  const HeightfieldOutcome& c = run.cases[s.controls[0].case_index];
  EXPECT_TRUE(run.controls_hold[0]) << "Cook-Torrance k = 1: L1 " << c.cook_torrance.l1[0] << " threshold "
                                    << c.cook_torrance.l1_threshold[0] << ", E_1 diff "
                                    << c.cook_torrance.energy_diff[0] << " threshold "
                                    << c.cook_torrance.energy_threshold[0];
  EXPECT_TRUE(run.pass);
}

// The command line: an oversized field is refused before any work, one line naming the key and
// the range, exit 2, no report; the tiny suite runs and prints its errors beside rays and time.
TEST(HeightfieldSuiteCli, AnOversizedFieldIsRefusedInOneLineAndNothingIsWritten) {
  if (support::memory_limit_bytes() >= sim::heightfield_bytes(65536)) GTEST_SKIP() << "this machine holds 126 GB";
  testing_files::TempDir dir;
  const std::string f = dir.file("big.json"), out = dir.file("r.json");
  json j = shipped();
  j["field_size"] = 65536;
  testing_files::write_text(f, j.dump());
  const testing_files::CliRun r =
      testing_files::vgroove("validate " + testing_files::quoted(f) + " --out " + testing_files::quoted(out));
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_EQ(testing_files::lines(r.err), 1) << r;
  EXPECT_NE(r.err.find("big.json: /field_size = 65536 needs 126.0 GB with its hierarchy"), std::string::npos) << r;
  EXPECT_NE(r.err.find("it must be a power of two in [16, "), std::string::npos) << r;
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_TRUE(r.out.empty()) << r;  // refused before any work: no table

  const std::string small_file = dir.file("small.json"), small_out = dir.file("s.json");
  testing_files::write_text(small_file, small().dump());
  const testing_files::CliRun ok = testing_files::vgroove("validate " + testing_files::quoted(small_file) +
                                                          " --threads 2 --out " + testing_files::quoted(small_out));
  EXPECT_EQ(ok.status, 0) << ok;
  EXPECT_NE(ok.out.find("16000 rays, lost 0"), std::string::npos) << ok;
  EXPECT_NE(ok.out.find("control: cook_torrance_smith on beckmann alpha 0.30 theta_i 0.0: within noise"),
            std::string::npos)
      << ok;
  EXPECT_TRUE(std::filesystem::exists(small_out));
}

}  // namespace
}  // namespace vgroove::validation
