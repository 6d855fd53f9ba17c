// Walter et al. 2007 (analytic/walter.h, flatland) against the exact dielectric tracer on a
// procedural V-groove surface (sim/dielectric_microsurface.h): the single-scattering model against
// the traced exits with exactly one interaction (k = 1: signature R above, T below for light from
// above). The two sides share no code: the model integrates D2 over facet orientations, the tracer
// refracts rays at facets drawn from sim::sample_theta_m (random branching: every ray is one exit).
//
// Noise. A cell c (side, exit-angle bin) receives the share a_g of the rays landing on groove g;
// over a surface of G independent grooves and N rays landing uniformly (q_c = sum_g a_g / G),
//   Var(o_c) = N E[q_c (1 - q_c)] + N^2 Var(q_c) <= N p_c (1 + (2m - 1) N / G),
// where a_g depends on the draws of m consecutive grooves (Cov(a_g, a_h) = 0 beyond, each covariance
// at most (Var a_g + Var a_h) / 2 and Var a_g <= E[a_g] = p_c): m = 1 for the reflection from above
// (the ray stays in its groove), m = 3 for transmission (its groove and the ridge on either side; a
// refracted ray that passes under more grooves before leaving is rare at these roughnesses, and the
// matching cases' X^2 / dof of 0.03-0.5 bear the bound out). X^2 over cells pooled to N p_c >= 5 is
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

// One case: the surface, the light and the traced tally, and the model's k = 1 lobes on both sides.
struct Case {
  sim::NdfKind ndf;
  double alpha, eta, theta_i_deg;
  sim::Medium from;
};

std::string name(const Case& c) {
  std::ostringstream os;
  os << (c.ndf == sim::NdfKind::ggx ? "ggx" : "beckmann") << " alpha " << c.alpha << " eta " << c.eta << " theta_i "
     << c.theta_i_deg << " from " << sim::medium_name(c.from);
  return os.str();
}

analytic::NdfKind analytic_ndf(sim::NdfKind k) {
  return k == sim::NdfKind::ggx ? analytic::NdfKind::ggx : analytic::NdfKind::beckmann;
}

struct CaseRun {
  Traced t;
  double n = 0.0;
  double inflate_r = 1.0, inflate_t = 1.0;
};

CaseRun run(const Case& c, int grooves, std::int64_t rays, int bins) {
  const sim::Microsurface m = surface(c.ndf, c.alpha, grooves, 7);
  CaseRun r{trace(m, c.eta, deg(c.theta_i_deg), c.from, rays, bins, 3)};
  r.n = static_cast<double>(rays);
  r.inflate_r = 1.0 + r.n / grooves;
  r.inflate_t = 1.0 + 5.0 * r.n / grooves;
  return r;
}

// The model in the frame of the light's side (analytic/walter.h): eta relative to that side, angles
// kept (sim::exit_angle's conventions are the point reflection of each other).
double eta_rel(const Case& c) { return c.from == sim::Medium::above ? c.eta : 1.0 / c.eta; }
sim::Medium other(sim::Medium m) { return m == sim::Medium::above ? sim::Medium::below : sim::Medium::above; }

Fit fit_reflection(const Case& c, const CaseRun& r, analytic::MaskingKind g, int bins, double eta_model) {
  const auto p = binned(
      [&](double o) {
        return analytic::walter_brdf2(deg(c.theta_i_deg), o, analytic_ndf(c.ndf), c.alpha, eta_model, g);
      },
      bins);
  return compare(p, r.t.tally.histogram(c.from, 1), r.n, r.inflate_r);
}

Fit fit_transmission(const Case& c, const CaseRun& r, analytic::MaskingKind g, int bins, double scale = 1.0) {
  const auto p = binned(
      [&](double o) {
        return scale * analytic::walter_btdf2(deg(c.theta_i_deg), o, analytic_ndf(c.ndf), c.alpha, eta_rel(c), g);
      },
      bins);
  return compare(p, r.t.tally.histogram(other(c.from), 1), r.n, r.inflate_t);
}

constexpr int kBins = 90;
constexpr int kGrooves = 100000;
constexpr std::int64_t kRays = 200000;

// Light from above: every ray stays in its groove until it leaves upwards, and shadowing and masking
// both cut a facet from its apex up, so the V-cavity G is exact for the k = 1 reflection (Lee et al.
// 2018, Eq. 2-3); with the exact Fresnel at the facet's angle the flatland Walter BRDF is the traced
// k = 1 R lobe, for eta above and below 1 (TIR at the facets) and at grazing light. Broken variant:
// the model with eta 10% off must fail (p < 1e-9) on the same tallies.
TEST(WalterSim, ReflectionFromAboveMatchesTheTracer) {
  const Case cases[] = {{sim::NdfKind::ggx, 0.1, 1.5, 0.0, sim::Medium::above},
                        {sim::NdfKind::ggx, 0.3, 1.5, 30.0, sim::Medium::above},
                        {sim::NdfKind::ggx, 0.6, 1.0 / 1.5, 60.0, sim::Medium::above},
                        {sim::NdfKind::beckmann, 1.0, 2.4, 80.0, sim::Medium::above}};
  for (const Case& c : cases) {
    const CaseRun r = run(c, kGrooves, kRays, kBins);
    const Fit f = fit_reflection(c, r, analytic::MaskingKind::vcavity, kBins, c.eta);
    const Fit broken = fit_reflection(c, r, analytic::MaskingKind::vcavity, kBins, 1.1 * c.eta);
    std::printf("%s: R model %.5f traced %.5f (X2 %.1f / %d dof, p %.3g; eta +10%%: X2 %.0f); %lld rays %.2f s\n",
                name(c).c_str(), f.model, f.traced, f.stat, f.dof, f.p, broken.stat, static_cast<long long>(kRays),
                r.t.seconds);
    EXPECT_GT(f.p, 1e-4) << name(c) << "\n" << f.table;
    EXPECT_GE(f.dof, 10) << name(c);
    EXPECT_LT(broken.p, 1e-9) << "the broken variant passed: " << name(c);
  }
}

// The eta factor, settled by the traced flux. At alpha = 0.1 masking is small (Smith and V-cavity
// agree within noise here), so the share of the flux transmitted with k = 1 tests the BTDF's
// normalization: the flux form with n_o^1 (flatland Walter Eq. 21) matches the traced T lobe per bin,
// from both sides; the article's extra factor n_v / n_l (its eta_v^2 / eta_l^2 in flatland) and its
// inverse miss by hundreds of sigma on the same tallies (ERRATA W1).
TEST(WalterSim, TransmittedFluxSettlesEta) {
  const Case cases[] = {{sim::NdfKind::ggx, 0.1, 1.5, 0.0, sim::Medium::above},
                        {sim::NdfKind::ggx, 0.1, 1.5, 30.0, sim::Medium::above},
                        {sim::NdfKind::ggx, 0.1, 2.4, 30.0, sim::Medium::above},
                        {sim::NdfKind::beckmann, 0.1, 1.5, 0.0, sim::Medium::below},
                        {sim::NdfKind::beckmann, 0.1, 2.4, 20.0, sim::Medium::below}};
  for (const Case& c : cases) {
    const CaseRun r = run(c, kGrooves, kRays, kBins);
    const Fit f = fit_transmission(c, r, analytic::MaskingKind::smith_separable, kBins);
    const double nv_nl = eta_rel(c);  // n_exit / n_light
    const Fit times = fit_transmission(c, r, analytic::MaskingKind::smith_separable, kBins, nv_nl);
    const Fit over = fit_transmission(c, r, analytic::MaskingKind::smith_separable, kBins, 1.0 / nv_nl);
    std::printf(
        "%s: T model %.5f traced %.5f (X2 %.1f / %d dof, p %.3g); x n_v/n_l: %.5f (X2 %.0f); / n_v/n_l: %.5f "
        "(X2 %.0f); %lld rays %.2f s\n",
        name(c).c_str(), f.model, f.traced, f.stat, f.dof, f.p, times.model, times.stat, over.model, over.stat,
        static_cast<long long>(kRays), r.t.seconds);
    EXPECT_GT(f.p, 1e-4) << name(c) << "\n" << f.table;
    EXPECT_GE(f.dof, 5) << name(c);
    EXPECT_LT(times.p, 1e-9) << "x n_v/n_l passed: " << name(c);
    EXPECT_LT(over.p, 1e-9) << "/ n_v/n_l passed: " << name(c);
  }
}

// What the tracer says about G for transmission (reported, not tuned): light from above at normal
// incidence on a rough surface (GGX, alpha 0.6, eta 1.5), the refracted rays pass under the ridges,
// whose apexes lie at independent depths: Smith's G matches the traced k = 1 T lobe within noise, the
// V-cavity G does not (it masks as if the ridges were a mirrored V-cavity: measured 0.6% of the flux
// too little, -3.5 sigma, X2 198 on 44 dof); at 60 deg both miss (V-cavity +10.4% of the flux, +31
// sigma; Smith -0.4% in total, -1.1 sigma, but its lobe's shape off, X2 1527 on 29 dof). The grid of
// misses: WalterSimLong.MissTable, docs/derivations/walter.md.
TEST(WalterSim, TransmissionMissesAreMeasured) {
  const Case normal{sim::NdfKind::ggx, 0.6, 1.5, 0.0, sim::Medium::above};
  const Case oblique{sim::NdfKind::ggx, 0.6, 1.5, 60.0, sim::Medium::above};
  const CaseRun rn = run(normal, kGrooves, kRays, kBins), ro = run(oblique, kGrooves, kRays, kBins);
  for (const auto* cr : {&normal, &oblique}) {
    const CaseRun& r = cr == &normal ? rn : ro;
    for (analytic::MaskingKind g : {analytic::MaskingKind::vcavity, analytic::MaskingKind::smith_separable}) {
      const Fit f = fit_transmission(*cr, r, g, kBins);
      const double sigma = std::sqrt(f.traced * (1 - f.traced) * r.inflate_t / r.n);
      std::printf("%s, %s: T model %.5f traced %.5f (%+.2f sigma), X2 %.1f / %d dof\n", name(*cr).c_str(),
                  analytic::masking_name(g), f.model, f.traced, (f.model - f.traced) / sigma, f.stat, f.dof);
      const bool matches = cr == &normal && g == analytic::MaskingKind::smith_separable;
      if (matches) {
        EXPECT_GT(f.p, 1e-4) << name(*cr) << " " << analytic::masking_name(g) << "\n" << f.table;
      } else {
        EXPECT_LT(f.p, 1e-9) << name(*cr) << " " << analytic::masking_name(g);
      }
    }
  }
}

// The grid behind docs/derivations/walter.md's table: per case and masking, the k = 1 R and T shares
// of model and tracer, their difference in sigma, and X^2 / dof over the bins. Asserts what holds on the
// whole grid: the V-cavity reflection from above matches per bin (p > 1e-6: 64 cases, a false alarm
// below 1e-4); the transmission misses are printed (docs/derivations/walter.md).
TEST(WalterSimLong, MissTable) {
  const int grooves = 500000;
  const std::int64_t rays = 1000000;
  for (sim::NdfKind ndf : {sim::NdfKind::ggx, sim::NdfKind::beckmann})
    for (sim::Medium from : {sim::Medium::above, sim::Medium::below})
      for (double alpha : {0.1, 0.3, 0.6, 1.0})
        for (double eta : {1.5, 2.4})
          for (double ti : {0.0, 30.0, 60.0, 80.0}) {
            const Case c{ndf, alpha, eta, ti, from};
            const CaseRun r = run(c, grooves, rays, kBins);
            for (analytic::MaskingKind g : {analytic::MaskingKind::vcavity, analytic::MaskingKind::smith_separable,
                                            analytic::MaskingKind::smith_height_correlated}) {
              const Fit fr = fit_reflection(c, r, g, kBins, eta_rel(c));
              const Fit ft = fit_transmission(c, r, g, kBins);
              if (from == sim::Medium::above && g == analytic::MaskingKind::vcavity) {
                EXPECT_GT(fr.p, 1e-6) << name(c) << "\n" << fr.table;
              }
              auto sig = [&](const Fit& f, double inflate) {
                const double s = std::sqrt(std::max(f.traced * (1 - f.traced), 1.0 / r.n) * inflate / r.n);
                return (f.model - f.traced) / s;
              };
              std::printf("| %s | %s | %.5f | %.5f | %+.1f | %.2f | %.5f | %.5f | %+.1f | %.2f |\n", name(c).c_str(),
                          analytic::masking_name(g), fr.model, fr.traced, sig(fr, r.inflate_r), fr.stat / fr.dof,
                          ft.model, ft.traced, sig(ft, r.inflate_t), ft.stat / ft.dof);
            }
          }
}

// A diagnosis of the transmission miss from above (docs/derivations/walter.md), not a model: the
// V-cavity G1 is exact on the light's side (the peaks on one line), and the ridges below, whose apexes
// lie at independent depths, mask the refracted rays much as Smith's G1 says. Their product,
// G1v(i, h) G1smith(o), matches the traced k = 1 T lobe within noise for GGX, eta 1.5, alpha 0.3 and
// 0.6, theta_i 0 and 30 deg; at alpha 1, 80 deg it overestimates (measured +39%): both cut the lit
// facet near its peak, so shadowing and masking are correlated and the product is too large.
TEST(WalterSimLong, LightSideVcavityTimesFarSideSmith) {
  for (double alpha : {0.3, 0.6, 1.0})
    for (double ti : {0.0, 30.0, 60.0, 80.0}) {
      const Case c{sim::NdfKind::ggx, alpha, 1.5, ti, sim::Medium::above};
      const CaseRun r = run(c, kGrooves, kRays, kBins);
      const double t = deg(ti);
      const auto p = binned(
          [&](double o) {
            const double f = analytic::walter_btdf2(t, o, analytic::NdfKind::ggx, alpha, 1.5,
                                                    analytic::MaskingKind::smith_separable);
            if (f == 0.0) return 0.0;
            const double h = analytic::walter_half_angle_t2(t, o, 1.5);
            return f * analytic::G1_vcavity_inplane(t, h) * (1.0 + analytic::Lambda(analytic::NdfKind::ggx, t, alpha));
          },
          kBins);
      const Fit f = compare(p, r.t.tally.histogram(sim::Medium::below, 1), r.n, r.inflate_t);
      std::printf("%s, G1v(i) G1smith(o): T model %.5f traced %.5f (%+.2f%%), X2 %.1f / %d dof\n", name(c).c_str(),
                  f.model, f.traced, 100 * (f.model / f.traced - 1), f.stat, f.dof);
      if (alpha <= 0.6 && ti <= 30.0) {
        EXPECT_GT(f.p, 1e-4) << name(c) << "\n" << f.table;
      }
      if (alpha == 1.0 && ti == 80.0) {
        EXPECT_LT(f.p, 1e-9) << name(c);
      }
    }
}

}  // namespace
}  // namespace vgroove
