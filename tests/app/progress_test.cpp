// The progress line of long runs (app/progress.h): what it counts, the rate and the time left.
#include "vgroove/app/progress.h"

#include <gtest/gtest.h>

namespace vgroove::app {
namespace {

TEST(Progress, CountsWorkItemsWithTheRateAndTheTimeLeft) {
  // 30 of 120 items in 10 s: 3 per s, 90 items left, 30 s.
  EXPECT_EQ(progress_text("validate x", 30, 120, 10.0),
            "validate x: 30/120 work items (25%), 3 per s, about 30 s left");
  // 1 of 400 in 2 s: 0.5 per s, 399 left, 798 s = 13.3 min.
  EXPECT_EQ(progress_text("v", 1, 400, 2.0), "v: 1/400 work items (0%), 0.5 per s, about 13 min left");
  // Nothing done yet: no rate to give.
  EXPECT_EQ(progress_text("v", 0, 7, 5.0), "v: 0/7 work items (0%)");
}

TEST(Progress, TheLastLineSaysHowLongItTook) {
  EXPECT_EQ(progress_text("v", 120, 120, 200.0), "v: 120/120 work items (100%), 3 min");
  EXPECT_EQ(progress_text("v", 5, 5, 4.2), "v: 5/5 work items (100%), 4 s");
  EXPECT_EQ(progress_text("v", 9, 9, 7200.0), "v: 9/9 work items (100%), 2.0 h");
}

TEST(Progress, ControlCharactersInTheLabelAreShownEscaped) {
  const std::string line = progress_text("validate \x1b[2Jname", 1, 2, 1.0);
  EXPECT_EQ(line.find('\x1b'), std::string::npos) << line;
}

}  // namespace
}  // namespace vgroove::app
