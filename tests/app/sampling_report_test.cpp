// The sampling report (`vgroove validate SAMPLING_SUITE --out R`): what it compares between runs
// is the same for any thread count and load. The weights' statistics are deterministic; the cost
// per sample and what follows from it (each strategy's efficiency = 1 / (variance x time), the
// most efficient strategy) are wall time, and they sit under "timing" (docs/conventions.md,
// "Timing"), beside the durations (*_s). They were among the compared fields (a strategy's
// "efficiency" and "ns_per_sample", the case's "most_efficient") and differed from run to run.
#include "tests/cli_run.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

namespace vgroove::app {
namespace {

using nlohmann::json;
using testing_files::quoted;
using testing_files::read_text;
using testing_files::TempDir;
using testing_files::vgroove;
using testing_files::write_text;

// Every key but "timing", "threads" and the durations (*_s), as the report's compared fields.
json compared(const json& j) {
  if (j.is_object()) {
    json out = json::object();
    for (const auto& [k, v] : j.items()) {
      const bool duration = k.size() > 2 && k.compare(k.size() - 2, 2, "_s") == 0;
      if (k != "timing" && k != "threads" && !duration) out[k] = compared(v);
    }
    return out;
  }
  if (j.is_array()) {
    json out = json::array();
    for (const json& v : j) out.push_back(compared(v));
    return out;
  }
  return j;
}

TEST(SamplingReport, ComparedFieldsDoNotDependOnThreadsAndTimingIsApart) {
  TempDir dir;
  const std::string suite = dir.file("s.json");
  write_text(suite, R"({"name": "s", "kind": "sampling", "seed": 1, "max_k": 64,
    "chi_square": {"level": 0.01, "samples": {"3d": 4000, "flatland": 4000}, "cos_bins": 4, "phi_bins": 8,
                   "theta_bins": 18,
                   "cases": [{"dimension": "3d", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30, "strategy": "vndf"}]},
    "variance": {"samples": 4000, "schlick_f0": [1.0, 0.5],
                 "cases": [{"dimension": "3d", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30},
                           {"dimension": "flatland", "ndf": "beckmann", "alpha": 1.0, "theta_i_deg": 60}]},
    "furnace": {"max_k": 16, "samples": 1000, "strategy": "vndf", "rays": 1000, "grooves": 500, "sigmas": 5,
                "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-5},
                "cases": [{"dimension": "flatland", "ndf": "ggx", "alpha": 0.5, "theta_i_deg": 30}]}})");
  json reports[2];
  for (int t : {1, 2}) {
    const std::string out = dir.file("r" + std::to_string(t) + ".json");
    const auto r = vgroove("validate " + quoted(suite) + " --threads " + std::to_string(t) + " --out " + quoted(out));
    ASSERT_TRUE(r.status == 0 || r.status == 1) << r;
    reports[t - 1] = json::parse(read_text(out));
  }
  EXPECT_EQ(compared(reports[0]), compared(reports[1]));
  // The timing is there, apart: per variance case the strategies' cost and efficiency (the
  // V-cavity strategy's is infinite with F = 1, written "inf") and the most efficient one; per
  // chi-square case the cost per sample.
  for (const json& v : reports[1].at("variance")) {
    const json& t = v.at("timing");
    ASSERT_EQ(t.at("strategies").size(), v.at("strategies").size());
    for (std::size_t n = 0; n < v.at("strategies").size(); ++n) {
      EXPECT_EQ(t["strategies"][n]["strategy"], v["strategies"][n]["strategy"]);
      EXPECT_FALSE(v["strategies"][n].contains("efficiency"));
      EXPECT_FALSE(v["strategies"][n].contains("ns_per_sample"));
      EXPECT_GT(t["strategies"][n]["ns_per_sample"].get<double>(), 0.0);
    }
    EXPECT_TRUE(t.at("most_efficient").is_string());
    EXPECT_FALSE(v.contains("most_efficient"));
  }
  EXPECT_GT(reports[1].at("chi_square")[0].at("timing").at("ns_per_sample").get<double>(), 0.0);
}

}  // namespace
}  // namespace vgroove::app
