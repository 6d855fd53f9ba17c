#include "vgroove/validation/sampling_check.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/analytic/brdf_nonsymmetric.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_flatland.h"
#include "vgroove/analytic/sampling_nonsymmetric.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/report.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

// Thrown by a density evaluated after the cancellation flag was set: the quadratures stop at once
// (run_chi2 and retest_chi2 catch it and say interrupted).
struct Stopped {};
void stop_if(const std::atomic<bool>* cancel) {
  if (support::cancelled(cancel)) throw Stopped{};
}

std::array<double, 4> uniforms(sim::Rng& rng) { return {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()}; }
std::array<double, 5> uniforms5(sim::Rng& rng) {
  return {rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
}

// The nonsymmetric sampler of a spec; the pdf to 1e-6 relative per B-piece (the cells ask 1e-4).
analytic::NonsymmetricSampler nonsymmetric_sampler(const Chi2Spec& s) {
  analytic::NonsymmetricSampler S = analytic::make_nonsymmetric_sampler(
      s.ndf, s.alpha, analytic::SamplerOptions{s.strategy, s.max_k}, s.dim == SurfaceDim::flatland);
  S.tolerance = 1e-6;
  return S;
}

struct Moments {
  double sum = 0.0, sum2 = 0.0;
  void add(double w) { sum += w, sum2 += w * w; }
  void into(Chi2Outcome& out, long n) const {
    out.weight_samples = n;
    const double N = static_cast<double>(n);
    out.weight_mean = sum / N;
    out.weight_variance = N > 1.0 ? std::max(0.0, sum2 / N - out.weight_mean * out.weight_mean) * N / (N - 1.0) : 0.0;
  }
};

// Cell integrals: relative kCellRelTol = 1e-4 and absolute 0.05 / N. A relative error e in every cell adds
// about N e^2 to the statistic (0.01 at N = 10^6), an absolute one d about (N d)^2 / 5 per pooled
// cell: far below the statistic's spread sqrt(2 dof).
analytic::AdaptiveOptions cell_options(long samples) {
  analytic::AdaptiveOptions o;
  o.rel_tol = kCellRelTol;
  o.abs_tol = 0.05 / static_cast<double>(samples);
  o.max_pieces = 400;
  return o;
}

// A sampled direction as the histogram sees it: its order k (0: no direction), whether it went
// beyond max_k, its weight (where weighed) and its cell (where k > 0).
struct Drawn {
  int k = 0;
  bool beyond_max_k = false;
  double weight = 0.0;
  std::size_t cell = 0;
};

// The histogram of the sampled directions and the weights' moments, in either dimension:
// `make_draw()` gives the dimension's draw(rng, weigh) (made inside the timing: the nonsymmetric
// sampler builds its partner table there); the stream is the dimension's.
template <class MakeDraw>
void sample_cells(Chi2Outcome& out, std::uint64_t stream, MakeDraw make_draw, const std::atomic<bool>* cancel) {
  const Chi2Spec& s = out.spec;
  Chi2Table& t = out.table;
  t.observed.assign(static_cast<std::size_t>(t.rows) * static_cast<std::size_t>(t.cols), 0.0);
  const auto t0 = Clock::now();
  sim::Rng rng(s.seed, 0x5a3d, stream);
  Moments w;
  const auto draw = make_draw();
  const long weighted = s.nonsymmetric ? std::min(s.samples, kNonsymmetricWeightSamples) : s.samples;
  for (long n = 0; n < s.samples; ++n) {
    stop_if(cancel);
    const Drawn x = draw(rng, n < weighted);
    if (n < weighted) w.add(x.weight);
    if (x.k == 0) {
      t.observed_none += 1.0;
      if (x.beyond_max_k) out.observed_beyond_max_k += 1.0;
      continue;
    }
    t.observed[x.cell] += 1.0;
  }
  out.sample_s = seconds_since(t0);
  w.into(out, weighted);
}

// 3D: cells over cos(theta_o) x phi_o.
void sample_3d(Chi2Outcome& out, const std::atomic<bool>* cancel) {
  const Chi2Spec& s = out.spec;
  Chi2Table& t = out.table;
  t.rows = s.cos_bins;
  t.cols = s.phi_bins;
  for (int r = 0; r <= t.rows; ++r) t.row_edges.push_back(static_cast<double>(r) / t.rows);
  for (int c = 0; c <= t.cols; ++c) t.col_edges.push_back(-std::numbers::pi + 2.0 * std::numbers::pi * c / t.cols);
  const analytic::Dir3 i = analytic::dir3(s.theta_i, std::numbers::pi);
  const analytic::SamplerOptions opt{s.strategy, s.max_k};
  sample_cells(
      out, 0,
      [&] {
        const analytic::NonsymmetricSampler ns =
            s.nonsymmetric ? nonsymmetric_sampler(s) : analytic::NonsymmetricSampler{};
        return [&s, &t, i, opt, ns](sim::Rng& rng, bool weigh) {
          Drawn d;
          analytic::Dir3 o{};
          if (s.nonsymmetric) {
            const std::array<double, 5> u = uniforms5(rng);
            const analytic::NonsymmetricDraw3d x = analytic::draw_nonsymmetric_3d(ns, i, u);
            o = x.o, d.k = x.k, d.beyond_max_k = x.beyond_max_k;
            if (weigh) d.weight = analytic::sample_nonsymmetric_3d(ns, i, u).weight;
          } else {
            const analytic::VgrooveSample3d x = analytic::sample_vgroove_3d(i, uniforms(rng), s.ndf, s.alpha, opt);
            o = x.o, d.k = x.k, d.beyond_max_k = x.beyond_max_k, d.weight = x.weight;
          }
          if (d.k == 0) return d;
          const int r = std::clamp(static_cast<int>(o.z * t.rows), 0, t.rows - 1);
          const double phi = std::atan2(o.y, o.x);
          const int c =
              std::clamp(static_cast<int>((phi + std::numbers::pi) / (2.0 * std::numbers::pi) * t.cols), 0, t.cols - 1);
          d.cell = static_cast<std::size_t>(r * t.cols + c);
          return d;
        };
      },
      cancel);
}

// The expected counts: the density integrated over each cell.
void expect_3d(Chi2Outcome& out, const HeldDensity* held, const std::atomic<bool>* cancel) {
  const Chi2Spec& s = out.spec;
  Chi2Table& t = out.table;
  t.expected.assign(t.observed.size(), 0.0);
  const analytic::Dir3 i = analytic::dir3(s.theta_i, std::numbers::pi);
  const analytic::SamplerOptions opt{s.strategy, s.max_k};
  const auto t1 = Clock::now();
  const analytic::NonsymmetricSampler ns = s.nonsymmetric ? nonsymmetric_sampler(s) : analytic::NonsymmetricSampler{};
  auto pdf = [&](const analytic::Dir3& o) {
    stop_if(cancel);
    if (held) return held->pdf3(o);
    return s.nonsymmetric ? analytic::nonsymmetric_pdf_3d(ns, i, o)
                          : analytic::vgroove_pdf_3d(i, o, s.ndf, s.alpha, opt);
  };
  const analytic::AdaptiveOptions outer = cell_options(s.samples);
  const double N = static_cast<double>(s.samples);
  // The light is in the (x, z) plane: the pdf is symmetric in phi, so the cells with phi >= 0 are
  // integrated and mirrored (column c and cols - 1 - c). The lobe peaks at the mirror direction
  // (cos(theta_o) = cos(theta_i), phi = 0; the k >= 2 terms diverge there like 1/sin(theta_h)) and
  // narrows in phi towards it at grazing light. Gauss-Kronrod's nodes must see a peak to refine
  // it, so in the cell that holds the mirror direction the pieces are graded geometrically
  // towards phi = 0 and towards cos(theta_i).
  const double ci = std::cos(s.theta_i);
  auto graded = [](std::vector<double>& cuts, double at, double lo, double hi) {
    for (int j = 1; j <= 12; ++j) {
      const double d = std::ldexp(hi - lo, -j);
      for (double x : {at - d, at + d})
        if (x > lo && x < hi) cuts.push_back(x);
    }
    if (at > lo && at < hi) cuts.push_back(at);
  };
  for (int r = 0; r < t.rows; ++r)
    for (int c = t.cols / 2; c < t.cols; ++c) {
      const double c0 = t.row_edges[r], c1 = t.row_edges[r + 1];
      const double p0 = t.col_edges[c], p1 = t.col_edges[c + 1];
      analytic::AdaptiveOptions inner = outer;
      inner.abs_tol = 0.25 * outer.abs_tol / (c1 - c0);
      // Near normal incidence the mirror direction is near the pole, which every column touches.
      const bool mirror_row = ci >= c0 && ci <= c1;
      const bool mirror_cell = mirror_row && (c == t.cols / 2 || std::sin(s.theta_i) < 0.1);
      std::vector<double> phi_cuts{p0, p1};
      if (mirror_row && c == t.cols / 2) graded(phi_cuts, p0, p0, p1);
      std::sort(phi_cuts.begin(), phi_cuts.end());
      auto row = [&](double ct) {
        const double st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
        return analytic::integrate_adaptive(
                   [&](double phi) {
                     return pdf(analytic::Dir3{st * std::cos(phi), st * std::sin(phi), ct});
                   },
                   phi_cuts, inner)
            .value;
      };
      std::vector<double> cuts{c0, c1};
      if (mirror_cell) graded(cuts, ci, c0, c1);
      if (ci > c0 && ci < c1) cuts.push_back(ci);
      std::sort(cuts.begin(), cuts.end());
      const analytic::AdaptiveResult a = analytic::integrate_adaptive(row, cuts, outer);
      for (int cc : {c, t.cols - 1 - c}) t.expected[static_cast<std::size_t>(r * t.cols + cc)] = N * a.value;
      out.pdf_integral += 2.0 * a.value;
      out.quadrature_error += 2.0 * a.error;
    }
  out.integrate_s = seconds_since(t1);
  out.failure_probability = s.nonsymmetric ? analytic::nonsymmetric_failure_probability_3d(ns, i, 1e-8)
                                           : analytic::sampler_failure_probability_3d(i, s.ndf, s.alpha, opt, 1e-9);
  // With every strategy but the printed one, the failures are the paths beyond max_k.
  out.beyond_max_k_probability = s.nonsymmetric ? -1.0
                                 : s.strategy != analytic::FacetStrategy::printed
                                     ? out.failure_probability
                                     : analytic::sampler_beyond_max_k_probability_3d(i, s.ndf, s.alpha, opt, 1e-9);
}

// Flatland: cells over theta_o in [-90, 90] deg.
void sample_flatland(Chi2Outcome& out, const std::atomic<bool>* cancel) {
  const Chi2Spec& s = out.spec;
  Chi2Table& t = out.table;
  t.rows = 1;
  t.cols = s.theta_bins;
  t.row_edges = {0.0, 1.0};
  for (int c = 0; c <= t.cols; ++c) t.col_edges.push_back(-0.5 * std::numbers::pi + std::numbers::pi * c / t.cols);
  const analytic::SamplerOptions opt{s.strategy, s.max_k};
  sample_cells(
      out, 1,
      [&] {
        const analytic::NonsymmetricSampler ns =
            s.nonsymmetric ? nonsymmetric_sampler(s) : analytic::NonsymmetricSampler{};
        return [&s, &t, opt, ns](sim::Rng& rng, bool weigh) {
          Drawn d;
          double theta_o = 0.0;
          if (s.nonsymmetric) {
            const std::array<double, 5> u = uniforms5(rng);
            const analytic::NonsymmetricDrawFlatland x = analytic::draw_nonsymmetric_flatland(ns, s.theta_i, u);
            theta_o = x.theta_o, d.k = x.k, d.beyond_max_k = x.beyond_max_k;
            if (weigh) d.weight = analytic::sample_nonsymmetric_flatland(ns, s.theta_i, u).weight;
          } else {
            const analytic::VgrooveSampleFlatland x =
                analytic::sample_vgroove_flatland(s.theta_i, uniforms(rng), s.ndf, s.alpha, opt);
            theta_o = x.theta_o, d.k = x.k, d.beyond_max_k = x.beyond_max_k, d.weight = x.weight;
          }
          if (d.k == 0) return d;
          d.cell = static_cast<std::size_t>(std::clamp(
              static_cast<int>((theta_o + 0.5 * std::numbers::pi) / std::numbers::pi * t.cols), 0, t.cols - 1));
          return d;
        };
      },
      cancel);
}

void expect_flatland(Chi2Outcome& out, const HeldDensity* held, const std::atomic<bool>* cancel) {
  const Chi2Spec& s = out.spec;
  Chi2Table& t = out.table;
  t.expected.assign(t.observed.size(), 0.0);
  const analytic::SamplerOptions opt{s.strategy, s.max_k};
  const auto t1 = Clock::now();
  const analytic::NonsymmetricSampler ns = s.nonsymmetric ? nonsymmetric_sampler(s) : analytic::NonsymmetricSampler{};
  auto pdf = [&](double to) {
    stop_if(cancel);
    if (held) return held->pdf2(to);
    return s.nonsymmetric ? analytic::nonsymmetric_pdf_flatland(ns, s.theta_i, to)
                          : analytic::vgroove_pdf_flatland(s.theta_i, to, s.ndf, s.alpha, opt);
  };
  const analytic::AdaptiveOptions o = cell_options(s.samples);
  for (int c = 0; c < t.cols; ++c) {
    std::vector<double> cuts{t.col_edges[c], t.col_edges[c + 1]};
    for (double x : {-s.theta_i, s.theta_i})
      if (x > cuts.front() && x < cuts.back()) cuts.insert(cuts.end() - 1, x);
    std::sort(cuts.begin(), cuts.end());
    const analytic::AdaptiveResult a = analytic::integrate_adaptive(pdf, cuts, o);
    t.expected[static_cast<std::size_t>(c)] = static_cast<double>(s.samples) * a.value;
    out.pdf_integral += a.value;
    out.quadrature_error += a.error;
  }
  out.integrate_s = seconds_since(t1);
  out.failure_probability = s.nonsymmetric
                                ? analytic::nonsymmetric_failure_probability_flatland(ns, s.theta_i, 1e-10)
                                : analytic::sampler_failure_probability_flatland(s.theta_i, s.ndf, s.alpha, opt);
  out.beyond_max_k_probability =
      s.nonsymmetric ? -1.0
      : s.strategy != analytic::FacetStrategy::printed
          ? out.failure_probability
          : analytic::sampler_beyond_max_k_probability_flatland(s.theta_i, s.ndf, s.alpha, opt);
}

// The expected counts under the sampler's pdf or the held density, and the test.
void expect_and_test(Chi2Outcome& out, const HeldDensity* held, const std::atomic<bool>* cancel) {
  const Chi2Spec& spec = out.spec;
  out.pdf_integral = out.quadrature_error = 0.0;
  if (spec.dim == SurfaceDim::three_d)
    expect_3d(out, held, cancel);
  else
    expect_flatland(out, held, cancel);
  stop_if(cancel);  // the failure probability's quadrature cannot be stopped: say so after it
  Chi2Table& t = out.table;
  t.expected_none = static_cast<double>(spec.samples) * (held ? held->none : out.failure_probability);
  out.normalization_error = out.pdf_integral + (held ? held->none : out.failure_probability) - 1.0;
  std::vector<double> observed = t.observed, expected = t.expected;
  observed.push_back(t.observed_none);
  expected.push_back(std::max(0.0, t.expected_none));
  out.test = chi_square_test(observed, expected, spec.level, spec.tests);
  // The cells' integrals are asked for to kCellRelTol relative, so their sum to kCellRelTol. (Their
  // error estimates |K15 - G7| are not bounds where the density jumps, which the printed and the
  // bounded densities do along curves that cross the cells: estimates of 1.5e-5 were seen beside
  // errors of 4.6e-5.) The failure probability's quadrature adds 1e-9.
  out.normalization_tolerance = std::max(kCellRelTol, 2.0 * out.quadrature_error) + 1e-9;
  out.pass = !out.test.reject && std::abs(out.normalization_error) <= out.normalization_tolerance;
}

}  // namespace

std::string chi2_table_shape_error(const Chi2Spec& spec, const Chi2Table& t) {
  const bool flat = spec.dim == SurfaceDim::flatland;
  const int rows = flat ? 1 : spec.cos_bins, cols = flat ? spec.theta_bins : spec.phi_bins;
  const auto cells = static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols);
  if (t.rows != rows || t.cols != cols)
    return "is a table of " + std::to_string(t.rows) + " x " + std::to_string(t.cols) + " cells, not the spec's " +
           std::to_string(rows) + " x " + std::to_string(cols);
  if (t.row_edges.size() != static_cast<std::size_t>(rows) + 1 ||
      t.col_edges.size() != static_cast<std::size_t>(cols) + 1)
    return "has " + std::to_string(t.row_edges.size()) + " row and " + std::to_string(t.col_edges.size()) +
           " column edges, not " + std::to_string(rows + 1) + " and " + std::to_string(cols + 1);
  if (t.observed.size() != cells || t.expected.size() != cells)
    return "has " + std::to_string(t.observed.size()) + " observed and " + std::to_string(t.expected.size()) +
           " expected cells, not " + std::to_string(cells);
  return {};
}

Chi2Outcome run_chi2(const Chi2Spec& spec, const HeldDensity* held, const std::atomic<bool>* cancel) {
  Chi2Outcome out;
  out.spec = spec;
  try {
    if (spec.dim == SurfaceDim::three_d)
      sample_3d(out, cancel);
    else
      sample_flatland(out, cancel);
    expect_and_test(out, held, cancel);
  } catch (const Stopped&) {
    out.interrupted = true;
    out.pass = false;
  }
  return out;
}

Chi2Outcome retest_chi2(const Chi2Outcome& sampled, const HeldDensity& held, const std::atomic<bool>* cancel) {
  Chi2Outcome out = sampled;
  try {
    expect_and_test(out, &held, cancel);
  } catch (const Stopped&) {
    out.interrupted = true;
    out.pass = false;
  }
  return out;
}

nlohmann::json chi2_json(const Chi2Outcome& o) {
  const Chi2Spec& s = o.spec;
  const Chi2Table& t = o.table;
  nlohmann::json observed = nlohmann::json::array(), expected = nlohmann::json::array();
  for (int r = 0; r < t.rows; ++r) {
    std::vector<double> ob(t.observed.begin() + r * t.cols, t.observed.begin() + (r + 1) * t.cols);
    std::vector<double> ex(t.expected.begin() + r * t.cols, t.expected.begin() + (r + 1) * t.cols);
    observed.push_back(ob);
    expected.push_back(ex);
  }
  nlohmann::json j = {
      {"dimension", surface_dim_name(s.dim)},
      {"ndf", analytic::ndf_name(s.ndf)},
      {"alpha", s.alpha},
      {"theta_i_deg", output_deg(s.theta_i)},
      {"strategy", analytic::strategy_name(s.strategy)},
      {"model", s.nonsymmetric ? "vgroove-nonsymmetric" : "vgroove"},
      {"max_k", s.max_k},
      {"samples", s.samples},
      {"seed", s.seed},
      {"statistic", o.test.statistic},
      {"dof", o.test.dof},
      {"p_value", o.test.p_value},
      {"level", o.test.level},
      {"pooled_in", o.test.pooled_in},
      {"pooled_out", o.test.pooled_out},
      {"samples_where_none_expected", o.test.samples_where_none_expected},
      {"reject", o.test.reject},
      {"pdf_integral", o.pdf_integral},
      {"quadrature_error", o.quadrature_error},
      {"failure_probability", o.failure_probability},
      {"observed_beyond_max_k", o.observed_beyond_max_k},
      {"beyond_max_k_probability",
       o.beyond_max_k_probability < 0.0 ? nlohmann::json(nullptr) : nlohmann::json(o.beyond_max_k_probability)},
      {"normalization_error", o.normalization_error},
      {"normalization_tolerance", o.normalization_tolerance},
      {"weight_mean", o.weight_mean},
      {"weight_variance", o.weight_variance},
      {"weight_samples", o.weight_samples},
      {"weight_standard_error", std::sqrt(o.weight_variance / static_cast<double>(std::max(1L, o.weight_samples)))},
      {"sample_s", o.sample_s},
      {"integrate_s", o.integrate_s},
      {"pass", o.pass}};
  if (s.ndf == analytic::NdfKind::student_t) j["gamma"] = s.ndf.gamma;
  // Rates from the wall time (report.h: durations end in _s, what is derived from them is under
  // "timing"; neither is compared between runs).
  j["timing"] = {{"ns_per_sample", 1e9 * o.sample_s / static_cast<double>(s.samples)}};
  j["table"] = {{"rows", s.dim == SurfaceDim::three_d ? "cos_theta_o" : "one row"},
                {"cols", s.dim == SurfaceDim::three_d ? "phi_o (rad)" : "theta_o (rad)"},
                {"row_edges", t.row_edges},
                {"col_edges", t.col_edges},
                {"observed", observed},
                {"expected", expected},
                {"observed_no_direction", t.observed_none},
                {"expected_no_direction", t.expected_none}};
  return j;
}

// ---- Variance and efficiency ---------------------------------------------------------------------

namespace {
analytic::NonsymmetricModel nonsymmetric_model(const VarianceSpec& spec) {
  analytic::NonsymmetricModel m;
  m.roughness = analytic::isotropic_roughness(spec.ndf, spec.alpha);
  return m;
}
}  // namespace

VarianceOutcome run_variance(const VarianceSpec& spec, const std::atomic<bool>* cancel) {
  VarianceOutcome out;
  out.spec = spec;
  const bool three_d = spec.dim == SurfaceDim::three_d;
  const analytic::Dir3 i = analytic::dir3(spec.theta_i, std::numbers::pi);
  analytic::FresnelFn F;
  if (spec.schlick_f0 < 1.0) {
    const double f0 = spec.schlick_f0;
    F = [f0](double c) { return f0 + (1.0 - f0) * std::pow(1.0 - std::clamp(c, 0.0, 1.0), 5.0); };
  }
  auto run = [&](const std::string& name, auto&& draw) {
    sim::Rng rng(spec.seed, 0x7a11, 0);
    double sum = 0.0, sum2 = 0.0;
    long none = 0;
    const auto t0 = Clock::now();
    for (long n = 0; n < spec.samples; ++n) {
      stop_if(cancel);
      const auto [w, returned] = draw(uniforms5(rng));
      sum += w, sum2 += w * w;
      none += !returned;
    }
    const double secs = seconds_since(t0);
    StrategyStats st;
    st.strategy = name;
    const double N = static_cast<double>(spec.samples);
    st.mean = sum / N;
    st.variance = std::max(0.0, sum2 / N - st.mean * st.mean) * N / std::max(1.0, N - 1.0);
    st.standard_error = std::sqrt(st.variance / N);
    st.no_direction = static_cast<double>(none) / N;
    st.ns_per_sample = 1e9 * secs / N;
    st.efficiency = st.variance > 0.0 ? 1.0 / (st.variance * secs / N) : std::numeric_limits<double>::infinity();
    out.rows.push_back(st);
  };
  try {
    for (analytic::FacetStrategy s : {analytic::FacetStrategy::printed, analytic::FacetStrategy::vndf,
                                      analytic::FacetStrategy::smith_vndf, analytic::FacetStrategy::bounded_vndf}) {
      if (!analytic::strategy_supports(s, spec.ndf, !three_d)) continue;
      const analytic::SamplerOptions opt{s, spec.max_k};
      if (spec.nonsymmetric) {
        const analytic::NonsymmetricSampler ns =
            analytic::make_nonsymmetric_sampler(spec.ndf, spec.alpha, opt, !three_d);
        if (three_d)
          run(analytic::strategy_name(s), [&](const std::array<double, 5>& u) {
            const analytic::VgrooveSample3d x = analytic::sample_nonsymmetric_3d(ns, i, u, F);
            return std::pair<double, bool>{x.weight, x.k > 0};
          });
        else
          run(analytic::strategy_name(s), [&](const std::array<double, 5>& u) {
            const analytic::VgrooveSampleFlatland x = analytic::sample_nonsymmetric_flatland(ns, spec.theta_i, u);
            return std::pair<double, bool>{x.weight, x.k > 0};
          });
        continue;
      }
      if (three_d)
        run(analytic::strategy_name(s), [&](const std::array<double, 5>& u5) {
          const std::array<double, 4> u{u5[0], u5[1], u5[2], u5[3]};
          const analytic::VgrooveSample3d x = analytic::sample_vgroove_3d(i, u, spec.ndf, spec.alpha, opt, F);
          return std::pair<double, bool>{x.weight, x.k > 0};
        });
      else
        run(analytic::strategy_name(s), [&](const std::array<double, 5>& u5) {
          const std::array<double, 4> u{u5[0], u5[1], u5[2], u5[3]};
          const analytic::VgrooveSampleFlatland x =
              analytic::sample_vgroove_flatland(spec.theta_i, u, spec.ndf, spec.alpha, opt);
          return std::pair<double, bool>{x.weight, x.k > 0};
        });
    }
    // Cosine-weighted sampling: weight = rho cos / (cos / pi) = pi rho (flatland: 2 rho2).
    if (three_d)
      run("cosine", [&](const std::array<double, 5>& u) {
        const analytic::Dir3 o = analytic::sample_cosine_hemisphere(u[0], u[1]);
        const double pdf = analytic::cosine_hemisphere_pdf(o);
        const double rho = spec.nonsymmetric
                               ? analytic::nonsymmetric_brdf(i, o, spec.max_k, nonsymmetric_model(spec), F)
                               : analytic::vgroove_brdf(i, o, spec.ndf, spec.alpha, spec.max_k, F);
        return std::pair<double, bool>{pdf > 0.0 && std::isfinite(rho) ? rho * o.z / pdf : 0.0, pdf > 0.0};
      });
    else
      run("cosine", [&](const std::array<double, 5>& u) {
        const double to = analytic::sample_cosine_flatland(u[0]);
        const double pdf = analytic::cosine_flatland_pdf(to);
        const analytic::SamplerOptions opt{analytic::FacetStrategy::vndf, spec.max_k};
        const double rho_cos =
            spec.nonsymmetric
                ? analytic::flatland_nonsymmetric_brdf(spec.theta_i, to, spec.max_k, nonsymmetric_model(spec)) *
                      std::cos(to)
                : analytic::vgroove_pdf_and_brdf_flatland(spec.theta_i, to, spec.ndf, spec.alpha, opt).rho_cos;
        return std::pair<double, bool>{pdf > 0.0 ? rho_cos / pdf : 0.0, pdf > 0.0};
      });
  } catch (const Stopped&) {
    out.interrupted = true;
    return out;
  }
  const auto lowest =
      std::min_element(out.rows.begin(), out.rows.end(),
                       [](const StrategyStats& a, const StrategyStats& b) { return a.variance < b.variance; });
  const auto best =
      std::max_element(out.rows.begin(), out.rows.end(),
                       [](const StrategyStats& a, const StrategyStats& b) { return a.efficiency < b.efficiency; });
  out.lowest_variance = lowest->strategy;
  out.most_efficient = best->strategy;
  return out;
}

nlohmann::json variance_json(const VarianceOutcome& o) {
  // The statistics of the weights, the same bits for any thread count and load; the cost per
  // sample and what follows from it (the efficiency 1 / (variance x time), infinite where the
  // variance is 0, and the strategy it favours) under "timing", which runs are not compared on.
  nlohmann::json rows = nlohmann::json::array(), timing = nlohmann::json::array();
  for (const StrategyStats& s : o.rows) {
    rows.push_back({{"strategy", s.strategy},
                    {"mean_weight", s.mean},
                    {"variance", s.variance},
                    {"standard_error", s.standard_error},
                    {"no_direction", s.no_direction}});
    timing.push_back({{"strategy", s.strategy}, {"ns_per_sample", s.ns_per_sample}, {"efficiency", s.efficiency}});
  }
  const VarianceSpec& s = o.spec;
  nlohmann::json v = {
      {"dimension", surface_dim_name(s.dim)},
      {"ndf", analytic::ndf_name(s.ndf)},
      {"alpha", s.alpha},
      {"theta_i_deg", output_deg(s.theta_i)},
      {"model", s.nonsymmetric ? "vgroove-nonsymmetric" : "vgroove"},
      {"max_k", s.max_k},
      {"samples", s.samples},
      {"fresnel", s.schlick_f0 < 1.0 ? "schlick F0 = " + std::to_string(s.schlick_f0) : std::string("none (F = 1)")},
      {"strategies", rows},
      {"lowest_variance", o.lowest_variance},
      {"timing", {{"strategies", timing}, {"most_efficient", o.most_efficient}}}};
  if (s.ndf == analytic::NdfKind::student_t) v["gamma"] = s.ndf.gamma;
  return v;
}

}  // namespace vgroove::validation
