// The flatland dielectric Smith walk (analytic/smith_walk_flatland_dielectric.h) against exact
// tracing on random profiles (sim/dielectric_polyline.h, sim/random_profile.h), eta = 1.5, light
// from above and below. Per case: the energies leaving above and below (reflected or transmitted
// by the side the light comes from), their k = 1, 2, 3+ parts, and the joint lobe over (exit side, k row, exit-angle
// bin), traced (the mean over `realizations` profiles, random branching, every ray weight 1) against the walk.
//
// Noise: per cell, the traced mean's variance is the larger of the binomial one of its rays and
// the realizations' spread over R (profiles differ); the walk's is binomial. chi2 = sum over
// cells of (traced - walk)^2 / (var_t + var_w), cells with fewer than 25 combined expected counts
// pooled per side; p from chi2 with (cells - 1) degrees of freedom. z for energies likewise.
//
// What must hold, asserted: no ray lost (vertex hits and the interaction limit counted, and
// nil on these profiles); at normal incidence the first interaction sees the profile's own
// normals, fully visible on any height profile (G1(0) = 1), so the share refracted at the first
// interaction (the first path bit) is the same quadrature for the tracer and the walk (the
// realization spread covers a profile's own slope statistics); a walk with the Fresnel law's eta
// inverted is rejected by that quadrature (kept in the test as the broken variant). The walk's agreement beyond that is
// a measured result: the full grid (SmithWalkDielectricProfilesLong, ctest -L long) prints it per case and asserts
// nothing about it (the conductor walk misses random profiles too: README, "Beyond V-grooves").
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/smith_walk_flatland_dielectric.h"
#include "vgroove/sim/dielectric_polyline.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/profile_tally.h"
#include "vgroove/sim/random_profile.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace vgroove {
namespace {

using analytic::WalkMedium;
using sim::Medium;

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

struct Config {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.3, theta_deg = 0.0, eta = 1.5;
  Medium from = Medium::above;
  bool conductor = false;  // F = 1 in both (the conductor tracer and walk: the control)
  int realizations = 4, segments = 1 << 14;
  long rays = 50000;  // per realization
  long walks = 200000;
  int k_rows = 3;  // rows k = 1 .. k_rows, and one for k > k_rows
  int bins = 18;   // exit angle over [-90, 90] deg
  std::uint64_t seed = 1;
};

struct Counts {
  std::vector<double> cell;  // (side, row, bin) -> count
  double first_refracted = 0.0, lost = 0.0, n = 0.0;
};

int cell_of(const Config& c, int side, int k, double angle) {
  const int rows = c.k_rows + 1;
  const int row = std::min(k, rows) - 1;
  const int b = std::clamp(static_cast<int>(std::floor((angle + 0.5 * kPi) / (kPi / c.bins))), 0, c.bins - 1);
  return (side * rows + row) * c.bins + b;
}
int cells(const Config& c) { return 2 * (c.k_rows + 1) * c.bins; }

Counts trace_realization(const Config& c, int r) {
  sim::RandomProfileOptions po;
  po.ndf = c.ndf, po.alpha = c.alpha, po.segments = c.segments, po.samples_per_length = 16;
  po.seed = sim::splitmix64(c.seed * 1000003 + static_cast<std::uint64_t>(r));
  const sim::Polyline p = sim::make_random_profile(po);
  sim::DielectricOptions opt;
  opt.eta = c.eta, opt.branching = sim::Branching::random, opt.conductor_limit = c.conductor;
  const sim::DielectricPolylineTracer tr(p, opt);
  const sim::Vec2 dir =
      c.from == Medium::above ? sim::beam_direction(deg(c.theta_deg)) : sim::direction_at(deg(c.theta_deg));
  Counts out;
  out.cell.assign(static_cast<std::size_t>(cells(c)), 0.0);
  sim::DielectricResult res;
  const std::uint64_t key = static_cast<std::uint64_t>(c.theta_deg * 16) * 4 + static_cast<std::uint64_t>(c.from) * 2;
  for (long j = 0; j < c.rays; ++j) {
    sim::Rng rng(po.seed, key, static_cast<std::uint64_t>(j));
    tr.trace(sim::landing_x(p, sim::uniform_open(rng)), dir, c.from, rng, res);
    out.n += 1.0;
    if (res.exits.empty()) {
      out.lost += 1.0;
      continue;
    }
    const sim::DielectricExit& e = res.exits[0];
    out.first_refracted += static_cast<double>(e.path & 1u);
    ++out.cell[static_cast<std::size_t>(cell_of(c, static_cast<int>(e.side), e.k, sim::exit_angle(e)))];
  }
  return out;
}

template <class Law>
Counts walk(const Config& c, const Law& law) {
  analytic::DielectricWalkOptions opt;
  opt.eta = c.eta, opt.conductor_limit = c.conductor;
  Counts out;
  out.cell.assign(static_cast<std::size_t>(cells(c)), 0.0);
  sim::Rng rng(c.seed, 0x77616c6bULL,
               static_cast<std::uint64_t>(c.theta_deg * 16) * 2 + static_cast<std::uint64_t>(c.from));
  auto uniform = [&] { return sim::uniform_open(rng); };
  const WalkMedium from = c.from == Medium::above ? WalkMedium::above : WalkMedium::below;
  for (long j = 0; j < c.walks; ++j) {
    const analytic::FlatlandDielectricWalk w =
        analytic::smith_walk_flatland_dielectric(c.ndf, c.alpha, deg(c.theta_deg), from, opt, uniform, law);
    out.n += 1.0;
    if (!w.left) {
      out.lost += 1.0;
      continue;
    }
    out.first_refracted += static_cast<double>(w.path & 1u);
    ++out.cell[static_cast<std::size_t>(cell_of(c, static_cast<int>(w.side), w.k, w.theta_o))];
  }
  return out;
}

// A traced mean over realizations with its variance: max(binomial of all rays, spread / R).
struct Stat {
  double mean = 0.0, var = 0.0;
};
Stat traced_stat(const std::vector<std::vector<double>>& per_real, const std::vector<double>& n) {
  const double R = static_cast<double>(per_real.size());
  std::vector<double> f;
  double total_n = 0.0;
  for (std::size_t r = 0; r < per_real.size(); ++r) total_n += n[r];
  Stat s;
  for (std::size_t r = 0; r < per_real.size(); ++r) {
    double v = 0.0;
    for (double x : per_real[r]) v += x;
    f.push_back(v / n[r]);
    s.mean += v / n[r] / R;
  }
  double spread = 0.0;
  for (double x : f) spread += (x - s.mean) * (x - s.mean);
  spread = R > 1.0 ? spread / (R - 1.0) / R : 0.0;
  s.var = std::max(s.mean * (1.0 - s.mean) / total_n, spread);
  return s;
}

struct Comparison {
  double E_t[2] = {0, 0}, E_w[2] = {0, 0}, z_E[2] = {0, 0};
  double Ek_t[2][3] = {}, Ek_w[2][3] = {}, z_Ek[2][3] = {};
  double chi2 = 0.0, p = 1.0, worst_cell_z = 0.0;
  int dof = 0;
  double first_t = 0.0, first_w = 0.0, z_first = 0.0, first_exact = 0.0, z_first_t = 0.0, z_first_w = 0.0;
  double lost_t = 0.0, lost_w = 0.0;
  double rays = 0.0, walks = 0.0, trace_s = 0.0, walk_s = 0.0;
};

// The first interaction's refracted share at normal incidence: 1 - int D_v(m) F(cos m) dm, the
// view along the normal of the side the light comes from (the same from either side: the slopes'
// law is symmetric).
double first_refracted_exact(const Config& c) {
  const double eta_rel = c.from == Medium::above ? c.eta : 1.0 / c.eta;
  auto f = [&](double m) {
    return analytic::visible_normal_pdf(c.ndf, c.alpha, 0.0, m) *
           (1.0 - optics::fresnel_dielectric(std::cos(m), eta_rel));
  };
  double s = test_stats::tanh_sinh(f, -0.5 * kPi, 0.0) + test_stats::tanh_sinh(f, 0.0, 0.5 * kPi);
  if (eta_rel < 1.0) {  // split at the critical angle's normals
    const double mc = std::asin(eta_rel);
    s = test_stats::tanh_sinh(f, -0.5 * kPi, -mc) + test_stats::tanh_sinh(f, -mc, 0.0) +
        test_stats::tanh_sinh(f, 0.0, mc) + test_stats::tanh_sinh(f, mc, 0.5 * kPi);
  }
  return s;
}

// Set A (traced realizations) against set B (traced realizations, or one walk sample: its
// variance binomial).
Comparison compare_sets(const Config& c, const std::vector<Counts>& tr, const std::vector<Counts>& wb) {
  Comparison out;
  std::vector<double> n, nb;
  for (const Counts& t : tr) n.push_back(t.n), out.rays += t.n, out.lost_t += t.lost;
  for (const Counts& t : wb) nb.push_back(t.n), out.walks += t.n, out.lost_w += t.lost;
  // A statistic of a set of cells (a subset chosen by pred).
  auto stat_of = [&](auto pred) {
    std::vector<std::vector<double>> per(tr.size()), per_b(wb.size());
    for (int q = 0; q < cells(c); ++q) {
      if (!pred(q)) continue;
      for (std::size_t r = 0; r < tr.size(); ++r) per[r].push_back(tr[r].cell[static_cast<std::size_t>(q)]);
      for (std::size_t r = 0; r < wb.size(); ++r) per_b[r].push_back(wb[r].cell[static_cast<std::size_t>(q)]);
    }
    const Stat t = traced_stat(per, n), b = traced_stat(per_b, nb);
    return std::tuple<Stat, double, double>(t, b.mean, b.var);
  };
  auto z_of = [](const Stat& t, double pw, double vw) {
    const double v = t.var + vw;
    return v > 0.0 ? (t.mean - pw) / std::sqrt(v) : (t.mean == pw ? 0.0 : INFINITY);
  };
  const int rows = c.k_rows + 1, per_side = rows * c.bins;
  for (int side = 0; side < 2; ++side) {
    auto [t, pw, vw] = stat_of([&](int q) { return q / per_side == side; });
    out.E_t[side] = t.mean, out.E_w[side] = pw, out.z_E[side] = z_of(t, pw, vw);
    for (int k = 0; k < 3; ++k) {
      auto [tk, pk, vk] = stat_of([&](int q) {
        const int row = (q % per_side) / c.bins;
        return q / per_side == side && (k < 2 ? row == k : row >= 2);
      });
      out.Ek_t[side][k] = tk.mean, out.Ek_w[side][k] = pk, out.z_Ek[side][k] = z_of(tk, pk, vk);
    }
  }
  // The lobe's chi-square: cells with >= 25 expected counts of the smaller sample; the rest pooled
  // per side.
  const double n_min = std::min(out.rays, out.walks);
  std::vector<int> pooled[2];
  for (int q = 0; q < cells(c); ++q) {
    auto [t, pw, vw] = stat_of([&](int x) { return x == q; });
    if (0.5 * (t.mean + pw) * n_min < 25.0) {
      pooled[q / per_side].push_back(q);
      continue;
    }
    const double z = z_of(t, pw, vw);
    out.chi2 += z * z, ++out.dof;
    out.worst_cell_z = std::max(out.worst_cell_z, std::abs(z));
  }
  for (int side = 0; side < 2; ++side) {
    if (pooled[side].empty()) continue;
    auto [t, pw, vw] =
        stat_of([&](int x) { return std::find(pooled[side].begin(), pooled[side].end(), x) != pooled[side].end(); });
    if (0.5 * (t.mean + pw) * n_min < 25.0) continue;
    const double z = z_of(t, pw, vw);
    out.chi2 += z * z, ++out.dof;
  }
  out.dof = std::max(1, out.dof - 1);
  out.p = test_stats::gamma_q(0.5 * out.dof, 0.5 * out.chi2);
  // The first interaction.
  {
    std::vector<std::vector<double>> per, per_b;
    for (const Counts& t : tr) per.push_back({t.first_refracted});
    for (const Counts& t : wb) per_b.push_back({t.first_refracted});
    const Stat t = traced_stat(per, n), b = traced_stat(per_b, nb);
    const double pw = b.mean, vw = b.var;
    out.first_t = t.mean, out.first_w = pw, out.z_first = z_of(t, pw, vw);
    out.first_exact = first_refracted_exact(c);
    out.z_first_t = z_of(t, out.first_exact, 0.0);
    out.z_first_w = z_of(Stat{pw, vw}, out.first_exact, 0.0);
  }
  return out;
}

std::vector<Counts> trace_all(const Config& c) {
  std::vector<Counts> tr;
  for (int r = 0; r < c.realizations; ++r) tr.push_back(trace_realization(c, r));
  return tr;
}

// The traced profiles against the walk, timed.
template <class Law = analytic::DielectricFresnelLaw>
Comparison compare(const Config& c, const Law& law = Law{}) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const std::vector<Counts> tr = trace_all(c);
  const auto t1 = Clock::now();
  const std::vector<Counts> w = {walk(c, law)};
  const auto t2 = Clock::now();
  Comparison out = compare_sets(c, tr, w);
  out.trace_s = std::chrono::duration<double>(t1 - t0).count();
  out.walk_s = std::chrono::duration<double>(t2 - t1).count();
  return out;
}

void print_header() {
  std::printf(
      "ndf       alpha theta from  against   | E_above traced / B (z)     | E_below traced / B (z)     | k=1,2,3+ z "
      "(above; below)"
      "              | lobe chi2/dof (p), worst |z| | T@1st traced/walk/exact (z_t, z_w) | rays walks trace_s "
      "walk_s\n");
}
void print_row(const Config& c, const Comparison& r, const char* what = "walk") {
  std::printf(
      "%-9s %5.2f %5.1f %-5s %-9s | %.5f / %.5f (%6.1f) | %.5f / %.5f (%6.1f) | %5.1f %5.1f %5.1f; %5.1f %5.1f %5.1f | "
      "%8.1f/%3d "
      "(%.1e) %5.1f | %.5f/%.5f/%.5f (%4.1f, %4.1f) | %.0f %.0f %.2f %.2f\n",
      ndf_name(c.ndf), c.alpha, c.theta_deg, c.from == Medium::above ? "above" : "below", what, r.E_t[0], r.E_w[0],
      r.z_E[0], r.E_t[1], r.E_w[1], r.z_E[1], r.z_Ek[0][0], r.z_Ek[0][1], r.z_Ek[0][2], r.z_Ek[1][0], r.z_Ek[1][1],
      r.z_Ek[1][2], r.chi2, r.dof, r.p, r.worst_cell_z, r.first_t, r.first_w, r.first_exact, r.z_first_t, r.z_first_w,
      r.rays, r.walks, r.trace_s, r.walk_s);
}

// Fresnel with eta inverted where Snell transmits: a deliberately wrong walk.
struct InvertedEtaLaw {
  double operator()(double cos_i, double eta_rel) const { return optics::fresnel_dielectric(cos_i, 1.0 / eta_rel); }
};

TEST(SmithWalkDielectricProfiles, FirstInteractionAtNormalIncidenceIsExactOnBothSides) {
  // 5 standard deviations; GGX alpha 0.3 and Beckmann 0.8, 4 profiles of 2^14 segments, 50,000
  // rays each, 200,000 walks.
  print_header();
  for (Medium from : {Medium::above, Medium::below})
    for (auto [ndf, alpha] : {std::pair{NdfKind::ggx, 0.3}, std::pair{NdfKind::beckmann, 0.8}}) {
      Config c;
      c.ndf = ndf, c.alpha = alpha, c.from = from;
      const Comparison r = compare(c);
      print_row(c, r);
      EXPECT_EQ(r.lost_t, 0.0);
      EXPECT_EQ(r.lost_w, 0.0);
      EXPECT_LE(std::abs(r.z_first_t), 5.0);
      EXPECT_LE(std::abs(r.z_first_w), 5.0);
      EXPECT_LE(std::abs(r.z_first), 5.0);
      // The broken walk (Fresnel with eta inverted) against the quadrature the tracer confirms.
      const Counts b = walk(c, InvertedEtaLaw{});
      const double pb = b.first_refracted / b.n;
      const double zb = (pb - r.first_exact) / std::sqrt(pb * (1.0 - pb) / b.n);
      std::printf("  inverted-eta walk: T@1st %.5f (z %.1f against the quadrature)\n", pb, zb);
      EXPECT_GT(std::abs(zb), 5.0);
    }
}

TEST(SmithWalkDielectricProfilesLong, FullGrid) {
  // GGX and Beckmann, alpha 0.3 and 0.8, theta_i 0, 45, 75 deg, eta 1.5, from above and below:
  // 8 profiles of 2^16 segments, 500,000 rays each, 4,000,000 walks per case. Asserts only what
  // must hold (nothing lost; the first interaction at normal incidence); prints the rest, with two
  // controls per (ndf, alpha, theta) from above: the conductor limit (F = 1: the conductor tracer
  // against the conductor walk on the same profiles, the miss Smith's walk has without any
  // dielectric), and at theta 45 deg the null control (the traced profiles against 8 other
  // profiles: the chi2 the noise model gives when both sides are the same ensemble).
  print_header();
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.3, 0.8})
      for (Medium from : {Medium::above, Medium::below})
        for (double th : {0.0, 45.0, 75.0}) {
          Config c;
          c.ndf = ndf, c.alpha = alpha, c.theta_deg = th, c.from = from;
          c.realizations = 8, c.segments = 1 << 16, c.rays = 500000, c.walks = 4000000, c.bins = 36;
          const Comparison r = compare(c);
          print_row(c, r);
          std::fflush(stdout);
          EXPECT_EQ(r.lost_t, 0.0);
          EXPECT_EQ(r.lost_w, 0.0);
          if (th == 0.0) {
            EXPECT_LE(std::abs(r.z_first_t), 5.0);
            EXPECT_LE(std::abs(r.z_first_w), 5.0);
          }
          if (from == Medium::above) {
            Config k = c;
            k.conductor = true;
            print_row(k, compare(k), "conductor");
            std::fflush(stdout);
          }
          if (th == 45.0) {
            Config o = c;
            o.seed = c.seed + 1;
            const Comparison z = compare_sets(c, trace_all(c), trace_all(o));
            print_row(c, z, "traced");
            std::fflush(stdout);
          }
        }
}

}  // namespace
}  // namespace vgroove
