// Chi-square goodness-of-fit tests of the V-groove samplers against their pdfs
// (analytic/sampling_3d.h, analytic/sampling_flatland.h), run as Mitsuba 3 and nori run them for
// their BSDFs (validation/sampling_check.h, validation/chi_square.h): directions histogrammed on
// (cos theta_o, phi_o) cells (flatland: theta_o), the pdf integrated over each cell by adaptive
// Gauss-Kronrod, one cell for the samples that return no direction, cells expecting fewer than 5
// pooled, the level 0.01 shared by the family of tests (Sidak). Each case also checks that the
// cells' integrals and the failure probability (integrated over the facets) sum to 1.
//
// The default run holds a representative subset; the grid (every NDF, alpha 0.1 to 1.5, theta_i 0
// to 85 deg, every strategy, 3D and flatland) carries the label long (suites *Long*).
//
// Power: a density wrong by a few percent in one lobe (the k = 2 paths' share raised by 5 %, the
// whole renormalized), the Jacobian of Eq. (13) off by (k + 1)/k for k >= 2, and the printed
// p(o) = |s.n| D(s) G (normalized to the routine's mass, so that only its shape is tested) must be
// rejected: those tests assert rejection.
#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_flatland.h"
#include "vgroove/analytic/sampling_nonsymmetric.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/sampling_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove::validation {
namespace {

using analytic::FacetStrategy;
using analytic::NdfKind;

std::string describe(const Chi2Outcome& o) {
  std::ostringstream os;
  const Chi2Spec& s = o.spec;
  os << surface_dim_name(s.dim) << " " << analytic::ndf_name(s.ndf) << " alpha=" << s.alpha
     << " theta_i=" << s.theta_i / kRadPerDeg << " " << analytic::strategy_name(s.strategy)
     << (s.nonsymmetric ? " nonsymmetric" : "") << ": stat " << o.test.statistic << " dof " << o.test.dof << " p "
     << o.test.p_value << " level " << o.test.level << " | pdf integral " << o.pdf_integral << " + failure "
     << o.failure_probability << " - 1 = " << o.normalization_error << " (quadrature error " << o.quadrature_error
     << ")";
  if (!o.pass) os << "\n" << chi2_json(o)["table"].dump();  // the table, for a failure
  return os.str();
}

Chi2Spec spec(SurfaceDim dim, NdfKind ndf, double alpha, double deg, FacetStrategy st, long samples, int tests) {
  Chi2Spec s;
  // The sampler against its own pdf does not depend on max_k; 256 keeps the cells' integrals
  // cheap near the retro direction (the default's share lost: tests/analytic/sampling_3d_test.cpp).
  s.max_k = 256;
  s.dim = dim;
  s.ndf = ndf;
  s.alpha = alpha;
  s.theta_i = deg * kRadPerDeg;
  s.strategy = st;
  s.samples = samples;
  s.tests = tests;
  s.seed = 7;
  return s;
}

// ---- The default subset: 14 tests in the family ---------------------------------------------------

constexpr int kDefaultFamily = 14;

TEST(SamplingChi2, ThreeD) {
  struct Case {
    NdfKind ndf;
    double alpha, deg;
    FacetStrategy st;
  };
  for (const Case& c :
       {Case{NdfKind::ggx, 0.5, 30.0, FacetStrategy::printed}, Case{NdfKind::ggx, 0.5, 30.0, FacetStrategy::vndf},
        Case{NdfKind::ggx, 0.5, 30.0, FacetStrategy::smith_vndf},
        Case{NdfKind::ggx, 1.5, 60.0, FacetStrategy::bounded_vndf},
        Case{NdfKind::beckmann, 0.3, 75.0, FacetStrategy::vndf}, Case{NdfKind::phong, 1.0, 0.0, FacetStrategy::printed},
        Case{NdfKind::beckmann, 0.1, 85.0, FacetStrategy::printed}}) {
    const Chi2Outcome o = run_chi2(spec(SurfaceDim::three_d, c.ndf, c.alpha, c.deg, c.st, 100000, kDefaultFamily));
    EXPECT_TRUE(o.pass) << describe(o);
  }
}

// The samples lost to max_k are reported beside the failures and the share expected of them: with
// max_k = 4 (GGX alpha 1, 30 deg) the printed strategy's lost samples are a binomial count within
// 4.5 sigma of N p, fewer than its failures (shadowed facets); the vndf strategy's are all its
// failures; both in the JSON report.
TEST(SamplingChi2, ReportsTheSamplesLostBeyondMaxK) {
  for (const SurfaceDim dim : {SurfaceDim::three_d, SurfaceDim::flatland})
    for (const FacetStrategy st : {FacetStrategy::printed, FacetStrategy::vndf}) {
      Chi2Spec s = spec(dim, NdfKind::ggx, 1.0, 30.0, st, 50000, 1);
      s.max_k = 4;
      const Chi2Outcome o = run_chi2(s);
      const double N = static_cast<double>(s.samples), p = o.beyond_max_k_probability;
      ASSERT_GT(p, 1e-3) << describe(o);
      EXPECT_NEAR(o.observed_beyond_max_k, N * p, 4.5 * std::sqrt(N * p * (1.0 - p))) << describe(o);
      if (st == FacetStrategy::vndf) {
        EXPECT_EQ(o.observed_beyond_max_k, o.table.observed_none);
        EXPECT_EQ(p, o.failure_probability);
      } else {
        EXPECT_LT(o.observed_beyond_max_k, o.table.observed_none);
        EXPECT_LT(p, o.failure_probability);
      }
      const nlohmann::json j = chi2_json(o);
      EXPECT_EQ(j.at("observed_beyond_max_k").get<double>(), o.observed_beyond_max_k);
      EXPECT_EQ(j.at("beyond_max_k_probability").get<double>(), p);
    }
}

TEST(SamplingChi2, Flatland) {
  struct Case {
    NdfKind ndf;
    double alpha, deg;
    FacetStrategy st;
  };
  for (const Case& c :
       {Case{NdfKind::ggx, 0.5, 30.0, FacetStrategy::printed}, Case{NdfKind::ggx, 0.5, 30.0, FacetStrategy::vndf},
        Case{NdfKind::ggx, 1.0, 60.0, FacetStrategy::smith_vndf}, Case{NdfKind::phong, 1.5, 85.0, FacetStrategy::vndf},
        Case{NdfKind::beckmann, 0.1, 0.0, FacetStrategy::printed},
        Case{NdfKind::phong, 0.3, 75.0, FacetStrategy::printed},
        Case{NdfKind::beckmann, 0.7, 45.0, FacetStrategy::vndf}}) {
    const Chi2Outcome o = run_chi2(spec(SurfaceDim::flatland, c.ndf, c.alpha, c.deg, c.st, 200000, kDefaultFamily));
    EXPECT_TRUE(o.pass) << describe(o);
  }
}

// ---- The grid (label long) ------------------------------------------------------------------------

constexpr double kAlphas[] = {0.1, 0.3, 0.5, 0.7, 1.0, 1.5};
constexpr double kThetas[] = {0.0, 30.0, 60.0, 75.0, 85.0};
constexpr NdfKind kNdfs[] = {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong};
constexpr FacetStrategy kStrategies[] = {FacetStrategy::printed, FacetStrategy::vndf, FacetStrategy::smith_vndf,
                                         FacetStrategy::bounded_vndf};

// Every (dimension, NDF, alpha, theta_i, strategy) the strategy supports: the family's size.
int grid_family() {
  int n = 0;
  for (bool flat : {false, true})
    for (NdfKind ndf : kNdfs)
      for (FacetStrategy st : kStrategies) n += analytic::strategy_supports(st, ndf, flat) ? 30 : 0;
  return n;
}

// Runs the cases on all cores (each case on one thread) and checks the outcomes in order.
void run_cases(const std::vector<Chi2Spec>& specs) {
  std::vector<Chi2Outcome> outcomes(specs.size());
  support::parallel_for(
      specs.size(), support::resolve_threads(0), [&](std::size_t n) { outcomes[n] = run_chi2(specs[n]); }, {}, nullptr,
      1);
  double p_min = 1.0, p_max = 0.0, norm = 0.0, seconds = 0.0;
  for (const Chi2Outcome& o : outcomes) {
    EXPECT_TRUE(o.pass) << describe(o);
    p_min = std::min(p_min, o.test.p_value);
    p_max = std::max(p_max, o.test.p_value);
    norm = std::max(norm, std::abs(o.normalization_error) / o.normalization_tolerance);
    seconds += o.sample_s + o.integrate_s;
  }
  std::printf(
      "%zu cases (level %.3g each): p from %.3g to %.3g; largest |normalization error| / tolerance %.3g; %.0f s "
      "of sampling and integration\n",
      specs.size(), outcomes.empty() ? 0.0 : outcomes[0].test.level, p_min, p_max, norm, seconds);
}

void run_grid(SurfaceDim dim, long samples) {
  const int family = grid_family();
  std::vector<Chi2Spec> specs;
  for (NdfKind ndf : kNdfs)
    for (FacetStrategy st : kStrategies) {
      if (!analytic::strategy_supports(st, ndf, dim == SurfaceDim::flatland)) continue;
      for (double alpha : kAlphas)
        for (double deg : kThetas) specs.push_back(spec(dim, ndf, alpha, deg, st, samples, family));
    }
  run_cases(specs);
}

TEST(SamplingChi2Long, ThreeDGrid) { run_grid(SurfaceDim::three_d, 200000); }
TEST(SamplingChi2Long, FlatlandGrid) { run_grid(SurfaceDim::flatland, 500000); }

// ---- Power ------------------------------------------------------------------------------------------

// A density built from the sampler's own: pdf + eps part, renormalized so that it claims the same
// probability of no direction (a density: only the shape is wrong).
struct Raised {
  double eps, part_mass, none;
  double scale() const { return (1.0 - none) / (1.0 - none + eps * part_mass); }
};

// The k = 2 paths' part of the pdf, and the back-scattering half (o on the light's side, phi_o in
// (pi/2, 3 pi/2); flatland theta_o > 0), each raised by eps.
HeldDensity raised_3d(const Chi2Outcome& base, double eps, bool k2) {
  const Chi2Spec& s = base.spec;
  const analytic::Dir3 i = analytic::dir3(s.theta_i, std::numbers::pi);
  const analytic::SamplerOptions opt{s.strategy, s.max_k};
  auto part = [=](const analytic::Dir3& o) {
    if (k2) return analytic::vgroove_pdf_3d_k(i, o, s.ndf, s.alpha, opt, 2, 2);
    return o.x < 0.0 ? analytic::vgroove_pdf_3d(i, o, s.ndf, s.alpha, opt) : 0.0;
  };
  analytic::HemisphereOptions ho;
  ho.tol = 1e-6;
  ho.scale = s.alpha;
  const Raised r{eps, analytic::integrate_hemisphere(analytic::Dir3{-i.x, -i.y, i.z}, part, ho).value,
                 base.failure_probability};
  HeldDensity h;
  h.pdf3 = [=](const analytic::Dir3& o) {
    return r.scale() * (analytic::vgroove_pdf_3d(i, o, s.ndf, s.alpha, opt) + r.eps * part(o));
  };
  h.none = r.none;
  return h;
}

HeldDensity raised_flatland(const Chi2Outcome& base, double eps, bool k2) {
  const Chi2Spec& s = base.spec;
  const analytic::SamplerOptions opt{s.strategy, s.max_k};
  auto part = [=](double o) {
    if (k2) return analytic::vgroove_pdf_flatland_k(s.theta_i, o, s.ndf, s.alpha, opt, 2, 2);
    return o > 0.0 ? analytic::vgroove_pdf_flatland(s.theta_i, o, s.ndf, s.alpha, opt) : 0.0;
  };
  const Raised r{eps, analytic::integrate_half_circle(s.theta_i, part, s.alpha, 1e-10).value, base.failure_probability};
  HeldDensity h;
  h.pdf2 = [=](double o) {
    return r.scale() * (analytic::vgroove_pdf_flatland(s.theta_i, o, s.ndf, s.alpha, opt) + r.eps * part(o));
  };
  h.none = r.none;
  return h;
}

// The sample counts are what the noncentrality asks for: lambda = N sum_c (p'_c - p_c)^2 / p_c
// is about 2e-4 N for the back half raised by 3 % (flatland and 3D, GGX 0.7 at 30 deg), 8e-5 N
// for the 3D k = 2 lobe raised by 5 %, but only 1.7e-5 N for the flatland k = 2 lobe (its shape
// is close to the whole lobe's). With dof ~ 130 and the level 7e-4 the statistic's critical
// value is ~ 180: lambda ~ 100 puts the wrong density 2 to 3 standard deviations beyond it.
TEST(SamplingChi2Power, FlatlandRejectsAThreePercentErrorInTheBackLobe) {
  const Chi2Outcome right =
      run_chi2(spec(SurfaceDim::flatland, NdfKind::ggx, 0.7, 30.0, FacetStrategy::vndf, 1000000, kDefaultFamily));
  EXPECT_FALSE(right.test.reject) << describe(right);
  const Chi2Outcome bad = retest_chi2(right, raised_flatland(right, 0.03, false));
  EXPECT_TRUE(bad.test.reject) << describe(bad);
}

TEST(SamplingChi2Power, ThreeDRejectsAThreePercentErrorInTheBackLobe) {
  const Chi2Outcome right =
      run_chi2(spec(SurfaceDim::three_d, NdfKind::ggx, 0.7, 30.0, FacetStrategy::vndf, 600000, kDefaultFamily));
  EXPECT_FALSE(right.test.reject) << describe(right);
  const Chi2Outcome bad = retest_chi2(right, raised_3d(right, 0.03, false));
  EXPECT_TRUE(bad.test.reject) << describe(bad);
}

TEST(SamplingChi2PowerLong, ThreeDRejectsAFivePercentErrorInTheK2Lobe) {
  const Chi2Outcome right =
      run_chi2(spec(SurfaceDim::three_d, NdfKind::ggx, 0.7, 30.0, FacetStrategy::vndf, 2000000, kDefaultFamily));
  EXPECT_FALSE(right.test.reject) << describe(right);
  const Chi2Outcome bad = retest_chi2(right, raised_3d(right, 0.05, true));
  EXPECT_TRUE(bad.test.reject) << describe(bad);
}

// The printed p(o) = |s.n| D(s) G (Lee et al. 2018, Sec. 6), scaled to the printed routine's mass
// (so that only its shape is on trial), against what the printed routine draws: rejected.
TEST(SamplingChi2Power, RejectsThePrintedP) {
  const Chi2Outcome right =
      run_chi2(spec(SurfaceDim::three_d, NdfKind::ggx, 0.5, 30.0, FacetStrategy::printed, 100000, kDefaultFamily));
  EXPECT_TRUE(right.pass) << describe(right);
  const Chi2Spec& s = right.spec;
  const analytic::Dir3 i = analytic::dir3(s.theta_i, std::numbers::pi);
  analytic::HemisphereOptions ho;
  ho.tol = 1e-5;
  ho.scale = s.alpha;
  const double total =
      analytic::integrate_hemisphere(
          analytic::Dir3{-i.x, -i.y, i.z},
          [&](const analytic::Dir3& o) { return analytic::printed_p_3d(i, o, s.ndf, s.alpha, s.max_k); }, ho)
          .value;
  HeldDensity printed;
  printed.none = right.failure_probability;
  printed.pdf3 = [&](const analytic::Dir3& o) {
    return (1.0 - printed.none) / total * analytic::printed_p_3d(i, o, s.ndf, s.alpha, s.max_k);
  };
  const Chi2Outcome bad = retest_chi2(right, printed);
  EXPECT_TRUE(bad.test.reject) << describe(bad);
  EXPECT_GT(bad.test.statistic, 10.0 * bad.test.dof);  // not a near miss
}

// ---- The nonsymmetric model (analytic/sampling_nonsymmetric.h) -------------------------------------

// Its pdf costs ~0.5 ms (an adaptive integral over the partner per k and orientation), so the default
// run holds flatland cases (36 cells); the 3D cases (4 x 8 cells) and the flatland grid are long.
// Phong only up to alpha = 1 (partner_table.h).
Chi2Spec nonsym(SurfaceDim dim, NdfKind ndf, double alpha, double deg, FacetStrategy st, long samples, int tests) {
  Chi2Spec s = spec(dim, ndf, alpha, deg, st, samples, tests);
  s.nonsymmetric = true;
  s.max_k = 32;
  if (dim == SurfaceDim::three_d) s.cos_bins = 4, s.phi_bins = 8;
  return s;
}

constexpr int kNonsymmetricFamily = 4;

TEST(SamplingChi2Nonsymmetric, Flatland) {
  struct Case {
    NdfKind ndf;
    double alpha, deg;
    FacetStrategy st;
  };
  for (const Case& c :
       {Case{NdfKind::ggx, 0.5, 30.0, FacetStrategy::vndf}, Case{NdfKind::beckmann, 0.3, 75.0, FacetStrategy::printed},
        Case{NdfKind::phong, 1.0, 0.0, FacetStrategy::vndf}}) {
    const Chi2Outcome o =
        run_chi2(nonsym(SurfaceDim::flatland, c.ndf, c.alpha, c.deg, c.st, 100000, kNonsymmetricFamily));
    EXPECT_TRUE(o.pass) << describe(o);
  }
}

TEST(SamplingChi2NonsymmetricLong, ThreeD) {
  const Chi2Outcome o =
      run_chi2(nonsym(SurfaceDim::three_d, NdfKind::ggx, 0.5, 30.0, FacetStrategy::vndf, 50000, kNonsymmetricFamily));
  EXPECT_TRUE(o.pass) << describe(o);
}

// The grid: every NDF, alpha 0.1 to 1.5 (Phong to 1.0), theta_i 0 to 85 deg. Flatland: printed and vndf at every point
// (66 cases). 3D: a case's 16 cells (mirrored to 32) cost ~10^5 pdf evaluations at 0.5-3 ms each (1-4 minutes), so each
// point has one of the two strategies, alternating along alpha and theta so that every NDF, alpha and theta_i meets
// both (33 cases, 31-36 minutes on two cores).
void run_nonsymmetric_grid(SurfaceDim dim, long samples) {
  constexpr double alphas[] = {0.1, 0.5, 1.0, 1.5};
  constexpr double thetas[] = {0.0, 45.0, 85.0};
  constexpr FacetStrategy strategies[] = {FacetStrategy::printed, FacetStrategy::vndf};
  std::vector<Chi2Spec> specs;
  for (NdfKind ndf : kNdfs)
    for (int a = 0; a < 4; ++a) {
      if (ndf == NdfKind::phong && alphas[a] > 1.0) continue;
      for (int t = 0; t < 3; ++t)
        for (int st = 0; st < 2; ++st)
          if (dim == SurfaceDim::flatland || st == (a + t) % 2)
            specs.push_back(nonsym(dim, ndf, alphas[a], thetas[t], strategies[st], samples, 0));
    }
  for (Chi2Spec& s : specs) s.tests = static_cast<int>(specs.size());
  run_cases(specs);
}
TEST(SamplingChi2NonsymmetricLong, FlatlandGrid) { run_nonsymmetric_grid(SurfaceDim::flatland, 200000); }
TEST(SamplingChi2NonsymmetricLong, ThreeDGrid) { run_nonsymmetric_grid(SurfaceDim::three_d, 50000); }

// Power: the back half (theta_o > 0, the light's side) raised by 3 % and renormalized is rejected;
// so is the symmetric model's pdf held against the nonsymmetric draws (the partner law matters).
TEST(SamplingChi2NonsymmetricPower, FlatlandRejectsAThreePercentErrorInTheBackLobe) {
  const Chi2Outcome right = run_chi2(
      nonsym(SurfaceDim::flatland, NdfKind::ggx, 0.7, 30.0, FacetStrategy::vndf, 1000000, kNonsymmetricFamily));
  EXPECT_FALSE(right.test.reject) << describe(right);
  const Chi2Spec& s = right.spec;
  analytic::NonsymmetricSampler S =
      analytic::make_nonsymmetric_sampler(s.ndf, s.alpha, analytic::SamplerOptions{s.strategy, s.max_k}, true);
  S.tolerance = 1e-6;
  auto part = [=](double o) { return o > 0.0 ? analytic::nonsymmetric_pdf_flatland(S, s.theta_i, o) : 0.0; };
  const Raised r{0.03, analytic::integrate_half_circle(s.theta_i, part, s.alpha, 1e-7).value,
                 right.failure_probability};
  HeldDensity h;
  h.pdf2 = [=](double o) {
    return r.scale() * (analytic::nonsymmetric_pdf_flatland(S, s.theta_i, o) + r.eps * part(o));
  };
  h.none = r.none;
  const Chi2Outcome bad = retest_chi2(right, h);
  EXPECT_TRUE(bad.test.reject) << describe(bad);
  HeldDensity sym;
  const analytic::SamplerOptions opt{s.strategy, s.max_k};
  sym.pdf2 = [=](double o) { return analytic::vgroove_pdf_flatland(s.theta_i, o, s.ndf, s.alpha, opt); };
  sym.none = analytic::sampler_failure_probability_flatland(s.theta_i, s.ndf, s.alpha, opt);
  const Chi2Outcome other = retest_chi2(right, sym);
  EXPECT_TRUE(other.test.reject) << describe(other);
}

}  // namespace
}  // namespace vgroove::validation
