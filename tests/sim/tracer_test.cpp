// Tests of sim/tracer.h: hand-derived cases, conservation, mirror symmetry, the bounce bound and
// the hard corners (very narrow grooves, grazing light, rays through the apex, the bounce limit).
//
// Conventions (sim/geometry.h): angles from the normal, counter-clockwise positive; theta_i is
// the direction towards the light, rays travel along -i; a flat mirror gives theta_o = -theta_i.
#include "vgroove/sim/tracer.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/tally.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

// Upper bound on the reflections of any ray in a wedge of aperture theta_v: unfolded, the ray is
// a straight line, which subtends an angle pi from the apex and so crosses at most ceil(pi/theta_v)
// of the mirror lines spaced theta_v apart. The 1e-9 keeps pi/theta_v = 2.0000000000000004 (a
// 90 deg groove from degrees) at 2.
int bounce_bound(double theta_v) { return static_cast<int>(std::ceil(std::numbers::pi / theta_v - 1e-9)); }

// The N stratified rays of a beam from theta_i over the interval, traced one by one.
std::vector<TraceResult> trace_rays(const Groove& g, double theta_i, const Interval& iv, long n,
                                    const TraceOptions& opt = {}) {
  Rng unused(0, 0, 0);
  const Vec2 dir = beam_direction(theta_i);
  std::vector<TraceResult> out;
  out.reserve(static_cast<std::size_t>(n));
  for (long j = 0; j < n; ++j)
    out.push_back(trace(g, beam_ray(g, dir, sample_position(Sampling::stratified, iv, j, n, unused)), opt));
  return out;
}

Tally tally_of(const std::vector<TraceResult>& rays) {
  Tally t;
  for (const TraceResult& r : rays) t.add(r);
  return t;
}

// Every ray ends in exactly one bucket, and every escaped ray in exactly one bin.
void expect_conserved(const Tally& t, long n, const std::string& where) {
  EXPECT_EQ(t.rays, n) << where;
  EXPECT_EQ(t.escaped + t.blocked + t.vertex_hits + t.bounce_limit, t.rays) << where;
  std::int64_t in_bins = 0, bounces = 0;
  for (const auto& side : t.bins)
    for (const auto& [k, b] : side) {
      in_bins += b.count;
      bounces += static_cast<std::int64_t>(k) * b.count;
    }
  EXPECT_EQ(in_bins, t.escaped) << where;
  EXPECT_EQ(bounces, t.bounces) << where;
}

std::string params(double theta_v, double theta_i) {
  std::ostringstream os;
  os.precision(17);
  os << "theta_v=" << theta_v * 180.0 / std::numbers::pi << " deg, theta_i=" << theta_i * 180.0 / std::numbers::pi
     << " deg";
  return os.str();
}

// Readable parameter names: "v37_i-89p9" for theta_v = 37 deg, theta_i = -89.9 deg.
std::string angle_name(double d) {
  std::ostringstream os;
  os << d;
  std::string s = os.str();
  for (char& c : s) {
    if (c == '.') c = 'p';
    if (c == '-') c = 'm';
  }
  return s;
}
using AnglePair = std::tuple<double, double>;  // (theta_v_deg, theta_i_deg)
std::string pair_name(const testing::TestParamInfo<AnglePair>& info) {
  return "v" + angle_name(std::get<0>(info.param)) + "_i" + angle_name(std::get<1>(info.param));
}

// ---------------------------------------------------------------------------------------------
// Hand cases over the whole opening. N is even: with an odd N the middle stratum's midpoint is
// x = 0 exactly, the apex at normal incidence (that ray is tested on its own below).
constexpr long kHandRays = 10000;

TEST(TracerHandCases, RightAngleGrooveRetroreflectsAtNormalIncidence) {
  // A 90 deg corner: the first facet turns the ray horizontal, the second sends it straight back.
  const Groove g = make_symmetric_groove(deg(90));
  const auto rays = trace_rays(g, 0.0, opening(g), kHandRays);
  for (long j = 0; j < kHandRays; ++j) {
    const TraceResult& r = rays[j];
    ASSERT_EQ(r.how, Termination::escaped) << "ray " << j;
    EXPECT_EQ(r.bounces, 2) << "ray " << j;
    EXPECT_NEAR(angle_from_normal(r.exit_dir), 0.0, 1e-12) << "ray " << j;
    // Rays left of the apex meet the left facet first.
    EXPECT_EQ(r.first, j < kHandRays / 2 ? Side::left : Side::right) << "ray " << j;
  }
}

TEST(TracerHandCases, SixtyDegreeGrooveBouncesThreeTimesAtNormalIncidence) {
  // pi / theta_v = 3: a vertical ray turns by 2 * 60 deg per pair of reflections; by hand, a ray
  // hitting the left facet at distance s from the apex meets the right one at s/2, the left one
  // at s again, and leaves straight up: 3 reflections, theta_o = 0, whatever s.
  const Groove g = make_symmetric_groove(deg(60));
  const auto rays = trace_rays(g, 0.0, opening(g), kHandRays);
  for (long j = 0; j < kHandRays; ++j) {
    const TraceResult& r = rays[j];
    ASSERT_EQ(r.how, Termination::escaped) << "ray " << j;
    EXPECT_EQ(r.bounces, 3) << "ray " << j;
    EXPECT_NEAR(angle_from_normal(r.exit_dir), 0.0, 1e-12) << "ray " << j;
  }
}

TEST(TracerHandCases, RightAngleGrooveAt30DegreesBouncesOnceForTan30OfTheBeam) {
  // theta_i = 30 deg in a 90 deg groove (by hand, facet coordinate s from the apex):
  // - left facet first: the ray turns to travel at -30 deg below horizontal, hits the right facet,
  //   leaves retro-reflected at theta_o = +30 deg (2 reflections);
  // - right facet first: the ray leaves at theta_o = 60 deg, travelling 30 deg above horizontal;
  //   it still meets the left facet (2 reflections, retro-reflected) iff s <= tan 15 deg.
  // The ray through s = tan 15 deg crosses the rim line at x = sin45 ((1 + tan30) tan15 - tan30),
  // so the one-bounce rays take (sin45 - x) / (2 sin45) = tan 30 deg of the opening.
  const double theta_i = deg(30);
  const Groove g = make_symmetric_groove(deg(90));
  const Tally t = tally_of(trace_rays(g, theta_i, opening(g), kHandRays));
  expect_conserved(t, kHandRays, "90/30");
  EXPECT_EQ(t.escaped, kHandRays);
  EXPECT_EQ(t.max_bounces(), 2);
  const double n = static_cast<double>(kHandRays);
  // With N strata the count in [x_b, hi] is within 1/2 of N times its width: 1/N is safe.
  EXPECT_NEAR(static_cast<double>(t.count(Side::right, 1)) / n, std::tan(deg(30)), 1.0 / n);
  EXPECT_EQ(t.count(Side::left, 1), 0);
  EXPECT_NEAR(static_cast<double>(t.count(Side::left, 2) + t.count(Side::right, 2)) / n, 1.0 - std::tan(deg(30)),
              1.0 / n);
  // The left facet receives sin(45 - 30 deg) of the 2 sin45 cos30 wide beam (its projected width).
  EXPECT_NEAR(static_cast<double>(t.count(Side::left, 2)) / n,
              std::sin(deg(15)) / (2 * std::sin(deg(45)) * std::cos(theta_i)), 1.0 / n);
  EXPECT_NEAR(t.bins[1][1].theta_o(), deg(60), 1e-12);
  EXPECT_NEAR(t.bins[0][2].theta_o(), deg(30), 1e-12);
  EXPECT_NEAR(t.bins[1][2].theta_o(), deg(30), 1e-12);
  for (const auto& side : t.bins)
    for (const auto& e : side) EXPECT_LT(e.bin.spread(), 1e-12);
}

class FlatGroove : public testing::TestWithParam<double> {};

TEST_P(FlatGroove, EveryRayBouncesOnceAndLeavesAsFromAMirror) {
  const double theta_i = deg(GetParam());
  const Groove g = make_symmetric_groove(std::numbers::pi);
  const auto rays = trace_rays(g, theta_i, opening(g), kHandRays);
  for (long j = 0; j < kHandRays; ++j) {
    const TraceResult& r = rays[j];
    ASSERT_EQ(r.how, Termination::escaped) << "theta_i=" << GetParam() << " ray " << j;
    EXPECT_EQ(r.bounces, 1) << "theta_i=" << GetParam() << " ray " << j;
    EXPECT_NEAR(angle_from_normal(r.exit_dir), -theta_i, 1e-12) << "theta_i=" << GetParam() << " ray " << j;
  }
}
INSTANTIATE_TEST_SUITE_P(ThetaIDeg, FlatGroove, testing::Values(-89.9, -60.0, -12.5, 0.0, 0.3, 45.0, 89.9),
                         [](const testing::TestParamInfo<double>& i) { return "i" + angle_name(i.param); });

// ---------------------------------------------------------------------------------------------
// Identities over a grid of (theta_v, theta_i).
class TracerGrid : public testing::TestWithParam<AnglePair> {
 protected:
  double theta_v() const { return deg(std::get<0>(GetParam())); }
  double theta_i() const { return deg(std::get<1>(GetParam())); }
};

TEST_P(TracerGrid, EveryRayIsCountedExactlyOnce) {
  // The opening, and the rays aimed at each facet (part of which may be shadowed, i.e. blocked).
  constexpr long n = 2001;
  const Groove g = make_symmetric_groove(theta_v());
  const std::string where = params(theta_v(), theta_i());
  expect_conserved(tally_of(trace_rays(g, theta_i(), opening(g), n)), n, where + " opening");
  for (Side s : {Side::left, Side::right}) {
    const Interval aim = aimed_at(g, theta_i(), s);
    if (aim.width() <= 0) continue;  // the facet is not lit
    expect_conserved(tally_of(trace_rays(g, theta_i(), aim, n)), n, where + " aimed at " + side_name(s));
  }
}

TEST_P(TracerGrid, MirroredBeamGivesTheMirroredTally) {
  // The groove is mirror symmetric about x = 0, and every operation of the tracer (products,
  // differences, IEEE rounding) commutes with flipping the sign of x: the ray at -x from -theta_i
  // is the exact mirror image of the ray at x from theta_i, so the counts swap sides exactly.
  constexpr long n = 2000;
  const Groove g = make_symmetric_groove(theta_v());
  const std::string where = params(theta_v(), theta_i());
  const Interval open = opening(g);
  const Interval mirrored{-open.hi, -open.lo};
  const Tally t = tally_of(trace_rays(g, theta_i(), open, n));
  Tally m;
  {
    Rng unused(0, 0, 0);
    const Vec2 dir = beam_direction(-theta_i());
    for (long j = 0; j < n; ++j)
      m.add(trace(g, beam_ray(g, dir, -sample_position(Sampling::stratified, open, j, n, unused))));
  }
  // The same beam placed by sample_position on the (mirror-symmetric) opening from -theta_i: the
  // strata mirror one another up to rounding, so each fraction is within 2/N.
  const Tally p = tally_of(trace_rays(g, -theta_i(), mirrored, n));
  EXPECT_EQ(m.escaped, t.escaped) << where;
  EXPECT_EQ(m.vertex_hits, t.vertex_hits) << where;
  const int kmax = std::max(t.max_bounces(), std::max(m.max_bounces(), p.max_bounces()));
  for (Side s : {Side::left, Side::right})
    for (int k = 0; k <= kmax; ++k) {
      EXPECT_EQ(m.count(other(s), k), t.count(s, k)) << where << " first=" << side_name(s) << " k=" << k;
      EXPECT_NEAR(static_cast<double>(p.count(other(s), k)) / n, static_cast<double>(t.count(s, k)) / n, 2.0 / n)
          << where << " first=" << side_name(s) << " k=" << k;
      if (t.count(s, k) == 0 || m.count(other(s), k) == 0) continue;
      const BounceBin& bt = t.bins[static_cast<int>(s)][k];
      const BounceBin& bm = m.bins[static_cast<int>(other(s))][k];
      EXPECT_NEAR(bm.theta_o(), -bt.theta_o(), 1e-12) << where << " first=" << side_name(s) << " k=" << k;
      if (p.count(other(s), k) > 0) {
        EXPECT_NEAR(p.bins[static_cast<int>(other(s))][k].theta_o(), -bt.theta_o(), 1e-12)
            << where << " first=" << side_name(s) << " k=" << k;
      }
    }
}

TEST_P(TracerGrid, EscapedRaysStayWithinTheBounceBoundAndLeaveUpwards) {
  constexpr long n = 1000;
  const Groove g = make_symmetric_groove(theta_v());
  const std::string where = params(theta_v(), theta_i());
  const int bound = bounce_bound(theta_v());
  const auto rays = trace_rays(g, theta_i(), opening(g), n);
  for (long j = 0; j < n; ++j) {
    const TraceResult& r = rays[j];
    if (r.how != Termination::escaped) continue;
    EXPECT_GE(r.bounces, 1) << where << " ray " << j;
    EXPECT_LE(r.bounces, bound) << where << " ray " << j;
    EXPECT_TRUE(std::isfinite(r.exit_dir.x()) && std::isfinite(r.exit_dir.y())) << where << " ray " << j;
    EXPECT_NEAR(r.exit_dir.norm(), 1.0, 1e-9) << where << " ray " << j;
    EXPECT_GT(r.exit_dir.y(), 0.0) << where << " ray " << j;  // out through the opening
  }
  const Tally t = tally_of(rays);
  expect_conserved(t, n, where);
  // Inside the opening no ray is blocked, and a midpoint never lands on a vertex (the apex at
  // normal incidence is x = 0, which an even N avoids).
  EXPECT_EQ(t.blocked, 0) << where;
  EXPECT_EQ(t.bounce_limit, 0) << where;
}

INSTANTIATE_TEST_SUITE_P(Grid, TracerGrid,
                         testing::Combine(testing::Values(0.1, 0.5, 1.0, 5.0, 37.0, 60.0, 90.0, 179.0, 180.0),
                                          testing::Values(-89.9, -60.0, -18.5, 0.0, 1.0, 30.0, 75.0, 89.9)),
                         pair_name);

// ---------------------------------------------------------------------------------------------
// Hard cases.
TEST(TracerHardCases, NarrowGrooveTakesOverAThousandBounces) {
  // 0.1 deg at normal incidence: pi / theta_v = 1800 mirror images, so rays near the axis bounce
  // up to 1800 times; the exit direction after that many reflections must still be clean.
  const double theta_v = deg(0.1);
  const Groove g = make_symmetric_groove(theta_v);
  constexpr long n = 2000;
  const auto rays = trace_rays(g, 0.0, opening(g), n);
  const Tally t = tally_of(rays);
  expect_conserved(t, n, "theta_v=0.1 theta_i=0");
  EXPECT_EQ(t.escaped, n);
  EXPECT_GT(t.max_bounces(), 1000);
  EXPECT_LE(t.max_bounces(), bounce_bound(theta_v));
  for (long j = 0; j < n; ++j)
    EXPECT_FALSE(std::isnan(rays[j].exit_dir.x()) || std::isnan(rays[j].exit_dir.y())) << "ray " << j;
}

class ApexRay : public testing::TestWithParam<AnglePair> {};

TEST_P(ApexRay, IsAVertexHitOrEscapesButIsNeverLost) {
  // The ray aimed exactly at the apex: the rim-line crossing of the line through the origin.
  const double theta_v = deg(std::get<0>(GetParam())), theta_i = deg(std::get<1>(GetParam()));
  const std::string where = params(theta_v, theta_i);
  const Groove g = make_symmetric_groove(theta_v);
  const double x = aimed_at(g, theta_i, Side::left).hi;
  EXPECT_EQ(x, aimed_at(g, theta_i, Side::right).lo) << where;
  const Ray2 ray = beam_ray(g, beam_direction(theta_i), x);
  // By construction the ray's line passes (up to rounding) through the origin.
  EXPECT_NEAR(cross(ray.origin, ray.dir), 0.0, 1e-14) << where;
  const TraceResult r = trace(g, ray);
  const Interval open = opening(g);
  if (x < open.lo || x > open.hi) {
    // The apex is in the shadow of a rim: the ray never enters this groove.
    EXPECT_EQ(r.how, Termination::blocked) << where << " how=" << termination_name(r.how);
  } else if (r.how == Termination::escaped) {
    EXPECT_GE(r.bounces, 1) << where;
    EXPECT_LE(r.bounces, bounce_bound(theta_v)) << where;
    EXPECT_TRUE(std::isfinite(r.exit_dir.x()) && std::isfinite(r.exit_dir.y())) << where;
    EXPECT_GT(r.exit_dir.y(), 0.0) << where;
  } else {
    EXPECT_EQ(r.how, Termination::vertex_hit) << where << " how=" << termination_name(r.how);
  }
  Tally t;
  t.add(r);
  expect_conserved(t, 1, where);
}
INSTANTIATE_TEST_SUITE_P(Grid, ApexRay,
                         testing::Combine(testing::Values(0.1, 1.0, 36.0, 60.0, 90.0, 133.0, 180.0),
                                          testing::Values(-70.0, -10.0, 0.0, 0.7, 30.0)),
                         pair_name);

TEST(TracerHardCases, NormalRayThroughTheApexIsAVertexHit) {
  // At normal incidence the apex ray is x = 0 exactly and meets both facets at s = 0 exactly.
  const Groove g = make_symmetric_groove(deg(90));
  const TraceResult r = trace(g, beam_ray(g, beam_direction(0.0), 0.0));
  EXPECT_EQ(r.how, Termination::vertex_hit) << termination_name(r.how);
}

TEST(TracerHardCases, RaysOnTheRimsAreVertexHitsAndOutsideAreBlocked) {
  const Groove g = make_symmetric_groove(deg(70));
  const Vec2 dir = beam_direction(deg(20));
  EXPECT_EQ(trace(g, beam_ray(g, dir, g.rim_x(Side::left))).how, Termination::vertex_hit);
  EXPECT_EQ(trace(g, beam_ray(g, dir, g.rim_x(Side::right))).how, Termination::vertex_hit);
  EXPECT_EQ(trace(g, beam_ray(g, dir, g.rim_x(Side::left) - 1e-9)).how, Termination::blocked);
  EXPECT_EQ(trace(g, beam_ray(g, dir, g.rim_x(Side::right) + 1e-9)).how, Termination::blocked);
}

TEST(TracerHardCases, BounceLimitStopsAndCountsTheRays) {
  // A 1 deg groove at normal incidence needs about 180 reflections; with a limit of 5 every ray
  // stops after exactly 5, is reported as bounce_limit and counted.
  const Groove g = make_symmetric_groove(deg(1));
  constexpr long n = 1000;
  const auto rays = trace_rays(g, 0.0, opening(g), n, TraceOptions{5});
  for (long j = 0; j < n; ++j) {
    EXPECT_EQ(rays[j].how, Termination::bounce_limit) << "ray " << j << " how=" << termination_name(rays[j].how);
    EXPECT_EQ(rays[j].bounces, 5) << "ray " << j;
  }
  const Tally t = tally_of(rays);
  expect_conserved(t, n, "theta_v=1 theta_i=0 max_bounces=5");
  EXPECT_EQ(t.bounce_limit, n);
  EXPECT_EQ(t.escaped, 0);
}

TEST(TracerHardCases, BounceLimitAtTheExactCountStillEscapes) {
  // The limit stops a ray that would need a further reflection, not one that has just enough.
  const Groove g = make_symmetric_groove(deg(90));
  const TraceResult r = trace(g, beam_ray(g, beam_direction(0.0), -0.3), TraceOptions{2});
  EXPECT_EQ(r.how, Termination::escaped) << termination_name(r.how);
  EXPECT_EQ(r.bounces, 2);
  const TraceResult s = trace(g, beam_ray(g, beam_direction(0.0), -0.3), TraceOptions{1});
  EXPECT_EQ(s.how, Termination::bounce_limit) << termination_name(s.how);
}

TEST(TracerObserver, SeesEveryReflection) {
  struct Counter {
    int calls = 0;
    Side last = Side::right;
    bool alternates = true;
    void on_bounce(Side s, const Vec2&, const Facet&) {
      if (calls > 0 && s == last) alternates = false;
      last = s;
      ++calls;
    }
  } counter;
  const Groove g = make_symmetric_groove(deg(10));
  const TraceResult r = trace(g, beam_ray(g, beam_direction(deg(5)), 0.01), TraceOptions{}, counter);
  ASSERT_EQ(r.how, Termination::escaped);
  EXPECT_EQ(counter.calls, r.bounces);
  EXPECT_TRUE(counter.alternates);  // a flat facet cannot be hit twice in a row
}

}  // namespace
}  // namespace vgroove::sim
