// vgroove validation: the checks of a BRDF sampler as the rendering community runs them
// (analytic/sampling_3d.h, analytic/sampling_flatland.h):
//   - chi-square goodness of fit of the sampled directions against the sampler's own pdf (or any
//     density a test holds it to), as Mitsuba 3 and nori do: the directions histogrammed on cells
//     of (cos theta_o, phi_o) (flatland: theta_o), the pdf integrated over each cell by adaptive
//     Gauss-Kronrod, plus one cell for the samples that returned no direction (expected: the
//     failure probability, integrated over the facets); validation/chi_square.h pools and tests;
//   - the normalization: the cells' integrals plus the failure probability must be 1 (two
//     independent quadratures, over o and over the facets);
//   - the variance of the weight rho cos / pdf per strategy and for cosine-weighted sampling, and
//     the cost per sample: which strategy is the most efficient where.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_nonsymmetric.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/chi_square.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vgroove::validation {

// The relative accuracy asked of each cell's integral: a relative error e in every cell adds about
// N e^2 to the statistic (0.01 at N = 10^6), far below its spread sqrt(2 dof).
inline constexpr double kCellRelTol = 1e-4;

struct Chi2Spec {
  SurfaceDim dim = SurfaceDim::three_d;
  analytic::NdfKind ndf = analytic::NdfKind::ggx;
  double alpha = 0.5;
  double theta_i = 0.0;  // radians; the light at i = dir3(theta_i, pi) (flatland: theta_i)
  analytic::FacetStrategy strategy = analytic::FacetStrategy::vndf;
  int max_k = analytic::kSamplerMaxK;  // the nonsymmetric model's default: analytic::kNonsymmetricSamplerMaxK
  long samples = 100000;
  std::uint64_t seed = 1;
  int cos_bins = 8, phi_bins = 16;  // 3D: cos(theta_o) in [0, 1] x phi_o in [-pi, pi), phi_bins even
  int theta_bins = 36;              // flatland: theta_o in (-pi/2, pi/2)
  double level = 0.01;              // the family's significance level
  int tests = 1;                    // tests run together (Sidak)
  // The nonsymmetric model (analytic/sampling_nonsymmetric.h: the independent partner law, Eq. 20)
  // instead of the symmetric one. Its directions are histogrammed from the draws alone; its pdf and
  // weight cost ~ms, so the weight's moments are taken over the first kNonsymmetricWeightSamples.
  bool nonsymmetric = false;
};
inline constexpr long kNonsymmetricWeightSamples = 256;

// The histogram and the expected counts, for plots: [row * cols + col]; 3D rows are cos(theta_o)
// bins (row_edges ascending) and columns phi_o bins (col_edges from -pi); flatland has one row
// and theta_o bins as columns.
struct Chi2Table {
  int rows = 0, cols = 0;
  std::vector<double> row_edges, col_edges;
  std::vector<double> observed, expected;
  double observed_none = 0.0, expected_none = 0.0;  // samples that returned no direction
};

struct Chi2Outcome {
  Chi2Spec spec;
  Chi2Table table;
  ChiSquareResult test;
  double pdf_integral = 0.0;         // the cells' integrals summed
  double quadrature_error = 0.0;     // their summed error estimates
  double failure_probability = 0.0;  // over the facets
  // The samples lost because their path has more than max_k reflections (part of observed_none),
  // and the share expected (part of failure_probability; symmetric model only, -1 for the
  // nonsymmetric one, whose failure probability is not split).
  double observed_beyond_max_k = 0.0;
  double beyond_max_k_probability = 0.0;
  double normalization_error = 0.0;  // pdf_integral + failure_probability - 1
  double normalization_tolerance = 0.0;
  double sample_s = 0.0, integrate_s = 0.0;
  // The weights rho cos / pdf of the same samples (zero-weight returns count 0), F = 1.
  double weight_mean = 0.0, weight_variance = 0.0;
  long weight_samples = 0;   // samples the weight's moments are over
  bool pass = false;         // the chi-square accepts and |normalization_error| <= normalization_tolerance
  bool interrupted = false;  // `cancel` was set: the numbers are incomplete and mean nothing
};
// Their members for a shard part (outcome_fields.h); the spec is the suite's.
template <class F>
void fields(Chi2Table& t, F&& f) {
  f("rows", t.rows), f("cols", t.cols), f("row_edges", t.row_edges), f("col_edges", t.col_edges);
  f("observed", t.observed), f("expected", t.expected);
  f("observed_none", t.observed_none), f("expected_none", t.expected_none);
}
template <class F>
void fields(Chi2Outcome& o, F&& f) {
  f("table", o.table), f("test", o.test), f("pdf_integral", o.pdf_integral), f("quadrature_error", o.quadrature_error);
  f("failure_probability", o.failure_probability), f("observed_beyond_max_k", o.observed_beyond_max_k);
  f("beyond_max_k_probability", o.beyond_max_k_probability), f("normalization_error", o.normalization_error);
  f("normalization_tolerance", o.normalization_tolerance), f("sample_s", o.sample_s), f("integrate_s", o.integrate_s);
  f("weight_mean", o.weight_mean), f("weight_variance", o.weight_variance), f("weight_samples", o.weight_samples);
  f("pass", o.pass), f("interrupted", o.interrupted);
}
// The shape `spec` gives a table (rows, columns, edges and cells), or what differs.
std::string chi2_table_shape_error(const Chi2Spec& spec, const Chi2Table& t);

// A density the test holds the sampler to in place of its own pdf (the power tests), with the
// probability of no direction it claims.
struct HeldDensity {
  std::function<double(const analytic::Dir3&)> pdf3;
  std::function<double(double)> pdf2;
  double none = 0.0;
};

// `cancel` (may be null) is read at every sample and every evaluation of the density; once set, the
// run stops within one evaluation and the outcome says interrupted (pass false).
Chi2Outcome run_chi2(const Chi2Spec& spec, const HeldDensity* held = nullptr,
                     const std::atomic<bool>* cancel = nullptr);
// The same samples held to another density (the histogram is reused, the expected counts redone).
Chi2Outcome retest_chi2(const Chi2Outcome& sampled, const HeldDensity& held, const std::atomic<bool>* cancel = nullptr);
nlohmann::json chi2_json(const Chi2Outcome& o);

// The weight's statistics per strategy.
struct VarianceSpec {
  SurfaceDim dim = SurfaceDim::three_d;
  analytic::NdfKind ndf = analytic::NdfKind::ggx;
  double alpha = 0.5;
  double theta_i = 0.0;
  int max_k = analytic::kSamplerMaxK;  // the nonsymmetric model's default: analytic::kNonsymmetricSamplerMaxK
  long samples = 20000;
  std::uint64_t seed = 1;
  double schlick_f0 = 1.0;    // Fresnel: Schlick with this F0 (1: F = 1, the furnace); 3D only
  bool nonsymmetric = false;  // the nonsymmetric model (Chi2Spec)
};
struct StrategyStats {
  std::string strategy;  // a FacetStrategy's name, or "cosine"
  double mean = 0.0, variance = 0.0, standard_error = 0.0;
  double no_direction = 0.0;  // fraction of zero-weight returns
  double ns_per_sample = 0.0;
  double efficiency = 0.0;  // 1 / (variance x seconds per sample); infinite when the variance is 0
};
struct VarianceOutcome {
  VarianceSpec spec;
  std::vector<StrategyStats> rows;
  std::string lowest_variance;  // among the strategies and cosine
  std::string most_efficient;
  bool interrupted = false;  // `cancel` was set: rows missing or incomplete
};
template <class F>
void fields(StrategyStats& s, F&& f) {
  f("strategy", s.strategy), f("mean", s.mean), f("variance", s.variance), f("standard_error", s.standard_error);
  f("no_direction", s.no_direction), f("ns_per_sample", s.ns_per_sample), f("efficiency", s.efficiency);
}
template <class F>
void fields(VarianceOutcome& o, F&& f) {
  f("rows", o.rows), f("lowest_variance", o.lowest_variance), f("most_efficient", o.most_efficient);
  f("interrupted", o.interrupted);
}
// `cancel` (may be null) is read at every sample.
VarianceOutcome run_variance(const VarianceSpec& spec, const std::atomic<bool>* cancel = nullptr);
nlohmann::json variance_json(const VarianceOutcome& o);

}  // namespace vgroove::validation
