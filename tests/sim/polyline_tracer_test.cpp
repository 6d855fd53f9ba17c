// Tests of sim/polyline.h and sim/polyline_tracer.h: the exact tracer over periodic polyline
// height profiles.
//
// - Against an independent brute-force tracer (every segment copy of five periods intersected
//   with the textbook formulas, the nearest positive t taken): the same segment, parameter and
//   direction at every step, so the skipping pyramid, the watertight side test and the period
//   wrap change nothing.
// - The reflection law at every bounce (observer), energy with F = 1 (every ray leaves, none
//   lost), hand cases (a flat profile is a mirror; a 90 deg corner retroreflects), rays exactly
//   through vertices, grazing light to 89.99 deg, near-flat and very rough profiles, the bounce
//   limit, a ray descending by 1e-9 per unit length (period skipping), a level ray.
// - A V-groove microsurface (sim/microsurface.h) expressed as a polyline gives, ray for ray, the
//   bounce count, first facet and exit direction of the groove tracer (sim/tracer.h).
#include "vgroove/sim/polyline_tracer.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

// A periodic profile of n segments on integer x with heights drawn uniformly in [-h, h] (a
// rough zigzag; h large gives steep segments).
Polyline random_zigzag(int n, double h, std::uint64_t seed) {
  std::vector<double> x(static_cast<std::size_t>(n) + 1), y(static_cast<std::size_t>(n) + 1);
  Rng rng(seed, 1, 2);
  for (int v = 0; v <= n; ++v) {
    x[static_cast<std::size_t>(v)] = v;
    y[static_cast<std::size_t>(v)] = v < n ? h * (2.0 * rng.uniform() - 1.0) : y[0];
  }
  return make_polyline(std::move(x), std::move(y));
}

// ---------------------------------------------------------------------------------------------
// The brute-force reference: nearest crossing over the segment copies of periods -2..2.
struct RefHit {
  int segment;
  double s;
};
std::optional<RefHit> brute_force_hit(const Polyline& p, const Vec2& o, const Vec2& d, int exclude) {
  double best_t = std::numeric_limits<double>::infinity();
  std::optional<RefHit> best;
  for (int m = -2; m <= 2; ++m)
    for (int j = 0; j < p.segments(); ++j) {
      if (m == 0 && j == exclude) continue;
      const Vec2 a = p.vertex(j) + Vec2(m * p.period, 0.0);
      const Vec2 e = p.vertex(j + 1) - p.vertex(j);
      // o + t d = a + s e:  t = cross(a - o, e) / cross(d, e),  s = cross(a - o, d) / cross(d, e).
      const double den = cross(d, e);
      if (den == 0.0) continue;
      const double t = cross(a - o, e) / den, s = cross(a - o, d) / den;
      if (t > 0.0 && s >= 0.0 && s <= 1.0 && t < best_t) best_t = t, best = RefHit{j, s};
    }
  return best;
}

// Traces from the top at x and checks every step against the brute force; returns the steps checked.
int check_against_brute_force(const Polyline& p, double x, const Vec2& dir, const std::string& where) {
  Vec2 o(x, p.y_max), d = dir;
  int exclude = -1;
  PolylineHit h = first_hit_from_top(p, x, d);
  for (int step = 0; step < 200; ++step) {
    const std::optional<RefHit> ref = brute_force_hit(p, o, d, exclude);
    if (!ref) {
      // Nothing within two periods: the tracer must not hit either (a ray that goes on further
      // is not checked).
      if (h.kind == PolylineHit::Kind::escaped) {
        EXPECT_GT(d.y(), 0.0) << where << " step " << step;
      }
      return step;
    }
    // Rays within 1e-9 of a vertex may be decided either way by rounding: not compared.
    if (ref->s < 1e-9 || ref->s > 1.0 - 1e-9) return step;
    EXPECT_EQ(h.kind, PolylineHit::Kind::segment) << where << " step " << step;
    if (h.kind != PolylineHit::Kind::segment) return step;
    EXPECT_EQ(h.segment, ref->segment) << where << " step " << step;
    EXPECT_NEAR(h.s, ref->s, 1e-9) << where << " step " << step;
    if (h.segment != ref->segment) return step;
    const Vec2& n = p.normal[static_cast<std::size_t>(h.segment)];
    d = d - 2.0 * d.dot(n) * n;
    o = p.point(h.segment, h.s);
    exclude = h.segment;
    h = first_hit_from(p, h.segment, h.s, d);
    if (h.kind == PolylineHit::Kind::escaped) {
      EXPECT_FALSE(brute_force_hit(p, o, d, exclude)) << where << " step " << step;
      return step + 1;
    }
  }
  return 200;
}

TEST(PolylineTracer, EveryStepIsTheBruteForceHit) {
  // Rough zigzags (slopes up to ~10) and gentle ones, long enough for the pyramid's three levels.
  int steps = 0;
  for (double h : {0.05, 1.0, 5.0}) {
    const Polyline p = random_zigzag(1200, h, 7);
    ASSERT_EQ(p.levels.size(), 3u);
    Rng rng(3, 4, static_cast<std::uint64_t>(h * 100));
    for (int ray = 0; ray < 300; ++ray) {
      const double theta_i = deg(-89.0 + 178.0 * rng.uniform());
      const double x = p.period * rng.uniform();
      std::ostringstream where;
      where.precision(17);
      where << "h=" << h << " theta_i=" << theta_i << " x=" << x;
      steps += check_against_brute_force(p, x, beam_direction(theta_i), where.str());
    }
  }
  EXPECT_GT(steps, 1000);  // the comparison did run over multiple scattering
}

// ---------------------------------------------------------------------------------------------
// Hand cases.
TEST(PolylineTracer, FlatProfileIsAMirror) {
  const Polyline p = make_polyline({0, 1, 2, 3, 4}, {0, 0, 0, 0, 0});
  for (double theta_deg : {-89.99, -60.0, -12.5, 0.0, 0.3, 45.0, 89.99})
    for (double x : {0.1, 1.7, 3.99}) {
      const PolylineTraceResult r = trace_polyline(p, x, beam_direction(deg(theta_deg)));
      ASSERT_EQ(r.how, Termination::escaped) << theta_deg << " " << x;
      EXPECT_EQ(r.bounces, 1);
      EXPECT_NEAR(angle_from_normal(r.exit_dir), -deg(theta_deg), 1e-15) << theta_deg;
    }
}

TEST(PolylineTracer, RightAngleCornersRetroreflectAtNormalIncidence) {
  // Grooves of 90 deg (slopes -1 and +1): a vertical ray turns horizontal, then straight back up.
  const Polyline p = make_polyline({0, 1, 2, 3, 4}, {0, -1, 0, -1, 0});
  for (double x : {0.25, 0.5, 1.3, 2.9, 3.75}) {
    const PolylineTraceResult r = trace_polyline(p, x, beam_direction(0.0));
    ASSERT_EQ(r.how, Termination::escaped) << x;
    EXPECT_EQ(r.bounces, 2) << x;
    EXPECT_EQ(r.first_segment, static_cast<int>(x)) << x;
    EXPECT_LT((r.exit_dir - Vec2(0.0, 1.0)).norm(), 1e-15) << x;
  }
}

TEST(PolylineTracer, ReflectionLawAndEnergyAtEveryBounce) {
  // With F = 1 every ray leaves (albedo 1); each reflection keeps the angle to the normal and
  // the unit length, and the ray stays above the segment it leaves.
  struct Check {
    const Polyline* p;
    Vec2 last_out = Vec2::Zero();
    bool have_last = false;
    double worst = 0.0;
    int calls = 0;
    void on_bounce(int seg, double s, const Vec2& d) {
      const Vec2& n = p->normal[static_cast<std::size_t>(seg)];
      if (have_last) worst = std::max(worst, (d - last_out).norm());  // the ray arrives as it left
      EXPECT_GT(s, 0.0);
      EXPECT_LT(s, 1.0);
      EXPECT_LT(d.dot(n), 0.0);  // arrives on the front face
      const Vec2 out = d - 2.0 * d.dot(n) * n;
      worst = std::max(worst, std::abs(out.norm() - 1.0));
      worst = std::max(worst, std::abs(out.dot(n) + d.dot(n)));        // angle of reflection
      worst = std::max(worst, std::abs(cross(n, out) - cross(n, d)));  // the same tangent component
      last_out = out;
      have_last = true;
      ++calls;
    }
  };
  const Polyline p = random_zigzag(2000, 3.0, 11);
  Rng rng(5, 6, 7);
  long escaped = 0, bounces = 0, n = 0;
  for (int ray = 0; ray < 4000; ++ray, ++n) {
    Check c{&p};
    const double theta_i = deg(-89.99 + 179.98 * rng.uniform());
    const PolylineTraceResult r = trace_polyline(p, p.period * rng.uniform(), beam_direction(theta_i), {}, c);
    EXPECT_EQ(c.calls, r.bounces);
    EXPECT_LT(c.worst, 1e-14) << "theta_i=" << theta_i;
    if (r.how == Termination::escaped) {
      ++escaped, bounces += r.bounces;
      EXPECT_GT(r.exit_dir.y(), 0.0);
      EXPECT_NEAR(r.exit_dir.norm(), 1.0, 1e-13);
      if (c.have_last) {
        EXPECT_EQ(r.exit_dir, c.last_out);
      }
    }
  }
  EXPECT_EQ(escaped, n);
  EXPECT_GT(bounces, 2 * n);  // a rough profile: multiple scattering on average
}

// ---------------------------------------------------------------------------------------------
// Vertices, grazing light, extreme roughness, limits.
TEST(PolylineTracer, RaysExactlyThroughVerticesAreVertexHits) {
  // Integer vertices: a vertical ray at a vertex's x and 45 deg rays aimed along an exact
  // diagonal meet the vertex exactly.
  const Polyline p = make_polyline({0, 1, 2, 3, 4, 5, 6, 7, 8}, {0, -2, -1, -3, 0, -1, -1, -4, 0});
  for (int v = 1; v < 8; ++v) {
    const PolylineTraceResult r = trace_polyline(p, v, beam_direction(0.0));
    EXPECT_EQ(r.how, Termination::vertex_hit) << "v=" << v << " " << termination_name(r.how);
  }
  // 45 deg from the upper left: the ray through (x_v, y_v) crosses the top line y = 0 at
  // x_v + y_v; for vertices 2 and 6 the profile lies below that line until the vertex.
  for (int v : {2, 6}) {
    const double x = p.x[static_cast<std::size_t>(v)] + p.y[static_cast<std::size_t>(v)];
    const PolylineTraceResult r = trace_polyline(p, x < 0 ? x + p.period : x, Vec2(1.0, -1.0) / std::sqrt(2.0));
    EXPECT_EQ(r.how, Termination::vertex_hit) << "v=" << v << " " << termination_name(r.how);
  }
  // A ray leaving a segment along an exact diagonal through a later vertex.
  {
    const Polyline q = make_polyline({0, 2, 4, 6}, {0, -2, 0, 0});
    // From the top at x = 0.5 straight down onto segment 0 (slope -1): reflected to travel
    // horizontally right at y = -0.5 ... meets segment 1 (slope +1) at x = 3.5: no vertex.
    const PolylineTraceResult r = trace_polyline(q, 0.5, beam_direction(0.0));
    ASSERT_EQ(r.how, Termination::escaped);
    EXPECT_EQ(r.bounces, 2);
    // From x = 2 - 0 (the apex column) straight down: the apex itself.
    EXPECT_EQ(trace_polyline(q, 2.0, beam_direction(0.0)).how, Termination::vertex_hit);
  }
}

TEST(PolylineTracer, GrazingLightNearFlatAndVeryRoughProfilesLoseNoRay) {
  struct Case {
    double h;
    const char* name;
  };
  for (const Case c : {Case{1e-9, "near-flat"}, Case{1e-3, "smooth"}, Case{1.0, "rough"}, Case{1e3, "very rough"}}) {
    const Polyline p = random_zigzag(3000, c.h, 13);
    Rng rng(8, 9, 10);
    for (double theta_deg : {-89.99, -89.9, -80.0, 0.0, 45.0, 89.9, 89.99}) {
      long escaped = 0, upward = 0;
      constexpr int kRays = 300;
      for (int ray = 0; ray < kRays; ++ray) {
        const PolylineTraceResult r = trace_polyline(p, p.period * rng.uniform(), beam_direction(deg(theta_deg)));
        if (r.how == Termination::escaped) {
          ++escaped;
          upward += r.exit_dir.y() > 0.0;
          EXPECT_TRUE(std::isfinite(r.exit_dir.x()) && std::isfinite(r.exit_dir.y()));
        }
      }
      EXPECT_EQ(escaped, kRays) << c.name << " theta_i=" << theta_deg;
      EXPECT_EQ(upward, kRays) << c.name << " theta_i=" << theta_deg;
    }
  }
}

TEST(PolylineTracer, NearFlatProfileReflectsOnceAroundTheMirrorDirection) {
  // Slopes below 2e-9: one reflection, within 4e-9 rad of -theta_i (twice the largest slope).
  const Polyline p = random_zigzag(1000, 1e-9, 17);
  Rng rng(1, 2, 3);
  for (double theta_deg : {-89.99, -30.0, 0.0, 60.0, 89.99}) {
    for (int ray = 0; ray < 200; ++ray) {
      const PolylineTraceResult r = trace_polyline(p, p.period * rng.uniform(), beam_direction(deg(theta_deg)));
      ASSERT_EQ(r.how, Termination::escaped);
      EXPECT_EQ(r.bounces, 1) << theta_deg;
      EXPECT_NEAR(angle_from_normal(r.exit_dir), -deg(theta_deg), 4.1e-9) << theta_deg;
    }
  }
}

TEST(PolylineTracer, BounceLimitStopsAndIsReported) {
  // A 1 deg V-groove needs about 180 reflections at normal incidence.
  const Polyline p = vgroove_polyline({deg(89.5)});
  for (double x : {0.3, 0.7, 1.2, 1.9}) {
    const PolylineTraceResult r = trace_polyline(p, x, beam_direction(0.0), TraceOptions{5});
    EXPECT_EQ(r.how, Termination::bounce_limit) << x;
    EXPECT_EQ(r.bounces, 5);
    const PolylineTraceResult full = trace_polyline(p, x, beam_direction(0.0));
    EXPECT_EQ(full.how, Termination::escaped) << x;
    EXPECT_GT(full.bounces, 170);
    EXPECT_LE(full.bounces, 180);
  }
}

TEST(PolylineTracer, NearlyLevelRaysMeetTheNextPeakOrLeave) {
  // Period 4, the highest vertex (2, 0.5) between segments 1 (rising, slope 1.5) and 2 (falling).
  const Polyline p = make_polyline({0, 1, 2, 3, 4}, {0, -1, 0.5, -1, 0});
  // Leaving segment 2 at s = 0.1, (2.1, 0.35), descending by 1e-9 per unit: it passes the
  // valleys and meets the next copy of segment 1, y = -1 + 1.5 u at x = 5 + u, where
  // 0.35 - 1e-9 (u + 2.9) = -1 + 1.5 u.
  const double eps = 1e-9;
  const PolylineHit down = first_hit_from(p, 2, 0.1, Vec2(1.0, -eps).normalized());
  ASSERT_EQ(down.kind, PolylineHit::Kind::segment);
  EXPECT_EQ(down.segment, 1);
  EXPECT_NEAR(down.s, (1.35 - 2.9 * eps) / (1.5 + eps), 1e-14);
  // Level from 1.5 x 2^-30 below the peak: the next copy of segment 1 at the same height.
  const double s0 = 0x1.0p-30;
  const PolylineHit level = first_hit_from(p, 2, s0, Vec2(1.0, 0.0));
  ASSERT_EQ(level.kind, PolylineHit::Kind::segment);
  EXPECT_EQ(level.segment, 1);
  EXPECT_NEAR(level.s, 1.0 - s0, 1e-15);
  // Rising by 1e-9 per unit from there: 4 units on it is 2.5e-9 above the peak's copy, and leaves.
  EXPECT_EQ(first_hit_from(p, 2, s0, Vec2(1.0, 1e-9).normalized()).kind, PolylineHit::Kind::escaped);
  // The same to the left, by the mirror: from segment 1 near the peak.
  EXPECT_EQ(first_hit_from(p, 1, 1.0 - s0, Vec2(-1.0, 1e-9).normalized()).kind, PolylineHit::Kind::escaped);
  const PolylineHit left = first_hit_from(p, 1, 1.0 - s0, Vec2(-1.0, 0.0));
  ASSERT_EQ(left.kind, PolylineHit::Kind::segment);
  EXPECT_EQ(left.segment, 2);
  EXPECT_NEAR(left.s, s0, 1e-15);
  // From the top line at 90 - 1e-7 deg: it descends 1.7e-9 per unit and meets segment 1 just
  // below the peak, within one period.
  const PolylineHit top = first_hit_from_top(p, 0.5, beam_direction(deg(90.0 - 1e-7)));
  ASSERT_EQ(top.kind, PolylineHit::Kind::segment);
  EXPECT_EQ(top.segment, 1);
  EXPECT_GT(top.s, 1.0 - 1e-8);
}

// ---------------------------------------------------------------------------------------------
// V-grooves: the polyline tracer against the groove tracer, ray for ray.
TEST(PolylineTracer, VGrooveSurfaceGivesTheGrooveTracersRays) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.1, 0.5, 1.0}) {
      MicrosurfaceOptions mo;
      mo.ndf = ndf;
      mo.alpha = alpha;
      mo.grooves = 1000;
      mo.seed = 21;
      const Microsurface m = make_microsurface(mo);
      const Polyline p = vgroove_polyline(m.theta_m);
      int multiple = 0;
      for (double theta_deg : {-89.99, -60.0, -20.0, 0.0, 35.0, 80.0}) {
        const Vec2 dir = beam_direction(deg(theta_deg));
        Rng rng(31, 32, static_cast<std::uint64_t>(theta_deg + 100));
        int compared = 0;
        for (int ray = 0; ray < 2000; ++ray) {
          const double x = uniform_open(rng) * mo.grooves;
          const int g = std::min(mo.grooves - 1, static_cast<int>(x));
          const double f = x - g;
          const Groove& groove = m.grooves[static_cast<std::size_t>(g)];
          const double xl = groove.rim_x(Side::left), xr = groove.rim_x(Side::right);
          const TraceResult a = trace(groove, beam_ray(groove, dir, xl + f * (xr - xl)));
          const PolylineTraceResult b = trace_polyline(p, 2.0 * x, dir);
          std::ostringstream where;
          where << ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << theta_deg << " ray " << ray;
          ASSERT_EQ(a.how, Termination::escaped) << where.str();
          ASSERT_EQ(b.how, Termination::escaped) << where.str() << " " << termination_name(b.how);
          ASSERT_EQ(a.bounces, b.bounces) << where.str();
          EXPECT_EQ(b.first_segment, 2 * g + (a.first == Side::left ? 0 : 1)) << where.str();
          EXPECT_LT((a.exit_dir - b.exit_dir).norm(), 1e-12 * a.bounces) << where.str();
          ++compared;
          multiple += a.bounces > 1;
        }
        EXPECT_EQ(compared, 2000);
      }
      if (alpha >= 0.5) {
        EXPECT_GT(multiple, 0) << ndf_name(ndf) << " alpha=" << alpha;
      }
    }
}

TEST(PolylineTracer, VGroovePolylineGeometry) {
  const Polyline p = vgroove_polyline({deg(30), deg(0), deg(60)});
  ASSERT_EQ(p.segments(), 6);
  EXPECT_EQ(p.period, 6.0);
  EXPECT_EQ(p.y_max, 0.0);
  EXPECT_NEAR(p.normal_angle(0), -deg(30), 1e-15);
  EXPECT_NEAR(p.normal_angle(1), deg(30), 1e-15);
  EXPECT_EQ(p.normal_angle(2), 0.0);
  EXPECT_NEAR(p.normal_angle(5), deg(60), 1e-15);
  EXPECT_NEAR(p.length(4), 2.0, 1e-15);  // 1 / cos 60
}

}  // namespace
}  // namespace vgroove::sim
