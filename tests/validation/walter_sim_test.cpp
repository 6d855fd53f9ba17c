// Walter et al. 2007 (analytic/walter.h, flatland) against the exact dielectric tracer on a
// procedural V-groove surface (sim/dielectric_microsurface.h): the single-scattering model against
// the traced exits with exactly one interaction (k = 1: signature R above, T below for light from
// above). The two sides share no code: the model integrates D2 over facet orientations, the tracer
// refracts rays at facets drawn from sim::sample_theta_m (random branching: every ray is one exit).
//
// Noise. A cell c (side, exit-angle bin) receives the fraction q_c of the rays that land on a
// groove; over a surface of G independent grooves and N rays landing uniformly,
//   Var(o_c) <= N p_c (1 + m N / G),
// where m bounds how many grooves' draws one ray's k = 1 outcome depends on: m = 1 for reflection
// (the ray stays in its groove), m = 3 for transmission (its groove and the ridge on either side;
// the covariance of a sum of m-dependent terms is at most (2m - 1)... taken as m = 3 here, an upper
// bound checked by X^2 / dof < 1 on the matching cases). X^2 over cells pooled to N p_c >= 5 is
// then at most chi-square with (cells - 1) dof; a case passes at p > 1e-4.
#include "vgroove/analytic/walter.h"
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/sim/dielectric_tally.h"
#include "vgroove/sim/microsurface.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove {
namespace {

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

struct Traced {
  sim::DielectricTally tally;
  double seconds = 0.0;
};

// N rays of light from `from` at theta_i (each side's own angle convention, sim::exit_angle), random
// branching, on a surface of G grooves.
Traced trace(const sim::Microsurface& m, double eta, double theta_i, sim::Medium from, std::int64_t n, int bins,
             std::uint64_t seed) {
  sim::DielectricOptions opt;
  opt.eta = eta;
  opt.branching = sim::Branching::random;
  const sim::DielectricSurfaceTracer tr(m, opt);
  Traced t{sim::DielectricTally(bins)};
  sim::DielectricResult r;
  const auto t0 = std::chrono::steady_clock::now();
  if (from == sim::Medium::above) {
    const std::int64_t chunks = (n + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
    for (std::int64_t c = 0; c < chunks; ++c) {
      sim::Rng rng(seed, 0x6272616e6368ULL, static_cast<std::uint64_t>(c));  // "branch"
      sim::for_each_landing(m.grooves, theta_i, sim::Sampling::random, n, seed, c,
                            [&](const sim::Groove& g, const sim::Ray2& ray) {
                              t.tally.add(tr.trace_from_above(static_cast<int>(&g - m.grooves.data()), ray, rng, r));
                            });
    }
  } else {
    sim::Rng pos(seed, 0x706f73ULL, 0), rng(seed, 0x6272616e6368ULL, 0);
    const double G = static_cast<double>(m.grooves.size());
    const sim::Vec2 up = sim::direction_at(theta_i);
    for (std::int64_t q = 0; q < n; ++q) t.tally.add(tr.trace_from_below(G * pos.uniform(), up, rng, r));
  }
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return t;
}

// The model's share of the incident flux in each of `bins` equal exit-angle bins over (-pi/2, pi/2):
// int_bin f(theta) cos(theta) d theta, tanh-sinh on 8 pieces per bin (f has kinks).
std::vector<double> binned(const std::function<double(double)>& f, int bins) {
  std::vector<double> p(static_cast<std::size_t>(bins));
  const double w = kPi / bins;
  for (int b = 0; b < bins; ++b) {
    double s = 0.0;
    for (int q = 0; q < 8; ++q) {
      const double lo = -0.5 * kPi + b * w + q * w / 8.0;
      s += test_stats::tanh_sinh([&](double t) { return f(t) * std::cos(t); }, lo, lo + w / 8.0, 1.0 / 16.0);
    }
    p[static_cast<std::size_t>(b)] = s;
  }
  return p;
}

struct Fit {
  double stat = 0.0;
  int dof = 0;
  double p = 1.0;
  double model = 0.0, traced = 0.0;  // hemispherical shares
  std::string table;
};

// Pooled, inflated chi-square (header comment) of the traced k = 1 histogram against N p_c.
Fit compare(const std::vector<double>& p, const std::vector<double>& hist, double n, double inflate) {
  Fit f;
  std::ostringstream os;
  double e = 0.0, o = 0.0;
  int cells = 0;
  for (std::size_t b = 0; b < p.size(); ++b) {
    f.model += p[b];
    f.traced += hist[b] / n;
    e += n * p[b];
    o += hist[b];
    if (e >= 5.0 || b + 1 == p.size()) {
      if (e > 0.0) {
        f.stat += (o - e) * (o - e) / (e * inflate);
        ++cells;
        if (std::abs(o - e) > 3.0 * std::sqrt(e * inflate))
          os << "  up to bin " << b << ": expected " << e << ", observed " << o << "\n";
      }
      e = o = 0.0;
    }
  }
  f.dof = std::max(1, cells - 1);
  f.p = test_stats::gamma_q(0.5 * f.dof, 0.5 * f.stat);
  f.table = os.str();
  return f;
}

sim::Microsurface surface(sim::NdfKind ndf, double alpha, int grooves, std::uint64_t seed) {
  sim::MicrosurfaceOptions o;
  o.ndf = ndf;
  o.alpha = alpha;
  o.grooves = grooves;
  o.seed = seed;
  return sim::make_microsurface(o);
}

TEST(WalterSimLong, Explore) {
  const int bins = 90, G = 200000;
  const std::int64_t N = 400000;
  struct C { sim::NdfKind sn; analytic::NdfKind an; double alpha, eta, ti; sim::Medium from; };
  std::vector<C> cs;
  for (double alpha : {0.1, 1.0})
    for (double eta : {1.5, 2.4})
      for (double ti : {0.0, 45.0, 80.0}) cs.push_back({sim::NdfKind::beckmann, analytic::NdfKind::beckmann, alpha, eta, ti, sim::Medium::below});
  for (double ti : {0.0, 45.0, 80.0}) cs.push_back({sim::NdfKind::beckmann, analytic::NdfKind::beckmann, 1.0, 2.4, ti, sim::Medium::above});
  for (double ti : {0.0}) cs.push_back({sim::NdfKind::ggx, analytic::NdfKind::ggx, 1.0, 1.5, ti, sim::Medium::above});
  for (const C& c : cs) {
        const sim::Microsurface m = surface(c.sn, c.alpha, G, 7);
        const Traced t = trace(m, c.eta, deg(c.ti), c.from, N, bins, 3);
        const double n = static_cast<double>(N);
        const bool above = c.from == sim::Medium::above;
        const double er = above ? c.eta : 1.0 / c.eta;
        const sim::Medium same = c.from, other = above ? sim::Medium::below : sim::Medium::above;
        for (analytic::Masking g :
             {analytic::Masking::vcavity, analytic::Masking::smith_separable, analytic::Masking::smith_correlated}) {
          const auto pr = binned(
              [&](double o) { return analytic::walter_brdf2(deg(c.ti), o, c.an, c.alpha, er, g); }, bins);
          const auto pt = binned(
              [&](double o) { return analytic::walter_btdf2(deg(c.ti), o, c.an, c.alpha, er, g); }, bins);
          const Fit fr = compare(pr, t.tally.histogram(same, 1), n, 1.0 + n / G);
          const Fit ft = compare(pt, t.tally.histogram(other, 1), n, 1.0 + 3.0 * n / G);
          std::printf("%s %s a=%.2f eta=%.3f ti=%4.0f %-16s R model %.5f traced %.5f X2/dof %.2f | T model %.5f traced %.5f X2/dof %.2f  (%.2fs)\n",
                      above ? "above" : "below", analytic::ndf_name(c.an), c.alpha, c.eta, c.ti, analytic::masking_name(g), fr.model, fr.traced, fr.stat / fr.dof, ft.model,
                      ft.traced, ft.stat / ft.dof, t.seconds);
        }
      }
}

}  // namespace
}  // namespace vgroove
