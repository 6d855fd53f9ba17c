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
#include "vgroove/common/angles.h"
#include "vgroove/validation/sampling_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace vgroove::validation {
namespace {

using analytic::FacetStrategy;
using analytic::NdfKind;

std::string describe(const Chi2Outcome& o) {
  std::ostringstream os;
  const Chi2Spec& s = o.spec;
  os << surface_dim_name(s.dim) << " " << analytic::ndf_name(s.ndf) << " alpha=" << s.alpha
     << " theta_i=" << s.theta_i / kRadPerDeg << " " << analytic::strategy_name(s.strategy) << ": stat "
     << o.test.statistic << " dof " << o.test.dof << " p " << o.test.p_value << " level " << o.test.level
     << " | pdf integral " << o.pdf_integral << " + failure " << o.failure_probability
     << " - 1 = " << o.normalization_error << " (quadrature error " << o.quadrature_error << ")";
  if (!o.pass) os << "\n" << chi2_json(o)["table"].dump();  // the table, for a failure
  return os.str();
}

Chi2Spec spec(SurfaceDim dim, NdfKind ndf, double alpha, double deg, FacetStrategy st, long samples, int tests) {
  Chi2Spec s;
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

void run_grid(SurfaceDim dim, long samples) {
  const int family = grid_family();
  for (NdfKind ndf : kNdfs)
    for (FacetStrategy st : kStrategies) {
      if (!analytic::strategy_supports(st, ndf, dim == SurfaceDim::flatland)) continue;
      for (double alpha : kAlphas)
        for (double deg : kThetas) {
          const Chi2Outcome o = run_chi2(spec(dim, ndf, alpha, deg, st, samples, family));
          EXPECT_TRUE(o.pass) << describe(o);
        }
    }
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

}  // namespace
}  // namespace vgroove::validation
