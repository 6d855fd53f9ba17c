// Tests of validation/groove_suite_run.h: results do not depend on the thread count, and the summary
// is what its cases say.
#include "vgroove/validation/groove_suite_run.h"
#include "vgroove/validation/validate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <sstream>
#include <string>

namespace vgroove::validation {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

// 5 x 11 = 55 cases: more than three chunks of 16, so 2 and 8 threads really share the work.
GrooveSuite small_suite() {
  GrooveSuite s;
  s.file = "(in code)";
  s.name = "determinism";
  for (double v : {3.0, 17.5, 45.0, 90.0, 150.0}) s.grooves.push_back(GrooveParams::make_symmetric(deg(v)));
  for (double i : {-85.0, -60.0, -33.0, -10.0, -1.5, 0.0, 2.0, 25.0, 44.0, 70.0, 88.0}) s.theta_i.push_back(deg(i));
  s.options.rays = 400;
  s.options.sampling = sim::Sampling::random;
  s.options.seed = 77;
  s.thresholds = {0.2, 0.1, 1e-9};
  return s;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_identical(const CaseOutcome& a, const CaseOutcome& b, std::size_t c, int threads) {
  const auto where = [&] { return "case " + std::to_string(c) + ", threads=" + std::to_string(threads); };
  EXPECT_TRUE(same_bits(a.groove.theta_v, b.groove.theta_v)) << where();
  EXPECT_TRUE(same_bits(a.theta_i, b.theta_i)) << where();
  EXPECT_TRUE(same_bits(a.l1, b.l1)) << where() << ": " << a.l1 << " vs " << b.l1;
  EXPECT_TRUE(same_bits(a.theta_o_error, b.theta_o_error)) << where();
  EXPECT_EQ(a.rays, b.rays) << where();
  EXPECT_EQ(a.bounces, b.bounces) << where();
  for (int f = 0; f < 2; ++f) {
    const FacetOutcome &x = a.facet[f], &y = b.facet[f];
    EXPECT_EQ(x.compared, y.compared) << where() << " facet " << f;
    EXPECT_TRUE(same_bits(x.l1, y.l1)) << where() << " facet " << f;
    EXPECT_EQ(x.rays, y.rays) << where() << " facet " << f;
    EXPECT_EQ(x.bounces, y.bounces) << where() << " facet " << f;
    EXPECT_EQ(x.vertex_hits, y.vertex_hits) << where() << " facet " << f;
    EXPECT_EQ(x.bounce_limit, y.bounce_limit) << where() << " facet " << f;
    EXPECT_EQ(x.wrong_first, y.wrong_first) << where() << " facet " << f;
    EXPECT_EQ(x.k, y.k) << where() << " facet " << f;
    EXPECT_TRUE(same_bits(x.theta_o_error, y.theta_o_error)) << where() << " facet " << f;
  }
}

TEST(GrooveSuiteRun, ResultsAreBitIdenticalForAnyThreadCount) {
  const GrooveSuite s = small_suite();
  const GrooveSuiteRun one = run_groove_suite(s, s.options, 1);
  ASSERT_EQ(one.cases.size(), s.cases());
  EXPECT_EQ(one.threads, 1);
  for (int threads : {2, 8}) {
    const GrooveSuiteRun many = run_groove_suite(s, s.options, threads);
    EXPECT_EQ(many.threads, threads);
    ASSERT_EQ(many.cases.size(), one.cases.size());
    for (std::size_t c = 0; c < one.cases.size(); ++c) expect_identical(one.cases[c], many.cases[c], c, threads);
    const GrooveSuiteSummary &a = one.summary, &b = many.summary;
    EXPECT_TRUE(same_bits(a.max_l1, b.max_l1)) << "threads=" << threads;
    EXPECT_TRUE(same_bits(a.mean_l1, b.mean_l1)) << "threads=" << threads;
    EXPECT_EQ(a.worst_case, b.worst_case) << "threads=" << threads;
    EXPECT_EQ(a.rays, b.rays) << "threads=" << threads;
    EXPECT_EQ(a.bounces, b.bounces) << "threads=" << threads;
    EXPECT_EQ(a.facets_compared, b.facets_compared) << "threads=" << threads;
  }
}

TEST(GrooveSuiteRun, CasesAreInSuiteOrderAndEachIsItsOwnRunCase) {
  // Case c is (theta_v[c / n_i], theta_i[c % n_i]) with random stream c, whoever runs it.
  const GrooveSuite s = small_suite();
  const GrooveSuiteRun run = run_groove_suite(s, s.options, 2);
  const std::size_t ni = s.theta_i.size();
  for (std::size_t c : {std::size_t{0}, std::size_t{13}, std::size_t{54}}) {
    EXPECT_EQ(run.cases[c].groove.theta_v, s.grooves[c / ni].theta_v) << "case " << c;
    EXPECT_EQ(run.cases[c].theta_i, s.theta_i[c % ni]) << "case " << c;
    expect_identical(run.cases[c], run_case(s.grooves[c / ni], s.theta_i[c % ni], s.options, c), c, 0);
  }
}

TEST(GrooveSuiteRun, SummaryIsWhatTheCasesSay) {
  const GrooveSuite s = small_suite();
  const GrooveSuiteRun run = run_groove_suite(s, s.options, 2);
  const GrooveSuiteSummary& sum = run.summary;
  double max_l1 = 0.0, total = 0.0, max_err = 0.0;
  std::int64_t rays = 0;
  std::size_t facets = 0;
  for (const CaseOutcome& c : run.cases) {
    max_l1 = std::max(max_l1, c.l1);
    total += c.l1;
    max_err = std::max(max_err, c.theta_o_error);
    rays += c.rays;
    for (const FacetOutcome& f : c.facet) facets += f.compared;
  }
  EXPECT_EQ(sum.cases, s.cases());
  EXPECT_EQ(sum.max_l1, max_l1);
  EXPECT_EQ(run.cases[sum.worst_case].l1, max_l1);
  EXPECT_DOUBLE_EQ(sum.mean_l1, total / static_cast<double>(s.cases()));
  EXPECT_EQ(sum.max_theta_o_error, max_err);
  EXPECT_EQ(sum.rays, rays);
  EXPECT_EQ(sum.facets_compared, facets);
  EXPECT_EQ(sum.pass_max_l1, max_l1 <= s.thresholds.max_l1);
  EXPECT_EQ(sum.pass_theta_o, max_err <= s.thresholds.max_theta_o_error_rad);
  // 400 random rays per facet: the model holds within a few binomial sigmas, and Eq. (5) exactly.
  EXPECT_LE(sum.max_theta_o_error, 1e-9);
  EXPECT_EQ(sum.vertex_hits, 0);
  EXPECT_EQ(sum.wrong_first, 0);
}

TEST(GrooveSuiteRun, CancelledRunSaysSo) {
  const GrooveSuite s = small_suite();
  const std::atomic<bool> cancel{true};
  const GrooveSuiteRun run = run_groove_suite(s, s.options, 2, {}, &cancel);
  EXPECT_TRUE(run.interrupted);
  const GrooveSuiteRun full = run_groove_suite(s, s.options, 2);
  EXPECT_FALSE(full.interrupted);
}

// The table without its timing line.
std::string without_times(const std::string& table) {
  std::istringstream in(table);
  std::string out, line;
  while (std::getline(in, line))
    if (line.find("wall") == std::string::npos && line.find("threads") == std::string::npos) out += line + "\n";
  return out;
}

// The command line without --out asks for no report (ValidationPlan::report): the same table and
// verdict, no JSON built (for Table 1 by breakpoints the report is most of the command's time).
TEST(Validate, ReportOnlyWhenAsked) {
  ValidateOptions o;
  o.suite = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table1_symmetric_breakpoints.json";
  o.threads = 2;
  ValidationPlan plan = plan_validation(o);
  const ValidationResult with = run_validation(plan);
  plan.report = false;
  const ValidationResult without = run_validation(plan);
  ASSERT_TRUE(with.report.is_object());
  EXPECT_EQ(with.report["cases"].size(), 6444u);
  EXPECT_TRUE(without.report.is_null());
  EXPECT_TRUE(with.pass);
  EXPECT_EQ(without.pass, with.pass);
  EXPECT_EQ(without_times(without.table), without_times(with.table));
  EXPECT_NE(without_times(with.table).find("3.592e-14"), std::string::npos) << with.table;
}

}  // namespace
}  // namespace vgroove::validation
