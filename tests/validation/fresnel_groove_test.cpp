// Fresnel along traced paths against the kaleidoscopic model's product (Lee et al. 2018,
// Eq. (11); Eq. (23)'s R): sim::trace with sim::FresnelEnergyObserver (the local angle taken from
// the traced direction and the real facet's normal at every bounce) against
// analytic::fresnel_energy (the local angles in closed form from the unfolded fan), ray by ray.
//
// Both sides call the same optics/ reflectance, so this test checks the angles, not F (F has its
// own tests, tests/optics/fresnel_test.cpp). The angles depend only on the bounce index, so every
// ray with n reflections from one facet must keep the model's energy for n.
//
// Tolerances. The local cosines themselves agree to cos_tolerance(j) = 1e-14 + (j - 1) 4.4e-16 at
// bounce j (asserted below, bounce by bounce). The 1e-14 is the tracer's rounding with room (the
// largest difference measured in symmetric grooves was 5.2e-15, theta_v = 0.1 deg after 1125
// bounces); the second term is the model's: a nonsymmetric aperture pi + theta_l - theta_r is
// computed with two roundings of at most 2.2e-16 rad each, and the fan's line j sits (j - 1)
// apertures on (1.4e-14 was measured at theta_l = -89, theta_r = 89.5 deg, bounce 117).
// For reflectances smooth in cos theta (conductors with kappa > 0, a dielectric seen from the
// less dense side, Schlick) |d ln F / d cos| stays moderate and the energies agree to 1e-12
// relative, the figure asserted. A dielectric seen from the denser side (eta < 1) has a
// square-root corner at its critical angle, where d F / d cos is unbounded: a cosine off by 1e-15
// there moves F by ~1e-8 x sqrt-scale, and 1e-12 fails (1.35e-12 was measured at theta_v = 1 deg
// after 168 bounces). For it the tolerance is propagated from cos_tolerance: 1e-12 plus, per bounce,
// the largest change of ln F over cos +- cos_tolerance(j) (F is monotone in cos
// there, so the ends bound it: checked below on a grid).
#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/kaleidoscope_fresnel.h"
#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/common/angles.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/effects.h"
#include "vgroove/sim/groove.h"
#include "vgroove/sim/tracer.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace vgroove {
namespace {

constexpr double kRelTol = 1e-12;
double cos_tolerance(int j) { return 1e-14 + (j - 1) * 4.4e-16; }
constexpr long kRays = 400;  // stratified across the opening

analytic::FacetSide to_analytic(sim::Side s) {
  return s == sim::Side::left ? analytic::FacetSide::left : analytic::FacetSide::right;
}

// What one (groove, theta_i) case found.
struct Outcome {
  long escaped = 0, compared = 0, vertex_hits = 0, mismatches = 0;
  double max_rel = 0.0;     // largest relative difference
  double max_excess = 0.0;  // largest relative difference / its tolerance (<= 1 passes)
  std::string worst;        // the ray of max_excess, described
  // Traced energy summed per (first facet, k), and the rays in each bin.
  std::map<std::pair<int, int>, std::pair<double, long>> per_bin;
};

// Traces kRays stratified rays across the opening with the observer, and compares each escaped
// ray's throughput with `model(n, first)`, to the relative tolerance `tolerance(n, first)`.
template <class Reflectance, class Model, class Tolerance>
Outcome run(const sim::Groove& g, double theta_i, const Reflectance& F, const Model& model,
            const Tolerance& tolerance) {
  Outcome o;
  const sim::Interval open = sim::opening(g);
  const sim::Vec2 dir = sim::beam_direction(theta_i);
  sim::Rng unused(0, 0, 0);
  sim::FresnelEnergyObserver<Reflectance> obs{F};
  for (long j = 0; j < kRays; ++j) {
    obs.reset();
    const double x = sim::sample_position(sim::Sampling::stratified, open, j, kRays, unused);
    const sim::TraceResult r = sim::trace(g, sim::beam_ray(g, dir, x), {}, obs);
    if (r.how == sim::Termination::vertex_hit) ++o.vertex_hits;
    if (r.how != sim::Termination::escaped) continue;
    ++o.escaped;
    auto& bin = o.per_bin[{static_cast<int>(r.first), r.bounces}];
    bin.first += obs.throughput;
    ++bin.second;
    const double expected = model(r.bounces, to_analytic(r.first));
    const double rel = std::abs(obs.throughput - expected) / expected;
    const double tol = tolerance(r.bounces, to_analytic(r.first));
    ++o.compared;
    if (!(rel <= tol)) ++o.mismatches;
    o.max_rel = std::max(o.max_rel, rel);
    if (!(rel / tol <= o.max_excess)) {
      o.max_excess = rel / tol;
      std::ostringstream os;
      os.precision(17);
      os << "ray " << j << ": first=" << sim::side_name(r.first) << " n=" << r.bounces << " traced=" << obs.throughput
         << " model=" << expected << " rel=" << rel << " tol=" << tol;
      o.worst = os.str();
    }
  }
  return o;
}
template <class Reflectance, class Model>
Outcome run(const sim::Groove& g, double theta_i, const Reflectance& F, const Model& model) {
  return run(g, theta_i, F, model, [](int, analytic::FacetSide) { return kRelTol; });
}

std::string sci(double v) {
  std::ostringstream os;
  os.precision(3);
  os << std::scientific << v;
  return os.str();
}

// The propagated tolerance for a reflectance with a corner (see the top of the file).
template <class Reflectance, class CosOfBounce>
double propagated_tolerance(const Reflectance& F, int n, const CosOfBounce& cos_of_bounce) {
  double t = kRelTol;
  for (int j = 1; j <= n; ++j) {
    const double c = cos_of_bounce(j), f = F(c);
    t += std::max(std::abs(std::log(F(std::min(1.0, c + cos_tolerance(j))) / f)),
                  std::abs(std::log(F(std::max(0.0, c - cos_tolerance(j))) / f)));
  }
  return t;
}

// Reflectances with their names, for readable failures.
struct Named {
  std::string name;
  // One of these is used, by kind.
  enum Kind { conductor, dielectric, schlick } kind;
  double a, b;
  bool corner = false;  // a critical angle: the propagated tolerance, not 1e-12
};
const std::vector<Named> kReflectances = {
    {"conductor_0.2+3i", Named::conductor, 0.2, 3.0},             // chosen values, a bright metal-like mirror
    {"conductor_1.5+0.5i", Named::conductor, 1.5, 0.5},           // a dark absorber: F ~ 0.1 near normal
    {"dielectric_1.5", Named::dielectric, 1.5, 0.0},              // glass-like, F = 0.04 at normal incidence
    {"dielectric_1/1.5", Named::dielectric, 1 / 1.5, 0.0, true},  // from inside: total reflection past 41.8 deg
    {"schlick_0.04", Named::schlick, 0.04, 0.0},
};

// gtest prints a parameter with this (instead of its bytes).
void PrintTo(const Named& n, std::ostream* os) { *os << n.name; }

// Calls f with the functor that `n` names.
template <class Fn>
void with_reflectance(const Named& n, Fn&& f) {
  switch (n.kind) {
    case Named::conductor:
      f(sim::ConductorReflectance{n.a, n.b});
      break;
    case Named::dielectric:
      f(sim::DielectricReflectance{n.a});
      break;
    case Named::schlick:
      f(sim::SchlickReflectance{n.a});
      break;
  }
}

void expect_matches(const Outcome& o, const std::string& where) {
  EXPECT_EQ(o.vertex_hits, 0) << where;
  EXPECT_GT(o.compared, 0) << where;
  EXPECT_EQ(o.mismatches, 0) << where << "\n  worst " << o.worst;
  EXPECT_LE(o.max_excess, 1.0) << where << "\n  worst " << o.worst;
}

// ---- Hand-derived cases -----------------------------------------------------------------------

TEST(FresnelGroove, NinetyDegreeGrooveAtNormalIncidenceBouncesTwiceAtFortyFive) {
  // Both facets at 45 deg to the light: bounce 1 at 45 deg, then a horizontal ray meets the
  // other facet at 45 deg too. The model: cos theta_j = |sin((j - 1/2) 90 deg)| = 1/sqrt2 for
  // j = 1, 2. With the dielectric eta = 1.5, F(45 deg) = (R_s + R_s^2)/2 with
  // R_s = (9 - 2 sqrt14)/(9 + 2 sqrt14) (tests/optics/fresnel_test.cpp), so E = F^2.
  const double Rs = (9 - 2 * std::sqrt(14.0)) / (9 + 2 * std::sqrt(14.0));
  const double F45 = 0.5 * (Rs + Rs * Rs);
  const sim::DielectricReflectance F{1.5};
  for (int j = 1; j <= 2; ++j)
    for (auto side : {analytic::FacetSide::left, analytic::FacetSide::right})
      EXPECT_NEAR(analytic::local_cos_theta(0.0, 90 * kRadPerDeg, j, side), std::sqrt(0.5), 1e-15) << "j=" << j;
  EXPECT_NEAR(analytic::fresnel_energy(0.0, 90 * kRadPerDeg, 2, analytic::FacetSide::left, F), F45 * F45, 1e-16);
  const Outcome o = run(sim::make_symmetric_groove(90 * kRadPerDeg), 0.0, F, [&](int n, analytic::FacetSide) {
    return analytic::fresnel_energy(0.0, 90 * kRadPerDeg, n, analytic::FacetSide::left, F);
  });
  expect_matches(o, "theta_v=90 theta_i=0");
  ASSERT_EQ(o.per_bin.size(), 2u);  // every ray: 2 bounces, from either facet
  for (const auto& [key, bin] : o.per_bin) {
    EXPECT_EQ(key.second, 2);
    EXPECT_NEAR(bin.first / bin.second, F45 * F45, 1e-15);
  }
}

TEST(FresnelGroove, SixtyDegreeGrooveAtNormalIncidenceHitsTheSecondFacetHeadOn) {
  // A 60 deg groove at normal incidence: 3 reflections. Bounce 1 at 60 deg (cos 1/2); the ray
  // then travels perpendicular to the other facet (it turned by 120 deg) and hits it head on
  // (cos 1), comes straight back and leaves after a third bounce at 60 deg. The model:
  // |sin(30)|, |sin(90)|, |sin(150)| = 1/2, 1, 1/2.
  const double expect_cos[3] = {0.5, 1.0, 0.5};
  for (int j = 1; j <= 3; ++j)
    EXPECT_NEAR(analytic::local_cos_theta(0.0, 60 * kRadPerDeg, j, analytic::FacetSide::left), expect_cos[j - 1],
                1e-15);
  const sim::ConductorReflectance F{0.2, 3.0};
  const double E = F(0.5) * F(1.0) * F(0.5);
  EXPECT_NEAR(analytic::fresnel_energy(0.0, 60 * kRadPerDeg, 3, analytic::FacetSide::right, F), E, 1e-15);
  const Outcome o = run(sim::make_symmetric_groove(60 * kRadPerDeg), 0.0, F, [&](int n, analytic::FacetSide s) {
    return analytic::fresnel_energy(0.0, 60 * kRadPerDeg, n, s, F);
  });
  expect_matches(o, "theta_v=60 theta_i=0");
  for (const auto& [key, bin] : o.per_bin) {
    EXPECT_EQ(key.second, 3);
    EXPECT_NEAR(bin.first / bin.second, E, 1e-15);
  }
}

TEST(FresnelGroove, UnitReflectanceKeepsEveryRayAtOne) {
  const sim::UnitReflectance F;
  for (double theta_v_deg : {1.0, 30.0, 150.0}) {
    const Outcome o = run(sim::make_symmetric_groove(theta_v_deg * kRadPerDeg), 20 * kRadPerDeg, F,
                          [](int, analytic::FacetSide) { return 1.0; });
    expect_matches(o, "theta_v=" + std::to_string(theta_v_deg));
    for (const auto& [key, bin] : o.per_bin) EXPECT_EQ(bin.first, static_cast<double>(bin.second));
  }
}

TEST(FresnelGroove, FlatGrooveIsOneMirrorReflection) {
  // theta_v = 180 deg: one reflection at the incidence angle itself, cos = |sin(90 - theta_i)|.
  for (double theta_i_deg : {-80.0, -30.0, 0.0, 45.0, 89.0})
    EXPECT_NEAR(analytic::local_cos_theta(theta_i_deg * kRadPerDeg, std::numbers::pi, 1, analytic::FacetSide::left),
                std::cos(theta_i_deg * kRadPerDeg), 1e-15)
        << "theta_i=" << theta_i_deg;
}

// ---- Grids: every traced ray against the model ------------------------------------------------

// Checks cos theta_j = |dir_in . normal| at every bounce against the closed form as the ray goes
// (no per-ray storage): the angles alone, with no F. The first call names the facet hit first.
template <class CosModel>
struct CosChecker {
  const CosModel& model;
  int j = 0;
  analytic::FacetSide first = analytic::FacetSide::left;
  double worst = 0.0;  // largest difference / its tolerance over the ray
  int worst_j = 0;
  void on_bounce(sim::Side side, const sim::Vec2& dir_in, const sim::Facet& f) {
    if (++j == 1) first = to_analytic(side);
    const double e = std::abs(std::abs(dir_in.dot(f.normal)) - model(j, first)) / cos_tolerance(j);
    if (e > worst) worst = e, worst_j = j;
  }
};

// Every bounce of every ray: the traced local cosine against the closed form, to cos_tolerance.
// 100 rays per case: the angles depend on the facet hit first and the bounce index only, not on
// where a ray enters, so a finer placement adds bounces already checked.
constexpr long kAngleRays = 100;
template <class CosModel>
void expect_cosines(const sim::Groove& g, double theta_i, const CosModel& model, const std::string& where) {
  const sim::Interval open = sim::opening(g);
  const sim::Vec2 dir = sim::beam_direction(theta_i);
  sim::Rng unused(0, 0, 0);
  double worst = 0.0;
  std::string worst_at;
  long bounces = 0;
  for (long j = 0; j < kAngleRays; ++j) {
    CosChecker<CosModel> check{model};
    const sim::TraceResult r = sim::trace(
        g, sim::beam_ray(g, dir, sim::sample_position(sim::Sampling::stratified, open, j, kAngleRays, unused)), {},
        check);
    if (r.how != sim::Termination::escaped) continue;
    ASSERT_EQ(check.j, r.bounces) << where;  // called once per reflection
    bounces += r.bounces;
    if (check.worst > worst) {
      worst = check.worst;
      worst_at = "ray " + std::to_string(j) + " first=" + sim::side_name(r.first) + " bounce " +
                 std::to_string(check.worst_j) + ": difference " + sci(worst * cos_tolerance(check.worst_j));
    }
  }
  EXPECT_GT(bounces, 0) << where;
  EXPECT_LE(worst, 1.0) << where << " worst at " << worst_at;
}

TEST(FresnelGroove, TracedLocalAnglesAreTheClosedFormSymmetric) {
  for (double theta_v_deg : {0.1, 1.0, 3.0, 10.0, 17.0, 30.0, 45.0, 60.0, 72.0, 90.0, 120.0, 150.0, 176.0, 180.0})
    for (double theta_i_deg = -88.5; theta_i_deg < 89.0; theta_i_deg += 3.5) {
      const double theta_v = theta_v_deg * kRadPerDeg, theta_i = theta_i_deg * kRadPerDeg;
      expect_cosines(
          sim::make_symmetric_groove(theta_v), theta_i,
          [&](int j, analytic::FacetSide s) { return analytic::local_cos_theta(theta_i, theta_v, j, s); },
          "theta_v=" + std::to_string(theta_v_deg) + " theta_i=" + std::to_string(theta_i_deg));
    }
}

TEST(FresnelGroove, TracedLocalAnglesAreTheClosedFormNonsymmetric) {
  for (double theta_l_deg : {-89.0, -60.0, -45.0, -20.0, -3.0, 0.0})
    for (double theta_r_deg : {0.0, 2.0, 15.0, 45.0, 70.0, 89.5})
      for (double theta_i_deg = -87.0; theta_i_deg < 89.0; theta_i_deg += 6.0) {
        if (theta_l_deg == 0.0 && theta_r_deg == 0.0) continue;  // flat: covered by theta_v = 180 above
        const double theta_l = theta_l_deg * kRadPerDeg, theta_r = theta_r_deg * kRadPerDeg,
                     theta_i = theta_i_deg * kRadPerDeg;
        expect_cosines(
            sim::make_nonsymmetric_groove(theta_l, theta_r), theta_i,
            [&](int j, analytic::FacetSide s) {
              return analytic::local_cos_theta_nonsymmetric(theta_i, theta_l, theta_r, j, s);
            },
            "theta_l=" + std::to_string(theta_l_deg) + " theta_r=" + std::to_string(theta_r_deg) +
                " theta_i=" + std::to_string(theta_i_deg));
      }
}

TEST(FresnelGroove, CornerReflectanceIsMonotoneInCos) {
  // propagated_tolerance bounds ln F over [c - d, c + d] by its ends: true when F is monotone.
  const sim::DielectricReflectance F{1 / 1.5};
  double prev = F(0.0);
  for (int i = 1; i <= 100000; ++i) {
    const double f = F(i / 100000.0);
    EXPECT_LE(f, prev) << "cos=" << i / 100000.0;
    prev = f;
  }
}

class FresnelGrooveSymmetric : public testing::TestWithParam<Named> {};

TEST_P(FresnelGrooveSymmetric, EveryRayKeepsTheModelsEnergy) {
  int cases = 0;
  double max_rel = 0.0;
  with_reflectance(GetParam(), [&](const auto& F) {
    for (double theta_v_deg : {1.0, 3.0, 10.0, 17.0, 30.0, 45.0, 60.0, 72.0, 90.0, 120.0, 150.0, 176.0, 180.0})
      for (double theta_i_deg = -88.5; theta_i_deg < 89.0; theta_i_deg += 7.5) {
        const double theta_v = theta_v_deg * kRadPerDeg, theta_i = theta_i_deg * kRadPerDeg;
        const auto tolerance = [&](int n, analytic::FacetSide s) {
          if (!GetParam().corner) return kRelTol;
          return propagated_tolerance(F, n, [&](int j) { return analytic::local_cos_theta(theta_i, theta_v, j, s); });
        };
        const Outcome o = run(
            sim::make_symmetric_groove(theta_v), theta_i, F,
            [&](int n, analytic::FacetSide s) { return analytic::fresnel_energy(theta_i, theta_v, n, s, F); },
            tolerance);
        std::ostringstream where;
        where << GetParam().name << " theta_v=" << theta_v_deg << " theta_i=" << theta_i_deg;
        expect_matches(o, where.str());
        max_rel = std::max(max_rel, o.max_rel);
        // Per (facet, k): the summed traced energy is the model's energy times the ray count.
        for (const auto& [key, bin] : o.per_bin) {
          const analytic::FacetSide s = to_analytic(static_cast<sim::Side>(key.first));
          const double model = analytic::fresnel_energy(theta_i, theta_v, key.second, s, F);
          EXPECT_NEAR(bin.first, model * bin.second, tolerance(key.second, s) * model * bin.second)
              << where.str() << " facet=" << key.first << " k=" << key.second;
        }
        ++cases;
      }
  });
  EXPECT_EQ(cases, 13 * 24);
  RecordProperty("max_rel_error", sci(max_rel));  // in --gtest_output=xml
}

class FresnelGrooveNonsymmetric : public testing::TestWithParam<Named> {};

TEST_P(FresnelGrooveNonsymmetric, EveryRayKeepsTheModelsEnergy) {
  int cases = 0;
  double max_rel = 0.0;
  with_reflectance(GetParam(), [&](const auto& F) {
    for (double theta_l_deg : {-88.0, -60.0, -45.0, -20.0, -3.0})
      for (double theta_r_deg : {2.0, 15.0, 45.0, 70.0, 89.0})
        for (double theta_i_deg = -87.0; theta_i_deg < 89.0; theta_i_deg += 12.0) {
          const double theta_l = theta_l_deg * kRadPerDeg, theta_r = theta_r_deg * kRadPerDeg,
                       theta_i = theta_i_deg * kRadPerDeg;
          const auto tolerance = [&](int n, analytic::FacetSide s) {
            if (!GetParam().corner) return kRelTol;
            return propagated_tolerance(
                F, n, [&](int j) { return analytic::local_cos_theta_nonsymmetric(theta_i, theta_l, theta_r, j, s); });
          };
          const Outcome o = run(
              sim::make_nonsymmetric_groove(theta_l, theta_r), theta_i, F,
              [&](int n, analytic::FacetSide s) {
                return analytic::fresnel_energy_nonsymmetric(theta_i, theta_l, theta_r, n, s, F);
              },
              tolerance);
          std::ostringstream where;
          where << GetParam().name << " theta_l=" << theta_l_deg << " theta_r=" << theta_r_deg
                << " theta_i=" << theta_i_deg;
          expect_matches(o, where.str());
          max_rel = std::max(max_rel, o.max_rel);
          ++cases;
        }
  });
  EXPECT_EQ(cases, 5 * 5 * 15);
  RecordProperty("max_rel_error", sci(max_rel));
}

TEST(FresnelGroove, SymmetricAndNonsymmetricFormsAgree) {
  // theta_l = theta_v/2 - pi/2 = -theta_r turns the nonsymmetric fan into the symmetric one.
  for (double theta_v_deg : {1.0, 30.0, 90.0, 179.0})
    for (double theta_i_deg : {-60.0, 0.0, 25.0})
      for (int j = 1; j <= 8; ++j)
        for (auto side : {analytic::FacetSide::left, analytic::FacetSide::right}) {
          const double tv = theta_v_deg * kRadPerDeg, ti = theta_i_deg * kRadPerDeg;
          EXPECT_NEAR(analytic::local_cos_theta(ti, tv, j, side),
                      analytic::local_cos_theta_nonsymmetric(ti, 0.5 * tv - 0.5 * std::numbers::pi,
                                                             0.5 * std::numbers::pi - 0.5 * tv, j, side),
                      1e-14)
              << "theta_v=" << theta_v_deg << " theta_i=" << theta_i_deg << " j=" << j;
        }
}

std::string reflectance_name(const testing::TestParamInfo<Named>& info) {
  std::string s = info.param.name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Reflectances, FresnelGrooveSymmetric, testing::ValuesIn(kReflectances), reflectance_name);
INSTANTIATE_TEST_SUITE_P(Reflectances, FresnelGrooveNonsymmetric, testing::ValuesIn(kReflectances), reflectance_name);

}  // namespace
}  // namespace vgroove
