// The stress suite (data/suites/stress.json) as a test: apertures 0.01..180 deg, grazing light,
// light parallel to a facet, Eq. 4's floor boundaries, facets at 0 and 90 deg, rays aimed exactly
// at vertices. It must pass its thresholds, with every ray accounted for and no NaN anywhere.
#include "vgroove/validation/groove_suite_run.h"

#include <gtest/gtest.h>

#include <cmath>

namespace vgroove::validation {
namespace {

TEST(StressSuite, PassesWithEveryRayAccountedForAndNoNaN) {
  const GrooveSuite suite = load_groove_suite(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/stress.json");
  ASSERT_TRUE(suite.options.probe_vertices);
  const GrooveSuiteRun run = run_groove_suite(suite, suite.options, 2);
  const GrooveSuiteSummary& s = run.summary;
  EXPECT_TRUE(s.pass()) << "max L1 " << s.max_l1 << ", mean L1 " << s.mean_l1 << ", theta_o error "
                        << s.max_theta_o_error;
  EXPECT_EQ(s.non_finite_cases, 0u);
  EXPECT_EQ(s.bounce_limit, 0);
  EXPECT_EQ(s.wrong_first, 0);
  // Rays aimed exactly at the apex and the rims: four per lit facet, each in one bucket.
  EXPECT_EQ(s.probe_rays, 4 * static_cast<std::int64_t>(s.facets_compared));
  EXPECT_EQ(s.probe_rays, s.probe_escaped + s.probe_vertex_hits + s.probe_blocked + s.probe_bounce_limit);
  for (const CaseOutcome& c : run.cases) {
    EXPECT_TRUE(std::isfinite(c.l1) && std::isfinite(c.theta_o_error))
        << "theta_v=" << c.groove.theta_v << " theta_i=" << c.theta_i;
    for (const FacetOutcome& f : c.facet)
      if (f.compared) {
        EXPECT_EQ(f.rays, suite.options.rays) << "theta_v=" << c.groove.theta_v << " theta_i=" << c.theta_i;
      }
  }
  // The narrowest aperture really is deep: 0.01 deg makes about 18,000 reflections.
  std::int64_t deepest = 0;
  for (const CaseOutcome& c : run.cases)
    if (c.rays > 0) deepest = std::max(deepest, c.bounces / c.rays);
  EXPECT_GT(deepest, 17000);
}

}  // namespace
}  // namespace vgroove::validation
