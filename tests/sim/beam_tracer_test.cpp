// Tests of sim::BeamTracer: it must give what sim::trace gives, bit for bit, for every ray of
// the beam (bounce count, termination, facet hit first, exit direction) and show the observer
// the same reflections in the same order, ray by ray and in its batch trace (blocks of rays,
// vectorized first hits): the validation's Table 1 figures rest on it.
//
// The rays cover the hard corners: narrow grooves (the reflection table's end and the loop past
// it), grazing beams (a beam more grazing than a facet, where both facets are tested), rays
// exactly through the apex and the rims, rays outside the opening, and small bounce limits.
#include "vgroove/sim/beam.h"
#include "vgroove/sim/tracer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove::sim {
namespace {

double deg(double d) { return d * std::numbers::pi / 180.0; }

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Records every reflection the tracer reports.
struct Recorder {
  struct Bounce {
    Side side;
    double dx, dy;
  };
  std::vector<Bounce> seen;
  void on_bounce(Side s, const Vec2& d, const Facet&) { seen.push_back({s, d.x(), d.y()}); }
};

// Positions on the rim line worth tracing: stratified across a band wider than the opening
// (some rays blocked), the rims, the line through the apex, and their floating-point neighbours.
std::vector<double> positions(const Groove& g, const Vec2& dir, long n) {
  const double lo = g.rim_x(Side::left), hi = g.rim_x(Side::right), w = hi - lo;
  std::vector<double> x;
  for (long j = 0; j < n; ++j)
    x.push_back(lo - 0.05 * w + 1.1 * w * (static_cast<double>(j) + 0.5) / static_cast<double>(n));
  const double apex_x = g.rim_height * dir.x() / dir.y();  // (x, h) + t dir passes through (0, 0)
  for (double v : {lo, hi, apex_x, 0.0}) {
    x.push_back(v);
    x.push_back(std::nextafter(v, -INFINITY));
    x.push_back(std::nextafter(v, INFINITY));
  }
  // The rays whose first reflection, off facet f, passes through the other facet's rim: traced
  // back from that rim along the reflected direction to facet f's line, then along the beam to
  // the rim line. Rounding puts the boundary within a few ulps; 32 either side catch the ties of
  // the "leaves after one reflection" test in some beams.
  for (int f = 0; f < 2; ++f) {
    const Facet& on = g.facet[f];
    const Vec2 rim_o = g.facet[1 - f].rim(), d1 = on.reflect(dir);
    const double den = cross(d1, on.edge);
    if (den == 0.0) continue;
    const Vec2 q = rim_o - (cross(rim_o, on.edge) / den) * d1;
    double v = q.x() - (q.y() - g.rim_height) / dir.y() * dir.x();
    if (!std::isfinite(v)) continue;
    for (int u = 0; u < 32; ++u) v = std::nextafter(v, -INFINITY);
    for (int u = 0; u <= 64; ++u, v = std::nextafter(v, INFINITY)) x.push_back(v);
  }
  return x;
}

std::string where(const Groove& g, const Vec2& dir, double x, int max_bounces) {
  std::ostringstream o;
  o.precision(17);
  o << "facet edges (" << g.facet[0].edge.transpose() << ") (" << g.facet[1].edge.transpose() << "), dir ("
    << dir.transpose() << "), x " << x << ", max_bounces " << max_bounces;
  return o.str();
}

// Compares BeamTracer with sim::trace on every position; adds the rays compared to `compared`.
void expect_identical(const Groove& g, double theta_i, int max_bounces, long n, long& compared) {
  const Vec2 dir = beam_direction(theta_i);
  const TraceOptions opt{max_bounces};
  const BeamTracer beam(g, dir, opt);
  const std::vector<double> xs = positions(g, dir, n);
  // The batch trace of all positions at once, its observer's calls kept in order.
  std::vector<TraceResult> batch(xs.size());
  Recorder rbatch;
  beam.trace(xs.data(), static_cast<long>(xs.size()), batch.data(), rbatch);
  std::size_t next_batch_bounce = 0;
  for (std::size_t j = 0; j < xs.size(); ++j) {
    const double x = xs[j];
    Recorder ra, rb;
    const TraceResult a = trace(g, beam_ray(g, dir, x), opt, ra);
    const TraceResult b = beam.trace(x, rb);
    const std::string at = where(g, dir, x, max_bounces);
    // The batch gives the single-ray results and reflections, ray after ray.
    const TraceResult& c = batch[j];
    ASSERT_TRUE(a.how == c.how && a.bounces == c.bounces && a.first == c.first &&
                same_bits(a.exit_dir.x(), c.exit_dir.x()) && same_bits(a.exit_dir.y(), c.exit_dir.y()))
        << at << ": batch result differs";
    for (std::size_t k = 0; k < ra.seen.size(); ++k, ++next_batch_bounce) {
      ASSERT_LT(next_batch_bounce, rbatch.seen.size()) << at;
      const Recorder::Bounce& e = rbatch.seen[next_batch_bounce];
      ASSERT_TRUE(e.side == ra.seen[k].side && same_bits(e.dx, ra.seen[k].dx) && same_bits(e.dy, ra.seen[k].dy))
          << at << ", batch reflection " << k;
    }
    ASSERT_EQ(a.how, b.how) << at;
    ASSERT_EQ(a.bounces, b.bounces) << at;
    ASSERT_EQ(a.first, b.first) << at;
    ASSERT_TRUE(same_bits(a.exit_dir.x(), b.exit_dir.x()) && same_bits(a.exit_dir.y(), b.exit_dir.y()))
        << at << ": exit " << a.exit_dir.transpose() << " vs " << b.exit_dir.transpose();
    ASSERT_EQ(ra.seen.size(), rb.seen.size()) << at;
    for (std::size_t k = 0; k < ra.seen.size(); ++k) {
      ASSERT_EQ(ra.seen[k].side, rb.seen[k].side) << at << ", reflection " << k;
      ASSERT_TRUE(same_bits(ra.seen[k].dx, rb.seen[k].dx) && same_bits(ra.seen[k].dy, rb.seen[k].dy))
          << at << ", reflection " << k;
    }
    ++compared;
  }
  EXPECT_EQ(next_batch_bounce, rbatch.seen.size());
}

const double kThetaIDeg[] = {-89.9, -75.0, -40.0, -20.0, -1e-9, 0.0, 10.0, 20.0, 45.0, 60.0, 80.0, 89.9};

TEST(BeamTracer, SymmetricGroovesMatchTraceBitForBit) {
  long compared = 0;
  for (double theta_v : {0.05, 0.5, 1.0, 5.0, 30.0, 60.0, 90.0, 120.0, 150.0, 179.0, 180.0}) {
    const Groove g = make_symmetric_groove(deg(theta_v));
    for (double ti : kThetaIDeg)
      expect_identical(g, deg(ti), TraceOptions{}.max_bounces, theta_v < 1.0 ? 101 : 997, compared);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(compared, 100000);
}

TEST(BeamTracer, NonsymmetricGroovesMatchTraceBitForBit) {
  long compared = 0;
  const double facets[][2] = {{-10.0, 80.0}, {-45.0, 30.0}, {-89.0, 2.0}, {-5.0, 5.5}, {-60.0, 60.0}, {0.0, 45.0}};
  for (const auto& lr : facets) {
    const Groove g = make_nonsymmetric_groove(deg(lr[0]), deg(lr[1]));
    for (double ti : kThetaIDeg) expect_identical(g, deg(ti), TraceOptions{}.max_bounces, 997, compared);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(compared, 50000);
}

// The bounce limit inside the table, at its end and past it (a 0.05 deg groove makes ~3600
// reflections; the table holds at most kMaxTable).
TEST(BeamTracer, BounceLimitsMatchTrace) {
  long compared = 0;
  for (int max_bounces : {0, 1, 2, 3, 50, 3000}) {
    for (double theta_v : {0.05, 1.0, 30.0, 150.0}) {
      const Groove g = make_symmetric_groove(deg(theta_v));
      for (double ti : {0.0, 20.0, 89.9}) expect_identical(g, deg(ti), max_bounces, 211, compared);
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(compared, 10000);
}

// sim::trace_beam hands over ray j's result for sample_position's ray j, for both samplings and
// a count that leaves a partial last block.
TEST(BeamTracer, TraceBeamGivesEachPlacedRaysResultInOrder) {
  const Groove g = make_symmetric_groove(deg(37.0));
  const Vec2 dir = beam_direction(deg(25.0));
  const BeamTracer beam(g, dir);
  const Interval iv = aimed_at(g, deg(25.0), Side::right);
  constexpr long n = 3 * BeamTracer::kBlock + 17;
  for (Sampling sampling : {Sampling::stratified, Sampling::random}) {
    Rng a(9, 1, 2), b(9, 1, 2);
    long next = 0;
    trace_beam(beam, sampling, iv, n, a, [&](long j, const TraceResult& r) {
      ASSERT_EQ(j, next++);
      const TraceResult e = trace(g, beam_ray(g, dir, sample_position(sampling, iv, j, n, b)));
      ASSERT_TRUE(r.how == e.how && r.bounces == e.bounces && r.first == e.first &&
                  same_bits(r.exit_dir.x(), e.exit_dir.x()) && same_bits(r.exit_dir.y(), e.exit_dir.y()))
          << sampling_name(sampling) << " ray " << j;
    });
    EXPECT_EQ(next, n) << sampling_name(sampling);
  }
}

}  // namespace
}  // namespace vgroove::sim
