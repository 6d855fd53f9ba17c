// Tests of sim/dielectric_groove.h and sim/dielectric_tally.h: the exactness of tracing across a
// dielectric V-groove (issue 32, "Must hold"): normal-incidence Fresnel, Brewster's angle, the
// critical angle and total internal reflection, a flat interface against Fresnel and Snell by
// hand, eta = 1, the conductor limit against sim::trace bit for bit, grazing light, vertex hits,
// conservation, and splitting against random branching in distribution.
//
// Conventions (sim/geometry.h): light from above at theta_i (from n, counter-clockwise positive)
// travels along -direction_at(theta_i) = (sin theta_i, -cos theta_i); light from below at theta_i
// (from -n, counter-clockwise positive: the light lies along (sin theta_i, -cos theta_i)) travels
// along direction_at(theta_i) = (-sin theta_i, cos theta_i). Either way Snell's law reads
// sin(exit_angle) = sin(theta_i) / eta_rel for the light that crosses.
#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/optics/snell.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/dielectric_tally.h"
#include "vgroove/sim/tally.h"
#include "vgroove/sim/tracer.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

// Travel direction of light from above at theta_i (sim/beam.h), and of light from below at
// theta_i measured from -n, travelling up.
Vec2 from_above(double theta_i) { return beam_direction(theta_i); }
Vec2 from_below(double theta_i) { return direction_at(theta_i); }

// Fresnel of a flat dielectric interface by hand (Born & Wolf 1.5.(21a)), independent of optics/:
// cos_t from Snell, r_s and r_p from the cosines.
struct HandFresnel {
  double Rs, Rp, cos_t;
  bool tir;
};
HandFresnel hand_fresnel(double theta_i, double eta) {
  const double ci = std::cos(theta_i), si = std::sin(theta_i);
  const double st = si / eta;
  if (std::abs(st) >= 1.0) return {1.0, 1.0, 0.0, true};
  const double ct = std::sqrt(1.0 - st * st);
  const double rs = (ci - eta * ct) / (ci + eta * ct);
  const double rp = (eta * ci - ct) / (eta * ci + ct);
  return {rs * rs, rp * rp, ct, false};
}

DielectricResult trace_one(const Groove& g, const DielectricOptions& opt, double x, const Vec2& dir, Medium from) {
  DielectricGrooveTracer tr(g, opt);
  Rng rng(1, 2, 3);
  DielectricResult r;
  tr.trace(Ray2{Vec2(x, g.rim_height), dir}, from, rng, r);
  return r;
}

// Where a ray of direction d crosses the rim line on the flat part of a groove of opening within
// [-1, 1], far upstream of the groove: neither its line before (light from below comes from
// y = -inf) nor its reflected or refracted rays after (down to 89.99 deg from the normal: 1e6
// tan(0.01 deg) = 175 below the rim line when they pass the groove) meet the groove.
double flat_x(const Vec2& d) { return d.x() > 0.0 ? -1e6 : 1e6; }

TEST(DielectricGroove, NormalIncidenceReflectsTheHandFresnel) {
  const Groove g = make_symmetric_groove(deg(60.0));
  for (double eta : {1.33, 1.5, 2.4, 1.0 / 1.5}) {
    const double R = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
    for (Medium from : {Medium::above, Medium::below}) {
      DielectricOptions opt;
      opt.eta = eta;
      const Vec2 d = from == Medium::above ? Vec2(0.0, -1.0) : Vec2(0.0, 1.0);
      const DielectricResult r = trace_one(g, opt, flat_x(d), d, from);
      const Medium back = from, across = from == Medium::above ? Medium::below : Medium::above;
      EXPECT_NEAR(r.left[static_cast<int>(back)], R, 1e-16) << "eta " << eta << " from " << medium_name(from);
      EXPECT_NEAR(r.left[static_cast<int>(across)], 1.0 - R, 2e-16) << "eta " << eta;
      ASSERT_EQ(r.exits.size(), 2u);
      for (const DielectricExit& e : r.exits) EXPECT_EQ(exit_angle(e), 0.0);
    }
  }
}

TEST(DielectricGroove, BrewsterAngleReflectsNoPPolarizedLight) {
  const Groove g = make_symmetric_groove(deg(60.0));
  for (double eta : {1.33, 1.5, 2.4}) {
    for (Medium from : {Medium::above, Medium::below}) {
      const double rel = from == Medium::above ? eta : 1.0 / eta;
      const double theta_b = std::atan(rel);
      const Vec2 d = from == Medium::above ? from_above(theta_b) : from_below(theta_b);
      DielectricOptions opt;
      opt.eta = eta;
      opt.polarization = Polarization::p;
      const DielectricResult rp = trace_one(g, opt, flat_x(d), d, from);
      const int back = static_cast<int>(from);
      EXPECT_LT(rp.left[back], 1e-30) << "eta " << eta << " from " << medium_name(from);
      EXPECT_NEAR(rp.left[1 - back], 1.0, 1e-15);
      // s-polarized at Brewster: r_s = (1 - n^2) / (1 + n^2) (theta_i + theta_t = 90 deg).
      opt.polarization = Polarization::s;
      const DielectricResult rs = trace_one(g, opt, flat_x(d), d, from);
      const double r_s = (1.0 - rel * rel) / (1.0 + rel * rel);
      EXPECT_NEAR(rs.left[back], r_s * r_s, 1e-15);
      // Unpolarized: the mean.
      opt.polarization = Polarization::unpolarized;
      const DielectricResult ru = trace_one(g, opt, flat_x(d), d, from);
      EXPECT_NEAR(ru.left[back], 0.5 * r_s * r_s, 1e-15);
    }
  }
}

TEST(DielectricGroove, BeyondTheCriticalAngleEverythingReflects) {
  const Groove g = make_symmetric_groove(deg(60.0));
  const double eta = 1.5;
  const double theta_c = std::asin(1.0 / eta);
  DielectricOptions opt;
  opt.eta = eta;
  for (double theta : {theta_c * (1.0 + 1e-12), theta_c + deg(1.0), deg(60.0), deg(89.99), -deg(70.0)}) {
    const DielectricResult r = trace_one(g, opt, flat_x(from_below(theta)), from_below(theta), Medium::below);
    EXPECT_EQ(r.left[static_cast<int>(Medium::below)], 1.0) << theta;
    EXPECT_EQ(r.left[static_cast<int>(Medium::above)], 0.0) << theta;
    ASSERT_EQ(r.exits.size(), 1u);
    EXPECT_EQ(r.exits[0].path, 0u);
  }
  // Just inside the critical angle light still crosses; and the same angles from above cross.
  const DielectricResult in = trace_one(g, opt, -1e6, from_below(theta_c * (1.0 - 1e-6)), Medium::below);
  EXPECT_GT(in.left[static_cast<int>(Medium::above)], 0.0);
  const DielectricResult above = trace_one(g, opt, -1e6, from_above(deg(60.0)), Medium::above);
  EXPECT_GT(above.left[static_cast<int>(Medium::below)], 0.5);
}

// The flat part of the interface against Fresnel and Snell by hand, both sides, both
// polarizations; then a groove of zero slope (theta_v = 180 deg) through its opening.
TEST(DielectricGroove, AFlatInterfaceIsFresnelAndSnell) {
  const Groove g = make_symmetric_groove(deg(60.0));
  const Groove flat = make_symmetric_groove(std::numbers::pi);
  for (double eta : {1.33, 1.5, 2.4, 1.0 / 1.33, 1.0 / 2.4}) {
    for (Medium from : {Medium::above, Medium::below}) {
      const double rel = from == Medium::above ? eta : 1.0 / eta;
      for (double theta_deg : {-80.0, -45.0, -10.0, 0.0, 5.0, 30.0, 41.0, 60.0, 89.0}) {
        const double theta = deg(theta_deg);
        const HandFresnel h = hand_fresnel(theta, rel);
        const Vec2 d = from == Medium::above ? from_above(theta) : from_below(theta);
        for (Polarization pol : {Polarization::s, Polarization::p, Polarization::unpolarized}) {
          DielectricOptions opt;
          opt.eta = eta;
          opt.polarization = pol;
          const double R = pol == Polarization::s ? h.Rs : pol == Polarization::p ? h.Rp : 0.5 * (h.Rs + h.Rp);
          const std::string where =
              "eta " + std::to_string(eta) + " from " + medium_name(from) + " theta " + std::to_string(theta_deg);
          for (const Groove* gr : {&g, &flat}) {
            const double x = gr == &g ? flat_x(d) : 0.1;
            // Both sides round their inputs differently (the tracer takes cos theta_i = |d.y|, the
            // hand formula sin theta_i), and cos_t = sqrt(1 - sin^2 theta_t) turns an input error
            // of eps into eps / cos_t near the critical angle: tolerances of a few eps times
            // (1 + 1 / cos_t), ten times more for the groove of zero slope (its facets lie at
            // 6e-17 rad from the rim line, cos(pi / 2) rounded). Total internal reflection is exact.
            const double tol = h.tir ? 0.0 : (gr == &g ? 4e-16 : 4e-15) * (1.0 + 1.0 / h.cos_t);
            const DielectricResult r = trace_one(*gr, opt, x, d, from);
            const int back = static_cast<int>(from);
            EXPECT_NEAR(r.left[back], R, tol) << where;
            EXPECT_NEAR(r.left[1 - back], 1.0 - R, tol) << where;
            for (const DielectricExit& e : r.exits) {
              EXPECT_EQ(e.k, 1) << where;
              if (e.side == from) {
                // Mirror direction, exactly on the flat part.
                if (gr == &g) {
                  EXPECT_EQ(e.dir.x(), d.x()) << where;
                  EXPECT_EQ(e.dir.y(), -d.y()) << where;
                } else {
                  EXPECT_NEAR(e.dir.x(), d.x(), 1e-15) << where;
                  EXPECT_NEAR(e.dir.y(), -d.y(), 1e-15) << where;
                }
              } else {
                // Snell: same sign of the tangential component, |sin| divided by rel.
                EXPECT_NEAR(e.dir.x(), d.x() / rel, tol) << where;
                EXPECT_NEAR(std::abs(e.dir.y()), h.cos_t, tol) << where;
                EXPECT_NEAR(std::sin(exit_angle(e)), std::sin(theta) / rel, tol) << where;
              }
            }
            if (h.tir) {
              EXPECT_EQ(r.left[1 - back], 0.0) << where;
            }
          }
        }
      }
    }
  }
}

// Index matched: no interface. Every ray goes straight through, in any groove, from either side.
TEST(DielectricGroove, EtaOnePassesStraightThrough) {
  for (const Groove& g : {make_symmetric_groove(deg(30.0)), make_symmetric_groove(deg(120.0)),
                          make_nonsymmetric_groove(deg(-20.0), deg(50.0))}) {
    DielectricOptions opt;
    opt.eta = 1.0;
    for (Medium from : {Medium::above, Medium::below})
      for (double theta_deg : {-60.0, 0.0, 25.0, 80.0})
        for (double x : {-1.5, -0.3, 0.01, 0.2, 3.0}) {
          const Vec2 d = from == Medium::above ? from_above(deg(theta_deg)) : from_below(deg(theta_deg));
          const DielectricResult r = trace_one(g, opt, x, d, from);
          ASSERT_EQ(r.exits.size(), 1u);
          const DielectricExit& e = r.exits[0];
          EXPECT_EQ(e.weight, 1.0);
          EXPECT_NE(e.side, from);
          EXPECT_EQ(e.dir.x(), d.x());
          EXPECT_EQ(e.dir.y(), d.y());
          EXPECT_EQ(r.total(), 1.0);
        }
  }
}

// With F forced to 1 the tracer is sim::trace's mirror groove: every ray through the opening gives
// sim::trace's result, and the tallies agree bit for bit (counts, reference exit directions,
// spreads), vertex hits and the bounce limit included.
// sim::trace's result for the same ray: a ray whose first hit is a flat part never entered the
// opening (blocked, in sim::trace's words).
TraceResult as_trace_result(const DielectricResult& r) {
  TraceResult t;
  if (!r.exits.empty() && (r.exits[0].first == Part::left_flat || r.exits[0].first == Part::right_flat)) {
    t.how = Termination::blocked;
  } else if (r.vertex > 0.0) {
    t.how = Termination::vertex_hit;
    t.bounces = r.max_k;
  } else if (r.bounce_limit > 0.0) {
    t.how = Termination::bounce_limit;
    t.bounces = r.max_k;
  } else {
    t.how = Termination::escaped;
    t.exit_dir = r.exits.at(0).dir;
    t.bounces = r.exits[0].k;
    t.first = static_cast<Side>(r.exits[0].first);
  }
  return t;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void expect_same_tallies(const Tally& a, const Tally& b, const std::string& where) {
  EXPECT_EQ(a.rays, b.rays) << where;
  EXPECT_EQ(a.escaped, b.escaped) << where;
  EXPECT_EQ(a.vertex_hits, b.vertex_hits) << where;
  EXPECT_EQ(a.blocked, b.blocked) << where;
  EXPECT_EQ(a.bounce_limit, b.bounce_limit) << where;
  EXPECT_EQ(a.bounces, b.bounces) << where;
  for (int f = 0; f < 2; ++f) {
    int na = 0, nb = 0;
    for (const auto& e : a.bins[f]) {
      ++na;
      const BounceBin& o = b.bins[f][e.k];
      EXPECT_EQ(e.bin.count, o.count) << where << " facet " << f << " k " << e.k;
      EXPECT_TRUE(same_bits(e.bin.exit_dir.x(), o.exit_dir.x()) && same_bits(e.bin.exit_dir.y(), o.exit_dir.y()))
          << where << " facet " << f << " k " << e.k;
      EXPECT_TRUE(same_bits(e.bin.spread_sin, o.spread_sin)) << where << " k " << e.k;
      EXPECT_EQ(e.bin.reversed, o.reversed) << where;
    }
    for (const auto& e : b.bins[f]) (void)e, ++nb;
    EXPECT_EQ(na, nb) << where;
  }
}

TEST(DielectricGroove, ConductorLimitIsTheConductorTracerBitForBit) {
  const std::vector<Groove> grooves = {make_symmetric_groove(deg(2.0)),
                                       make_symmetric_groove(deg(30.0)),
                                       make_symmetric_groove(deg(60.0)),
                                       make_symmetric_groove(deg(90.0)),
                                       make_symmetric_groove(deg(137.0)),
                                       make_symmetric_groove(deg(179.9)),
                                       make_nonsymmetric_groove(deg(-10.0), deg(70.0)),
                                       make_nonsymmetric_groove(deg(-80.0), deg(5.0))};
  for (std::size_t gi = 0; gi < grooves.size(); ++gi) {
    const Groove& g = grooves[gi];
    for (double theta_deg : {-89.99, -50.0, -12.5, 0.0, 33.0, 75.0, 89.99}) {
      for (int max_k : {100000, 1}) {
        DielectricOptions opt;
        opt.conductor_limit = true;
        opt.eta = 1.5;
        opt.max_interactions = max_k;
        TraceOptions topt;
        topt.max_bounces = max_k;
        const DielectricGrooveTracer tr(g, opt);
        const Vec2 dir = beam_direction(deg(theta_deg));
        const Interval iv = opening(g);
        const long n = 2001;  // odd: the middle ray crosses the rim line at the opening's centre
        Tally ta, tb;
        Rng rng(7, 0, 0);
        DielectricResult r;
        for (long j = 0; j < n; ++j) {
          const Ray2 ray = beam_ray(g, dir, sample_position(Sampling::stratified, iv, j, n, rng));
          ta.add(trace(g, ray, topt));
          tb.add(as_trace_result(tr.trace(ray, Medium::above, rng, r)));
          ASSERT_EQ(r.total(), 1.0);
        }
        // The apex exactly: a vertex hit in both.
        const Ray2 apex{Vec2(g.rim_height * dir.x() / dir.y(), g.rim_height), dir};
        ta.add(trace(g, apex, topt));
        tb.add(as_trace_result(tr.trace(apex, Medium::above, rng, r)));
        const std::string where = "groove " + std::to_string(gi) + " theta_i " + std::to_string(theta_deg) + " max_k " +
                                  std::to_string(max_k);
        expect_same_tallies(ta, tb, where);
        EXPECT_GT(ta.escaped + ta.bounce_limit, n / 2) << where;
      }
    }
  }
}

// The same at the zones' edges: between two stratified rays whose outcomes differ (bounce count,
// first facet, termination), bisection on sim::trace down to adjacent doubles finds the edge, where
// the outcome hangs on the last rounding of the position along the facets; both rays there must
// come out of the conductor limit exactly as out of sim::trace.
TEST(DielectricGroove, ConductorLimitAgreesAtTheZoneEdges) {
  const std::vector<Groove> grooves = {make_symmetric_groove(deg(7.0)), make_symmetric_groove(deg(45.0)),
                                       make_symmetric_groove(deg(100.0)),
                                       make_nonsymmetric_groove(deg(-25.0), deg(40.0))};
  int edges = 0;
  for (const Groove& g : grooves)
    for (double theta_deg : {-70.0, -20.0, 10.0, 55.0}) {
      DielectricOptions opt;
      opt.conductor_limit = true;
      const DielectricGrooveTracer tr(g, opt);
      const Vec2 dir = beam_direction(deg(theta_deg));
      const Interval iv = opening(g);
      Rng rng(7, 0, 0);
      DielectricResult r;
      auto key = [&](double x) {
        const TraceResult t = trace(g, beam_ray(g, dir, x));
        return std::make_tuple(t.bounces, static_cast<int>(t.first), static_cast<int>(t.how));
      };
      auto same = [&](double x) {
        const TraceResult a = trace(g, beam_ray(g, dir, x));
        const TraceResult b = as_trace_result(tr.trace(beam_ray(g, dir, x), Medium::above, rng, r));
        return a.how == b.how && a.bounces == b.bounces && (a.how != Termination::escaped || a.first == b.first) &&
               same_bits(a.exit_dir.x(), b.exit_dir.x()) && same_bits(a.exit_dir.y(), b.exit_dir.y());
      };
      const long n = 256;
      for (long j = 0; j + 1 < n; ++j) {
        double lo = sample_position(Sampling::stratified, iv, j, n, rng);
        double hi = sample_position(Sampling::stratified, iv, j + 1, n, rng);
        const auto k_lo = key(lo);
        if (key(hi) == k_lo) continue;
        while (std::nextafter(lo, hi) < hi) {
          const double mid = 0.5 * (lo + hi);
          if (mid <= lo || mid >= hi) break;
          (key(mid) == k_lo ? lo : hi) = mid;
        }
        ++edges;
        EXPECT_TRUE(same(lo)) << "theta_i " << theta_deg << " x " << lo;
        EXPECT_TRUE(same(hi)) << "theta_i " << theta_deg << " x " << hi;
      }
    }
  EXPECT_GE(edges, 12);
}

// Snell's total internal reflection is Fresnel's: refract() refuses exactly where
// fresnel_dielectric gives 1 for that reason, in a sweep across the critical angle to the last bit.
TEST(DielectricGroove, SnellAndFresnelAgreeOnTotalInternalReflection) {
  for (double eta : {1.0 / 1.33, 1.0 / 1.5, 1.0 / 2.4}) {
    const double c_crit = std::sqrt(1.0 - eta * eta);
    int tir = 0, crossing = 0;
    double c = c_crit * (1.0 - 1e-14);
    for (int i = 0; i < 400; ++i, c = std::nextafter(c, 1.0)) {
      const Vec2 d(std::sqrt(1.0 - c * c), -c), m(0.0, 1.0);
      Vec2 t;
      const bool crosses = optics::refract(d, m, eta, t);
      const double F = optics::fresnel_dielectric(std::abs(d.y()), eta);
      EXPECT_EQ(crosses, F < 1.0) << "eta " << eta << " cos " << c;
      if (crosses) {
        ++crossing;
        EXPECT_TRUE(std::isfinite(t.x()) && std::isfinite(t.y()) && t.y() < 0.0);
      } else {
        ++tir;
      }
    }
    EXPECT_GT(tir, 0);
    EXPECT_GT(crossing, 0);
  }
}

// The deliberately broken variant: with F not forced to 1 the dielectric tracer is not the mirror
// groove (the comparison above can fail).
TEST(DielectricGroove, ConductorLimitComparisonSeesADielectric) {
  const Groove g = make_symmetric_groove(deg(60.0));
  DielectricOptions opt;
  opt.eta = 1.5;
  const DielectricGrooveTracer tr(g, opt);
  const Vec2 dir = beam_direction(deg(20.0));
  Rng rng(7, 0, 0);
  DielectricResult r;
  const Ray2 ray = beam_ray(g, dir, 0.1);
  const TraceResult a = trace(g, ray);
  const TraceResult b = as_trace_result(tr.trace(ray, Medium::above, rng, r));
  EXPECT_FALSE(a.exit_dir == b.exit_dir && a.bounces == b.bounces);
}

// Grazing light to 89.99 deg on either side, in grooves narrow to flat, from both media: never a
// NaN, and everything accounted for.
TEST(DielectricGroove, GrazingLightNeverGivesNaN) {
  for (const Groove& g : {make_symmetric_groove(deg(1.0)), make_symmetric_groove(deg(60.0)),
                          make_symmetric_groove(deg(179.99)), make_nonsymmetric_groove(deg(-89.0), deg(1.0))}) {
    for (double eta : {1.5, 1.0 / 1.5, 2.4}) {
      DielectricOptions opt;
      opt.eta = eta;
      opt.min_weight = 0.0;
      const DielectricGrooveTracer tr(g, opt);
      Rng rng(1, 0, 0);
      DielectricResult r;
      for (Medium from : {Medium::above, Medium::below})
        for (double theta_deg : {-89.99, -89.9, 89.9, 89.99})
          for (int j = 0; j < 101; ++j) {
            const double x = -1.2 + 2.4 * (j + 0.5) / 101.0;
            const Vec2 d = from == Medium::above ? from_above(deg(theta_deg)) : from_below(deg(theta_deg));
            tr.trace(Ray2{Vec2(x, g.rim_height), d}, from, rng, r);
            EXPECT_NEAR(r.total(), 1.0, 1e-13);
            for (const DielectricExit& e : r.exits) {
              ASSERT_TRUE(std::isfinite(e.dir.x()) && std::isfinite(e.dir.y()) && std::isfinite(e.weight));
              ASSERT_TRUE(std::isfinite(exit_angle(e)));
              EXPECT_NEAR(e.dir.norm(), 1.0, 1e-14);
              // Left into the medium its direction points into.
              EXPECT_TRUE(e.side == Medium::above ? e.dir.y() >= 0.0 : e.dir.y() <= 0.0);
            }
          }
    }
  }
}

TEST(DielectricGroove, VertexHitsAreCountedNotDropped) {
  const Groove g = make_symmetric_groove(deg(60.0));
  DielectricOptions opt;
  // The apex, from above and from below; a rim from above; a flat part's end (the rim) from below.
  EXPECT_EQ(trace_one(g, opt, 0.0, Vec2(0.0, -1.0), Medium::above).vertex, 1.0);
  EXPECT_EQ(trace_one(g, opt, 0.0, Vec2(0.0, 1.0), Medium::below).vertex, 1.0);
  EXPECT_EQ(trace_one(g, opt, g.rim_x(Side::left), from_above(deg(10.0)), Medium::above).vertex, 1.0);
  EXPECT_EQ(trace_one(g, opt, g.rim_x(Side::right), Vec2(0.0, 1.0), Medium::below).vertex, 1.0);
  // A position that is no number meets nothing: counted as a vertex hit, as sim::trace does.
  const DielectricResult r = trace_one(g, opt, std::nan(""), Vec2(0.0, -1.0), Medium::above);
  EXPECT_EQ(r.vertex, 1.0);
  EXPECT_EQ(r.total(), 1.0);
}

// Conservation to rounding over many grooves, indices, sides and angles: reflected + transmitted +
// cut + bounce limit + vertex = 1 for every ray; with a low bounce limit and a high cut weight the
// shares move into those buckets and the sum stays 1.
TEST(DielectricGroove, EnergyIsConservedToRounding) {
  const std::vector<Groove> grooves = {make_symmetric_groove(deg(5.0)), make_symmetric_groove(deg(40.0)),
                                       make_symmetric_groove(deg(100.0)),
                                       make_nonsymmetric_groove(deg(-30.0), deg(60.0))};
  double worst = 0.0;
  double cut_seen = 0.0, limit_seen = 0.0;
  for (const Groove& g : grooves)
    for (double eta : {1.33, 1.5, 2.4, 1.0 / 1.33, 1.0 / 1.5, 1.0 / 2.4})
      for (int setting = 0; setting < 3; ++setting) {
        DielectricOptions opt;
        opt.eta = eta;
        opt.min_weight = setting == 1 ? 0.05 : 0.0;
        opt.max_interactions = setting == 2 ? 2 : 100000;
        const DielectricGrooveTracer tr(g, opt);
        Rng rng(3, 0, 0);
        DielectricResult r;
        for (Medium from : {Medium::above, Medium::below})
          for (double theta_deg : {-70.0, -20.0, 0.0, 35.0, 85.0})
            for (int j = 0; j < 41; ++j) {
              const double x = -1.5 + 3.0 * (j + 0.5) / 41.0;
              const Vec2 d = from == Medium::above ? from_above(deg(theta_deg)) : from_below(deg(theta_deg));
              tr.trace(Ray2{Vec2(x, g.rim_height), d}, from, rng, r);
              worst = std::max(worst, std::abs(r.total() - 1.0));
              cut_seen += r.cut;
              limit_seen += r.bounce_limit;
            }
      }
  EXPECT_LT(worst, 1e-14);
  EXPECT_GT(cut_seen, 0.0);
  EXPECT_GT(limit_seen, 0.0);
}

// Whether a path (k interactions, R/T bits) of light from `from` met the interface while travelling
// in medium 2 after its first interaction: the medium after interaction j flips with each T.
bool met_again_from_below(Medium from, int k, std::uint64_t bits) {
  bool below = from == Medium::below;
  for (int j = 0; j + 1 < k && j < 64; ++j) {
    if ((bits >> j) & 1u) below = !below;
    if (below) return true;
  }
  return false;
}

// Light refracted into the material meets the interface again from below, and is traced on: a
// 60 deg groove lit from above at normal incidence sends part of its light, refracted through one
// facet, onto the flat part's underside; lit from below at 80 deg, light reflected by the flat part
// meets the facets' undersides. Those paths carry energy, and in the tally every exit is
// accounted for (histograms against energies, energies against rays).
TEST(DielectricGroove, RefractedLightMeetsTheInterfaceAgainFromBelow) {
  const Groove g = make_symmetric_groove(deg(60.0));
  DielectricOptions opt;
  opt.eta = 1.5;
  opt.min_weight = 0.0;
  const DielectricGrooveTracer tr(g, opt);
  for (Medium from : {Medium::above, Medium::below}) {
    DielectricTally tally(90);
    Rng rng(5, 0, 0);
    DielectricResult r;
    // From below, upstream of the opening: the light travels left, and crosses the rim line over
    // the flat part right of the opening.
    const Interval iv = from == Medium::above ? opening(g) : Interval{opening(g).hi, opening(g).hi + 2.0};
    const Vec2 dir = from == Medium::above ? from_above(0.0) : from_below(deg(80.0));
    const long n = 1000;
    for (long j = 0; j < n; ++j)
      tally.add(tr.trace(beam_ray(g, dir, sample_position(Sampling::stratified, iv, j, n, rng)), from, rng, r));
    double again = 0.0;
    for (Medium side : {Medium::above, Medium::below})
      for (const auto& [key, w] : tally.by_path(side))
        if (met_again_from_below(from, key.first, key.second)) again += w;
    EXPECT_GT(again, 1e-3 * n) << medium_name(from);
    EXPECT_NEAR(tally.total(), static_cast<double>(n), 1e-12 * n);
    double in_hist = 0.0, by_k = 0.0;
    for (Medium side : {Medium::above, Medium::below})
      for (int k = 0; k <= tally.max_k(side); ++k) {
        by_k += tally.energy(side, k);
        for (double v : tally.histogram(side, k)) in_hist += v;
      }
    EXPECT_NEAR(in_hist, tally.energy(Medium::above) + tally.energy(Medium::below), 1e-12 * n);
    EXPECT_NEAR(by_k, tally.energy(Medium::above) + tally.energy(Medium::below), 1e-12 * n);
  }
}

// Mirror symmetry: a symmetric groove lit from -theta gives the mirror image of theta's result.
TEST(DielectricGroove, MirrorSymmetry) {
  const Groove g = make_symmetric_groove(deg(50.0));
  DielectricOptions opt;
  opt.eta = 1.7;
  opt.min_weight = 0.0;
  const DielectricGrooveTracer tr(g, opt);
  DielectricTally a(36), b(36);
  Rng rng(5, 0, 0);
  DielectricResult r;
  for (Medium from : {Medium::above, Medium::below})
    for (int j = 0; j < 301; ++j) {
      const double x = -1.2 + 2.4 * (j + 0.5) / 301.0;
      const Vec2 d = from == Medium::above ? from_above(deg(37.0)) : from_below(deg(37.0));
      a.add(tr.trace(Ray2{Vec2(x, g.rim_height), d}, from, rng, r));
      b.add(tr.trace(Ray2{Vec2(-x, g.rim_height), Vec2(-d.x(), d.y())}, from, rng, r));
    }
  for (Medium side : {Medium::above, Medium::below})
    for (int k = 0; k <= std::max(a.max_k(side), b.max_k(side)); ++k) {
      const std::vector<double> ha = a.histogram(side, k), hb = b.histogram(side, k);
      for (int i = 0; i < 36; ++i) EXPECT_NEAR(ha[i], hb[35 - i], 1e-9) << medium_name(side) << " k " << k;
    }
}

// Random branching samples the paths that splitting weighs: over many rays the counts of random
// branching per (side, k, exit-angle bin) follow the split energies. Rays at the same stratified
// positions; each random ray's count is a sum of independent Bernoulli draws, whose variance is
// at most the binomial's, so the chi-square test is conservative. Fixed seed, threshold p > 1e-4.
// Kept beside it, the broken variant: the random counts against the split energies of another eta
// (1.5 against 1.6) fail with p < 1e-9.
struct Cells {
  std::vector<double> expected;
  std::vector<std::int64_t> observed;
};
// Two sets of cells: (side, k, exit-angle bin), and (side, path signature).
struct BothCells {
  Cells by_angle, by_path;
};
BothCells split_against_random(const Groove& g, double theta_deg, Medium from, const Interval& iv, double eta_split,
                               double eta_random, long n) {
  DielectricOptions os;
  os.eta = eta_split;
  os.min_weight = 0.0;
  DielectricOptions orand = os;
  orand.eta = eta_random;
  orand.branching = Branching::random;
  const DielectricGrooveTracer ts(g, os), tr(g, orand);
  const int bins = 45;
  DielectricTally split(bins), random(bins);
  DielectricResult r;
  const Vec2 d = from == Medium::above ? from_above(deg(theta_deg)) : from_below(deg(theta_deg));
  for (long j = 0; j < n; ++j) {
    const double x = iv.lo + iv.width() * (static_cast<double>(j) + 0.5) / static_cast<double>(n);
    const Ray2 ray{Vec2(x, g.rim_height), d};
    Rng unused(0, 0, 0);
    split.add(ts.trace(ray, from, unused, r));
    Rng rng(2026, 32, static_cast<std::uint64_t>(j));  // one stream per ray: any order, same draws
    random.add(tr.trace(ray, from, rng, r));
  }
  BothCells c;
  for (Medium side : {Medium::above, Medium::below}) {
    const int k_max = std::max(split.max_k(side), random.max_k(side));
    for (int k = 0; k <= k_max; ++k) {
      const std::vector<double> a = split.histogram(side, k), b = random.histogram(side, k);
      for (int i = 0; i < bins; ++i) {
        c.by_angle.expected.push_back(a[i]);
        c.by_angle.observed.push_back(std::llround(b[i]));
      }
    }
    std::map<std::pair<int, std::uint64_t>, std::pair<double, double>> paths;
    for (const auto& [key, w] : split.by_path(side)) paths[key].first += w;
    for (const auto& [key, w] : random.by_path(side)) paths[key].second += w;
    for (const auto& [key, ew] : paths) {
      c.by_path.expected.push_back(ew.first);
      c.by_path.observed.push_back(std::llround(ew.second));
    }
  }
  return c;
}

test_stats::ChiSquare chi_square(const Cells& c) {
  std::vector<double> edges(c.expected.size() + 1);
  for (std::size_t i = 0; i < edges.size(); ++i) edges[i] = static_cast<double>(i);
  return test_stats::chi_square_gof(edges, c.expected, c.observed);
}

TEST(DielectricGroove, SplittingAndRandomBranchingAgreeInDistribution) {
  struct Case {
    double theta_v_deg, theta_deg;
    Medium from;
    double x_lo, x_hi;  // where the rays cross the rim line, in units of the opening's half width
  };
  for (const Case& cs_ : {Case{20.0, 0.0, Medium::above, -1.0, 1.0}, Case{10.0, 30.0, Medium::above, -1.0, 1.0},
                          Case{60.0, 80.0, Medium::below, -1.0, 4.0}, Case{120.0, 60.0, Medium::below, -1.0, 1.0}}) {
    const Groove g = make_symmetric_groove(deg(cs_.theta_v_deg));
    const double half = opening(g).hi;
    const Interval iv{cs_.x_lo * half, cs_.x_hi * half};
    const std::string where = "theta_v " + std::to_string(cs_.theta_v_deg) + " from " + medium_name(cs_.from) +
                              " theta " + std::to_string(cs_.theta_deg);
    const BothCells c = split_against_random(g, cs_.theta_deg, cs_.from, iv, 1.5, 1.5, 100000);
    const BothCells wrong = split_against_random(g, cs_.theta_deg, cs_.from, iv, 1.6, 1.5, 100000);
    for (int set = 0; set < 2; ++set) {
      const char* what = set ? " by path" : " by angle";
      const test_stats::ChiSquare cs = chi_square(set == 0 ? c.by_angle : c.by_path);
      EXPECT_GT(cs.p, 1e-4) << where << what << " chi2 " << cs.stat << " dof " << cs.dof << "\n" << cs.table;
      EXPECT_GE(cs.dof, 3) << where << what;
      const test_stats::ChiSquare cw = chi_square(set == 0 ? wrong.by_angle : wrong.by_path);
      EXPECT_LT(cw.p, 1e-9) << "the broken variant passed: " << where << what;
    }
  }
}

TEST(DielectricGroove, BadInputIsRefusedNamingTheFieldAndRange) {
  const Groove g = make_symmetric_groove(deg(60.0));
  auto message = [&](DielectricOptions opt) {
    try {
      DielectricGrooveTracer tr(g, opt);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  DielectricOptions o;
  for (double eta : {0.0, -1.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    o.eta = eta;
    const std::string m = message(o);
    EXPECT_EQ(m.rfind("eta = ", 0), 0u) << m;
    EXPECT_NE(m.find("is out of range (0, inf)"), std::string::npos) << m;
  }
  o = DielectricOptions{};
  o.min_weight = 1.0;
  EXPECT_EQ(message(o), "min_weight = 1 is out of range [0, 1)");
  o = DielectricOptions{};
  o.max_interactions = -1;
  EXPECT_EQ(message(o), "max_interactions = -1 is out of range [0, 2147483647]");
  EXPECT_EQ(message(DielectricOptions{}), "accepted");
  // Light on the wrong side for the medium it comes from.
  const DielectricGrooveTracer tr(g, DielectricOptions{});
  Rng rng(0, 0, 0);
  DielectricResult r;
  try {
    tr.trace(Ray2{Vec2(0.1, g.rim_height), Vec2(0.0, 1.0)}, Medium::above, rng, r);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "ray.dir.y = 1 is out of range [-1, 0) for light from above");
  }
  EXPECT_THROW(tr.trace(Ray2{Vec2(0.1, g.rim_height), Vec2(0.0, -1.0)}, Medium::below, rng, r), std::invalid_argument);
  EXPECT_THROW(tr.trace(Ray2{Vec2(0.1, g.rim_height), Vec2(std::nan(""), std::nan(""))}, Medium::below, rng, r),
               std::invalid_argument);
}

}  // namespace
}  // namespace vgroove::sim
