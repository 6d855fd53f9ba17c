#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"

#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/analytic/kaleidoscope_dielectric_lobe.h"
#include "vgroove/analytic/masking_kind.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_dielectric.h"
#include "vgroove/analytic/sampling_nonsymmetric.h"
#include "vgroove/analytic/walter_sampling.h"
#include "vgroove/app/options.h"
#include "vgroove/app/progress.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/seconds_since.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/chi_square.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/sampling_check.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <utility>
#include <vector>

namespace vgroove::app {

namespace {

[[noreturn]] void out_of_range(const std::string& flag, double v, const std::string& range) {
  throw support::UserError(flag + " = " + support::number_text(v) + " is out of range " + range);
}

// Walter's options (--eta, --masking), refused with the other models, and the reflection
// samplers' options (--strategy, --max-k, --dim flatland) refused with Walter's.
analytic::MaskingKind check_walter_options(const SampleArgs& a, NdfKind ndf) {
  const bool walter = a.model == "walter";
  const bool dielectric = a.model == "vgroove-dielectric";
  if (a.eta_given && !walter && !dielectric)
    // The words of python/vgroove/_sampling.py's message (tests/python/test_sample_walter.py holds the
    // two equal).
    throw support::UserError("--eta applies to --model walter and vgroove-dielectric only (--model = \"" + a.model +
                             "\")");
  if (a.masking_given && !walter)
    throw support::UserError("--masking applies to --model walter only (--model = \"" + a.model + "\")");
  if (dielectric) {
    if (a.strategy_given)
      throw support::UserError(
          "--strategy applies to --model vgroove and vgroove-nonsymmetric only (vgroove-dielectric draws its "
          "grooves from the NDF and its chains by their energy)");
    if (a.max_k_given)
      throw support::UserError(
          "--max-k applies to --model vgroove and vgroove-nonsymmetric only (vgroove-dielectric takes every chain "
          "of grooves with k <= 32)");
    if (!(a.eta > 0.0 && a.eta <= validation::kMaxFresnelEta && a.eta != 1.0))
      out_of_range("--eta", a.eta,
                   support::interval_text(0, false, validation::kMaxFresnelEta, true) +
                       ", not 1, with --model vgroove-dielectric (at eta = 1 every chain goes straight through: "
                       "a delta, no lobe to sample)");
  }
  if (!walter) return analytic::MaskingKind::smith_separable;
  if (a.strategy_given)
    throw support::UserError(
        "--strategy applies to --model vgroove and vgroove-nonsymmetric only (walter draws "
        "its facets from the Smith VNDF for ggx, from |m.n| D(m) for beckmann and phong)");
  if (a.max_k_given)
    throw support::UserError(
        "--max-k applies to --model vgroove and vgroove-nonsymmetric only (walter is single "
        "scattering)");
  if (a.dim != "3d")
    throw support::UserError("--dim = \"" + a.dim + "\" is not available with --model walter (its sampler is 3d only)");
  if (!(a.eta > 0.0 && a.eta <= validation::kMaxFresnelEta && a.eta != 1.0))
    out_of_range("--eta", a.eta,
                 support::interval_text(0, false, validation::kMaxFresnelEta, true) +
                     ", not 1, with --model walter (at eta = 1 the light goes straight through: a delta, no "
                     "density to sample)");
  const auto masking = analytic::masking_from_flag(a.masking);
  if (!masking)
    throw support::UserError("--masking = \"" + a.masking +
                             "\" is not one of \"smith\", \"smith_separable\", \"vcavity\"");
  if (!analytic::masking_supported(*masking, ndf))
    throw support::UserError("--masking = \"" + a.masking +
                             "\" needs --ndf ggx or beckmann (Smith's Lambda has no closed form for phong); "
                             "--masking vcavity takes phong");
  return *masking;
}

// Walter's BSDF sampled (analytic/walter_sampling.h): draws over the whole sphere, histogrammed on
// cells of (cos theta_o in [-1, 1], phi_o), held to walter_pdf integrated over each cell (nested
// adaptive Gauss-Kronrod) by chi-square; one cell for the draws that give no direction, expected
// N (1 - the cells' sum). The weights f |cos theta_o| / pdf: their mean is the albedo R + T.
struct WalterRun {
  int rows = 0, cols = 0;  // rows: cos theta_o from -1 (2 --cos-bins), cols: phi_o from -pi
  std::vector<double> observed, expected;
  double observed_none = 0.0, expected_none = 0.0;
  double pdf_reflected = 0.0, pdf_transmitted = 0.0;  // the pdf's integral over each hemisphere
  long reflected = 0, transmitted = 0;
  double sum = 0.0, sum2 = 0.0, sum_r = 0.0, sum_t = 0.0;  // the weights: all, reflected, transmitted
  double sample_s = 0.0, integrate_s = 0.0;
  validation::ChiSquareResult test;
  bool interrupted = false;
};

// The stream of the walter draws: (seed, (0x5a3d, 2)), three numbers a draw (u0, u1: the facet; u2:
// the branch), as Python's vgroove.uniforms(n, seed, (0x5a3d, 2), dims=3).
constexpr std::uint64_t kWalterStream = 2;

// Thrown by the density once the cancellation flag is set: the quadrature stops at once.
struct Stopped {};

WalterRun run_walter(const SampleArgs& a, NdfKind ndf, analytic::MaskingKind g) {
  using support::Clock;
  WalterRun w;
  w.rows = 2 * a.cos_bins, w.cols = a.phi_bins;
  w.observed.assign(static_cast<std::size_t>(w.rows * w.cols), 0.0);
  const analytic::Dir3 i = analytic::dir3(a.theta_i_deg * kRadPerDeg, std::numbers::pi);
  const auto t0 = Clock::now();
  sim::Rng rng(static_cast<std::uint64_t>(a.seed), 0x5a3d, kWalterStream);
  for (long n = 0; n < a.n; ++n) {
    if (support::cancelled(a.cancel)) {
      w.interrupted = true;
      return w;
    }
    const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    const analytic::WalterSample x = analytic::sample_walter(ndf, a.alpha, a.eta, g, i, u0, u1, u2);
    w.sum += x.weight, w.sum2 += x.weight * x.weight;
    if (!x.ok) {
      w.observed_none += 1.0;
      continue;
    }
    (x.transmitted ? w.sum_t : w.sum_r) += x.weight;
    ++(x.transmitted ? w.transmitted : w.reflected);
    const int r = std::clamp(static_cast<int>((x.o.z + 1.0) * 0.5 * w.rows), 0, w.rows - 1);
    const int c =
        std::clamp(static_cast<int>((std::atan2(x.o.y, x.o.x) + std::numbers::pi) / (2.0 * std::numbers::pi) * w.cols),
                   0, w.cols - 1);
    w.observed[static_cast<std::size_t>(r * w.cols + c)] += 1.0;
  }
  w.sample_s = support::seconds_since(t0);

  // The expected counts. The light is in the (x, z) plane: the pdf is symmetric in phi, so the cells
  // with phi >= 0 are integrated and mirrored. Both lobes peak at phi = 0, the reflection at
  // cos theta_o = cos theta_i and the transmission at -cos theta_t (Snell; none under total
  // internal reflection): the cells that hold a peak are cut geometrically towards it, as
  // validation/sampling_check.cpp does, so that Gauss-Kronrod's nodes see it.
  const auto t1 = Clock::now();
  w.expected.assign(w.observed.size(), 0.0);
  const double ci = std::cos(a.theta_i_deg * kRadPerDeg), si = std::sin(a.theta_i_deg * kRadPerDeg);
  std::vector<double> peaks{ci};
  if (si < a.eta) peaks.push_back(-std::sqrt(1.0 - si * si / (a.eta * a.eta)));
  auto graded = [](std::vector<double>& cuts, double at, double lo, double hi) {
    for (int j = 1; j <= 12; ++j) {
      const double d = std::ldexp(hi - lo, -j);
      for (double x : {at - d, at + d})
        if (x > lo && x < hi) cuts.push_back(x);
    }
    if (at > lo && at < hi) cuts.push_back(at);
  };
  const double N = static_cast<double>(a.n);
  analytic::AdaptiveOptions outer;
  outer.rel_tol = validation::kCellRelTol;
  outer.abs_tol = 0.05 / N;
  outer.max_pieces = 400;
  double sum = 0.0;
  try {
    for (int r = 0; r < w.rows; ++r)
      for (int c = w.cols / 2; c < w.cols; ++c) {
        const double c0 = -1.0 + 2.0 * r / w.rows, c1 = -1.0 + 2.0 * (r + 1) / w.rows;
        const double p0 = -std::numbers::pi + 2.0 * std::numbers::pi * c / w.cols;
        const double p1 = -std::numbers::pi + 2.0 * std::numbers::pi * (c + 1) / w.cols;
        analytic::AdaptiveOptions inner = outer;
        inner.abs_tol = 0.25 * outer.abs_tol / (c1 - c0);
        std::vector<double> cuts{c0, c1}, phi_cuts{p0, p1};
        bool peak_row = false;
        for (double pk : peaks) {
          if (!(pk >= c0 && pk <= c1)) continue;
          peak_row = true;
          // Near a pole every column touches the peak.
          if (c == w.cols / 2 || std::sqrt(std::max(0.0, 1.0 - pk * pk)) < 0.1) graded(cuts, pk, c0, c1);
        }
        if (peak_row && c == w.cols / 2) graded(phi_cuts, p0, p0, p1);
        std::sort(cuts.begin(), cuts.end());
        std::sort(phi_cuts.begin(), phi_cuts.end());
        auto row = [&](double ct) {
          const double st = std::sqrt(std::max(0.0, 1.0 - ct * ct));
          return analytic::integrate_adaptive(
                     [&](double phi) {
                       if (support::cancelled(a.cancel)) throw Stopped{};
                       return analytic::walter_pdf(ndf, a.alpha, a.eta, i,
                                                   analytic::Dir3{st * std::cos(phi), st * std::sin(phi), ct});
                     },
                     phi_cuts, inner)
              .value;
        };
        const double v = analytic::integrate_adaptive(row, cuts, outer).value;
        for (int cc : {c, w.cols - 1 - c}) w.expected[static_cast<std::size_t>(r * w.cols + cc)] = N * v;
        sum += 2.0 * v;
        (r < w.rows / 2 ? w.pdf_transmitted : w.pdf_reflected) += 2.0 * v;
      }
  } catch (const Stopped&) {
    w.interrupted = true;
    return w;
  }
  w.integrate_s = support::seconds_since(t1);
  w.expected_none = N * std::max(0.0, 1.0 - sum);
  std::vector<double> observed = w.observed, expected = w.expected;
  observed.push_back(w.observed_none);
  expected.push_back(w.expected_none);
  w.test = validation::chi_square_test(observed, expected, 0.01, 1);
  return w;
}

int sample_walter_command(const SampleArgs& a, NdfKind ndf, analytic::MaskingKind g) {
  const WalterRun w = run_walter(a, ndf, g);
  if (w.interrupted) return interrupted_no_report();
  if (w.test.dof < 1 && !w.test.samples_where_none_expected)
    throw support::UserError("--n = " + std::to_string(a.n) + " is too few samples for a chi-square test (the " +
                             std::to_string(w.test.pooled_in) + " cells pool into " +
                             std::to_string(w.test.pooled_out) +
                             " with >= 5 expected samples each; the test needs two): give a larger --n");
  const double N = static_cast<double>(a.n);
  const double mean = w.sum / N;
  const double variance = N > 1.0 ? std::max(0.0, w.sum2 / N - mean * mean) * N / (N - 1.0) : 0.0;
  const double se = std::sqrt(variance / N);
  const double share_r = static_cast<double>(w.reflected) / N, share_t = static_cast<double>(w.transmitted) / N;
  std::printf("sample: walter 3d %s alpha %g, eta %g, masking %s, theta_i %g deg, %ld samples (seed %lld)\n",
              a.ndf.c_str(), a.alpha, a.eta, a.masking.c_str(), a.theta_i_deg, a.n, a.seed);
  std::printf(
      "  reflected %ld (share %.6f; the pdf's integral above %.6f), transmitted %ld (share %.6f; below %.6f), "
      "no direction %.0f (expected %.1f)\n",
      w.reflected, share_r, w.pdf_reflected, w.transmitted, share_t, w.pdf_transmitted, w.observed_none,
      w.expected_none);
  std::printf(
      "  weight f |cos theta_o| / pdf: mean %.6f (the albedo R + T), standard deviation %.4g, standard error %.2g; "
      "R %.6f, T %.6f; %.0f ns per sample\n",
      mean, std::sqrt(variance), se, w.sum_r / N, w.sum_t / N, 1e9 * w.sample_s / N);
  std::printf("  chi-square %.2f, dof %d (%d cells pooled into %d), p = %.4g at level %.3g: %s\n", w.test.statistic,
              w.test.dof, w.test.pooled_in, w.test.pooled_out, w.test.p_value, w.test.level,
              w.test.reject ? "REJECTED" : "accepted");
  if (!a.out.empty()) {
    nlohmann::json observed = nlohmann::json::array(), expected = nlohmann::json::array();
    for (int r = 0; r < w.rows; ++r) {
      observed.push_back(std::vector<double>(w.observed.begin() + r * w.cols, w.observed.begin() + (r + 1) * w.cols));
      expected.push_back(std::vector<double>(w.expected.begin() + r * w.cols, w.expected.begin() + (r + 1) * w.cols));
    }
    std::vector<double> row_edges, col_edges;
    for (int r = 0; r <= w.rows; ++r) row_edges.push_back(-1.0 + 2.0 * r / w.rows);
    for (int c = 0; c <= w.cols; ++c) col_edges.push_back(-std::numbers::pi + 2.0 * std::numbers::pi * c / w.cols);
    nlohmann::json j = validation::provenance();
    j["command"] = "sample";
    j["result"] = {{"dimension", "3d"},
                   {"model", "walter"},
                   {"ndf", a.ndf},
                   {"alpha", a.alpha},
                   {"eta", a.eta},
                   {"masking", a.masking},
                   {"theta_i_deg", a.theta_i_deg},
                   {"samples", a.n},
                   {"seed", a.seed},
                   {"table",
                    {{"row_edges", row_edges},
                     {"col_edges", col_edges},
                     {"observed", observed},
                     {"expected", expected},
                     {"observed_no_direction", w.observed_none},
                     {"expected_no_direction", w.expected_none}}},
                   {"statistic", w.test.statistic},
                   {"dof", w.test.dof},
                   {"p_value", w.test.p_value},
                   {"level", w.test.level},
                   {"pooled_in", w.test.pooled_in},
                   {"pooled_out", w.test.pooled_out},
                   {"samples_where_none_expected", w.test.samples_where_none_expected},
                   {"reject", w.test.reject},
                   {"reflected", w.reflected},
                   {"transmitted", w.transmitted},
                   {"pdf_reflected", w.pdf_reflected},
                   {"pdf_transmitted", w.pdf_transmitted},
                   {"weight_mean", mean},
                   {"weight_variance", variance},
                   {"weight_samples", a.n},
                   {"weight_standard_error", se},
                   {"weight_mean_reflected", w.sum_r / N},
                   {"weight_mean_transmitted", w.sum_t / N},
                   {"sample_s", w.sample_s},
                   {"integrate_s", w.integrate_s},
                   {"pass", !w.test.reject}};
    support::write_file_atomically(a.out, support::json_text(j, 1) + "\n", a.force);
    std::cout << "result: " << support::printable(a.out) << "\n";
  }
  return w.test.reject ? 1 : 0;
}

// The kaleidoscopic dielectric model sampled (analytic/sampling_dielectric.h): the draws histogrammed
// on the bins of kaleidoscope_dielectric_lobe.h (flatland: --theta-bins over (-90, 90) deg on each
// side; 3d: --theta-bins from the exit side's normal x --phi-bins), reflected and transmitted, plus
// one cell for the draws that give no direction, held to the lobe (deterministic quadrature) by
// chi-square. The draws: the stream (seed, (0x5a3d, 3)) in 3d (five numbers) and (seed, (0x5a3d, 4))
// in flatland (four).
constexpr std::uint64_t kDielectricStream3d = 3, kDielectricStreamFlatland = 4;

int sample_dielectric_command(const SampleArgs& a, NdfKind ndf) {
  using support::Clock;
  const bool flatland = a.dim == "flatland";
  const double ti = a.theta_i_deg * kRadPerDeg;
  const int bins = flatland ? a.theta_bins : a.theta_bins * a.phi_bins;
  const auto t0 = Clock::now();
  const analytic::DielectricLobe L =
      flatland ? analytic::kaleidoscope_dielectric_lobe_flatland(ndf, a.alpha, a.eta, ti, a.theta_bins, 0)
               : analytic::kaleidoscope_dielectric_lobe_3d(ndf, a.alpha, a.eta, ti, a.theta_bins, a.phi_bins, 0);
  const double integrate_s = support::seconds_since(t0);
  if (support::cancelled(a.cancel)) return interrupted_no_report();
  const double N = static_cast<double>(a.n);
  // Cells: reflected [bins], transmitted [bins], no direction.
  std::vector<double> observed(2 * bins + 1, 0.0), expected(2 * bins + 1, 0.0);
  for (int b = 0; b < bins; ++b) expected[b] = N * L.reflected[b], expected[bins + b] = N * L.transmitted[b];
  expected.back() = N * std::max(0.0, 1.0 - L.albedo_r - L.albedo_t);
  long upward = 0, unresolved = 0, reflected = 0, transmitted = 0;
  const auto t1 = Clock::now();
  sim::Rng rng(static_cast<std::uint64_t>(a.seed), 0x5a3d, flatland ? kDielectricStreamFlatland : kDielectricStream3d);
  const double dtheta = (flatland ? std::numbers::pi : 0.5 * std::numbers::pi) / a.theta_bins;
  const double dphi = 2.0 * std::numbers::pi / a.phi_bins;
  for (long n = 0; n < a.n; ++n) {
    if (support::cancelled(a.cancel)) return interrupted_no_report();
    int bin = -1;
    bool refl = false;
    analytic::DielectricSampleFailure failure = analytic::DielectricSampleFailure::other;
    if (flatland) {
      const std::array<double, 4> u{rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
      const analytic::DielectricSampleFlatland x =
          analytic::sample_vgroove_dielectric_flatland(ti, u, ndf, a.alpha, a.eta);
      failure = x.failure;
      if (x.weight > 0.0) {
        refl = x.reflected;
        bin = std::clamp(static_cast<int>(std::floor((x.theta_o + 0.5 * std::numbers::pi) / dtheta)), 0,
                         a.theta_bins - 1);
      }
    } else {
      const std::array<double, 5> u{rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
      const analytic::DielectricSample3d x = analytic::sample_vgroove_dielectric_3d(ti, u, ndf, a.alpha, a.eta);
      failure = x.failure;
      if (x.weight > 0.0) {
        refl = x.reflected;
        // The lobe's bins: theta from the exit side's normal, phi bins centred on phi = 0 (light at pi).
        const int t = std::min(a.theta_bins - 1,
                               static_cast<int>(std::atan2(std::hypot(x.o.x, x.o.y), std::abs(x.o.z)) / dtheta));
        int p = static_cast<int>(std::floor((std::atan2(x.o.y, x.o.x) + 0.5 * dphi) / dphi));
        p = ((p % a.phi_bins) + a.phi_bins) % a.phi_bins;
        bin = t * a.phi_bins + p;
      }
    }
    if (bin < 0) {
      observed.back() += 1.0;
      if (failure == analytic::DielectricSampleFailure::upward) ++upward;
      if (failure == analytic::DielectricSampleFailure::unresolved) ++unresolved;
      continue;
    }
    ++(refl ? reflected : transmitted);
    observed[static_cast<std::size_t>(refl ? bin : bins + bin)] += 1.0;
  }
  const double sample_s = support::seconds_since(t1);
  const validation::ChiSquareResult test = validation::chi_square_test(observed, expected, 0.01, 1);
  if (test.dof < 1 && !test.samples_where_none_expected)
    throw support::UserError("--n = " + std::to_string(a.n) + " is too few samples for a chi-square test (the " +
                             std::to_string(test.pooled_in) + " cells pool into " + std::to_string(test.pooled_out) +
                             " with >= 5 expected samples each; the test needs two): give a larger --n");
  std::printf("sample: vgroove-dielectric %s %s alpha %g, eta %g, theta_i %g deg, %ld samples (seed %lld)\n",
              a.dim.c_str(), a.ndf.c_str(), a.alpha, a.eta, a.theta_i_deg, a.n, a.seed);
  std::printf(
      "  reflected %ld (share %.6f; the model's R %.6f), transmitted %ld (share %.6f; T %.6f), no direction %.0f "
      "(expected %.1f; of them upward %ld, k > 32 %ld); weight 1 a direction; %.0f ns per sample\n",
      reflected, reflected / N, L.albedo_r, transmitted, transmitted / N, L.albedo_t, observed.back(), expected.back(),
      upward, unresolved, 1e9 * sample_s / N);
  std::printf("  the lobe: error estimate %.2e a bin (%.2f s)\n", L.error_estimate, integrate_s);
  std::printf("  chi-square %.2f, dof %d (%d cells pooled into %d), p = %.4g at level %.3g: %s\n", test.statistic,
              test.dof, test.pooled_in, test.pooled_out, test.p_value, test.level,
              test.reject ? "REJECTED" : "accepted");
  if (!a.out.empty()) {
    nlohmann::json j = validation::provenance();
    j["command"] = "sample";
    j["result"] = {{"dimension", a.dim},
                   {"model", "vgroove-dielectric"},
                   {"ndf", a.ndf},
                   {"alpha", a.alpha},
                   {"eta", a.eta},
                   {"theta_i_deg", a.theta_i_deg},
                   {"samples", a.n},
                   {"seed", a.seed},
                   {"theta_bins", a.theta_bins},
                   {"phi_bins", flatland ? 0 : a.phi_bins},
                   {"observed_reflected", std::vector<double>(observed.begin(), observed.begin() + bins)},
                   {"observed_transmitted", std::vector<double>(observed.begin() + bins, observed.end() - 1)},
                   {"expected_reflected", std::vector<double>(expected.begin(), expected.begin() + bins)},
                   {"expected_transmitted", std::vector<double>(expected.begin() + bins, expected.end() - 1)},
                   {"observed_no_direction", observed.back()},
                   {"expected_no_direction", expected.back()},
                   {"albedo_r", L.albedo_r},
                   {"albedo_t", L.albedo_t},
                   {"lobe_error_estimate", L.error_estimate},
                   {"statistic", test.statistic},
                   {"dof", test.dof},
                   {"p_value", test.p_value},
                   {"level", test.level},
                   {"pooled_in", test.pooled_in},
                   {"pooled_out", test.pooled_out},
                   {"samples_where_none_expected", test.samples_where_none_expected},
                   {"reject", test.reject},
                   {"sample_s", sample_s},
                   {"integrate_s", integrate_s},
                   {"pass", !test.reject}};
    support::write_file_atomically(a.out, support::json_text(j, 1) + "\n", a.force);
    std::cout << "result: " << support::printable(a.out) << "\n";
  }
  return test.reject ? 1 : 0;
}

}  // namespace

int cmd_sample(const SampleArgs& a) {
  const auto ndf = ndf_from_name(a.ndf);
  if (!ndf) throw support::UserError("--ndf = \"" + a.ndf + "\" is not one of \"ggx\", \"beckmann\", \"phong\"");
  if (!(a.alpha >= validation::kMinAlpha && a.alpha <= validation::kMaxAlpha))
    out_of_range("--alpha", a.alpha, support::interval_text(validation::kMinAlpha, true, validation::kMaxAlpha, true));
  if (!(a.theta_i_deg >= 0.0 && a.theta_i_deg <= validation::kMaxSurfaceThetaIDeg))
    out_of_range("--theta-i-deg", a.theta_i_deg,
                 support::interval_text(0.0, true, validation::kMaxSurfaceThetaIDeg, true));
  if (a.n < 1 || a.n > validation::kMaxRays)
    out_of_range("--n", static_cast<double>(a.n), support::interval_text(1, true, validation::kMaxRays, true));
  if (a.dim != "3d" && a.dim != "flatland")
    throw support::UserError("--dim = \"" + a.dim + "\" is not one of \"3d\", \"flatland\"");
  const bool flatland = a.dim == "flatland";
  const auto strategy = analytic::strategy_from_name(a.strategy);
  if (!strategy)
    throw support::UserError("--strategy = \"" + a.strategy +
                             "\" is not one of \"printed\", \"vndf\", \"smith-vndf\", \"bounded-vndf\"");
  if (!analytic::strategy_supports(*strategy, *ndf, flatland))
    throw support::UserError("--strategy = \"" + a.strategy + "\" does not exist for --ndf " + a.ndf + " --dim " +
                             a.dim + " (smith-vndf: ggx only; bounded-vndf: ggx in 3d only)");
  // The message is python/vgroove/_sampling.py's too (python/src/sampling.cpp, parse_sampler_model).
  if (a.model != "vgroove" && a.model != "vgroove-nonsymmetric" && a.model != "walter" &&
      a.model != "vgroove-dielectric")
    throw support::UserError(
        "--model = \"" + a.model +
        "\" is not one of \"vgroove\", \"vgroove-nonsymmetric\", \"walter\", \"vgroove-dielectric\"");
  const analytic::MaskingKind masking = check_walter_options(a, *ndf);
  const bool walter = a.model == "walter";
  const bool nonsymmetric = a.model == "vgroove-nonsymmetric";
  if (nonsymmetric && *ndf == analytic::NdfKind::phong && a.alpha > 1.0)
    out_of_range("--alpha", a.alpha,
                 "(0, 1] for --model vgroove-nonsymmetric with --ndf phong (the partner law's table)");
  using validation::kMaxSamplerK, validation::kMaxSampleCosBins, validation::kMaxSamplePhiBins,
      validation::kMaxSampleThetaBins;
  auto range = [](int lo, int hi) { return "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]"; };
  if (a.max_k < 1 || a.max_k > kMaxSamplerK) out_of_range("--max-k", a.max_k, range(1, kMaxSamplerK));
  check_seed(a.seed, "--seed");
  if (a.cos_bins < 1 || a.cos_bins > kMaxSampleCosBins)
    out_of_range("--cos-bins", a.cos_bins, range(1, kMaxSampleCosBins));
  if (a.phi_bins < 2 || a.phi_bins > kMaxSamplePhiBins || a.phi_bins % 2 != 0)
    out_of_range("--phi-bins", a.phi_bins, range(2, kMaxSamplePhiBins) + ", even");
  if (a.theta_bins < 1 || a.theta_bins > kMaxSampleThetaBins)
    out_of_range("--theta-bins", a.theta_bins, range(1, kMaxSampleThetaBins));
  if (!a.out.empty()) support::check_writable_target(a.out, a.force);  // fail before the work, not after
  if (a.dry_run) return 0;
  if (walter) return sample_walter_command(a, *ndf, masking);
  if (a.model == "vgroove-dielectric") return sample_dielectric_command(a, *ndf);

  validation::Chi2Spec s;
  s.dim = flatland ? validation::SurfaceDim::flatland : validation::SurfaceDim::three_d;
  s.ndf = *ndf;
  s.alpha = a.alpha;
  s.theta_i = a.theta_i_deg * kRadPerDeg;
  s.strategy = *strategy;
  s.nonsymmetric = nonsymmetric;
  s.max_k = nonsymmetric && !a.max_k_given ? analytic::kNonsymmetricSamplerMaxK : a.max_k;
  s.samples = a.n;
  s.seed = static_cast<std::uint64_t>(a.seed);
  s.cos_bins = a.cos_bins;
  s.phi_bins = a.phi_bins;
  s.theta_bins = a.theta_bins;
  const validation::Chi2Outcome o = validation::run_chi2(s, nullptr, a.cancel);
  if (o.interrupted) return interrupted_no_report();
  // With too few samples the cells pool into fewer than two of >= 5 expected samples each: no
  // chi-square test is possible, which is no verdict on the sampler ("p = 1 ... REJECTED").
  if (o.test.dof < 1 && !o.test.samples_where_none_expected)
    throw support::UserError("--n = " + std::to_string(a.n) + " is too few samples for a chi-square test (the " +
                             std::to_string(o.test.pooled_in) + " cells pool into " +
                             std::to_string(o.test.pooled_out) +
                             " with >= 5 expected samples each; the test needs two): give a larger --n");

  const double se = std::sqrt(o.weight_variance / static_cast<double>(std::max(1L, o.weight_samples)));
  std::printf("sample: %s %s %s alpha %g, theta_i %g deg, strategy %s, max_k %d, %ld samples (seed %lld)\n",
              a.model.c_str(), a.dim.c_str(), a.ndf.c_str(), a.alpha, a.theta_i_deg, a.strategy.c_str(), s.max_k, a.n,
              a.seed);
  std::printf("  no direction: %.0f of %ld (expected %.1f: the sampler's failure probability %.3e)\n",
              o.table.observed_none, a.n, o.table.expected_none, o.failure_probability);
  if (o.beyond_max_k_probability >= 0.0)
    std::printf("  lost beyond max_k = %d reflections: %.0f of %ld (share %.3e; expected %.3e)\n", s.max_k,
                o.observed_beyond_max_k, a.n, o.observed_beyond_max_k / static_cast<double>(a.n),
                o.beyond_max_k_probability);
  else
    std::printf("  lost beyond max_k = %d reflections: %.0f of %ld (share %.3e; part of the failure probability)\n",
                s.max_k, o.observed_beyond_max_k, a.n, o.observed_beyond_max_k / static_cast<double>(a.n));
  std::printf(
      "  weight rho cos / pdf (over %ld samples): mean %.6f, standard deviation %.4g, standard error %.2g; %.0f ns per "
      "sample\n",
      o.weight_samples, o.weight_mean, std::sqrt(o.weight_variance), se, 1e9 * o.sample_s / static_cast<double>(a.n));
  std::printf("  pdf over the cells %.8f + failure %.3e - 1 = %.2e (tolerance %.1e)\n", o.pdf_integral,
              o.failure_probability, o.normalization_error, o.normalization_tolerance);
  std::printf("  chi-square %.2f, dof %d (%d cells pooled into %d), p = %.4g at level %.3g: %s\n", o.test.statistic,
              o.test.dof, o.test.pooled_in, o.test.pooled_out, o.test.p_value, o.test.level,
              o.test.reject ? "REJECTED" : "accepted");
  if (!a.out.empty()) {
    nlohmann::json j = validation::provenance();
    j["command"] = "sample";
    j["result"] = validation::chi2_json(o);
    support::write_file_atomically(a.out, support::json_text(j, 1) + "\n", a.force);
    std::cout << "result: " << support::printable(a.out) << "\n";
  }
  return o.pass ? 0 : 1;
}

void add_sample_command(CLI::App& app, Commands& commands) {
  using validation::kMaxAlpha;
  using validation::kMaxSampleCosBins;
  using validation::kMaxSamplePhiBins;
  using validation::kMaxSamplerK;
  using validation::kMaxSampleThetaBins;
  using validation::kMaxSurfaceThetaIDeg;
  using validation::kMinAlpha;
  auto* smp = app.add_subcommand(
      "sample",
      "Importance-sample the V-groove BRDF (Lee et al. 2018, Sec. 6; symmetric or, with --model "
      "vgroove-nonsymmetric, Eq. 23) or, with --model walter, Walter et al. 2007's rough dielectric BSDF "
      "(--eta, --masking; reflected and transmitted): draw --n exit directions, hold them "
      "to the sampler's pdf by a chi-square test (cells of (cos theta_o, phi_o), walter: cos theta_o in [-1, 1] "
      "over both sides; flatland theta_o; pdf integrated per cell) and report the weights rho cos / pdf (walter: "
      "f |cos| / pdf, their mean the albedo R + T, and the reflected and transmitted shares); exit 1 if the "
      "chi-square rejects.");
  SampleArgs& sma = commands.add(smp, cmd_sample);
  sma.cancel = commands.context().cancel;
  add_text(smp, "--ndf", sma.ndf, "normal distribution: ggx, beckmann or phong")->capture_default_str();
  add_real(smp, "--alpha", sma.alpha, "roughness alpha, " + support::interval_text(kMinAlpha, true, kMaxAlpha, true))
      ->capture_default_str();
  add_real(smp, "--theta-i-deg", sma.theta_i_deg,
           "incident angle in degrees, " + support::interval_text(0.0, true, kMaxSurfaceThetaIDeg, true))
      ->capture_default_str();
  add_integer(smp, "--n", sma.n, "samples", 1, kMaxRays)->capture_default_str();
  auto* smp_strategy =
      add_text(smp, "--strategy", sma.strategy,
               "facet distribution: printed (|s.n| D(s), the paper's), vndf (the V-cavity's visible normals), "
               "smith-vndf (Smith-GGX visible normals; ggx only) or bounded-vndf (Tokuyoshi and Eto 2024; ggx, "
               "3d only); not with walter")
          ->capture_default_str();
  add_text(smp, "--dim", sma.dim, "3d or flatland (walter: 3d only)")->capture_default_str();
  add_text(smp, "--model", sma.model,
           "vgroove (symmetric grooves, Eq. 16), vgroove-nonsymmetric (Eq. 23, the partner's tilt from the "
           "tabulated inverse CDF of P(theta_r); phong alpha <= 1; its pdf costs ~1 ms: use --n ~10^4 to "
           "10^5 and, in 3d, few cells) or walter (Walter et al. 2007, single scattering, 3d: facets from the Smith "
           "VNDF for ggx, |m.n| D(m) otherwise, then reflected with probability F, else refracted; draws from the "
           "stream (--seed, (0x5a3d, 2)), three numbers each) or vgroove-dielectric (the kaleidoscopic dielectric "
           "model, --eta: chains drawn by their energy, held to its binned lobe over --theta-bins (3d: theta from the "
           "exit side's normal x --phi-bins) on both sides; streams (--seed, (0x5a3d, 3)) in 3d, 4 in flatland)")
      ->capture_default_str();
  auto* smp_eta = add_real(smp, "--eta", sma.eta,
                           "walter and vgroove-dielectric only: n_far / n_near, the light in the near medium (below "
                           "1: from inside the denser medium), " +
                               support::interval_text(0, false, validation::kMaxFresnelEta, true) + ", not 1")
                      ->capture_default_str();
  auto* smp_masking = add_text(smp, "--masking", sma.masking,
                               "walter only: the G2 of the weights, smith (height-correlated), smith_separable "
                               "(Walter's Eq. 23) or vcavity; smith ones need ggx or beckmann")
                          ->capture_default_str();
  auto* smp_max_k = add_integer(smp, "--max-k", sma.max_k,
                                "paths with more reflections return zero weight, counted as lost beyond max_k "
                                "(default " +
                                    std::to_string(analytic::kSamplerMaxK) + "; vgroove-nonsymmetric " +
                                    std::to_string(analytic::kNonsymmetricSamplerMaxK) +
                                    ", its pdf costs O(max_k)); not with walter (single scattering)",
                                1, kMaxSamplerK);
  add_seed(smp, sma.seed, "seed of the uniform numbers")->capture_default_str();
  add_integer(smp, "--cos-bins", sma.cos_bins,
              "3d: cells over cos theta_o in [0, 1] (walter: as many again over [-1, 0])", 1, kMaxSampleCosBins)
      ->capture_default_str();
  add_integer(smp, "--phi-bins", sma.phi_bins, "3d: cells over phi_o, even", 2, kMaxSamplePhiBins)
      ->capture_default_str();
  add_integer(smp, "--theta-bins", sma.theta_bins,
              "flatland: cells over theta_o in (-90, 90); vgroove-dielectric 3d: theta_o in [0, 90)", 1,
              kMaxSampleThetaBins)
      ->capture_default_str();
  add_text(smp, "--out", sma.out, "result JSON to write (the chi-square table, observed and expected per cell)");
  smp->add_flag("--force", sma.force, "overwrite an existing result");
  smp->callback([&sma, smp_max_k, smp_strategy, smp_eta, smp_masking]() {
    sma.max_k_given = smp_max_k->count() > 0;
    sma.strategy_given = smp_strategy->count() > 0;
    sma.eta_given = smp_eta->count() > 0;
    sma.masking_given = smp_masking->count() > 0;
  });
}

}  // namespace vgroove::app
