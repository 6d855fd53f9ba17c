// The Table 2 suite (Lee et al. 2018, Table 2: the bounce counts' percentiles): traced surfaces
// against the rule's N, entry by entry, and the rays the report says it traced.
#include "vgroove/validation/table2_suite.h"

#include "tests/test_files.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;

TEST(Table2Suite, AllEntriesAgree) {
  const Table2Suite s = parse_table2_suite(
      json::parse(testing_files::read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table2.json")),
      "table2.json");
  const Table2Run run = run_table2_suite(s, 5000, 2);
  EXPECT_EQ(run.agree, 27);
  EXPECT_TRUE(run.pass);
  // The rays traced (here the override, not the suite's 200,000) are what the table and the
  // report say (both said the suite's).
  EXPECT_EQ(run.rays, 5000);
  EXPECT_EQ(table2_report_json(s, run)["rays"], 5000);
  std::ostringstream table;
  print_table2(table, s, run);
  EXPECT_NE(table.str().find("; 5000 rays per traced surface;"), std::string::npos) << table.str();
  // The traced percentiles never exceed the rule's N: at normal incidence a groove's rays make
  // k - 1 or k reflections, k = Eq. (4), and N is Eq. (4) at the q-th percentile groove.
  for (std::size_t n = 0; n < run.ours.size(); ++n) EXPECT_LE(run.traced[n], run.ours[n]) << n;
}

}  // namespace
}  // namespace vgroove::validation
