// Tests of sim/beam.h and sim/groove.h: the opening, the rays aimed at each facet, placement.
#include "vgroove/sim/beam.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <tuple>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

TEST(Groove, SymmetricGrooveHasUnitFacetsAndInwardNormals) {
  for (double v : {0.1, 30.0, 90.0, 179.0, 180.0}) {
    const double theta_v = deg(v);
    const Groove g = make_symmetric_groove(theta_v);
    for (Side s : {Side::left, Side::right}) {
      EXPECT_NEAR(g[s].edge.norm(), 1.0, 1e-15) << "theta_v=" << v << " " << side_name(s);
      EXPECT_NEAR(g[s].normal.norm(), 1.0, 1e-15) << "theta_v=" << v << " " << side_name(s);
      EXPECT_NEAR(g[s].normal.dot(g[s].edge), 0.0, 1e-15) << "theta_v=" << v << " " << side_name(s);
      // The normal points into the groove: towards the other facet's rim.
      EXPECT_GT(g[s].normal.dot(g[other(s)].rim() - g[s].rim()), 0.0) << "theta_v=" << v << " " << side_name(s);
      EXPECT_EQ(g[s].rim().y(), g.rim_height) << "theta_v=" << v << " " << side_name(s);
    }
    EXPECT_NEAR(angle_from_normal(g[Side::left].edge), 0.5 * theta_v, 1e-15) << "theta_v=" << v;
    EXPECT_NEAR(angle_between(g[Side::right].edge, g[Side::left].edge), theta_v, 1e-15) << "theta_v=" << v;
    EXPECT_EQ(g.rim_x(Side::left), -g.rim_x(Side::right)) << "theta_v=" << v;
    EXPECT_NEAR(g.rim_x(Side::right), std::sin(0.5 * theta_v), 1e-16) << "theta_v=" << v;
  }
}

TEST(Geometry, SignConvention) {
  // direction_at(theta) = (-sin, cos): positive angles lean left (counter-clockwise from n).
  EXPECT_NEAR(direction_at(deg(90)).x(), -1.0, 1e-16);
  EXPECT_NEAR(angle_from_normal(Vec2(-1, 1)), deg(45), 1e-15);
  EXPECT_NEAR(angle_between(Vec2(1, 0), Vec2(0, 1)), deg(90), 1e-15);
  // A flat mirror: the beam travelling along -i leaves along the direction at -theta_i.
  const double theta_i = deg(25);
  EXPECT_NEAR(angle_from_normal(reflect(beam_direction(theta_i), Vec2(0, 1))), -theta_i, 1e-15);
}

TEST(Beam, OpeningIsBetweenTheRims) {
  const Groove g = make_symmetric_groove(deg(70));
  const Interval open = opening(g);
  EXPECT_EQ(open.lo, g.rim_x(Side::left));
  EXPECT_EQ(open.hi, g.rim_x(Side::right));
  EXPECT_NEAR(open.width(), 2 * std::sin(deg(35)), 1e-15);
}

class AimedAt : public testing::TestWithParam<std::tuple<double, double>> {};

TEST_P(AimedAt, SpansTheFacetsProjectedWidth) {
  const double v = std::get<0>(GetParam()), i = std::get<1>(GetParam());
  const double theta_v = deg(v), theta_i = deg(i), half = 0.5 * theta_v;
  const Groove g = make_symmetric_groove(theta_v);
  const Interval l = aimed_at(g, theta_i, Side::left), r = aimed_at(g, theta_i, Side::right);
  // Both start or end at their facet's rim and meet at the apex's crossing.
  EXPECT_EQ(l.lo, g.rim_x(Side::left)) << "theta_v=" << v << " theta_i=" << i;
  EXPECT_EQ(r.hi, g.rim_x(Side::right)) << "theta_v=" << v << " theta_i=" << i;
  EXPECT_EQ(l.hi, r.lo) << "theta_v=" << v << " theta_i=" << i;
  // The apex's crossing is where the line through the origin along the beam meets the rim line:
  // x = -cos(half) tan(theta_i).
  EXPECT_NEAR(l.hi, -std::cos(half) * std::tan(theta_i), 1e-12) << "theta_v=" << v << " theta_i=" << i;
  // Across the beam the widths are the projected widths, sin(half - theta_i) for the left facet
  // and sin(half + theta_i) for the right one (negative: the facet faces away from the light).
  EXPECT_NEAR(l.width() * std::cos(theta_i), std::sin(half - theta_i), 1e-12) << "theta_v=" << v << " theta_i=" << i;
  EXPECT_NEAR(r.width() * std::cos(theta_i), std::sin(half + theta_i), 1e-12) << "theta_v=" << v << " theta_i=" << i;
}
INSTANTIATE_TEST_SUITE_P(Grid, AimedAt,
                         testing::Combine(testing::Values(1.0, 45.0, 90.0, 150.0, 180.0),
                                          testing::Values(-80.0, -30.0, 0.0, 10.0, 60.0)),
                         [](const testing::TestParamInfo<std::tuple<double, double>>& param) {
                           const auto name = [](double d) {
                             return (d < 0 ? "m" : "") + std::to_string(static_cast<int>(std::abs(d)));
                           };
                           return "v" + name(std::get<0>(param.param)) + "_i" + name(std::get<1>(param.param));
                         });

TEST(Beam, StratifiedPositionsAreStratumMidpoints) {
  Rng rng(1, 2, 3);
  const Interval iv{-1.0, 3.0};
  constexpr long n = 8;
  for (long j = 0; j < n; ++j)
    EXPECT_DOUBLE_EQ(sample_position(Sampling::stratified, iv, j, n, rng), -1.0 + 4.0 * (j + 0.5) / n) << "j=" << j;
}

TEST(Beam, RandomPositionsStayInsideAndFollowTheStream) {
  const Interval iv{-0.25, 0.5};
  Rng a(11, 4, 1), b(11, 4, 1);
  for (long j = 0; j < 10000; ++j) {
    const double x = sample_position(Sampling::random, iv, j, 10000, a);
    ASSERT_GE(x, iv.lo) << "j=" << j;
    ASSERT_LT(x, iv.hi) << "j=" << j;
    ASSERT_EQ(x, iv.lo + b.uniform() * iv.width()) << "j=" << j;
  }
}

// The block placement gives sample_position's values bit for bit (==, not near), for both
// samplings, blocks of any length from any start, and counts up to 2^40.
TEST(Beam, BlockPositionsAreTheSinglePositions) {
  const Interval iv{-0.7071067811865476, 0.31};
  for (long n : {1L, 7L, 1000L, 1000003L, 1L << 40}) {
    for (long j0 : {0L, 1L, n / 3, n - 1}) {
      for (Sampling sampling : {Sampling::stratified, Sampling::random}) {
        const int count = static_cast<int>(std::min<long>(261, n - j0));
        Rng a(5, static_cast<std::uint64_t>(n), static_cast<std::uint64_t>(j0)), b = a;
        std::vector<double> block(static_cast<std::size_t>(count));
        sample_positions(sampling, iv, j0, count, n, a, block.data());
        for (int i = 0; i < count; ++i)
          ASSERT_EQ(block[i], sample_position(sampling, iv, j0 + i, n, b))
              << sampling_name(sampling) << " n=" << n << " j=" << j0 + i;
      }
    }
  }
}

TEST(Beam, BeamRaysStartOnTheRimLineTravellingAlongMinusI) {
  const Groove g = make_symmetric_groove(deg(100));
  const double theta_i = deg(-33);
  const Ray2 r = beam_ray(g, beam_direction(theta_i), 0.2);
  EXPECT_EQ(r.origin.x(), 0.2);
  EXPECT_EQ(r.origin.y(), g.rim_height);
  EXPECT_LT(r.dir.y(), 0.0);
  EXPECT_NEAR(angle_from_normal(-r.dir), theta_i, 1e-15);
}

}  // namespace
}  // namespace vgroove::sim
