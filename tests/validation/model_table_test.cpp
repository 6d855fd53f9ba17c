// Tests of the model-table route: a table of vgroove's own lobes passes, Cook-Torrance's fails,
// and every kind of bad table is refused with the file, the JSON path and what was expected;
// through the CLI, exit 2 and no report.
#include "vgroove/validation/model_table.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"

#include "tests/cli_run.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace vgroove::validation {
namespace {

using nlohmann::json;
using testing_files::TempDir;
using testing_files::write_text;

const char* kSuite = R"({"name": "mini", "kind": "brdf", "ndf": ["ggx"], "alpha": [0.7],
  "theta_i_deg": [0, 50], "dimensions": ["flatland", "3d"], "rays": 200000, "grooves": 100000, "seed": 3,
  "flatland_bins": 45, "theta_bins": 15, "phi_bins": 12, "max_k": 16,
  "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}}})";

BrdfSuite suite() { return parse_brdf_suite(json::parse(kSuite), "mini.json"); }

// The table of vgroove's own lobes (or Cook-Torrance's single scattering), from the layout.
json table_of(const BrdfSuite& s, bool cook_torrance) {
  const json layout = bin_layout_json(s);
  json t = {{"kind", "model_table"}, {"suite", s.name}, {"model", cook_torrance ? "ct" : "vgroove"}};
  t["cases"] = json::array();
  for (const json& c : layout["cases"]) {
    const BrdfCase k = s.case_at(c["case"].get<std::size_t>());
    std::vector<double> flux;
    if (k.dim == SurfaceDim::flatland) {
      flux = cook_torrance ? analytic::flatland_single_lobe(k.ndf, k.alpha, k.theta_i, s.flatland_bins).theta_o
                           : analytic::flatland_lobe(k.ndf, k.alpha, k.theta_i, s.flatland_bins, s.max_k).theta_o;
    } else {
      flux = cook_torrance
                 ? analytic::cook_torrance_lobe_3d(k.ndf, k.alpha, k.theta_i, s.theta_bins, s.phi_bins).hist
                 : analytic::vgroove_lobe_3d(k.ndf, k.alpha, k.theta_i, s.theta_bins, s.phi_bins, s.max_k).hist;
    }
    json e = c;
    e.erase("bins");
    e["flux"] = flux;
    t["cases"].push_back(e);
  }
  return t;
}

TEST(ModelTable, OwnLobesPassCookTorranceFails) {
  const BrdfSuite s = suite();
  const ModelTableRun ours = run_model_table(s, parse_model_table(table_of(s, false), "t.json", s), 0, 2);
  EXPECT_TRUE(ours.pass) << model_table_report_json(s, {}, ours).dump(1);
  const ModelTableRun ct = run_model_table(s, parse_model_table(table_of(s, true), "t.json", s), 0, 2);
  EXPECT_FALSE(ct.pass);
  for (const CheckBrdfCase& c : ct.cases) EXPECT_GT(c.albedo_sim - c.albedo_model, c.albedo_threshold);
}

std::string refusal(const json& t) {
  try {
    parse_model_table(t, "t.json", suite());
  } catch (const support::UserError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ModelTable, BadTablesAreRefused) {
  const json good = table_of(suite(), false);
  json t = good;
  t["cases"][1]["flux"].erase(0);
  EXPECT_EQ(refusal(t),
            "t.json: /cases/1/flux must be a list of 45 numbers (the layout's bins for flatland), found 44 values");
  t = good;
  t["cases"][2]["flux"][7] = -0.5;
  EXPECT_EQ(refusal(t), "t.json: /cases/2/flux/7 = -0.5 must be a number in [0, 1] (a fraction of the incident flux)");
  t = good;
  t["cases"][2]["flux"][7] = nullptr;
  EXPECT_EQ(refusal(t), "t.json: /cases/2/flux/7 = null must be a number in [0, 1] (a fraction of the incident flux)");
  t = good;
  t["cases"][2]["flux"][7] = "NaN";
  EXPECT_EQ(refusal(t),
            "t.json: /cases/2/flux/7 = \"NaN\" must be a number in [0, 1] (a fraction of the incident flux)");
  // 1e308 overflowed the case's albedo to infinity (a report with null and non_finite false).
  for (double big : {1e308, 1.5}) {
    t = good;
    t["cases"][2]["flux"][7] = big;
    EXPECT_EQ(refusal(t), "t.json: /cases/2/flux/7 = " + support::value_text(big) +
                              " must be a number in [0, 1] (a fraction of the incident flux)");
  }
  t = good;
  t["cases"].erase(3);
  EXPECT_EQ(refusal(t), "t.json: /cases has no entry for case 3 (4 cases expected, see `vgroove bins mini.json`)");
  t = good;
  t["cases"][0]["case"] = 1;
  EXPECT_EQ(refusal(t).rfind("t.json: /cases/0/case = 1 is ndf ggx, alpha 0.7, theta_i_deg 50, dimension flatland", 0),
            0u)
      << refusal(t);
  t = good;
  t["suite"] = "fig11";
  EXPECT_EQ(refusal(t), "t.json: /suite = \"fig11\" names another suite; this table must be made for \"mini\"");
  t = good;
  t["cases"][0]["fluxes"] = t["cases"][0]["flux"];
  EXPECT_NE(refusal(t).find("/cases/0/fluxes"), std::string::npos);
}

TEST(ModelTable, CliRefusesABadTableWithoutAReport) {
  TempDir d;
  const std::string suite_file = d.file("mini.json"), table = d.file("t.json"), out = d.file("r.json");
  write_text(suite_file, kSuite);
  json t = table_of(suite(), false);
  t["suite"] = "mini";
  t["cases"][0]["flux"][0] = -1;
  write_text(table, t.dump());
  const auto r =
      testing_files::vgroove("validate '" + suite_file + "' --model-table '" + table + "' --out '" + out + "'");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_NE(r.err.find("/cases/0/flux/0 = -1 must be a number in [0, 1]"), std::string::npos) << r;
  EXPECT_FALSE(std::filesystem::exists(out));
  const auto single = testing_files::vgroove(std::string("validate '") + VGROOVE_SOURCE_DIR +
                                             "/data/suites/table1_symmetric.json' --model-table '" + table + "'");
  EXPECT_EQ(single.status, 2) << single;
  EXPECT_NE(single.err.find("--model-table applies to suites of kind \"brdf\""), std::string::npos) << single;
}

}  // namespace
}  // namespace vgroove::validation
