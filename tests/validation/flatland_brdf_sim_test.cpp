// The flatland multiple-scattering BRDF (analytic/brdf_flatland.h) against the exact tracer on a
// procedural microsurface (sim/microsurface.h), per theta_o bin and per bounce count k. The two
// sides share no code: the analytic lobe integrates Lee et al. 2018, Eq. (4)-(6) over the NDF,
// the tracer reflects rays in grooves drawn from sim::sample_theta_m.
//
// Noise and tolerance. A cell c (a (k row, theta_o bin) pair) receives the fraction q_c(g) of the
// rays that land on groove g. The surface holds G grooves drawn independently from the NDF, and
// N rays land uniformly on it; the observed count o_c has
//   E[o_c] = N p_c   (p_c: the analytic lobe, the expectation of q_c over the NDF),
//   Var(o_c) = N^2 Var(q_c)/G + N E[q_c (1 - q_c)]  <=  N p_c (1 + N/G)
// (rays: multinomial given the surface; grooves: Var(q_c) <= E[q_c^2] <= E[q_c] = p_c since
// 0 <= q_c <= 1). So the effective sample size is N_eff = N / (1 + N/G): the statistic
//   X^2 = sum_c (o_c - N p_c)^2 / (N p_c (1 + N/G)),
// over cells pooled until N p_c >= 5 (within each row, in bin order), is at most chi-square with
// (cells - 1) degrees of freedom in distribution (conservative: the inflation is an upper bound).
// Each case must pass at p > 1e-4 (with 7 cases, a false alarm has probability < 1e-3).
// Seeds are fixed: the test is deterministic. Measured (G = 1e5, N = 2e5): X^2 / dof between 0.44
// and 0.64 over the 7 cases (the inflation 1 + N/G = 3 is an upper bound, so the test is
// conservative: moving 5% of row 2 into row 1 is caught only at G = 1e6, N = 3e5, X^2 = 394 on
// 331 dof, which costs ~2-4 s per case for Beckmann and Phong sampling; not run here).
#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/sim/microsurface.h"

#include "tests/stats.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove {
namespace {

struct Case {
  sim::NdfKind sim_ndf;
  analytic::NdfKind ndf;
  double alpha;
  double theta_i_deg;
};

std::string case_name(const Case& c) {
  std::ostringstream os;
  os << analytic::ndf_name(c.ndf) << " alpha=" << c.alpha << " theta_i=" << c.theta_i_deg << " deg";
  return os.str();
}

constexpr int kBins = 90;
constexpr int kMaxK = 16;
constexpr int kGrooves = 100000;
constexpr std::int64_t kRays = 200000;

struct Fit {
  double stat = 0.0;
  int dof = 0;
  double p = 1.0;
  std::string table;
};

// The pooled, inflated chi-square of the header comment over every (row, bin) cell.
Fit compare(const analytic::FlatlandLobe& lobe, const sim::MicrosurfaceTally& t) {
  const double n = static_cast<double>(t.rays);
  const double inflate = 1.0 + n / kGrooves;
  Fit f;
  std::ostringstream os;
  int cells = 0;
  for (int r = 0; r <= kMaxK + 1; ++r) {
    double e = 0.0, last_e = 0.0;
    std::int64_t o = 0, last_o = 0;
    bool have_last = false;
    auto flush = [&](double ee, std::int64_t oo, int row, int bin) {
      f.stat += (oo - ee) * (oo - ee) / (ee * inflate);
      ++cells;
      if (std::abs(oo - ee) > 3.0 * std::sqrt(ee * inflate))
        os << "  row " << row << " up to bin " << bin << ": expected " << ee << ", observed " << oo << "\n";
    };
    for (int b = 0; b < kBins; ++b) {
      e += n * lobe.theta_o_by_k[static_cast<std::size_t>(r) * kBins + b];
      o += t.hist(r, b);
      if (e >= 5.0) {
        if (have_last) flush(last_e, last_o, r, b);
        last_e = e, last_o = o, have_last = true;
        e = 0.0, o = 0;
      }
    }
    // A leftover joins the row's last cell; a row with no cell of 5 expected is one cell if it
    // expects anything, and must then be empty-ish (its count enters with its expectation).
    if (have_last)
      flush(last_e + e, last_o + o, r, kBins - 1);
    else if (e > 0.0)
      flush(e, o, r, kBins - 1);
    else
      EXPECT_EQ(o, 0) << "row " << r << " expects nothing";
  }
  f.dof = cells - 1;
  f.p = test_stats::gamma_q(0.5 * f.dof, 0.5 * f.stat);
  f.table = os.str();
  return f;
}

class FlatlandBrdfSim : public ::testing::TestWithParam<Case> {};

TEST_P(FlatlandBrdfSim, LobePerKMatchesTheTracer) {
  const Case c = GetParam();
  sim::MicrosurfaceOptions mo;
  mo.ndf = c.sim_ndf;
  mo.alpha = c.alpha;
  mo.grooves = kGrooves;
  mo.seed = 2018;
  const sim::Microsurface surface = sim::make_microsurface(mo);
  sim::MicrosurfaceTraceOptions to;
  to.theta_i = c.theta_i_deg * std::numbers::pi / 180.0;
  to.rays = kRays;
  to.seed = 11;
  to.theta_o_bins = kBins;
  to.max_k = kMaxK;
  const sim::MicrosurfaceTally t = sim::trace_microsurface(surface, to);
  const analytic::FlatlandLobe lobe = analytic::flatland_lobe(c.ndf, c.alpha, to.theta_i, kBins, kMaxK);

  // Peaks on one line: nothing is lost (a vertex hit has probability 0; these NDFs and alphas put
  // no groove near the bounce limit).
  EXPECT_EQ(t.lost(), 0) << case_name(c);
  EXPECT_NEAR(lobe.albedo, 1.0, 1e-9) << case_name(c);

  const Fit f = compare(lobe, t);
  EXPECT_GT(f.p, 1e-4) << case_name(c) << ": X^2 = " << f.stat << " on " << f.dof << " dof\n" << f.table;

  // The per-k totals alone, the same bound: |o_k - N p_k| <= 5 sqrt(N p_k (1 + N/G)) (+1 for
  // rows expecting almost nothing).
  const double n = static_cast<double>(t.rays);
  for (int r = 0; r <= kMaxK + 1; ++r) {
    const double e = n * lobe.by_k[static_cast<std::size_t>(r)];
    EXPECT_LE(std::abs(static_cast<double>(t.by_k[static_cast<std::size_t>(r)]) - e),
              5.0 * std::sqrt(e * (1.0 + n / kGrooves)) + 1.0)
        << case_name(c) << " row " << r;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, FlatlandBrdfSim,
                         ::testing::Values(Case{sim::NdfKind::ggx, analytic::NdfKind::ggx, 0.3, 0.0},
                                           Case{sim::NdfKind::ggx, analytic::NdfKind::ggx, 0.7, 40.0},
                                           Case{sim::NdfKind::ggx, analytic::NdfKind::ggx, 1.0, -70.0},
                                           Case{sim::NdfKind::beckmann, analytic::NdfKind::beckmann, 0.5, 20.0},
                                           Case{sim::NdfKind::beckmann, analytic::NdfKind::beckmann, 1.0, 60.0},
                                           Case{sim::NdfKind::phong, analytic::NdfKind::phong, 0.5, 0.0},
                                           Case{sim::NdfKind::phong, analytic::NdfKind::phong, 0.8, -50.0}),
                         [](const ::testing::TestParamInfo<Case>& p) {
                           std::ostringstream os;
                           os << analytic::ndf_name(p.param.ndf) << "_a" << static_cast<int>(p.param.alpha * 100)
                              << "_ti" << (p.param.theta_i_deg < 0 ? "m" : "")
                              << static_cast<int>(std::abs(p.param.theta_i_deg));
                           return os.str();
                         });

}  // namespace
}  // namespace vgroove
