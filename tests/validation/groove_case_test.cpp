// Tests of validation/groove_case.h: the exact tracer against the kaleidoscopic model, case by
// case, on grids outside the paper's sweep and at the hard corners.
//
// Error budget of a stratified case. run_case spreads N rays over the interval aimed at a facet,
// at the midpoints (j + 1/2)/N of equal strata. The model splits that interval into at most three
// bins (shadow | k reflections | k - 1 reflections), so there are two interior boundaries. The
// number of midpoints below any point u is within 1/2 of N u, so each boundary moves each of its
// two neighbouring fractions by at most 1/(2N): L1 <= 2 boundaries x 2 fractions x 1/(2N) = 2/N.
// We allow 4/N: the factor 2 covers a ray within rounding distance (~1e-15) of a boundary landing
// on the other side (that can cost up to 2/N more per boundary, but needs a midpoint within 1e-15
// of it: about N x 1e-15 likely).
#include "vgroove/validation/groove_case.h"

#include "vgroove/analytic/kaleidoscope.h"

#include "tests/param_names.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>

namespace vgroove::validation {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

constexpr long kRays = 2000;

GrooveParams sym(double theta_v) { return GrooveParams::make_symmetric(theta_v); }

CaseOptions stratified(long rays = kRays) {
  CaseOptions o;
  o.rays = rays;
  o.sampling = sim::Sampling::stratified;
  return o;
}

std::string describe(const CaseOutcome& c) {
  std::ostringstream os;
  os.precision(10);
  os << "theta_v=" << c.groove.theta_v * 180 / std::numbers::pi << " theta_i=" << c.theta_i * 180 / std::numbers::pi
     << " l1=" << c.l1 << " theta_o_error=" << c.theta_o_error;
  for (int f = 0; f < 2; ++f) {
    const FacetOutcome& o = c.facet[f];
    os << (f == 0 ? "\n  left: " : "\n  right: ");
    if (!o.compared) {
      os << "not lit";
      continue;
    }
    os << "l1=" << o.l1 << " k=" << o.k << " rays=" << o.rays << " vertex_hits=" << o.vertex_hits
       << " bounce_limit=" << o.bounce_limit << " wrong_first=" << o.wrong_first;
  }
  return os.str();
}

// What every case must satisfy whatever the sampling.
void expect_clean(const CaseOutcome& c, long rays) {
  EXPECT_LE(c.theta_o_error, 1e-9) << describe(c);
  int compared = 0;
  for (const FacetOutcome& f : c.facet) {
    if (!f.compared) continue;
    ++compared;
    EXPECT_EQ(f.rays, rays) << describe(c);
    EXPECT_EQ(f.vertex_hits, 0) << describe(c);
    EXPECT_EQ(f.bounce_limit, 0) << describe(c);
    EXPECT_EQ(f.wrong_first, 0) << describe(c);
    EXPECT_LE(f.l1, c.l1) << describe(c);
  }
  EXPECT_GE(compared, 1) << describe(c);  // |theta_i| < 90: the light reaches some facet
  EXPECT_EQ(c.l1, std::max(c.facet[0].compared ? c.facet[0].l1 : 0.0, c.facet[1].compared ? c.facet[1].l1 : 0.0))
      << describe(c);
}

using test_names::AnglePair;
using test_names::pair_name;

// ---------------------------------------------------------------------------------------------
// Agreement on a grid outside the paper's sweep (the paper uses whole degrees, theta_v = 1 + 5 n).
class OffSweepGrid : public testing::TestWithParam<AnglePair> {
 protected:
  double theta_v() const { return deg(std::get<0>(GetParam())); }
  double theta_i() const { return deg(std::get<1>(GetParam())); }
};

TEST_P(OffSweepGrid, StratifiedTraceMatchesTheModelToTheStratificationError) {
  const CaseOutcome c = run_case(sym(theta_v()), theta_i(), stratified(), 0);
  expect_clean(c, kRays);
  EXPECT_LE(c.l1, 4.0 / kRays) << describe(c);
}

TEST_P(OffSweepGrid, RandomTraceMatchesTheModelWithinBinomialBounds) {
  // With random placement the count in a model bin of probability p is Binomial(N, p). Bernstein's
  // inequality bounds |count/N - p| by sqrt(2 p (1 - p) L / N) + 2 L / (3 N), L = ln(2 / delta),
  // except with probability delta; delta = 1e-9 per bin (L = 21.4) makes the first term 6.5 sigma
  // and the second keeps bins with N p ~ 1 (where the normal approximation fails) honest.
  // Summed over the facet's bins (union bound), fixed seed.
  CaseOptions opt = stratified();
  opt.sampling = sim::Sampling::random;
  opt.seed = 20240611;
  const std::uint64_t stream =
      static_cast<std::uint64_t>(std::get<0>(GetParam()) * 1000 + std::get<1>(GetParam()) + 1e5);
  const CaseOutcome c = run_case(sym(theta_v()), theta_i(), opt, stream);
  expect_clean(c, kRays);
  const double n = static_cast<double>(kRays), L = std::log(2.0 / 1e-9);
  for (sim::Side s : {sim::Side::left, sim::Side::right}) {
    const FacetOutcome& f = c.facet[static_cast<int>(s)];
    if (!f.compared) continue;
    const analytic::FacetPrediction p = analytic::G_kaleidoscopic(
        theta_i(), theta_v(), s == sim::Side::left ? analytic::FacetSide::left : analytic::FacetSide::right);
    double bound = 0.0;
    for (double g : {p.shadow, p.fewer.G, p.more.G})
      if (g > 0.0) bound += std::sqrt(2.0 * g * (1.0 - g) * L / n) + 2.0 * L / (3.0 * n);
    EXPECT_LE(f.l1, bound) << describe(c) << "\n  facet " << sim::side_name(s) << " bound=" << bound;
  }
}

INSTANTIATE_TEST_SUITE_P(Grid, OffSweepGrid,
                         testing::Combine(testing::Values(2.5, 7.3, 33.3, 121.7, 179.0),
                                          testing::Values(-89.5, -45.25, -3.3, 0.7, 12.1, 60.6, 88.8)),
                         pair_name);

// ---------------------------------------------------------------------------------------------
// Hard corners: very narrow grooves (over a thousand reflections), grazing light, flat grooves.
class HardCase : public testing::TestWithParam<AnglePair> {};

TEST_P(HardCase, TraceMatchesTheModel) {
  const double theta_v = deg(std::get<0>(GetParam())), theta_i = deg(std::get<1>(GetParam()));
  const CaseOutcome c = run_case(sym(theta_v), theta_i, stratified(), 0);
  expect_clean(c, kRays);
  EXPECT_LE(c.l1, 4.0 / kRays) << describe(c);
}
INSTANTIATE_TEST_SUITE_P(Grid, HardCase,
                         testing::Combine(testing::Values(0.1, 0.5, 1.0, 90.0, 179.0, 180.0),
                                          testing::Values(-89.9, 0.0, 89.9)),
                         pair_name);

TEST(HardCase, NarrowGrooveCountsOverAThousandBounces) {
  const CaseOutcome c = run_case(sym(deg(0.1)), 0.0, stratified(), 0);
  for (const FacetOutcome& f : c.facet) {
    ASSERT_TRUE(f.compared) << describe(c);
    EXPECT_EQ(f.k, 1801) << describe(c);  // Eq. (4): floor(1800) + 1
    // The mean reflection count is about 1800 (k - 1 for all rays at this integer point).
    EXPECT_GT(static_cast<double>(f.bounces) / static_cast<double>(f.rays), 1000.0) << describe(c);
  }
}

// Where (pi + 2 theta_i) / theta_v is an integer (for one facet or both), Eq. (4) jumps.
class EqFourBoundaryCase : public testing::TestWithParam<AnglePair> {};

TEST_P(EqFourBoundaryCase, TraceMatchesTheModel) {
  const double theta_v = deg(std::get<0>(GetParam())), theta_i = deg(std::get<1>(GetParam()));
  for (double d : {-1e-9, 0.0, 1e-9}) {
    const CaseOutcome c = run_case(sym(theta_v), theta_i + d, stratified(), 0);
    expect_clean(c, kRays);
    EXPECT_LE(c.l1, 4.0 / kRays) << "offset " << d << ": " << describe(c);
  }
}
INSTANTIATE_TEST_SUITE_P(Integers, EqFourBoundaryCase,
                         testing::Values(AnglePair{60, 0}, AnglePair{36, 0}, AnglePair{40, 10}, AnglePair{90, 0},
                                         AnglePair{50, -15}, AnglePair{72, -18}),
                         pair_name);

// ---------------------------------------------------------------------------------------------
TEST(RunCase, PrintedEquationSixIsOffByTwoAtNormalIncidence) {
  // theta_v = 90, theta_i = 0: every traced ray reflects twice; the printed Eq. (6) predicts
  // G_2 = 2 and G_3 = -1 (see the analytic tests), so L1 = |1 - 2| + |0 - (-1)| = 2 per facet.
  CaseOptions opt = stratified();
  opt.form = analytic::Eq6Form::printed;
  const CaseOutcome c = run_case(sym(deg(90)), 0.0, opt, 0);
  EXPECT_NEAR(c.l1, 2.0, 4.0 / kRays) << describe(c);
  opt.form = analytic::Eq6Form::corrected;
  EXPECT_LE(run_case(sym(deg(90)), 0.0, opt, 0).l1, 4.0 / kRays);
}

TEST(RunCase, UnlitFacetIsNotCompared) {
  // theta_i = 60 deg in a 90 deg groove: the left facet faces away (sin(45 - 60 deg) < 0).
  const CaseOutcome c = run_case(sym(deg(90)), deg(60), stratified(), 0);
  EXPECT_FALSE(c.facet[0].compared) << describe(c);
  EXPECT_TRUE(c.facet[1].compared) << describe(c);
  EXPECT_EQ(c.rays, kRays) << describe(c);
}

TEST(RunCase, BounceLimitCountsAgainstTheModel) {
  // A 1 deg groove needs ~180 reflections; with max_bounces = 5 every ray stops, and the rays the
  // model has no bin for count in full: the model's share 1 is missed and the stopped rays add 1.
  CaseOptions opt = stratified(500);
  opt.max_bounces = 5;
  const CaseOutcome c = run_case(sym(deg(1)), 0.0, opt, 0);
  for (const FacetOutcome& f : c.facet) {
    ASSERT_TRUE(f.compared) << describe(c);
    EXPECT_EQ(f.bounce_limit, 500) << describe(c);
    EXPECT_NEAR(f.l1, 2.0, 1e-12) << describe(c);
  }
}

TEST(RunCase, RandomStreamsAreKeyedByTheCase) {
  CaseOptions opt = stratified(300);
  opt.sampling = sim::Sampling::random;
  const CaseOutcome a = run_case(sym(deg(33.3)), deg(12.1), opt, 5);
  const CaseOutcome b = run_case(sym(deg(33.3)), deg(12.1), opt, 5);
  EXPECT_EQ(a.l1, b.l1);
  EXPECT_EQ(a.bounces, b.bounces);
  // Other streams place other rays: their bin counts (seen through the sums) cannot all agree.
  int same = 0;
  for (std::uint64_t stream = 6; stream < 11; ++stream) {
    const CaseOutcome d = run_case(sym(deg(33.3)), deg(12.1), opt, stream);
    same += d.bounces == a.bounces && d.l1 == a.l1;
  }
  EXPECT_LT(same, 5);
}

}  // namespace
}  // namespace vgroove::validation

namespace vgroove::validation {
namespace {

// The tracer's rounding at the narrowest apertures. The beam entering the opening is split by the
// rays' positions into zones (facet hit first, bounce count); the traced zone widths are found
// exactly by bisection on the position (to 1e-15 of the opening) and compared with the model's
// fractions of the entering beam (G f_a / entering_width): their L1 distance is what a stratified
// `trace` sees against `analytic` on top of its bound 1/N. It grows like theta_v^-2 (each
// reflection's rounding adds up over pi / theta_v of them; README, "Float limits"): ~2.6e-9
// (0.01 deg / theta_v)^2, largest where Eq. (4) is at an integer boundary (theta_i = 30 deg at
// these apertures: a zone the model makes empty). So 2.6e-7 at the narrowest accepted aperture,
// far below 1/N for any run one can afford there, and 2.6e-5 at 1e-4 deg.
double zone_l1(double theta_v_deg, double theta_i_deg) {
  const GrooveParams p = GrooveParams::make_symmetric(deg(theta_v_deg));
  const sim::Groove g = make_groove(p);
  const double theta_i = deg(theta_i_deg);
  const sim::Vec2 dir = sim::beam_direction(theta_i);
  const sim::Interval open = sim::opening(g);
  auto zone = [&](double x) {  // 2 k + facet hit first; -1: not escaped
    const sim::TraceResult r = sim::trace(g, sim::beam_ray(g, dir, x), sim::TraceOptions{1'000'000'000});
    return r.how == sim::Termination::escaped ? 2 * r.bounces + static_cast<int>(r.first) : -1;
  };
  std::map<int, double> traced;
  const int m = 64;
  double edge = open.lo, prev_x = open.lo + 1e-9 * open.width();
  int prev = zone(prev_x);
  for (int j = 1; j <= m; ++j) {
    const double x = j == m ? open.hi - 1e-9 * open.width() : open.lo + j * open.width() / m;
    const int z = zone(x);
    if (z != prev) {
      double lo = prev_x, hi = x;
      while (hi - lo > 1e-15 * open.width()) {
        const double mid = 0.5 * (lo + hi);
        (zone(mid) == prev ? lo : hi) = mid;
      }
      traced[prev] += (0.5 * (lo + hi) - edge) / open.width();
      edge = 0.5 * (lo + hi);
      prev = z;
    }
    prev_x = x;
  }
  traced[prev] += (open.hi - edge) / open.width();
  ModelShares s[2];
  for (sim::Side side : {sim::Side::left, sim::Side::right})
    s[static_cast<int>(side)] = model_shares(p, theta_i, side, analytic::Eq6Form::corrected);
  const double width = entering_width(s);
  std::map<int, double> model;
  for (int f = 0; f < 2; ++f)
    if (s[f].lit)
      for (int z = 0; z < s[f].shares; ++z) model[2 * s[f].share[z].n + f] += s[f].share[z].G * s[f].f_a / width;
  double l1 = 0.0;
  for (const auto& [k, f] : traced) l1 += std::abs(f - (model.count(k) ? model[k] : 0.0));
  for (const auto& [k, f] : model)
    if (!traced.count(k)) l1 += std::abs(f);
  return l1;
}

TEST(NarrowGroove, TracerRoundingIsFarBelowTheStratifiedBoundAtTheNarrowestAperture) {
  for (double theta_i : {0.0, 30.0, 70.1234567, 89.7654321, kMaxThetaIDeg, -kMaxThetaIDeg, -45.5})
    EXPECT_LE(zone_l1(kMinApertureDeg, theta_i), 1e-6) << "theta_i " << theta_i;
}

// Power: ten times narrower, the same measure is past 1e-6, grown as theta_v^-2.
TEST(NarrowGroove, BelowTheNarrowestApertureTheRoundingShowsUp) {
  const double at_min = zone_l1(kMinApertureDeg, 30.0), below = zone_l1(0.1 * kMinApertureDeg, 30.0);
  EXPECT_GT(below, 1e-6);
  EXPECT_GT(below, 30.0 * at_min);  // theta_v^-2: 100x, give or take the rounding's luck
}

}  // namespace
}  // namespace vgroove::validation
