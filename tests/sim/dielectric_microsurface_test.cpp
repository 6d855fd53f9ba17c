// Tests of sim/dielectric_microsurface.h: a procedural V-groove surface between two dielectrics.
// The conductor limit against today's microsurface tallies bit for bit, eta = 1, conservation to
// rounding from both sides, light crossing under several grooves, grazing light, and splitting
// against random branching in distribution (the broken variant kept beside it).
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/sim/dielectric_tally.h"
#include "vgroove/sim/microsurface.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

Microsurface surface_of(NdfKind ndf, double alpha, int grooves, std::uint64_t seed) {
  MicrosurfaceOptions o;
  o.ndf = ndf;
  o.alpha = alpha;
  o.grooves = grooves;
  o.seed = seed;
  return make_microsurface(o);
}

// What sim::trace would have returned for the same ray: the conductor limit's single path.
TraceResult as_trace_result(const DielectricResult& r) {
  TraceResult t;
  if (r.vertex > 0.0) {
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

void expect_same(const MicrosurfaceTally& a, const MicrosurfaceTally& b, const std::string& where) {
  EXPECT_EQ(a.rays, b.rays) << where;
  EXPECT_EQ(a.escaped, b.escaped) << where;
  EXPECT_EQ(a.vertex_hits, b.vertex_hits) << where;
  EXPECT_EQ(a.bounce_limit, b.bounce_limit) << where;
  EXPECT_EQ(a.not_upward, b.not_upward) << where;
  EXPECT_EQ(a.bounces, b.bounces) << where;
  EXPECT_EQ(a.max_k_seen, b.max_k_seen) << where;
  EXPECT_EQ(a.by_k, b.by_k) << where;
  EXPECT_EQ(a.theta_o_by_k, b.theta_o_by_k) << where;
}

// F forced to 1: the surface is today's conductor microsurface, ray by ray, and the tallies are
// trace_microsurface_chunk's (what the suites run) and its reference's, bit for bit.
TEST(DielectricSurface, ConductorLimitIsTodaysMicrosurfaceTally) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.1, 0.6, 1.5})
      for (double theta_deg : {-80.0, 0.0, 35.0, 89.0}) {
        const Microsurface m = surface_of(ndf, alpha, 1000, 11);
        MicrosurfaceTraceOptions to;
        to.theta_i = deg(theta_deg);
        to.rays = 20000;
        to.seed = 5;
        DielectricOptions opt;
        opt.conductor_limit = true;
        const DielectricSurfaceTracer tr(m, opt);
        MicrosurfaceTally mine(to.theta_o_bins, to.max_k);
        Rng rng(1, 0, 0);
        DielectricResult r;
        for_each_landing(m.grooves, to.theta_i, to.sampling, to.rays, to.seed, 0,
                         [&](const Groove& g, const Ray2& ray) {
                           const int j = static_cast<int>(&g - m.grooves.data());
                           mine.add(as_trace_result(tr.trace_from_above(j, ray, rng, r)));
                         });
        const std::string where = "alpha " + std::to_string(alpha) + " theta_i " + std::to_string(theta_deg);
        expect_same(mine, trace_microsurface_chunk(m, to, 0), where);
        expect_same(mine, trace_microsurface_chunk_reference(m, to, 0), where + " (reference)");
        EXPECT_GT(mine.escaped, to.rays / 2) << where;
      }
}

// Index matched: every ray goes straight through, from either side.
TEST(DielectricSurface, EtaOnePassesStraightThrough) {
  const Microsurface m = surface_of(NdfKind::ggx, 0.8, 200, 3);
  DielectricOptions opt;
  opt.eta = 1.0;
  const DielectricSurfaceTracer tr(m, opt);
  Rng rng(1, 0, 0);
  DielectricResult r;
  for (double theta_deg : {-70.0, 0.0, 20.0, 85.0}) {
    const Vec2 down = -direction_at(deg(theta_deg)), up = direction_at(deg(theta_deg));
    int n = 0;
    for_each_landing(m.grooves, deg(theta_deg), Sampling::random, 2000, 9, 0, [&](const Groove& g, const Ray2& ray) {
      tr.trace_from_above(static_cast<int>(&g - m.grooves.data()), ray, rng, r);
      ASSERT_EQ(r.exits.size(), 1u);
      EXPECT_EQ(r.exits[0].side, Medium::below);
      EXPECT_EQ(r.exits[0].dir, down);
      tr.trace_from_below(0.1 * n++ + 0.0123, up, rng, r);  // off the peaks (whole x) and apexes (x + 1/2)
      ASSERT_EQ(r.exits.size(), 1u);
      EXPECT_EQ(r.exits[0].side, Medium::above);
      EXPECT_EQ(r.exits[0].dir, up);
    });
  }
}

// The surface's geometry below and above, checked by a count made without the tracer: at eta = 1
// a ray goes straight on and interacts once at every crossing of its line with the surface, so
// its single exit's k is the number of the surface polyline's segments its line crosses. The
// polyline here is built from the grooves' slopes alone (groove n: (n, 0), (n + 1/2,
// -tan(theta_m) / 2), (n + 1, 0)), and a crossing is a segment whose ends lie strictly on either
// side of the line.
int crossings(const Microsurface& m, const Vec2& p0, const Vec2& d) {
  const long G = static_cast<long>(m.grooves.size());
  double depth = 0.0;
  for (double t : m.theta_m) depth = std::max(depth, 0.5 * std::tan(t));
  // The line's x between y = 0 and y = -depth, and a groove more on each side.
  const double xa = p0.x() + (0.0 - p0.y()) / d.y() * d.x(), xb = p0.x() + (-depth - p0.y()) / d.y() * d.x();
  const long n_lo = static_cast<long>(std::floor(std::min(xa, xb))) - 1;
  const long n_hi = static_cast<long>(std::floor(std::max(xa, xb))) + 1;
  auto side = [&](const Vec2& q) { return cross(d, q - p0); };
  int count = 0;
  for (long n = n_lo; n <= n_hi; ++n) {
    const double dep = 0.5 * std::tan(m.theta_m[static_cast<std::size_t>(((n % G) + G) % G)]);
    const Vec2 a(static_cast<double>(n), 0.0), b(static_cast<double>(n) + 0.5, -dep),
        c(static_cast<double>(n) + 1.0, 0.0);
    if (side(a) * side(b) < 0.0) ++count;
    if (side(b) * side(c) < 0.0) ++count;
  }
  return count;
}

TEST(DielectricSurface, EtaOneCrossesTheSurfaceWhereItsLineDoes) {
  const Microsurface m = surface_of(NdfKind::ggx, 0.9, 100, 4);
  DielectricOptions opt;
  opt.eta = 1.0;
  const DielectricSurfaceTracer tr(m, opt);
  Rng rng(1, 0, 0);
  DielectricResult r;
  int most = 0;
  for (double theta_deg : {-85.0, -40.0, 5.0, 60.0, 88.0})
    for (int q = 0; q < 400; ++q) {
      const double x = 100.0 * (q + 0.37) / 400.0;
      // From below, crossing y = -depth_max at x.
      const Vec2 up = direction_at(deg(theta_deg));
      tr.trace_from_below(x, up, rng, r);
      ASSERT_EQ(r.exits.size(), 1u);
      const int want_up = crossings(m, Vec2(x, -tr.depth_max()), up);
      EXPECT_EQ(r.exits[0].k, want_up) << "from below, theta " << theta_deg << " x " << x;
      // From above, landing at x on the peaks' line: groove floor(x), at f = x - floor(x) across its opening.
      const Vec2 down = -direction_at(deg(theta_deg));
      const int j = static_cast<int>(std::floor(x));
      const Groove& g = m.grooves[static_cast<std::size_t>(j)];
      const double f = x - j;
      const double xu = g.rim_x(Side::left) + f * (g.rim_x(Side::right) - g.rim_x(Side::left));
      tr.trace_from_above(j, Ray2{Vec2(xu, g.rim_height), down}, rng, r);
      ASSERT_EQ(r.exits.size(), 1u);
      const int want_down = crossings(m, Vec2(x, 0.0), down);
      EXPECT_EQ(r.exits[0].k, want_down) << "from above, theta " << theta_deg << " x " << x;
      most = std::max({most, want_up, want_down});
    }
  EXPECT_GE(most, 5);  // lines that cross several grooves
}

// Whether a path met the surface while travelling in medium 2 after its first interaction.
bool met_again_from_below(Medium from, int k, std::uint64_t bits) {
  bool below = from == Medium::below;
  for (int j = 0; j + 1 < k && j < 64; ++j) {
    if ((bits >> j) & 1u) below = !below;
    if (below) return true;
  }
  return false;
}

// No absorption: exits + cut + bounce limit + vertex = 1 per ray to rounding, for both sides, GGX
// and Beckmann, smooth to rough, eta and its inverse, grazing light included; and light refracted
// into the material meets the surface again from below (the undersides of other grooves).
TEST(DielectricSurface, EnergyIsConservedAndRefractedLightIsTracedOn) {
  double worst = 0.0;
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.05, 0.5, 1.0})
      for (double eta : {1.5, 1.0 / 1.5, 2.4}) {
        const Microsurface m = surface_of(ndf, alpha, 500, 7);
        DielectricOptions opt;
        opt.eta = eta;
        opt.min_weight = 1e-9;
        const DielectricSurfaceTracer tr(m, opt);
        Rng rng(1, 0, 0);
        DielectricResult r;
        double again = 0.0;
        for (double theta_deg : {-89.99, -60.0, 0.0, 30.0, 75.0, 89.99}) {
          const double theta = deg(theta_deg);
          for_each_landing(m.grooves, theta, Sampling::random, 300, 2, 0, [&](const Groove& g, const Ray2& ray) {
            tr.trace_from_above(static_cast<int>(&g - m.grooves.data()), ray, rng, r);
            worst = std::max(worst, std::abs(r.total() - 1.0));
            for (const DielectricExit& e : r.exits) {
              ASSERT_TRUE(std::isfinite(e.dir.x()) && std::isfinite(e.dir.y()) && std::isfinite(e.weight));
              if (met_again_from_below(Medium::above, e.k, e.path)) again += e.weight;
            }
          });
          for (int j = 0; j < 300; ++j) {
            tr.trace_from_below(500.0 * (j + 0.5) / 300.0, direction_at(theta), rng, r);
            worst = std::max(worst, std::abs(r.total() - 1.0));
            for (const DielectricExit& e : r.exits)
              ASSERT_TRUE(std::isfinite(e.dir.x()) && std::isfinite(e.dir.y()) && std::isfinite(e.weight));
          }
        }
        if (alpha >= 1.0 && eta > 1.0) {
          EXPECT_GT(again, 0.0) << "alpha " << alpha << " eta " << eta;
        }
      }
  EXPECT_LT(worst, 1e-13);
}

// Random branching samples what splitting weighs, on a rough surface, from both sides: chi-square
// over (side, k, exit-angle bin) and over path signatures, fixed seeds, p > 1e-4 (each ray's count
// is a sum of independent Bernoulli draws, at most binomially spread: a conservative test). The
// broken variant (split at eta 1.6 against random at 1.5) must fail with p < 1e-9.
struct Cells {
  std::vector<double> expected;
  std::vector<std::int64_t> observed;
};
test_stats::ChiSquare chi_square(const Cells& c) {
  std::vector<double> edges(c.expected.size() + 1);
  for (std::size_t i = 0; i < edges.size(); ++i) edges[i] = static_cast<double>(i);
  return test_stats::chi_square_gof(edges, c.expected, c.observed);
}
std::pair<Cells, Cells> split_against_random(const Microsurface& m, double theta, Medium from, double eta_split,
                                             long n) {
  DielectricOptions os;  // paths cut below 1e-12 (the default): at most 1e-12 of a ray per cut
  os.eta = eta_split;
  DielectricOptions orand;
  orand.eta = 1.5;
  orand.branching = Branching::random;
  const DielectricSurfaceTracer ts(m, os), tr(m, orand);
  const int bins = 30;
  DielectricTally split(bins), random(bins);
  DielectricResult r;
  Rng unused(0, 0, 0);
  long j = 0;
  auto one = [&](int groove, const Ray2& ray, double x_below) {
    Rng rng(2026, 33, static_cast<std::uint64_t>(j++));
    if (from == Medium::above) {
      split.add(ts.trace_from_above(groove, ray, unused, r));
      random.add(tr.trace_from_above(groove, ray, rng, r));
    } else {
      split.add(ts.trace_from_below(x_below, direction_at(theta), unused, r));
      random.add(tr.trace_from_below(x_below, direction_at(theta), rng, r));
    }
  };
  if (from == Medium::above) {
    for_each_landing(m.grooves, theta, Sampling::stratified, n, 0, 0,
                     [&](const Groove& g, const Ray2& ray) { one(static_cast<int>(&g - m.grooves.data()), ray, 0.0); });
  } else {
    const double G = static_cast<double>(m.grooves.size());
    for (long q = 0; q < n; ++q) one(0, Ray2{}, G * (static_cast<double>(q) + 0.5) / static_cast<double>(n));
  }
  std::pair<Cells, Cells> c;
  for (Medium side : {Medium::above, Medium::below}) {
    for (int k = 0; k <= std::max(split.max_k(side), random.max_k(side)); ++k) {
      const std::vector<double> a = split.histogram(side, k), b = random.histogram(side, k);
      for (int i = 0; i < bins; ++i) {
        c.first.expected.push_back(a[i]);
        c.first.observed.push_back(std::llround(b[i]));
      }
    }
    std::map<std::pair<int, std::uint64_t>, std::pair<double, double>> paths;
    for (const auto& [key, w] : split.by_path(side)) paths[key].first += w;
    for (const auto& [key, w] : random.by_path(side)) paths[key].second += w;
    for (const auto& [key, ew] : paths) {
      c.second.expected.push_back(ew.first);
      c.second.observed.push_back(std::llround(ew.second));
    }
  }
  return c;
}

TEST(DielectricSurface, SplittingAndRandomBranchingAgreeInDistribution) {
  const Microsurface m = surface_of(NdfKind::ggx, 0.7, 2000, 21);
  for (Medium from : {Medium::above, Medium::below})
    for (double theta_deg : {10.0, 60.0}) {
      const std::string where = std::string("from ") + medium_name(from) + " theta " + std::to_string(theta_deg);
      const auto c = split_against_random(m, deg(theta_deg), from, 1.5, 20000);
      const auto wrong = split_against_random(m, deg(theta_deg), from, 1.6, 20000);
      for (int set = 0; set < 2; ++set) {
        const char* what = set ? " by path" : " by angle";
        const test_stats::ChiSquare cs = chi_square(set ? c.second : c.first);
        EXPECT_GT(cs.p, 1e-4) << where << what << " chi2 " << cs.stat << " dof " << cs.dof << "\n" << cs.table;
        EXPECT_GE(cs.dof, 5) << where << what;
        const test_stats::ChiSquare cw = chi_square(set ? wrong.second : wrong.first);
        EXPECT_LT(cw.p, 1e-9) << "the broken variant passed: " << where << what;
      }
    }
}

TEST(DielectricSurface, BadInputIsRefused) {
  const Microsurface m = surface_of(NdfKind::ggx, 0.5, 10, 1);
  DielectricOptions o;
  o.eta = std::nan("");
  try {
    DielectricSurfaceTracer tr(m, o);
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "eta = nan is out of range (0, inf)");
  }
  const DielectricSurfaceTracer tr(m, DielectricOptions{});
  Rng rng(0, 0, 0);
  DielectricResult r;
  EXPECT_THROW(tr.trace_from_below(0.5, Vec2(0.0, -1.0), rng, r), std::invalid_argument);
  EXPECT_THROW(tr.trace_from_above(0, Ray2{Vec2(0.0, m.grooves[0].rim_height), Vec2(0.0, 1.0)}, rng, r),
               std::invalid_argument);
}

}  // namespace
}  // namespace vgroove::sim
