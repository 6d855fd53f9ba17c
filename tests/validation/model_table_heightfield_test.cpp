// The model-table route on random heightfields ("brdf" suites with "surface": "heightfield",
// data/suites/brdf_heightfield.json): Cook-Torrance with Smith's height-correlated G on smooth
// Beckmann fields (alpha 0.2, theta_i 0 and 30 deg: single scattering carries all but ~1e-5 of
// the light) passes, the same lobe 1.1 times brighter or at 1.5 alpha fails, and every number
// is check_brdf's with surface heightfield on the same options (the same fields and rays, the
// noise from the fields' spread), for any thread count and any split into shards. Bad surfaces
// are refused in one line; through the CLI, exit 2 and no file.
#include "vgroove/validation/model_table.h"

#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_lobe_shape.h"

#include "tests/cli_run.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace vgroove::validation {
namespace {

using nlohmann::json;
using testing_files::TempDir;
using testing_files::write_text;

const std::string kSuiteFile = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/brdf_heightfield.json";

json suite_json() { return support::read_json_file(kSuiteFile); }
BrdfSuite suite() { return parse_brdf_suite(suite_json(), kSuiteFile); }

const analytic::MicrofacetModel kSmith{NdfKind::beckmann, analytic::MaskingKind::smith_height_correlated};

// Cook-Torrance with Smith's G at `alpha`, times `scale`.
BrdfFn smith(double alpha, double scale = 1.0) {
  return [=](const analytic::Dir3& i, const analytic::Dir3& o) {
    return scale * single_scattering_brdf(kSmith, alpha, i, o);
  };
}

// The model table of f: its lobe integrated over the layout's bins as check_brdf integrates it.
json table_of(const BrdfSuite& s, const BrdfFn& f) {
  const json layout = bin_layout_json(s);
  json t = {{"kind", "model_table"}, {"suite", s.name}, {"model", "Cook-Torrance, Smith G"}};
  t["cases"] = json::array();
  for (const json& c : layout["cases"]) {
    const std::size_t n = c["case"].get<std::size_t>();
    json e = c;
    e.erase("bins");
    e["flux"] = integrate_model_lobe(batch_of(f), c["theta_i_deg"].get<double>(), case_check_options(s, n, 0)).flux;
    t["cases"].push_back(e);
  }
  return t;
}

ModelTableRun run(const BrdfSuite& s, const BrdfFn& f, int threads = 2) {
  return run_model_table(s, parse_model_table(table_of(s, f), "t.json", s), 0, threads);
}

// The table's verdict and numbers are check_brdf's on the suite's options (its cases share ndf
// and alpha: one check_brdf run over the suite's theta_i). The thresholds differ only by
// check_brdf's integration error, which widens its thresholds and not the table's.
void expect_same_as_check_brdf(const BrdfSuite& s, const BrdfFn& f, const ModelTableRun& table) {
  CheckBrdfOptions o = case_check_options(s, 0, 0);
  o.threads = 2;
  const CheckBrdfResult check = check_brdf(f, o);
  ASSERT_EQ(check.cases.size(), table.cases.size());
  EXPECT_EQ(check.pass, table.pass);
  for (std::size_t c = 0; c < table.cases.size(); ++c) {
    const CheckBrdfCase &a = check.cases[c], &b = table.cases[c];
    EXPECT_EQ(a.rays, b.rays);
    EXPECT_EQ(a.albedo_sim, b.albedo_sim);
    EXPECT_EQ(a.albedo_model, b.albedo_model);
    EXPECT_EQ(a.l1, b.l1);
    EXPECT_EQ(a.l1_flux, b.l1_flux);
    EXPECT_EQ(a.l1_expected, b.l1_expected);
    EXPECT_EQ(a.l1_flux_expected, b.l1_flux_expected);
    EXPECT_NEAR(a.l1_threshold - b.l1_threshold, a.model_error, 1e-15);
    EXPECT_NEAR(a.l1_flux_threshold - b.l1_flux_threshold, a.model_error, 1e-15);
    EXPECT_NEAR(a.albedo_threshold - b.albedo_threshold, a.model_error, 1e-15);
    EXPECT_EQ(a.pass, b.pass) << "case " << c;
  }
}

TEST(ModelTableHeightfield, SmithPassesAsInCheckBrdf) {
  const BrdfSuite s = suite();
  ASSERT_EQ(s.surface, CheckSurface::heightfield);
  const ModelTableRun ok = run(s, smith(0.2));
  ASSERT_EQ(ok.cases.size(), 2u);
  EXPECT_TRUE(ok.pass) << model_table_report_json(s, {}, ok).dump(1);
  for (const CheckBrdfCase& c : ok.cases) {
    EXPECT_EQ(c.rays, 20000);
    EXPECT_NEAR(c.albedo_sim, 1.0, 1e-15);  // F = 1: every ray leaves
  }
  expect_same_as_check_brdf(s, smith(0.2), ok);
  const json report = model_table_report_json(s, {}, ok);
  EXPECT_EQ(report["surface"], "heightfield");
  EXPECT_EQ(report["heightfield"]["fields"], 4);
  EXPECT_FALSE(report.contains("grooves"));
}

TEST(ModelTableHeightfield, WrongModelsFailAsInCheckBrdf) {
  const BrdfSuite s = suite();
  // 10% too bright: the albedo, 0.1 against a threshold of 1 / rays + tolerance.
  const ModelTableRun bright = run(s, smith(0.2, 1.1));
  EXPECT_FALSE(bright.pass);
  for (const CheckBrdfCase& c : bright.cases) EXPECT_GT(c.albedo_model - c.albedo_sim, c.albedo_threshold);
  expect_same_as_check_brdf(s, smith(0.2, 1.1), bright);
  // 1.5 times the roughness: the shape.
  const ModelTableRun rough = run(s, smith(0.3));
  EXPECT_FALSE(rough.pass);
  EXPECT_GT(rough.cases[0].l1, rough.cases[0].l1_threshold);
  expect_same_as_check_brdf(s, smith(0.3), rough);
}

TEST(ModelTableHeightfield, OneReportForAnyThreadsAndShards) {
  BrdfSuite s = suite();
  s.rays = 9001;  // not a multiple of the fields or the chunks
  const ModelTable t = parse_model_table(table_of(s, smith(0.2)), "t.json", s);
  const json one = model_table_report_json(s, t, run_model_table(s, t, 0, 1))["cases"];
  const json two = model_table_report_json(s, t, run_model_table(s, t, 0, 3))["cases"];
  // Three shards, merged as `vgroove merge` merges them.
  const auto job =
      model_table_job(s, 0, {{"input_file", kSuiteFile}, {"input_path", kSuiteFile}, {"command", "validate"}});
  std::vector<Part> parts;
  for (int k = 1; k <= 3; ++k)
    parts.push_back(part_from_json(*run_job_part(job, support::Shard{k, 3}, 1), "part " + std::to_string(k)));
  const json merged =
      model_table_report_json(s, t, model_table_run_from(s, t, 0, merge_job_parts(job, parts)))["cases"];
  ASSERT_EQ(one.size(), 2u);
  for (const json* other : {&two, &merged}) {
    for (std::size_t c = 0; c < one.size(); ++c) {
      EXPECT_EQ(one[c]["rays"], 9001);
      for (const char* key : {"rays", "albedo_sim", "l1", "l1_threshold", "l1_flux", "l1_flux_threshold", "pass"})
        EXPECT_EQ(one[c][key], (*other)[c][key]) << key;
    }
  }
}

std::string refusal(const json& j) {
  try {
    parse_brdf_suite(j, "s.json");
  } catch (const support::UserError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ModelTableHeightfield, BadSurfacesAreRefusedInOneLine) {
  json j = suite_json();
  j["surface"] = "heightfields";
  EXPECT_EQ(refusal(j), "s.json: /surface = \"heightfields\" is not one of \"vgroove\", \"heightfield\"");
  j = suite_json();
  j["heightfield"]["field_size"] = 100;
  EXPECT_EQ(refusal(j), "s.json: surface heightfield: field_size = 100 is out of range [16, 65536], a power of two");
  j["heightfield"]["field_size"] = 8;
  EXPECT_EQ(refusal(j).find("s.json: /heightfield/field_size = 8"), 0u) << refusal(j);
  j = suite_json();
  j["heightfield"]["fields"] = 1;
  EXPECT_EQ(refusal(j).find("s.json: /heightfield/fields = 1"), 0u) << refusal(j);
  j = suite_json();
  j["rays"] = 3;  // fewer rays than fields
  EXPECT_EQ(refusal(j), "s.json: surface heightfield: fields = 4 is out of range [2, 3]");
  j = suite_json();
  j["heightfield"]["correlation_length"] = 9;  // > 64 / 8
  EXPECT_EQ(refusal(j), "s.json: surface heightfield: correlation_length = 9 is out of range [2, 8]");
  j = suite_json();
  j["dimensions"] = {"3d", "flatland"};
  EXPECT_EQ(refusal(j), "s.json: surface heightfield: dim = flatland: surface heightfield is a 3D surface (dim 3d)");
  j = suite_json();
  j["ndf"] = {"phong"};
  EXPECT_NE(refusal(j).find("ndf = phong: surface heightfield takes beckmann or ggx"), std::string::npos) << refusal(j);
  j = suite_json();
  j.erase("heightfield");
  EXPECT_EQ(refusal(j).find("s.json: /heightfield"), 0u) << refusal(j);
  j = suite_json();
  j["surface"] = "vgroove";
  j["grooves"] = 1000;
  EXPECT_EQ(refusal(j).find("s.json: /heightfield is given but surface is \"vgroove\""), 0u) << refusal(j);
  j.erase("heightfield");
  EXPECT_EQ(refusal(j), "accepted");
}

TEST(ModelTableHeightfield, CliWritesTheLayoutAndRefusesBadSuitesWithoutAFile) {
  TempDir d;
  const std::string layout = d.file("layout.json"), out = d.file("r.json"), bad = d.file("bad.json");
  const auto bins = testing_files::vgroove("bins '" + kSuiteFile + "' --out '" + layout + "'");
  ASSERT_EQ(bins.status, 0) << bins;
  const json l = support::read_json_file(layout);
  EXPECT_EQ(l["surface"], "heightfield");
  EXPECT_EQ(l["heightfield"]["field_size"], 64);
  EXPECT_EQ(l["cases"].size(), 2u);
  json j = suite_json();
  j["heightfield"]["field_size"] = 100;
  write_text(bad, j.dump());
  for (const std::string& cmd :
       {"bins '" + bad + "' --out '" + out + "'", "validate '" + bad + "' --out '" + out + "'"}) {
    const auto r = testing_files::vgroove(cmd);
    EXPECT_EQ(r.status, 2) << r;
    EXPECT_EQ(testing_files::lines(r.err), 1) << r;
    EXPECT_NE(r.err.find("field_size = 100 is out of range [16, 65536], a power of two"), std::string::npos) << r;
    EXPECT_FALSE(std::filesystem::exists(out));
  }
  // The table through the CLI, whole and in two shards merged: the same cases.
  const std::string table = d.file("t.json"), p1 = d.file("p1.json"), p2 = d.file("p2.json"), m = d.file("m.json");
  write_text(table, table_of(suite(), smith(0.2)).dump());
  const std::string run = "validate '" + kSuiteFile + "' --model-table '" + table + "' --threads 2 --out ";
  const auto whole = testing_files::vgroove(run + "'" + out + "'");
  ASSERT_EQ(whole.status, 0) << whole;
  EXPECT_NE(whole.out.find("rays over 4 heightfields of 64^2 cells"), std::string::npos) << whole;
  ASSERT_EQ(testing_files::vgroove(run + "'" + p1 + "' --shard 1/2").status, 0);
  ASSERT_EQ(testing_files::vgroove(run + "'" + p2 + "' --shard 2/2").status, 0);
  const auto merged = testing_files::vgroove("merge '" + p2 + "' '" + p1 + "' --out '" + m + "'");
  ASSERT_EQ(merged.status, 0) << merged;
  const json a = support::read_json_file(out), b = support::read_json_file(m);
  EXPECT_TRUE(a["pass"].get<bool>());
  EXPECT_EQ(a["cases"], b["cases"]);
  std::filesystem::remove(out);
  // Without a model table there is no model to hold against the fields.
  const auto none = testing_files::vgroove("validate '" + kSuiteFile + "' --out '" + out + "'");
  EXPECT_EQ(none.status, 2) << none;
  EXPECT_NE(none.err.find("surface heightfield is held against a model table: give --model-table FILE"),
            std::string::npos)
      << none;
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace vgroove::validation
