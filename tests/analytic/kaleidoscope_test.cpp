// Tests of analytic/kaleidoscope.h (Lee et al. 2018, Eq. 4-6) at hand-derived points, and its
// identities: shares sum to one, mirror symmetry, continuity where Eq. (4) jumps.
//
// Hand notation: half = theta_v / 2. For the left facet, f_a = sin(half - theta_i) (its projected
// width), f(b) = -sin(half + theta_i), and the transition point f(k) = sin(k theta_v - half - theta_i).
#include "vgroove/analytic/kaleidoscope.h"

#include "tests/param_names.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <tuple>

namespace vgroove::analytic {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

// The model's fraction of the rays aimed at a facet, per reflection count n (the fewer and more
// shares merged when they name the same n, zero shares dropped); the shadow under n = -1.
std::map<int, double> by_count(const FacetPrediction& p) {
  std::map<int, double> m;
  if (!p.lit) return m;
  m[p.fewer.n] += p.fewer.G;
  m[p.more.n] += p.more.G;
  m[-1] += p.shadow;
  for (auto it = m.begin(); it != m.end();) it = it->second == 0.0 ? m.erase(it) : std::next(it);
  return m;
}

std::string dump(const std::map<int, double>& m) {
  std::ostringstream os;
  os.precision(17);
  for (const auto& [n, g] : m) os << " n=" << n << ":" << g;
  return os.str();
}

const char* name(FacetSide s) { return s == FacetSide::left ? "left" : "right"; }

// ---------------------------------------------------------------------------------------------
TEST(BounceCount, HandPoints) {
  // Eq. (4): k = floor((pi + 2 theta_i) / theta_v) + 1, the larger of the two counts.
  EXPECT_EQ(bounce_count(0.0, deg(90)), 3);       // pi / (pi/2) = 2 exactly: counts 2 and 3
  EXPECT_EQ(bounce_count(0.0, deg(60)), 4);       // pi / (pi/3) = 3 exactly: counts 3 and 4
  EXPECT_EQ(bounce_count(deg(30), deg(90)), 3);   // 240 / 90 = 2.67
  EXPECT_EQ(bounce_count(deg(-30), deg(90)), 2);  // 120 / 90 = 1.33
  EXPECT_EQ(bounce_count(deg(10), deg(60)), 4);   // 200 / 60 = 3.33
  EXPECT_EQ(bounce_count(0.0, deg(180)), 2);      // a flat mirror: 1 reflection (k - 1)
  EXPECT_EQ(bounce_count(0.0, deg(0.1)), 1801);
}

TEST(BounceCount, NarrowestGroovesDoNotOverflow) {
  // Library bug (analytic/kaleidoscope.cpp, bounce_count): floor((pi + 2 theta_i) / theta_v) is
  // cast to int. Any theta_v in (0, pi] is accepted (validation::check_theta_v takes (0, 180]
  // deg), but below pi / INT_MAX = 1.46e-9 rad (8.4e-8 deg) the count does not fit: the cast is
  // undefined behaviour and on x86 gives INT_MIN, so k = -2147483647 and fewer.n = INT_MIN.
  const double theta_v = deg(1e-8);  // pi / theta_v = 1.8e10 reflections
  EXPECT_GE(bounce_count(0.0, theta_v), 1);
  const FacetPrediction p = G_kaleidoscopic(0.0, theta_v, FacetSide::left);
  ASSERT_TRUE(p.lit);
  EXPECT_GE(p.fewer.n, 0);
  EXPECT_GE(p.more.n, 1);
}

TEST(BounceCount, IntegerPointsStillPredictTheHandCounts) {
  // Where (pi + 2 theta_i) / theta_v is an integer Eq. (4) may round either way; the model's
  // fractions must say what the hand derivation says regardless: all rays bounce 2 times in a
  // 90 deg groove and 3 times in a 60 deg one at normal incidence.
  for (auto [v, n] : {std::pair{90.0, 2}, std::pair{60.0, 3}, std::pair{36.0, 5}}) {
    for (FacetSide s : {FacetSide::left, FacetSide::right}) {
      const auto m = by_count(G_kaleidoscopic(0.0, deg(v), s));
      ASSERT_EQ(m.size(), 1u) << "theta_v=" << v << " " << name(s) << dump(m);
      EXPECT_EQ(m.begin()->first, n) << "theta_v=" << v << " " << name(s) << dump(m);
      EXPECT_NEAR(m.begin()->second, 1.0, 1e-12) << "theta_v=" << v << " " << name(s) << dump(m);
    }
  }
}

TEST(ExitAngle, HandPoints) {
  // Eq. (5): theta_o = (-1)^n (theta_i + pi - n theta_v).
  EXPECT_NEAR(exit_angle(deg(25), deg(180), 1), deg(-25), 1e-15);  // a mirror
  EXPECT_NEAR(exit_angle(deg(25), deg(90), 2), deg(25), 1e-15);    // a corner retro-reflects
  EXPECT_NEAR(exit_angle(0.0, deg(60), 3), 0.0, 1e-15);
  EXPECT_NEAR(exit_angle(deg(30), deg(90), 1, FacetSide::right), deg(60), 1e-15);
  EXPECT_NEAR(exit_angle(deg(30), deg(90), 2, FacetSide::right), deg(30), 1e-15);
  // n = 0 would be the light itself turned back: theta_i + pi wraps to theta_i - pi.
  EXPECT_NEAR(exit_angle(deg(30), deg(90), 0), deg(30) - std::numbers::pi, 1e-15);
}

TEST(ExitAngle, IsWrappedIntoMinusPiPi) {
  for (int n = 0; n < 50; ++n)
    for (double i : {-89.0, -10.0, 0.0, 33.0, 89.0}) {
      const double o = exit_angle(deg(i), deg(7.3), n);
      EXPECT_GE(o, -std::numbers::pi) << "n=" << n << " theta_i=" << i;
      EXPECT_LE(o, std::numbers::pi) << "n=" << n << " theta_i=" << i;
      EXPECT_NEAR(
          std::remainder(o - (n % 2 ? -1 : 1) * (deg(i) + std::numbers::pi - n * deg(7.3)), 2 * std::numbers::pi), 0.0,
          1e-12)
          << "n=" << n << " theta_i=" << i;
    }
}

TEST(GKaleidoscopic, RightAngleGrooveAt30DegreesByHand) {
  // Left facet: f_a = sin15, f(b) = -sin75 -> f_b = 0, k = 3, f(3) = sin(195 deg) < 0 -> f_k = 0:
  // every ray reflects twice.
  const FacetPrediction l = G_kaleidoscopic(deg(30), deg(90), FacetSide::left);
  ASSERT_TRUE(l.lit);
  EXPECT_EQ(l.k, 3);
  EXPECT_NEAR(l.f_a, std::sin(deg(15)), 1e-15);
  EXPECT_EQ(l.f_b, 0.0);
  EXPECT_EQ(l.fewer.n, 2);
  EXPECT_NEAR(l.fewer.G, 1.0, 1e-15);
  EXPECT_NEAR(l.more.G, 0.0, 1e-15);
  EXPECT_NEAR(l.fewer.theta_o, deg(30), 1e-15);
  // Right facet (mirrored: theta_i = -30 for the left one): f_a = sin75, f_b = 0, k = 2,
  // f(2) = sin(165 deg) = sin15: sin15 / sin75 = tan15 of it reflects twice, the rest once.
  const FacetPrediction r = G_kaleidoscopic(deg(30), deg(90), FacetSide::right);
  ASSERT_TRUE(r.lit);
  EXPECT_EQ(r.k, 2);
  EXPECT_NEAR(r.f_a, std::sin(deg(75)), 1e-15);
  EXPECT_NEAR(r.more.G, std::tan(deg(15)), 1e-15);
  EXPECT_NEAR(r.fewer.G, 1.0 - std::tan(deg(15)), 1e-15);
  EXPECT_NEAR(r.fewer.theta_o, deg(60), 1e-15);
  EXPECT_NEAR(r.more.theta_o, deg(30), 1e-15);
  // Of the beam entering the opening (width 2 sin45 cos30), the one-bounce rays are tan30.
  EXPECT_NEAR(r.fewer.G * r.f_a / opening_width(deg(30), deg(90)), std::tan(deg(30)), 1e-15);
}

TEST(GKaleidoscopic, ShadowedFacetByHand) {
  // theta_i = -60 deg in a 90 deg groove: the right rim shadows part of the left facet,
  // f_b = -f(b) clamp = sin(60 - 45 deg) = sin15 of f_a = sin105 deg.
  const FacetPrediction l = G_kaleidoscopic(deg(-60), deg(90), FacetSide::left);
  ASSERT_TRUE(l.lit);
  EXPECT_NEAR(l.shadow, std::sin(deg(15)) / std::sin(deg(105)), 1e-15);
  // The right facet faces away from the light.
  EXPECT_FALSE(G_kaleidoscopic(deg(-60), deg(90), FacetSide::right).lit);
}

TEST(GKaleidoscopic, PrintedFormGivesANegativeShareAtNormalIncidence) {
  // ERRATA E1: at theta_v = 90, theta_i = 0, k = 3 and f(3) = sin(225 deg) = -sin45 < f_b = 0;
  // the printed Eq. (6) does not clamp f_k, so G_3 = (f_k - f_b) / f_a = -1 and G_2 = 2.
  const FacetPrediction p = G_kaleidoscopic(0.0, deg(90), FacetSide::left, Eq6Form::printed);
  ASSERT_TRUE(p.lit);
  EXPECT_EQ(p.k, 3);
  EXPECT_LT(p.more.G, 0.0);
  EXPECT_NEAR(p.more.G, -1.0, 1e-15);
  EXPECT_NEAR(p.fewer.G, 2.0, 1e-15);
  const FacetPrediction c = G_kaleidoscopic(0.0, deg(90), FacetSide::left, Eq6Form::corrected);
  EXPECT_EQ(c.more.G, 0.0);
  EXPECT_NEAR(c.fewer.G, 1.0, 1e-15);
}

// ---------------------------------------------------------------------------------------------
using test_names::AnglePair;
using test_names::pair_name;

class ModelGrid : public testing::TestWithParam<AnglePair> {};

TEST_P(ModelGrid, SharesAreFractionsThatSumToOne) {
  const double v = std::get<0>(GetParam()), i = std::get<1>(GetParam());
  for (FacetSide s : {FacetSide::left, FacetSide::right}) {
    const FacetPrediction p = G_kaleidoscopic(deg(i), deg(v), s);
    const double f_a = std::sin(deg(0.5 * v) + (s == FacetSide::left ? -1 : 1) * deg(i));
    EXPECT_EQ(p.lit, f_a > 0) << "theta_v=" << v << " theta_i=" << i << " " << name(s);
    if (!p.lit) continue;
    EXPECT_NEAR(p.fewer.G + p.more.G + p.shadow, 1.0, 1e-12) << "theta_v=" << v << " theta_i=" << i << " " << name(s);
    for (double g : {p.fewer.G, p.more.G, p.shadow}) {
      EXPECT_GE(g, 0.0) << "theta_v=" << v << " theta_i=" << i << " " << name(s);
      EXPECT_LE(g, 1.0) << "theta_v=" << v << " theta_i=" << i << " " << name(s);
    }
    EXPECT_EQ(p.fewer.n, p.k - 1) << "theta_v=" << v << " theta_i=" << i << " " << name(s);
    EXPECT_EQ(p.more.n, p.k) << "theta_v=" << v << " theta_i=" << i << " " << name(s);
    EXPECT_LE(p.f_b, p.f_k) << "theta_v=" << v << " theta_i=" << i << " " << name(s);
    EXPECT_LE(p.f_k, p.f_a) << "theta_v=" << v << " theta_i=" << i << " " << name(s);
  }
}

TEST_P(ModelGrid, RightFacetIsTheMirrorImageOfTheLeft) {
  const double v = std::get<0>(GetParam()), i = std::get<1>(GetParam());
  const FacetPrediction r = G_kaleidoscopic(deg(i), deg(v), FacetSide::right);
  const FacetPrediction l = G_kaleidoscopic(deg(-i), deg(v), FacetSide::left);
  ASSERT_EQ(r.lit, l.lit) << "theta_v=" << v << " theta_i=" << i;
  if (!r.lit) return;
  EXPECT_EQ(r.k, l.k) << "theta_v=" << v << " theta_i=" << i;
  EXPECT_EQ(r.fewer.G, l.fewer.G) << "theta_v=" << v << " theta_i=" << i;
  EXPECT_EQ(r.more.G, l.more.G) << "theta_v=" << v << " theta_i=" << i;
  EXPECT_EQ(r.shadow, l.shadow) << "theta_v=" << v << " theta_i=" << i;
  // Exit angles mirror too (up to the wrap at +-pi).
  EXPECT_NEAR(std::remainder(r.fewer.theta_o + l.fewer.theta_o, 2 * std::numbers::pi), 0.0, 1e-12)
      << "theta_v=" << v << " theta_i=" << i;
  EXPECT_NEAR(std::remainder(r.more.theta_o + l.more.theta_o, 2 * std::numbers::pi), 0.0, 1e-12)
      << "theta_v=" << v << " theta_i=" << i;
}

TEST_P(ModelGrid, LitWidthsOfBothFacetsMakeTheOpening) {
  // Every ray entering the opening is aimed at exactly one facet and not shadowed:
  // (f_a - f_b)_left + (f_a - f_b)_right = 2 sin(theta_v/2) cos(theta_i).
  const double v = std::get<0>(GetParam()), i = std::get<1>(GetParam());
  double lit = 0.0;
  for (FacetSide s : {FacetSide::left, FacetSide::right}) {
    const FacetPrediction p = G_kaleidoscopic(deg(i), deg(v), s);
    if (p.lit) lit += p.f_a - p.f_b;
  }
  EXPECT_NEAR(lit, opening_width(deg(i), deg(v)), 1e-12) << "theta_v=" << v << " theta_i=" << i;
  EXPECT_NEAR(opening_width(deg(i), deg(v)), 2 * std::sin(deg(0.5 * v)) * std::cos(deg(i)), 1e-15)
      << "theta_v=" << v << " theta_i=" << i;
}

INSTANTIATE_TEST_SUITE_P(Grid, ModelGrid,
                         testing::Combine(testing::Values(0.1, 2.5, 7.3, 33.3, 60.0, 90.0, 121.7, 179.0, 180.0),
                                          testing::Values(-89.9, -45.25, -3.3, 0.0, 0.7, 12.1, 60.6, 89.9)),
                         pair_name);

// ---------------------------------------------------------------------------------------------
// Where (pi + 2 theta_i) / theta_v is an integer, k jumps by one; the fractions per reflection
// count must not (the jump only moves which of "fewer" / "more" carries the share).
class EqFourBoundary : public testing::TestWithParam<AnglePair> {};

TEST_P(EqFourBoundary, FractionsPerBounceCountAreContinuous) {
  const double v = std::get<0>(GetParam()), i = std::get<1>(GetParam());
  constexpr double eps = 1e-12;
  for (FacetSide s : {FacetSide::left, FacetSide::right}) {
    const double mirrored = s == FacetSide::left ? i : -i;
    // The point is a boundary for this facet when (pi + 2 theta_i') / theta_v is an integer.
    const double q = (180.0 + 2.0 * mirrored) / v;
    const auto below = by_count(G_kaleidoscopic(deg(i) - eps, deg(v), s));
    const auto at = by_count(G_kaleidoscopic(deg(i), deg(v), s));
    const auto above = by_count(G_kaleidoscopic(deg(i) + eps, deg(v), s));
    const std::string where = "theta_v=" + std::to_string(v) + " theta_i=" + std::to_string(i) + " " + name(s) +
                              " (pi + 2 theta_i)/theta_v=" + std::to_string(q) + "\n below:" + dump(below) +
                              "\n at:" + dump(at) + "\n above:" + dump(above);
    // Integer points are chosen where the facet is lit on both sides (f_a well above 0).
    ASSERT_FALSE(below.empty() || at.empty() || above.empty()) << where;
    std::map<int, double> all;
    for (const auto* m : {&below, &at, &above})
      for (const auto& [n, g] : *m) all[n] = 0.0;
    // The shares are (f_a - f_k) / f_a and the like, with |d f / d theta_i| <= 1: moving theta_i
    // by eps moves a share by at most about 2 eps / f_a. That is far below 1e-9 unless the facet's
    // projected width f_a is tiny (a 0.1 deg groove: f_a = sin 0.05 deg, slope ~ 2300).
    const double f_a = G_kaleidoscopic(deg(i), deg(v), s).f_a;
    const double tol = std::max(1e-9, 4.0 * eps / f_a);
    for (const auto& [n, unused] : all) {
      const auto get = [n = n](const std::map<int, double>& m) {
        const auto it = m.find(n);
        return it == m.end() ? 0.0 : it->second;
      };
      EXPECT_NEAR(get(below), get(above), tol) << where << "\n n=" << n;
      EXPECT_NEAR(get(at), get(above), tol) << where << "\n n=" << n;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Integers, EqFourBoundary,
                         testing::Values(AnglePair{60, 0}, AnglePair{36, 0}, AnglePair{40, 10}, AnglePair{40, -10},
                                         AnglePair{90, 0}, AnglePair{50, -15}, AnglePair{72, -18}, AnglePair{0.1, 0}),
                         pair_name);

TEST(EqFourBoundary, HandValuesAtSixtyDegrees) {
  // theta_v = 60, theta_i = 0: every ray aimed at a facet reflects exactly 3 times (hand trace:
  // s -> s/2 on the other facet -> s again -> straight up), on either side of the boundary.
  for (double i : {-1e-12, 0.0, 1e-12}) {
    const auto m = by_count(G_kaleidoscopic(i, deg(60), FacetSide::left));
    const auto it = m.find(3);
    ASSERT_NE(it, m.end()) << "theta_i=" << i << dump(m);
    EXPECT_NEAR(it->second, 1.0, 1e-9) << "theta_i=" << i << dump(m);
  }
}

}  // namespace
}  // namespace vgroove::analytic
