// The lobe histogram's bins and rows have one range in every suite kind that bins exit directions:
// the brdf and nonsymmetric suites accept and refuse the same max_k and bins with the same message,
// and both bound the histogram's cells before any work.
#include "vgroove/validation/lobe_bins.h"

#include "tests/test_files.h"
#include "tests/user_error_of.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/nonsymmetric_suite.h"
#include "vgroove/validation/ranges.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;
using testing_files::user_error_of;

json shipped(const std::string& name) {
  return json::parse(testing_files::read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/" + name));
}

// Each kind that reads lobe bins, as a parser of its shipped suite with one key changed.
struct Kind {
  std::string name;
  json suite;
  std::function<void(const json&)> parse;
};
std::vector<Kind> kinds() {
  return {{"brdf", shipped("fig11.json"), [](const json& j) { parse_brdf_suite(j, "s.json"); }},
          {"nonsymmetric_brdf", shipped("nonsymmetric_brdf.json"),
           [](const json& j) { parse_nonsymmetric_suite(j, "s.json"); }}};
}

TEST(LobeBins, MaxKHasOneRangeInEveryKind) {
  for (const Kind& k : kinds()) {
    json j = k.suite;
    j["max_k"] = 5000;
    EXPECT_EQ(user_error_of([&] { k.parse(j); }), "s.json: /max_k = 5000 is out of range [" +
                                                      std::to_string(kMinHistogramK) + ", " +
                                                      std::to_string(kMaxHistogramK) + "]")
        << k.name;
    j["max_k"] = kMaxHistogramK;
    j["flatland_bins"] = 10;
    j["theta_bins"] = 10;
    j["phi_bins"] = 10;
    EXPECT_NO_THROW(k.parse(j)) << k.name;
  }
}

TEST(LobeBins, BinsHaveOneRangeInEveryKind) {
  for (const Kind& k : kinds()) {
    for (const auto& [key, hi] : {std::pair<std::string, int>{"flatland_bins", kMaxFlatlandBins},
                                  {"theta_bins", kMaxThetaBins},
                                  {"phi_bins", kMaxPhiBins}}) {
      json j = k.suite;
      j[key] = hi + 2;
      const int lo = key == "phi_bins" ? 2 : 1;
      EXPECT_EQ(user_error_of([&] { k.parse(j); }), "s.json: /" + key + " = " + std::to_string(hi + 2) +
                                                        " is out of range [" + std::to_string(lo) + ", " +
                                                        std::to_string(hi) + "]")
          << k.name;
    }
    json odd = k.suite;
    odd["phi_bins"] = 7;
    EXPECT_NE(user_error_of([&] { k.parse(odd); }).find("/phi_bins = 7 must be even"), std::string::npos) << k.name;
  }
}

TEST(LobeBins, EveryKindBoundsTheHistogramBeforeWork) {
  for (const Kind& k : kinds()) {
    json j = k.suite;
    j["theta_bins"] = 1000;
    j["phi_bins"] = 1000;  // 10^6 bins x 18 rows
    EXPECT_EQ(user_error_of([&] { k.parse(j); }),
              "s.json: theta_bins x phi_bins x (max_k + 2) = 18000000 histogram cells, out of range [1, " +
                  std::to_string(kMaxHistogramCells) + "]")
        << k.name;
  }
}

}  // namespace
}  // namespace vgroove::validation
