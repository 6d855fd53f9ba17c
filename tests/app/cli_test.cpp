// Tests of the vgroove command line, through the built binary: exit status 2 and one line on
// stderr for bad input, no silent overwrite, and trace / analytic agreeing in the same JSON shape.
#include "tests/cli_run.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <cstdio>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>

namespace vgroove::validation {
namespace {

using nlohmann::json;
using testing_files::CliRun;
using testing_files::read_text;
using testing_files::TempDir;
using testing_files::vgroove;
using testing_files::write_text;

using testing_files::lines;
using testing_files::quoted;

// A bad value: exit 2, nothing on stdout, one line on stderr naming the option and its range.
void expect_user_error(const CliRun& r, const std::string& option, const std::string& range) {
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_EQ(r.out, "") << r;
  EXPECT_EQ(lines(r.err), 1) << r;
  EXPECT_CONTAINS(r.err, option);
  EXPECT_CONTAINS(r.err, range);
}

TEST(Cli, ThetaVOutOfRange) {
  expect_user_error(vgroove("trace --theta-v-deg 195"), "--theta-v-deg", "[0.001, 180]");
  expect_user_error(vgroove("trace --theta-v-deg 0"), "--theta-v-deg", "[0.001, 180]");
  expect_user_error(vgroove("analytic --theta-v-deg 195"), "--theta-v-deg", "[0.001, 180]");
}

TEST(Cli, ThetaIOutOfRange) {
  expect_user_error(vgroove("trace --theta-i-deg 90"), "--theta-i-deg", "[-89.999, 89.999]");
  expect_user_error(vgroove("trace --theta-i-deg=-90"), "--theta-i-deg", "[-89.999, 89.999]");
  expect_user_error(vgroove("analytic --theta-i-deg 90"), "--theta-i-deg", "[-89.999, 89.999]");
}

TEST(Cli, TooFewRays) {
  expect_user_error(vgroove("trace --rays 0"), "--rays", "[1, ");
  expect_user_error(vgroove("trace --rays -3"), "--rays", "[1, ");
}

TEST(Cli, BadChoice) {
  expect_user_error(vgroove("trace --sampling sobol"), "--sampling", "\"stratified\", \"random\"");
  expect_user_error(vgroove("analytic --eq6-form fixed"), "--eq6-form", "\"corrected\", \"printed\"");
}

TEST(Cli, NarrowestAcceptedGrooveGivesNoNegativeBounceCount) {
  // --theta-v-deg 1e-8: Eq. (4) would overflow int below pi / INT_MAX (8.4e-8 deg); the CLI must
  // either refuse it (exit 2, as it does: the range starts at 1e-6 deg) or predict k >= 0.
  const CliRun a = vgroove("analytic --json --theta-v-deg 1e-8");
  if (a.status == 2) return;
  ASSERT_EQ(a.status, 0) << a;
  const json j = json::parse(a.out);
  ASSERT_FALSE(j.at("bounces").empty()) << a;
  for (const json& row : j.at("bounces")) EXPECT_GE(row.at("k").get<long long>(), 0) << a;
}

TEST(Cli, UnknownOptionExitsTwo) {
  const CliRun r = vgroove("trace --theta-w-deg 10");
  EXPECT_EQ(r.status, 2) << r;
}

TEST(Cli, HelpExitsZero) {
  const CliRun r = vgroove("--help");
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_CONTAINS(r.out, "trace");
  EXPECT_CONTAINS(r.out, "validate");
}

// ---------------------------------------------------------------------------------------------
// validate

// A suite of 2 x 3 cases, quick to run.
std::string small_suite(const TempDir& dir) {
  const std::string f = dir.file("small.json");
  write_text(f, R"({
    "name": "cli_small",
    "kind": "table1",
    "groove": {"type": "symmetric", "theta_v_deg": [30, 90]},
    "theta_i_deg": [-40, 0, 25],
    "rays": 200,
    "thresholds": {"max_l1": 0.05, "mean_l1": 0.05, "max_theta_o_error_rad": 1e-9}
  })");
  return f;
}

TEST(Cli, NegativeSeedIsRejected) {
  // Strict input: a value the user gives is checked, never ignored or wrapped. Library bugs:
  // - validate: commands.cpp options_with_overrides() applies --seed only `if (seed >= 0)`, so
  //   `--seed -5` silently runs with the suite's seed (exit 0);
  // - trace: TraceArgs::seed is std::uint64_t and CLI11 2.1 wraps "-5" to 2^64 - 5 (exit 0).
  TempDir dir;
  const std::string suite = small_suite(dir);
  const CliRun v = vgroove("validate " + quoted(suite) + " --seed -5");
  EXPECT_EQ(v.status, 2) << v;
  EXPECT_EQ(lines(v.err), 1) << v;
  EXPECT_CONTAINS(v.err, "--seed");
  const CliRun t = vgroove("trace --rays 10 --seed -5");
  EXPECT_EQ(t.status, 2) << t;
  EXPECT_EQ(lines(t.err), 1) << t;
  EXPECT_CONTAINS(t.err, "--seed");
}

TEST(Cli, ValidateRejectsBadOverrides) {
  TempDir dir;
  const std::string suite = small_suite(dir);
  expect_user_error(vgroove("validate " + quoted(suite) + " --rays 0"), "--rays", "[1, ");
  expect_user_error(vgroove("validate " + quoted(suite) + " --threads -1"), "--threads", "[0, 1024]");
  expect_user_error(vgroove("validate " + quoted(suite) + " --sampling sobol"), "--sampling", "\"breakpoints\"");
  // `trace` places rays across the opening: no breakpoint search there.
  expect_user_error(vgroove("trace --sampling breakpoints"), "--sampling", "\"stratified\", \"random\"");
  // An --out in a directory that does not exist fails before any work.
  expect_user_error(vgroove("validate " + quoted(suite) + " --out " + quoted(dir.file("no/dir/r.json"))), "no/dir",
                    "does not exist");
}

// --sampling breakpoints: exact fractions, reported with the zones found; the report says how.
TEST(Cli, ValidateWithBreakpointsIsExact) {
  TempDir dir;
  const std::string suite = small_suite(dir), out = dir.file("bp.json");
  const CliRun r = vgroove("validate " + quoted(suite) + " --sampling breakpoints --rays 4 --out " + quoted(out));
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_CONTAINS(r.out, "breakpoints: grid of 4 rays per lit facet");
  const nlohmann::json j = nlohmann::json::parse(read_text(out));
  EXPECT_EQ(j["sampling"], "breakpoints");
  EXPECT_LT(j["summary"]["max_l1"].get<double>(), 1e-12);
  EXPECT_EQ(j["summary"]["breakpoints"]["uncertified_cells"], 0);
  EXPECT_GT(j["summary"]["breakpoints"]["zones"].get<long>(), 6);
  EXPECT_TRUE(j["cases"][0]["left"].contains("zones"));
}

TEST(Cli, ValidateMissingSuiteIsNamed) {
  TempDir dir;
  const std::string f = dir.file("missing.json");
  const CliRun r = vgroove("validate " + quoted(f));
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_EQ(lines(r.err), 1) << r;
  EXPECT_CONTAINS(r.err, f);
}

TEST(Cli, ValidateSpecErrorIsNamed) {
  TempDir dir;
  const std::string f = dir.file("bad.json");
  write_text(f, R"({"name": "x", "kind": "table1", "groove": {"type": "symmetric", "theta_v_deg": [195]},
                    "theta_i_deg": [0], "rays": 10, "thresholds": {"max_l1": 1, "mean_l1": 1, "max_theta_o_error_rad": 1}})");
  const CliRun r = vgroove("validate " + quoted(f));
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_EQ(lines(r.err), 1) << r;
  EXPECT_CONTAINS(r.err, f + ": /groove/theta_v_deg/0 = 195 is out of range [0.001, 180]");
}

TEST(Cli, ValidateRefusesToOverwriteWithoutForce) {
  TempDir dir;
  const std::string suite = small_suite(dir);
  const std::string out = dir.file("report.json");
  write_text(out, "precious");
  const CliRun r = vgroove("validate " + quoted(suite) + " --out " + quoted(out));
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_EQ(lines(r.err), 1) << r;
  EXPECT_CONTAINS(r.err, out);
  EXPECT_CONTAINS(r.err, "--force");
  EXPECT_EQ(read_text(out), "precious");
  EXPECT_EQ(dir.entries().size(), 2u);  // the suite and the untouched report, no temporaries
}

TEST(Cli, ValidateWritesAndWithForceReplacesTheReport) {
  TempDir dir;
  const std::string suite = small_suite(dir);
  const std::string out = dir.file("report.json");
  const CliRun r = vgroove("validate " + quoted(suite) + " --out " + quoted(out) + " --threads 2");
  EXPECT_EQ(r.status, 0) << r;  // 200 stratified rays: L1 <= 4/200 = 0.02 < 0.05
  const json j = json::parse(read_text(out));
  EXPECT_EQ(j.at("suite"), "cli_small");
  EXPECT_EQ(j.at("cases").size(), 6u);
  EXPECT_EQ(j.at("rays_per_facet"), 200);
  EXPECT_LE(j.at("summary").at("max_l1").get<double>(), 4.0 / 200);
  const CliRun f = vgroove("validate " + quoted(suite) + " --out " + quoted(out) + " --rays 100 --force");
  EXPECT_EQ(f.status, 0) << f;
  EXPECT_EQ(json::parse(read_text(out)).at("rays_per_facet"), 100);
  EXPECT_EQ(dir.entries().size(), 2u);
}

TEST(Cli, ValidateExitsOneWhenAThresholdIsExceeded) {
  // The printed Eq. (6) is off by L1 = 2 at theta_v = 90, theta_i = 0 (ERRATA E1).
  TempDir dir;
  const std::string suite = small_suite(dir);
  const CliRun r = vgroove("validate " + quoted(suite) + " --eq6-form printed");
  EXPECT_EQ(r.status, 1) << r;
}

TEST(Cli, ValidateRunsAProfilesSuite) {
  TempDir dir;
  const std::string f = dir.file("profiles.json"), out = dir.file("r.json");
  write_text(f, R"({"name": "cli_profiles", "kind": "profiles", "ndf": ["ggx"], "alpha": [0.5], "theta_deg": [60],
                    "surfaces": ["random", "vgroove"], "realizations": 2, "segments": 2048, "rays": 5000,
                    "walk_paths": 5000, "thresholds": {"p_min": 1e-3, "sigmas": 5}})");
  const CliRun r = vgroove("validate " + quoted(f) + " --out " + quoted(out) + " --threads 2");
  EXPECT_EQ(r.status, 0) << r;
  const json j = json::parse(read_text(out));
  EXPECT_EQ(j.at("kind"), "profiles");
  EXPECT_EQ(j.at("cases").size(), 1u);
  EXPECT_EQ(j.at("cases").at(0).at("surfaces").size(), 2u);
  expect_user_error(vgroove("validate " + quoted(f) + " --sampling random"), "--sampling", "single-groove");
  write_text(f, R"({"name": "x", "kind": "profiles", "ndf": ["phong"], "alpha": [0.5], "theta_deg": [60],
                    "surfaces": ["random"], "rays": 10, "walk_paths": 10, "thresholds": {"p_min": 1e-3, "sigmas": 5}})");
  expect_user_error(vgroove("validate " + quoted(f)), f + ": /ndf/0", "\"beckmann\", \"ggx\"");
}

// ---------------------------------------------------------------------------------------------
// trace --json and analytic --json: the same rows, (first facet, k) -> (fraction, theta_o_deg).
using Rows = std::map<std::pair<std::string, int>, std::pair<double, double>>;

Rows rows_of(const CliRun& r) {
  Rows rows;
  const json j = json::parse(r.out);
  for (const json& row : j.at("bounces"))
    rows[{row.at("first_facet").get<std::string>(), row.at("k").get<int>()}] = {row.at("fraction").get<double>(),
                                                                                row.at("theta_o_deg").get<double>()};
  return rows;
}

class TraceVsAnalytic : public testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(TraceVsAnalytic, SameRowsFractionsAndExitAngles) {
  const double v = std::get<0>(GetParam()), i = std::get<1>(GetParam());
  constexpr long n = 10000;  // even: no stratum midpoint on the apex at normal incidence
  std::ostringstream angles;
  angles << "--theta-v-deg " << v << " --theta-i-deg " << i;
  const CliRun t = vgroove("trace --json --rays " + std::to_string(n) + " " + angles.str());
  const CliRun a = vgroove("analytic --json " + angles.str());
  ASSERT_EQ(t.status, 0) << t;
  ASSERT_EQ(a.status, 0) << a;
  const Rows tr = rows_of(t), an = rows_of(a);
  const auto where =
      "theta_v=" + std::to_string(v) + " theta_i=" + std::to_string(i) + "\ntrace:\n" + t.out + "\nanalytic:\n" + a.out;
  ASSERT_EQ(tr.size(), an.size()) << where;
  // The opening holds at most two boundaries between rows of the model (the apex's crossing, and
  // one transition point): each moves the stratified fractions by at most 1/N in all: 2/N.
  for (const auto& [key, value] : an) {
    const auto it = tr.find(key);
    ASSERT_NE(it, tr.end()) << where << "\nmissing in trace: " << key.first << " k=" << key.second;
    EXPECT_NEAR(it->second.first, value.first, 2.0 / n) << where << "\nrow " << key.first << " k=" << key.second;
    EXPECT_EQ(it->second.second, value.second) << where << "\nrow " << key.first << " k=" << key.second;
  }
  const json tj = json::parse(t.out);
  EXPECT_EQ(tj.at("rays"), n);
  EXPECT_EQ(tj.at("buckets").at("escaped"), n);
}

INSTANTIATE_TEST_SUITE_P(Grid, TraceVsAnalytic,
                         testing::Values(std::tuple{90.0, 30.0}, std::tuple{33.3, 12.1}, std::tuple{60.0, 0.0},
                                         std::tuple{90.0, -60.0}, std::tuple{121.7, -45.25}, std::tuple{7.3, 60.6}),
                         [](const testing::TestParamInfo<std::tuple<double, double>>& param) {
                           std::ostringstream os;
                           os << "v" << std::get<0>(param.param) << "_i" << std::get<1>(param.param);
                           std::string s = os.str();
                           for (char& c : s) c = c == '.' ? 'p' : c == '-' ? 'm' : c;
                           return s;
                         });

TEST(Cli, TraceAt90And30ByHand) {
  // Right facet first, one reflection, leaving at 60 deg: tan 30 of the beam (tracer tests).
  const CliRun t = vgroove("trace --json --rays 10000 --theta-v-deg 90 --theta-i-deg 30");
  ASSERT_EQ(t.status, 0) << t;
  const Rows rows = rows_of(t);
  const auto it = rows.find({"right", 1});
  ASSERT_NE(it, rows.end()) << t;
  EXPECT_NEAR(it->second.first, std::tan(std::numbers::pi / 6), 1e-4) << t;
  EXPECT_EQ(it->second.second, 60.0) << t;
}

// ---------------------------------------------------------------------------------------------
// sample

TEST(Cli, SampleRejectsValuesOutOfRange) {
  expect_user_error(vgroove("sample --alpha 0"), "--alpha", "[0.01, 2]");
  expect_user_error(vgroove("sample --alpha 2.5"), "--alpha", "[0.01, 2]");
  expect_user_error(vgroove("sample --theta-i-deg 90"), "--theta-i-deg", "[0, 89.9]");
  expect_user_error(vgroove("sample --n 0"), "--n", "[1, 1000000000]");
  expect_user_error(vgroove("sample --max-k 0"), "--max-k", "[1, 100000]");
  expect_user_error(vgroove("sample --phi-bins 7"), "--phi-bins", "even");
  expect_user_error(vgroove("sample --ndf trowbridge"), "--ndf", "\"ggx\", \"beckmann\", \"phong\"");
  expect_user_error(vgroove("sample --dim 2d"), "--dim", "\"3d\", \"flatland\"");
  expect_user_error(vgroove("sample --strategy uniform"), "--strategy", "\"printed\", \"vndf\"");
  expect_user_error(vgroove("sample --ndf phong --strategy smith-vndf"), "--strategy", "ggx only");
  expect_user_error(vgroove("sample --dim flatland --strategy bounded-vndf"), "--strategy", "3d only");
  expect_user_error(vgroove("sample --model cook-torrance"), "--model", "\"vgroove\", \"vgroove-nonsymmetric\"");
  expect_user_error(vgroove("sample --model vgroove-nonsymmetric --ndf phong --alpha 1.2"), "--alpha", "(0, 1]");
}

// A small run: the chi-square accepts (exit 0) and the result holds the table for plots.
TEST(Cli, SampleWritesTheChiSquareTable) {
  TempDir dir;
  const std::string out = dir.file("S.json");
  const CliRun r = vgroove(
      "sample --ndf beckmann --alpha 0.5 --theta-i-deg 40 --n 20000 --dim flatland --strategy "
      "printed --out '" +
      out + "'");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_CONTAINS(r.out, "accepted");
  const json j = json::parse(read_text(out));
  const json& t = j.at("result").at("table");
  EXPECT_EQ(t.at("observed").size(), 1u);
  EXPECT_EQ(t.at("observed").at(0).size(), 36u);
  EXPECT_EQ(t.at("col_edges").size(), 37u);
  double observed = t.at("observed_no_direction").get<double>();
  for (const json& v : t.at("observed").at(0)) observed += v.get<double>();
  EXPECT_EQ(observed, 20000.0);
  EXPECT_FALSE(j.at("result").at("reject").get<bool>());
}

// The nonsymmetric model (Eq. 23): a small flatland run accepts and says so in its JSON.
TEST(Cli, SampleNonsymmetric) {
  TempDir dir;
  const std::string out = dir.file("S.json");
  const CliRun r = vgroove(
      "sample --model vgroove-nonsymmetric --ndf ggx --alpha 0.5 --theta-i-deg 30 --n 20000 --dim flatland "
      "--theta-bins 18 --max-k 16 --out '" +
      out + "'");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_CONTAINS(r.out, "accepted");
  const json j = json::parse(read_text(out));
  EXPECT_EQ(j.at("result").at("model").get<std::string>(), "vgroove-nonsymmetric");
  EXPECT_FALSE(j.at("result").at("reject").get<bool>());
}

// Table 2's traced percentile is an estimate from a finite sample: the rule bounds the light's
// percentile (P(b <= N) >= q, Table2.TheRuleBoundsTheLightsPercentileByTheseMargins), not every
// sample's. At 10 rays per surface and seed 2 it shows more than the rule in four cells (the
// README said it never does); the suite still passes (its verdict is the paper against the rule).
TEST(CliTable2, TheTracedPercentileExceedsTheRuleAtFewRays) {
  TempDir dir;
  const std::string out = dir.file("t2.json");
  const CliRun r = vgroove("validate " + quoted(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table2.json") +
                           " --rays 10 --seed 2 --threads 2 --out " + quoted(out));
  ASSERT_EQ(r.status, 0) << r;
  std::map<std::tuple<std::string, double, double>, std::pair<int, int>> cells;
  const json report = json::parse(read_text(out));
  for (const json& e : report.at("entries"))
    cells[{e.at("ndf").get<std::string>(), e.at("alpha").get<double>(), e.at("percentile").get<double>()}] = {
        e.at("ours").get<int>(), e.at("traced_percentile_k").get<int>()};
  EXPECT_EQ(cells.at({"ggx", 0.5, 95.0}), std::make_pair(4, 6));
  EXPECT_EQ(cells.at({"ggx", 0.7, 95.0}), std::make_pair(5, 9));
  EXPECT_EQ(cells.at({"ggx", 1.0, 95.0}), std::make_pair(7, 13));
  EXPECT_EQ(cells.at({"phong", 1.0, 95.0}), std::make_pair(7, 13));
}

}  // namespace
}  // namespace vgroove::validation
