// Tests of validation/heightfield_albedo.h: the albedo of random heightfields per k, F = 1.
#include "vgroove/validation/heightfield_albedo.h"

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/outcome_fields.h"
#include "vgroove/validation/partial_report.h"

#include "tests/user_error_of.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;

// Beckmann alpha 0.1 and 0.3 on 64^2 fields (l = 4 cells), mu 1 and cos 70 deg.
json small() {
  return {{"name", "small"},
          {"kind", "heightfield_albedo"},
          {"ndf", {"beckmann"}},
          {"alpha", {0.1, 0.3}},
          {"mu", {1.0, 0.3420201433256687}},
          {"field_size", 64},
          {"correlation_length", 4},
          {"fields", 4},
          {"rays", 6000},
          {"walk_paths", 5000},
          {"seed", 1},
          {"thresholds", {{"sigmas", 5}}}};
}

json outcome_without_timing(HeightfieldAlbedoOutcome o) {
  o.field_s = o.trace_s = o.walk_s = o.model_s = 0.0;
  return outcome_fields::to_json(o);
}

// One shared run of the small suite (about 0.4 s in Release).
const HeightfieldAlbedoRun& small_run() {
  static const HeightfieldAlbedoRun run =
      run_heightfield_albedo(parse_heightfield_albedo_suite(small(), "s.json"), 0, 1);
  return run;
}

TEST(HeightfieldAlbedo, EveryRayLeavesSoTheFurnaceIsExactlyOneAndALostRayFails) {
  const HeightfieldAlbedoSuite s = parse_heightfield_albedo_suite(small(), "s.json");
  const HeightfieldAlbedoRun& run = small_run();
  ASSERT_EQ(run.items.size(), 2u);
  ASSERT_EQ(run.points.size(), 4u);
  EXPECT_TRUE(run.pass);
  for (const HeightfieldAlbedoOutcome& o : run.items) {
    EXPECT_EQ(o.rays, 4 * 2 * 6000);
    EXPECT_EQ(o.lost, 0);
    EXPECT_EQ(o.bounce_limit, 0);
    // F = 1 and no ray lost: each field's E is its escaped fraction, exactly 1, and the orders
    // add up to it (counts over the same rays).
    for (std::size_t q = 0; q < o.traced.size(); q += 4) {
      EXPECT_EQ(o.traced[q], 1.0) << "field/mu " << q / 4;
      EXPECT_NEAR(o.traced[q + 1] + o.traced[q + 2] + o.traced[q + 3], 1.0, 4e-16) << "field/mu " << q / 4;
    }
  }
  for (const AlbedoPoint& p : run.points) {
    EXPECT_EQ(p.traced[0], 1.0);
    EXPECT_NEAR(p.traced[1] + p.traced[2], 1.0, 1e-15);
    // The walk and the V-groove model keep the white furnace too.
    EXPECT_TRUE(p.models[0][0].within_noise) << p.models[0][0].value;
    EXPECT_NEAR(p.models[2][0].value, 1.0, 1e-8);
  }
  // Deliberately broken: one ray of one field kept at the bounce limit: E < 1 there, the item fails.
  std::vector<UnitResult<HeightfieldAlbedoWork>> results;
  for (const auto& o : run.items) results.push_back({o, std::nullopt});
  results[1].tally.bounce_limit = 1;
  results[1].tally.traced[0] -= 1.0 / 6000;
  const HeightfieldAlbedoRun broken = heightfield_albedo_run_from(s, results);
  EXPECT_FALSE(broken.pass);
  EXPECT_TRUE(broken.item_pass[0]);
  EXPECT_FALSE(broken.item_pass[1]);
}

TEST(HeightfieldAlbedo, SmoothFieldsAtNormalIncidenceScatterOnce) {
  // Beckmann alpha 0.1, mu = 1: a facet at 45 deg would be needed for a second bounce (slopes of
  // 10 sigma): Smith's E_ss is 1 to 1e-9 and the traced E_1 is 1 but for its count.
  const AlbedoPoint& p = small_run().points[0];
  ASSERT_EQ(p.alpha, 0.1);
  ASSERT_EQ(p.mu, 1.0);
  const double ess = p.models[1][1].value;
  EXPECT_GT(ess, 1.0 - 1e-9);
  EXPECT_LE(ess, 1.0);
  EXPECT_EQ(p.traced[1], 1.0);
  EXPECT_TRUE(p.models[1][1].within_noise);
  // Its se is that of a count of 24000 rays (1 / N), so that a model 1e-3 short is caught.
  EXPECT_NEAR(p.traced_se[1], 1.0 / 24000.0, 1e-12);
  EXPECT_GT(std::abs(p.traced[1] - 0.999), 5.0 * p.traced_se[1] + 1e-4);
}

TEST(HeightfieldAlbedo, FirstOrderIsSmithsEssOnBeckmannFieldsAndTheVcavityIsCaught) {
  // Beckmann alpha 0.1 at 70 deg: E_1 0.994, E_2 0.006 on the fields; Smith's E_ss and the walk
  // within noise. Deliberately wrong: the V-cavity G's E_ss (Cook-Torrance's albedo), 0.005 lower.
  const HeightfieldAlbedoRun& run = small_run();
  const AlbedoPoint& p = run.points[1];
  ASSERT_EQ(p.alpha, 0.1);
  ASSERT_NEAR(p.mu, 0.342, 1e-3);
  for (int m : {0, 1})
    EXPECT_TRUE(p.models[m][1].within_noise)
        << kAlbedoModelNames[m] << " " << p.models[m][1].value << " traced " << p.traced[1] << " se " << p.traced_se[1];
  const analytic::MicrofacetModel vcavity{NdfKind::beckmann, analytic::MaskingKind::vcavity};
  const double wrong = analytic::albedo_single(vcavity, 0.1, p.mu).value;
  const double sd = p.traced_se[1];
  EXPECT_GT(std::abs(p.traced[1] - wrong), 5.0 * sd + 1e-4) << "V-cavity " << wrong << " traced " << p.traced[1];
  // The plain text names the models within noise.
  EXPECT_NE(albedo_row_text(p, 1).find("within noise: smith_walk, smith_ess"), std::string::npos)
      << albedo_row_text(p, 1);
}

TEST(HeightfieldAlbedo, ThreadsAndShardsGiveTheSameBits) {
  const HeightfieldAlbedoSuite s = parse_heightfield_albedo_suite(small(), "s.json");
  const HeightfieldAlbedoRun& one = small_run();
  const HeightfieldAlbedoRun two = run_heightfield_albedo(s, 0, 2);
  ASSERT_EQ(two.items.size(), one.items.size());
  for (std::size_t i = 0; i < one.items.size(); ++i)
    EXPECT_EQ(outcome_without_timing(two.items[i]), outcome_without_timing(one.items[i])) << "item " << i;
  // Shards 1/2 and 2/2, written as parts and merged: the one-process outcomes.
  const json descriptor = {{"command", "test"}, {"input_file", "s.json"}, {"input_path", "/s.json"}};
  const auto job = heightfield_albedo_job(s, 0, descriptor);
  std::vector<Part> parts;
  for (int k = 1; k <= 2; ++k)
    parts.push_back(part_from_json(*run_job_part(job, support::Shard{k, 2}, 1), "part " + std::to_string(k)));
  const HeightfieldAlbedoRun merged = heightfield_albedo_run_from(s, merge_job_parts(job, parts));
  ASSERT_EQ(merged.items.size(), one.items.size());
  for (std::size_t i = 0; i < one.items.size(); ++i)
    EXPECT_EQ(outcome_without_timing(merged.items[i]), outcome_without_timing(one.items[i])) << "item " << i;
  // Deliberately broken: another seed changes the bits.
  HeightfieldAlbedoSuite other = s;
  other.seed = 2;
  other.alphas = {0.3};
  EXPECT_NE(outcome_without_timing(run_heightfield_albedo_item(other, 0, 0)), outcome_without_timing(one.items[1]));
}

TEST(HeightfieldAlbedo, ReportAndTableSayWhichModelIsWithinNoise) {
  const HeightfieldAlbedoSuite s = parse_heightfield_albedo_suite(small(), "s.json");
  const HeightfieldAlbedoRun& run = small_run();
  const json r = heightfield_albedo_report_json(s, run);
  EXPECT_EQ(r["kind"], "heightfield_albedo");
  ASSERT_EQ(r["points"].size(), 4u);
  EXPECT_EQ(r["points"][1]["traced"].size(), 5u);
  EXPECT_TRUE(r["points"][1]["models"]["smith_ess"]["value"][0].is_null());
  EXPECT_EQ(r["points"][1]["models"]["smith_ess"]["within_noise"][1], true);
  EXPECT_NE(r["points"][1]["plainly"]["E_1"].get<std::string>().find("smith_ess"), std::string::npos);
  EXPECT_EQ(r["pass"], true);
  std::ostringstream table;
  print_heightfield_albedo_table(table, s, run);
  EXPECT_NE(table.str().find("beckmann alpha 0.10 mu 0.3420 (70.0 deg)"), std::string::npos) << table.str();
  EXPECT_NE(table.str().find("2/2 (ndf, alpha) pass"), std::string::npos) << table.str();
}

TEST(HeightfieldAlbedo, BadSpecsNameTheFieldAndRange) {
  json j = small();
  j["mu"] = {1.0, 0.0};
  EXPECT_TRUE(testing_files::user_error_contains([&] { parse_heightfield_albedo_suite(j, "s.json"); },
                                                 "s.json: /mu/1 = 0 is out of range"));
  j = small();
  j["field_size"] = 100;
  EXPECT_TRUE(testing_files::user_error_contains([&] { parse_heightfield_albedo_suite(j, "s.json"); },
                                                 "/field_size = 100 must be a power of two"));
  j = small();
  j["correlation_length"] = 9;
  EXPECT_TRUE(testing_files::user_error_contains([&] { parse_heightfield_albedo_suite(j, "s.json"); },
                                                 "/correlation_length = 9 is out of range"));
  j = small();
  j["ndf"] = {"phong"};
  EXPECT_TRUE(testing_files::user_error_contains([&] { parse_heightfield_albedo_suite(j, "s.json"); }, "/ndf/0"));
  j = small();
  j["muu"] = 1;
  EXPECT_TRUE(testing_files::user_error_contains([&] { parse_heightfield_albedo_suite(j, "s.json"); }, "muu"));
}

}  // namespace
}  // namespace vgroove::validation
