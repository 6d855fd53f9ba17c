// The accuracy plot is drawn from the report alone: every run is a point, every placement two lines.
#include "vgroove/validation/plot.h"
#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>

#include <string>

namespace vgroove::validation {
namespace {

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(AccuracyPlot, OnePointPerRunAndTwoLinesPerPlacement) {
  const nlohmann::json report = {
      {"suite", "s"},
      {"version", "0"},
      {"git", "g"},
      {"threads", 2},
      {"seed", 1},
      {"runs",
       {{{"sampling", "stratified"}, {"rays_per_facet", 1000}, {"wall_s", 0.1}, {"max_l1", 2e-3}, {"mean_l1", 4e-4}},
        {{"sampling", "stratified"}, {"rays_per_facet", 10000}, {"wall_s", 1.0}, {"max_l1", 2e-4}, {"mean_l1", 4e-5}},
        {{"sampling", "random"}, {"rays_per_facet", 1000}, {"wall_s", 0.3}, {"max_l1", 1e-1}, {"mean_l1", 1e-2}}}}};
  const std::string svg = accuracy_svg(report, "r.json");
  EXPECT_EQ(count(svg, "<circle"), 6u);  // max and mean per run
  EXPECT_EQ(count(svg, "<path"), 4u);    // max and mean per placement
  EXPECT_NE(svg.find("N=10000"), std::string::npos);
  EXPECT_NE(svg.find("git g"), std::string::npos);
}

TEST(AccuracyPlot, RefusesOtherJson) {
  try {
    accuracy_svg(nlohmann::json{{"cases", nlohmann::json::array()}}, "report.json");
    FAIL() << "no support::UserError";
  } catch (const support::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("report.json: not an accuracy report"), std::string::npos) << e.what();
  }
}

// The cost curves: one point per aperture on each of the two lines; nothing without the data.
TEST(AccuracyPlot, CostCurveHasTracerAndModelLines) {
  nlohmann::json report = {{"version", "0"}, {"git", "g"}};
  EXPECT_TRUE(cost_svg(report).empty());
  report["cost_vs_theta_v"] = {{"theta_i_deg", 30.0},
                               {"points",
                                {{{"theta_v_deg", 1.0}, {"tracer_ns_per_ray", 500.0}, {"model_ns_per_eval", 150.0}},
                                 {{"theta_v_deg", 10.0}, {"tracer_ns_per_ray", 50.0}, {"model_ns_per_eval", 150.0}},
                                 {{"theta_v_deg", 100.0}, {"tracer_ns_per_ray", 10.0}, {"model_ns_per_eval", 160.0}}}}};
  const std::string svg = cost_svg(report);
  EXPECT_EQ(count(svg, "<circle"), 6u);
  EXPECT_EQ(count(svg, "<path"), 2u);
  EXPECT_NE(svg.find("theta_i = 30 deg"), std::string::npos);
}

}  // namespace
}  // namespace vgroove::validation
