// Every suite kind's printed table shows a hostile suite name escaped and whole: no control
// character reaches the terminal, and a name longer than any line buffer keeps its line and its
// newline.
#include "vgroove/validation/table_frame.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/energy_audit.h"
#include "vgroove/validation/furnace_suite.h"
#include "vgroove/validation/groove_suite.h"
#include "vgroove/validation/groove_suite_run.h"
#include "vgroove/validation/model_table.h"
#include "vgroove/validation/nonsymmetric_suite.h"
#include "vgroove/validation/profiles_suite.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/sampling_suite.h"
#include "vgroove/validation/table2_suite.h"

#include <gtest/gtest.h>

#include <functional>
#include <sstream>
#include <string>

namespace vgroove::validation {
namespace {

const std::string kTail(420, 'x');
const std::string kName = "evil\x1b[2J\r\n" + kTail;
const std::string kShown = "evil\\x1b[2J\\r\\n" + kTail;  // support::printable's escapes

// `title_end`: how the title line ends when it is whole.
void expect_escaped_and_whole(const std::string& what, const std::string& title_end,
                              const std::function<void(std::ostream&)>& print) {
  std::ostringstream os;
  print(os);
  const std::string out = os.str();
  EXPECT_EQ(out.find('\x1b'), std::string::npos) << what << " printed ESC raw";
  EXPECT_EQ(out.find('\r'), std::string::npos) << what << " printed CR raw";
  const std::size_t at = out.find(kShown);
  ASSERT_NE(at, std::string::npos) << what << " lost part of the name:\n" << out.substr(0, 600);
  EXPECT_EQ(out.rfind('\n', at), std::string::npos) << what << ": the title is not the first line";
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out.back(), '\n') << what << " lost its last newline";
  const std::size_t eol = out.find('\n', at);
  ASSERT_NE(eol, std::string::npos) << what;
  const std::string title = out.substr(0, eol + 1);
  ASSERT_GE(title.size(), title_end.size()) << what;
  EXPECT_EQ(title.substr(title.size() - title_end.size()), title_end) << what << ": the title line was cut";
}

TEST(TableFrame, TitleAndCloseLines) {
  std::ostringstream os;
  print_table_title(os, "a\tb", "kind", "3 cases", 2);
  print_table_title(os, "c", "kind", "", 1);
  print_table_close(os, 2, 3, 1.25);
  const std::string want = std::string("a\\tb (kind): 3 cases, vgroove ") + version_string() + " (git " +
                           git_revision() + "), 2 threads\nc (kind): vgroove " + version_string() + " (git " +
                           git_revision() + "), 1 threads\n  2/3 cases pass; wall 1.25 s\n";
  EXPECT_EQ(os.str(), want);
}

TEST(TableFrame, EveryKindEscapesAndKeepsLongNames) {
  {
    BrdfSuite s;
    s.name = kName;
    s.kind = "brdf";
    expect_escaped_and_whole("brdf", " threads\n", [&](std::ostream& os) { print_brdf_table(os, s, BrdfRun{}); });
  }
  {
    FurnaceSuite s;
    s.name = kName;
    expect_escaped_and_whole("furnace", " threads\n",
                             [&](std::ostream& os) { print_furnace_table(os, s, FurnaceRun{}); });
  }
  {
    SamplingSuite s;
    s.name = kName;
    s.furnace.name = kName;
    expect_escaped_and_whole("sampling", " threads\n",
                             [&](std::ostream& os) { print_sampling_table(os, s, SamplingRun{}); });
  }
  {
    NonsymmetricSuite s;
    s.name = kName;
    expect_escaped_and_whole("nonsymmetric", " threads\n",
                             [&](std::ostream& os) { print_nonsymmetric_table(os, s, NonsymmetricRun{}); });
  }
  {
    ProfilesSuite s;
    s.name = kName;
    expect_escaped_and_whole("profiles", " threads\n",
                             [&](std::ostream& os) { print_profiles_table(os, s, ProfilesRun{}); });
  }
  {
    BrdfSuite s;
    s.name = kName;
    s.kind = "brdf";
    ModelTable t;
    t.file = kName;
    t.model = kName;
    expect_escaped_and_whole("model table", " grooves each\n",
                             [&](std::ostream& os) { print_model_table(os, s, t, ModelTableRun{}); });
  }
  {
    Table2Suite s;
    s.name = kName;
    s.source = kName;
    expect_escaped_and_whole("table2", " threads\n", [&](std::ostream& os) { print_table2(os, s, Table2Run{}); });
  }
  {
    EnergyAuditSuite s;
    s.name = kName;
    expect_escaped_and_whole("energy_audit", " threads\n",
                             [&](std::ostream& os) { print_energy_audit(os, s, EnergyAuditRun{}); });
  }
}

// A set's summary table sizes its first column to the longest suite name: a 420-character name
// keeps its row whole, every column after it, and the row's newline.
TEST(TableFrame, SetSummaryKeepsLongSuiteNames) {
  GrooveSuiteSet set;
  set.name = "set";
  set.suites.resize(2);
  set.suites[0].name = "short";
  set.suites[1].name = kName;
  std::vector<GrooveSuiteRun> runs(2);
  runs[1].summary.wall_s = 12.5;
  std::ostringstream os;
  print_set_table(os, set, runs);
  const std::string out = os.str();
  const std::size_t at = out.rfind(kShown);
  ASSERT_NE(at, std::string::npos) << out.substr(out.size() > 800 ? out.size() - 800 : 0);
  const std::size_t eol = out.find('\n', at);
  ASSERT_NE(eol, std::string::npos) << "the long name's row lost its newline";
  const std::string row = out.substr(at, eol - at);
  EXPECT_EQ(row.substr(row.size() - 6), "12.500") << row.substr(row.size() > 80 ? row.size() - 80 : 0);
  const std::string verdict = out.substr(eol + 1);
  EXPECT_TRUE(verdict == "PASS\n" || verdict == "FAIL\n") << verdict;
}

}  // namespace
}  // namespace vgroove::validation
