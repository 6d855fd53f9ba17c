// Tests of sim/dielectric_polyline.h: polyline profiles as a dielectric interface. Conservation per
// ray, a flat profile against Fresnel and Snell by hand, eta = 1, the conductor limit against
// trace_polyline bit for bit, grazing light, rays meeting the profile from below (by hand on a
// ridge, and counted on a rough profile), split against random branching, bad input.
//
// Conventions (as tests/sim/dielectric_groove_test.cpp): light from above at theta_i travels along
// (sin theta_i, -cos theta_i), light from below at theta_i along (-sin theta_i, cos theta_i);
// sim::exit_angle measures from the normal of the exit side.
#include "vgroove/sim/dielectric_polyline.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/polyline_tracer.h"
#include "vgroove/sim/random_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }
Vec2 from_above(double theta_i) { return beam_direction(theta_i); }
Vec2 from_below(double theta_i) { return direction_at(theta_i); }
Vec2 light_dir(double theta_i, Medium from) {
  return from == Medium::above ? from_above(theta_i) : from_below(theta_i);
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

Polyline rough(NdfKind ndf, double alpha, int segments, std::uint64_t seed) {
  RandomProfileOptions o;
  o.ndf = ndf, o.alpha = alpha, o.segments = segments, o.samples_per_length = 16, o.seed = seed;
  return make_random_profile(o);
}

// The x of ray j of n, stratified over one period (sim/profile_tally.h's landing_x rule), offset
// within its stratum by an irrational fraction so that no x is a vertex's (multiples of 1/16).
double x_of(const Polyline& p, long j, long n) {
  const double x = p.x.front() + (static_cast<double>(j) + 0.3819660112501051) / static_cast<double>(n) * p.period;
  return x < p.x.back() ? x : std::nextafter(p.x.back(), p.x.front());
}

// Fresnel of a flat interface by hand (Born & Wolf 1.5.(21a)), unpolarized, independent of optics/.
double hand_fresnel(double cos_i, double eta) {
  const double si = std::sqrt(1.0 - cos_i * cos_i), st = si / eta;
  if (st >= 1.0) return 1.0;
  const double ct = std::sqrt(1.0 - st * st);
  const double rs = (cos_i - eta * ct) / (cos_i + eta * ct), rp = (eta * cos_i - ct) / (eta * cos_i + ct);
  return 0.5 * (rs * rs + rp * rp);
}

TEST(DielectricPolyline, EnergyIsConservedPerRay) {
  const Polyline p = rough(NdfKind::ggx, 0.8, 4096, 3);
  for (Branching br : {Branching::random, Branching::split}) {
    DielectricOptions opt;
    opt.eta = 1.5, opt.branching = br, opt.max_interactions = 200;
    const DielectricPolylineTracer tr(p, opt);
    DielectricResult out;
    double worst = 0.0;
    long from_below_exits = 0;
    for (Medium from : {Medium::above, Medium::below})
      for (double th : {0.0, 45.0, 75.0}) {
        for (long j = 0; j < 1000; ++j) {
          Rng rng(7, static_cast<std::uint64_t>(th), static_cast<std::uint64_t>(j));
          tr.trace(x_of(p, j, 1000), light_dir(deg(th), from), from, rng, out);
          double sum = 0.0;
          for (const DielectricExit& e : out.exits) sum += e.weight;
          if (br == Branching::random) {
            // One path, weight 1, in exactly one bucket.
            ASSERT_EQ(out.total(), 1.0) << th << " " << j;
            ASSERT_EQ(out.exits.size() + (out.bounce_limit + out.vertex + out.cut == 1.0 ? 1u : 0u), 1u);
          }
          worst = std::max(worst, std::abs(out.total() - 1.0));
          ASSERT_NEAR(sum, out.left[0] + out.left[1], 1e-15);
          from_below_exits += from == Medium::below ? static_cast<long>(out.exits.size()) : 0;
        }
      }
    EXPECT_LE(worst, 64 * std::numeric_limits<double>::epsilon());
    EXPECT_GT(from_below_exits, 0);
  }
}

TEST(DielectricPolyline, AFlatProfileIsFresnelAndSnell) {
  const Polyline p = make_polyline({0.0, 1.0, 2.0, 3.0}, {0.0, 0.0, 0.0, 0.0});
  for (double eta : {1.5, 1.0 / 1.5, 2.4})
    for (Medium from : {Medium::above, Medium::below})
      for (double th : {0.0, 20.0, 40.0, 41.0, 42.0, 60.0, 85.0}) {
        DielectricOptions opt;
        opt.eta = eta, opt.branching = Branching::split, opt.min_weight = 0.0;
        const DielectricPolylineTracer tr(p, opt);
        DielectricResult out;
        Rng rng(1, 2, 3);
        tr.trace(1.375, light_dir(deg(th), from), from, rng, out);
        const double eta_rel = from == Medium::above ? eta : 1.0 / eta;
        const double F = hand_fresnel(std::cos(deg(th)), eta_rel);
        const int refl = static_cast<int>(from), trans = 1 - refl;
        EXPECT_NEAR(out.left[refl], F, 1e-14) << eta << " " << th;
        EXPECT_NEAR(out.left[trans], 1.0 - F, 1e-14) << eta << " " << th;
        EXPECT_EQ(out.max_k, 1);
        for (const DielectricExit& e : out.exits) {
          if (e.side == from) {
            EXPECT_NEAR(exit_angle(e), -deg(th), 1e-15);  // the mirror direction
          } else {
            EXPECT_NEAR(std::sin(exit_angle(e)), std::sin(deg(th)) / eta_rel, 1e-15);  // Snell
            EXPECT_EQ(e.path, 1u);
          }
        }
      }
}

TEST(DielectricPolyline, EtaOnePassesStraightThrough) {
  const Polyline p = rough(NdfKind::beckmann, 1.0, 4096, 5);
  DielectricOptions opt;
  opt.eta = 1.0, opt.branching = Branching::random;
  const DielectricPolylineTracer tr(p, opt);
  DielectricResult out;
  long recrossed = 0;
  for (Medium from : {Medium::above, Medium::below})
    for (double th : {0.0, 60.0, 85.0})
      for (long j = 0; j < 1000; ++j) {
        Rng rng(3, static_cast<std::uint64_t>(th), static_cast<std::uint64_t>(j));
        const Vec2 d = light_dir(deg(th), from);
        tr.trace(x_of(p, j, 1000), d, from, rng, out);
        ASSERT_EQ(out.exits.size(), 1u) << static_cast<int>(from) << " " << th << " " << j << " vertex " << out.vertex
                                        << " limit " << out.bounce_limit;
        const DielectricExit& e = out.exits[0];
        ASSERT_NE(e.side, from);
        ASSERT_TRUE(same_bits(e.dir.x(), d.x()) && same_bits(e.dir.y(), d.y()));
        // Every interaction crossed; an odd number of them.
        ASSERT_EQ(e.k % 2, 1);
        ASSERT_EQ(e.path, e.k >= 64 ? ~0ULL : (1ULL << e.k) - 1);
        recrossed += e.k >= 3;
      }
  EXPECT_GT(recrossed, 0);  // lines through ridges: met from both sides
}

TEST(DielectricPolyline, ConductorLimitIsThePolylineTracerBitForBit) {
  for (NdfKind ndf : {NdfKind::beckmann, NdfKind::ggx})
    for (double alpha : {0.3, 1.0}) {
      const Polyline p = rough(ndf, alpha, 4096, 11);
      for (int max_b : {100000, 2}) {
        DielectricOptions opt;
        opt.conductor_limit = true, opt.branching = Branching::random, opt.max_interactions = max_b;
        const DielectricPolylineTracer tr(p, opt);
        TraceOptions to;
        to.max_bounces = max_b;
        DielectricResult out;
        for (double th : {0.0, 45.0, 75.0, 89.0})
          for (long j = 0; j < 1000; ++j) {
            const double x = x_of(p, j, 1000);
            const Vec2 d = from_above(deg(th));
            const PolylineTraceResult c = trace_polyline(p, x, d, to);
            Rng rng(1, 1, 1);
            tr.trace(x, d, Medium::above, rng, out);
            if (c.how == Termination::escaped) {
              ASSERT_EQ(out.exits.size(), 1u);
              const DielectricExit& e = out.exits[0];
              ASSERT_EQ(e.side, Medium::above);
              ASSERT_EQ(e.k, c.bounces);
              ASSERT_EQ(e.path, 0u);
              ASSERT_TRUE(same_bits(e.dir.x(), c.exit_dir.x()) && same_bits(e.dir.y(), c.exit_dir.y()));
            } else if (c.how == Termination::bounce_limit) {
              ASSERT_EQ(out.bounce_limit, 1.0);
            } else {
              ASSERT_EQ(out.vertex, 1.0);
            }
          }
      }
    }
}

TEST(DielectricPolyline, GrazingLightNeverGivesNaN) {
  const Polyline p = rough(NdfKind::ggx, 0.3, 4096, 13);
  for (double eta : {1.5, 1.0 / 1.5})
    for (Medium from : {Medium::above, Medium::below})
      for (double th : {89.99, -89.99}) {
        DielectricOptions opt;
        opt.eta = eta, opt.branching = Branching::random;
        const DielectricPolylineTracer tr(p, opt);
        DielectricResult out;
        for (long j = 0; j < 1000; ++j) {
          Rng rng(5, 5, static_cast<std::uint64_t>(j));
          tr.trace(x_of(p, j, 1000), light_dir(deg(th), from), from, rng, out);
          ASSERT_EQ(out.total(), 1.0);
          for (const DielectricExit& e : out.exits) {
            ASSERT_TRUE(std::isfinite(e.dir.x()) && std::isfinite(e.dir.y()));
            ASSERT_TRUE(std::isfinite(exit_angle(e)));
            ASSERT_NEAR(e.dir.norm(), 1.0, 1e-14);
          }
        }
      }
}

TEST(DielectricPolyline, RaysMeetTheProfileFromBelow) {
  // A ridge with flanks of slope +-8: (1, 0) - (1.5, 4) - (2, 0). Light straight down at x = 1.25
  // meets the left flank at (1.25, 2), normal n1 = (-8, 1) / sqrt 65, cos_i = 1 / sqrt 65; the
  // refracted ray (eta 1.5) crosses the ridge and meets the right flank (normal (8, 1) / sqrt 65)
  // from below at cos = t . n2 = 0.614 (by hand), sin 0.789 > 1 / 1.5: total internal reflection.
  const Polyline p = make_polyline({0.0, 1.0, 1.5, 2.0, 3.0}, {0.0, 0.0, 4.0, 0.0, 0.0});
  DielectricOptions opt;
  opt.eta = 1.5, opt.branching = Branching::split, opt.min_weight = 0.0, opt.max_interactions = 1000;
  const DielectricPolylineTracer tr(p, opt);
  DielectricResult out;
  Rng rng(1, 1, 1);
  tr.trace(1.25, Vec2(0.0, -1.0), Medium::above, rng, out);
  const double c1 = 1.0 / std::sqrt(65.0), s1 = 8.0 / std::sqrt(65.0);
  const double F1 = hand_fresnel(c1, 1.5);
  // The refracted direction by hand: t = d / eta + (c1 / eta - cos_t) n1.
  const double ct = std::sqrt(1.0 - s1 * s1 / 2.25);
  const double tx = (c1 / 1.5 - ct) * (-8.0 / std::sqrt(65.0)), ty = -1.0 / 1.5 + (c1 / 1.5 - ct) * c1;
  const double cos2 = (tx * 8.0 + ty) / std::sqrt(65.0);
  ASSERT_GT(std::sqrt(1.0 - cos2 * cos2), 1.0 / 1.5);  // beyond the critical angle
  double refracted_first = 0.0;
  for (const DielectricExit& e : out.exits) {
    if (!(e.path & 1u)) continue;
    refracted_first += e.weight;
    EXPECT_GE(e.k, 2);                  // met the right flank from below
    EXPECT_EQ(e.path & 2u, 0u) << e.k;  // ... and reflected there whole
  }
  EXPECT_NEAR(out.total(), 1.0, 1e-15);
  EXPECT_EQ(out.bounce_limit + out.cut + out.vertex, 0.0);
  EXPECT_NEAR(refracted_first, 1.0 - F1, 1e-15);

  // On a rough profile: the energy of paths that met the profile from below after entering from
  // above (an interaction after an odd number of refractions), in random branching.
  const Polyline q = rough(NdfKind::ggx, 0.8, 4096, 17);
  DielectricOptions ro;
  ro.eta = 1.5, ro.branching = Branching::random;
  const DielectricPolylineTracer rt(q, ro);
  long met_from_below = 0;
  for (long j = 0; j < 2000; ++j) {
    Rng r(9, 9, static_cast<std::uint64_t>(j));
    rt.trace(x_of(q, j, 2000), from_above(deg(45.0)), Medium::above, r, out);
    for (const DielectricExit& e : out.exits) {
      int crossings = 0;
      for (int i = 0; i < e.k - 1 && i < 63; ++i)
        if ((crossings += (e.path >> i) & 1u) % 2 == 1) {
          ++met_from_below;
          break;
        }
    }
  }
  std::printf("GGX 0.8, 45 deg, eta 1.5: %ld of 2000 rays met the profile from below\n", met_from_below);
  EXPECT_GT(met_from_below, 20);
}

// Under the profile, a ray going down escapes only below the lowest vertex: one that runs just above
// the valleys' floor meets the next valley's wall there. Valleys (0, 0) - (1, -1) - (2, 0) - (3, 0),
// period 3; the ray leaves the right wall at (1.03, -0.97) along (1, -0.01) and meets the next left
// wall (3 + s, -s) at s = 0.9897 / 0.99 (by hand), 0.0003 above the floor.
TEST(DielectricPolyline, ADownwardRayJustAboveTheFloorMeetsTheNextValley) {
  const Polyline p = make_polyline({0.0, 1.0, 2.0, 3.0}, {0.0, -1.0, 0.0, 0.0});
  const PolylineLows lows = polyline_lows(p);
  const Vec2 d = Vec2(1.0, -0.01).normalized();
  const PolylineHit h = first_hit_from_below(p, lows, 1, 0.03, d);
  ASSERT_EQ(h.kind, PolylineHit::Kind::segment);
  EXPECT_EQ(h.segment, 0);
  EXPECT_NEAR(h.s, 0.9897 / 0.99, 1e-12);
  // Below the floor it has left.
  EXPECT_EQ(first_hit_from_below(p, lows, 1, 0.03, Vec2(1.0, -0.05).normalized()).kind, PolylineHit::Kind::escaped);
}

TEST(DielectricPolyline, LightFromBelowIsTheMirrorImageOfLightFromAbove) {
  // Mirrored in y = 0, the profile y(x) becomes -y(x), medium 2 lies above it (eta -> 1 / eta) and
  // light from below at theta_i arrives from above at -theta_i: the same paths, mirrored. The
  // march under the profile (first_hit_from_bottom, first_hit_from_below) is checked against the
  // one above it, ray by ray, with the same random choices.
  const Polyline p = rough(NdfKind::ggx, 0.8, 4096, 23);
  std::vector<double> y_flip(p.y.size());
  for (std::size_t v = 0; v < p.y.size(); ++v) y_flip[v] = -p.y[v];
  const Polyline q = make_polyline(p.x, y_flip);
  for (double eta : {1.5, 1.0 / 1.5}) {
    DielectricOptions o1, o2;
    o1.eta = eta, o2.eta = 1.0 / eta;
    o1.branching = o2.branching = Branching::random;
    const DielectricPolylineTracer below(p, o1), above(q, o2);
    DielectricResult a, b;
    long exits = 0, worst_ulps = 0;
    for (double th : {0.0, 30.0, -60.0, 80.0})
      for (long j = 0; j < 1000; ++j) {
        Rng r1(31, 0, static_cast<std::uint64_t>(j)), r2(31, 0, static_cast<std::uint64_t>(j));
        const double x = x_of(p, j, 1000);
        below.trace(x, from_below(deg(th)), Medium::below, r1, a);
        above.trace(x, from_above(-deg(th)), Medium::above, r2, b);
        ASSERT_EQ(a.exits.size(), b.exits.size());
        ASSERT_EQ(a.vertex, b.vertex);
        for (std::size_t e = 0; e < a.exits.size(); ++e) {
          const DielectricExit &ea = a.exits[e], &eb = b.exits[e];
          ASSERT_EQ(ea.k, eb.k);
          ASSERT_EQ(ea.path, eb.path);
          ASSERT_NE(ea.side, eb.side);
          ASSERT_NEAR(ea.dir.x(), eb.dir.x(), 1e-15);
          ASSERT_NEAR(ea.dir.y(), -eb.dir.y(), 1e-15);
          worst_ulps += !(same_bits(ea.dir.x(), eb.dir.x()) && same_bits(ea.dir.y(), -eb.dir.y()));
          ++exits;
        }
      }
    EXPECT_EQ(exits, 4000);
    EXPECT_EQ(worst_ulps, 0);  // bit for bit: every operation of the two marches is mirrored exactly
  }
}

TEST(DielectricPolyline, SplitAndRandomBranchingAgree) {
  // Per ray, the random path's indicator of leaving above minus the split tracer's reflected energy
  // has mean 0; z from the sample variance.
  const Polyline p = rough(NdfKind::ggx, 0.5, 4096, 19);
  for (Medium from : {Medium::above, Medium::below}) {
    DielectricOptions so, ro;
    so.eta = ro.eta = 1.5;
    so.branching = Branching::split, so.min_weight = 0.0, so.max_interactions = 10000;
    ro.branching = Branching::random, ro.max_interactions = 10000;
    const DielectricPolylineTracer st(p, so), rt(p, ro);
    DielectricResult a, b;
    double sum = 0.0, sum2 = 0.0;
    const long n = 4000;
    for (long j = 0; j < n; ++j) {
      Rng r1(21, 0, static_cast<std::uint64_t>(j)), r2(21, 1, static_cast<std::uint64_t>(j));
      const double x = x_of(p, j, n);
      const Vec2 d = light_dir(deg(50.0), from);
      st.trace(x, d, from, r1, a);
      rt.trace(x, d, from, r2, b);
      const double diff = b.left[0] - a.left[0];
      sum += diff, sum2 += diff * diff;
    }
    const double mean = sum / n, var = (sum2 / n - mean * mean) / (n - 1);
    EXPECT_LE(std::abs(mean) / std::sqrt(var), 4.0) << "mean " << mean << " se " << std::sqrt(var);
  }
}

TEST(DielectricPolyline, BadInputIsRefused) {
  const Polyline p = make_polyline({0.0, 1.0, 2.0}, {0.0, -1.0, 0.0});
  DielectricOptions opt;
  opt.eta = 0.0;
  try {
    DielectricPolylineTracer tr(p, opt);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("eta"), std::string::npos);
  }
  opt.eta = 1.5;
  const DielectricPolylineTracer tr(p, opt);
  DielectricResult out;
  Rng rng(1, 1, 1);
  EXPECT_THROW(tr.trace(0.5, from_above(0.1), Medium::below, rng, out), std::invalid_argument);
  EXPECT_THROW(tr.trace(0.5, from_below(0.1), Medium::above, rng, out), std::invalid_argument);
  EXPECT_THROW(tr.trace(2.0, from_above(0.1), Medium::above, rng, out), std::invalid_argument);
  EXPECT_THROW(tr.trace(std::nan(""), from_above(0.1), Medium::above, rng, out), std::invalid_argument);
}

}  // namespace
}  // namespace vgroove::sim
