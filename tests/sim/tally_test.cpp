// Tests of sim/tally.h: buckets, bins, and merging (the parallel runs depend on merge being exact).
#include "vgroove/sim/tally.h"
#include "vgroove/sim/beam.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <numbers>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

TraceResult escaped(Side first, int k, double theta_o) {
  TraceResult r;
  r.bounces = k;
  r.first = first;
  r.exit_dir = direction_at(theta_o);
  r.how = Termination::escaped;
  return r;
}

TraceResult ended(Termination how, int bounces = 0) {
  TraceResult r;
  r.how = how;
  r.bounces = bounces;
  return r;
}

// A mixed batch: real traces aimed at both facets of a shadowing configuration (so some rays are
// blocked), and a few synthetic vertex hits and bounce-limit stops.
std::vector<TraceResult> mixed_rays() {
  const Groove g = make_symmetric_groove(deg(50));
  const double theta_i = deg(-40);  // light from the upper right: the left facet is partly shadowed
  const Vec2 dir = beam_direction(theta_i);
  Rng rng(7, 0, 0);
  std::vector<TraceResult> out;
  for (Side s : {Side::left, Side::right}) {
    const Interval aim = aimed_at(g, theta_i, s);
    for (long j = 0; j < 300; ++j)
      out.push_back(trace(g, beam_ray(g, dir, sample_position(Sampling::random, aim, j, 300, rng))));
  }
  out.insert(out.begin() + 17, ended(Termination::vertex_hit));
  out.insert(out.begin() + 401, ended(Termination::bounce_limit, 100000));
  out.push_back(ended(Termination::vertex_hit));
  return out;
}

TEST(Tally, BucketsAndBinsCountEveryRayOnce) {
  Tally t;
  t.add(escaped(Side::left, 2, 0.1));
  t.add(escaped(Side::left, 2, 0.1));
  t.add(escaped(Side::right, 1, -0.4));
  t.add(ended(Termination::blocked));
  t.add(ended(Termination::vertex_hit, 3));
  t.add(ended(Termination::bounce_limit, 9));
  EXPECT_EQ(t.rays, 6);
  EXPECT_EQ(t.escaped, 3);
  EXPECT_EQ(t.blocked, 1);
  EXPECT_EQ(t.vertex_hits, 1);
  EXPECT_EQ(t.bounce_limit, 1);
  EXPECT_EQ(t.bounces, 5);  // escaped rays only: 2 + 2 + 1
  EXPECT_EQ(t.count(Side::left, 2), 2);
  EXPECT_EQ(t.count(Side::right, 1), 1);
  EXPECT_EQ(t.count(Side::right, 2), 0);
  EXPECT_EQ(t.count(Side::left, -1), 0);
  EXPECT_EQ(t.count(Side::left, 1000), 0);
  EXPECT_EQ(t.max_bounces(), 2);
  EXPECT_NEAR(t.bins[0][2].theta_o(), 0.1, 1e-15);
  EXPECT_EQ(t.bins[0][2].spread(), 0.0);
  EXPECT_EQ(Tally{}.max_bounces(), 0);
}

TEST(Tally, SpreadBoundsTheAnglesWithinABin) {
  Tally t;
  t.add(escaped(Side::left, 3, 0.2));
  t.add(escaped(Side::left, 3, 0.2 + 1e-6));
  t.add(escaped(Side::left, 3, 0.2 - 3e-6));
  EXPECT_NEAR(t.bins[0][3].spread(), 3e-6, 1e-12);
  t.add(escaped(Side::left, 3, 0.2 + 2.0));  // more than 90 deg away: the bound becomes pi
  EXPECT_EQ(t.bins[0][3].spread(), std::numbers::pi);
}

TEST(Tally, MergeOfPartsEqualsTheTallyOfAllRays) {
  const std::vector<TraceResult> rays = mixed_rays();
  Tally all;
  for (const TraceResult& r : rays) all.add(r);
  ASSERT_GT(all.blocked, 0);
  ASSERT_GT(all.escaped, 0);
  for (std::size_t split :
       {std::size_t{0}, std::size_t{1}, std::size_t{17}, std::size_t{250}, rays.size() - 1, rays.size()}) {
    Tally a, b;
    for (std::size_t j = 0; j < rays.size(); ++j) (j < split ? a : b).add(rays[j]);
    Tally merged = a;
    merged.merge(b);
    EXPECT_EQ(merged.rays, all.rays) << "split=" << split;
    EXPECT_EQ(merged.escaped, all.escaped) << "split=" << split;
    EXPECT_EQ(merged.blocked, all.blocked) << "split=" << split;
    EXPECT_EQ(merged.vertex_hits, all.vertex_hits) << "split=" << split;
    EXPECT_EQ(merged.bounce_limit, all.bounce_limit) << "split=" << split;
    EXPECT_EQ(merged.bounces, all.bounces) << "split=" << split;
    EXPECT_EQ(merged.max_bounces(), all.max_bounces()) << "split=" << split;
    for (Side s : {Side::left, Side::right}) {
      const int f = static_cast<int>(s);
      for (int k = 0; k <= all.max_bounces() + 1; ++k) {
        EXPECT_EQ(merged.count(s, k), all.count(s, k)) << "split=" << split << " first=" << side_name(s) << " k=" << k;
        if (all.count(s, k) == 0) continue;
        // The merged bin keeps the first tally's reference ray: the first ray of the whole batch.
        EXPECT_EQ(merged.bins[f][k].exit_dir, all.bins[f][k].exit_dir)
            << "split=" << split << " first=" << side_name(s) << " k=" << k;
        // The merged spread is an upper bound of the true one (sin(a + b) <= sin a + sin b).
        EXPECT_GE(merged.bins[f][k].spread() + 1e-15, all.bins[f][k].spread())
            << "split=" << split << " first=" << side_name(s) << " k=" << k;
        EXPECT_LT(merged.bins[f][k].spread(), 1e-12) << "split=" << split << " first=" << side_name(s) << " k=" << k;
      }
    }
  }
}

TEST(Tally, MergeIsAssociativeInCounts) {
  const std::vector<TraceResult> rays = mixed_rays();
  Tally parts[3];
  for (std::size_t j = 0; j < rays.size(); ++j) parts[j % 3].add(rays[j]);
  Tally left = parts[0];
  left.merge(parts[1]);
  left.merge(parts[2]);
  Tally bc = parts[1];
  bc.merge(parts[2]);
  Tally right = parts[0];
  right.merge(bc);
  EXPECT_EQ(left.rays, right.rays);
  EXPECT_EQ(left.bounces, right.bounces);
  for (Side s : {Side::left, Side::right})
    for (int k = 0; k <= left.max_bounces(); ++k)
      EXPECT_EQ(left.count(s, k), right.count(s, k)) << "first=" << side_name(s) << " k=" << k;
}

}  // namespace
}  // namespace vgroove::sim

namespace vgroove::sim {
namespace {

// Memory grows with the bounce counts the rays make, not with the largest: rays of 10^8 and
// 2 x 10^8 reflections (a 1e-6 deg groove) cost two bins, not 2 x 10^8 (a dense tally took
// gigabytes). Breaking it (a dense vector) makes the entries count 2 x 10^8 + 1.
TEST(Tally, BinsGrowWithTheBounceCountsSeenNotTheLargest) {
  Tally t;
  t.add(escaped(Side::left, 100'000'000, 0.1));
  t.add(escaped(Side::left, 200'000'000, 0.2));
  t.add(escaped(Side::left, 100'000'000, 0.1));
  t.add(escaped(Side::right, 3, -0.3));
  EXPECT_EQ(std::distance(t.bins[0].begin(), t.bins[0].end()), 2);
  EXPECT_EQ(std::distance(t.bins[1].begin(), t.bins[1].end()), 1);
  EXPECT_EQ(t.count(Side::left, 100'000'000), 2);
  EXPECT_EQ(t.count(Side::left, 200'000'000), 1);
  EXPECT_EQ(t.count(Side::left, 150'000'000), 0);
  EXPECT_EQ(t.max_bounces(), 200'000'000);
  Tally u;
  u.add(escaped(Side::left, 150'000'000, 0.15));
  u.merge(t);
  int previous = -1;
  for (const auto& [k, b] : u.bins[0]) {  // ascending k, only bins with rays
    EXPECT_GT(k, previous);
    EXPECT_GT(b.count, 0);
    previous = k;
  }
  EXPECT_EQ(std::distance(u.bins[0].begin(), u.bins[0].end()), 3);
  EXPECT_EQ(u.escaped, 5);
}

}  // namespace
}  // namespace vgroove::sim
