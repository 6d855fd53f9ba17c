#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"

#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_nonsymmetric.h"
#include "vgroove/app/options.h"
#include "vgroove/app/progress.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/sampling_check.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

namespace vgroove::app {

namespace {

[[noreturn]] void out_of_range(const std::string& flag, double v, const std::string& range) {
  throw support::UserError(flag + " = " + support::number_text(v) + " is out of range " + range);
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
  if (a.model != "vgroove" && a.model != "vgroove-nonsymmetric")
    throw support::UserError("--model = \"" + a.model + "\" is not one of \"vgroove\", \"vgroove-nonsymmetric\"");
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
      "vgroove-nonsymmetric, Eq. 23): draw --n exit directions, hold them "
      "to the sampler's pdf by a chi-square test (cells of (cos theta_o, phi_o), flatland theta_o; pdf integrated per "
      "cell) and report the weights rho cos / pdf; exit 1 if the chi-square rejects.");
  SampleArgs& sma = commands.add(smp, cmd_sample);
  sma.cancel = commands.context().cancel;
  add_text(smp, "--ndf", sma.ndf, "normal distribution: ggx, beckmann or phong")->capture_default_str();
  add_real(smp, "--alpha", sma.alpha, "roughness alpha, " + support::interval_text(kMinAlpha, true, kMaxAlpha, true))
      ->capture_default_str();
  add_real(smp, "--theta-i-deg", sma.theta_i_deg,
           "incident angle in degrees, " + support::interval_text(0.0, true, kMaxSurfaceThetaIDeg, true))
      ->capture_default_str();
  add_integer(smp, "--n", sma.n, "samples", 1, kMaxRays)->capture_default_str();
  add_text(smp, "--strategy", sma.strategy,
           "facet distribution: printed (|s.n| D(s), the paper's), vndf (the V-cavity's visible normals), "
           "smith-vndf (Smith-GGX visible normals; ggx only) or bounded-vndf (Tokuyoshi and Eto 2024; ggx, "
           "3d only)")
      ->capture_default_str();
  add_text(smp, "--dim", sma.dim, "3d or flatland")->capture_default_str();
  add_text(smp, "--model", sma.model,
           "vgroove (symmetric grooves, Eq. 16) or vgroove-nonsymmetric (Eq. 23, the partner's tilt from the "
           "tabulated inverse CDF of P(theta_r); phong alpha <= 1; its pdf costs ~1 ms: use --n ~10^4 to "
           "10^5 and, in 3d, few cells)")
      ->capture_default_str();
  auto* smp_max_k = add_integer(smp, "--max-k", sma.max_k,
                                "paths with more reflections return zero weight, counted as lost beyond max_k "
                                "(default " +
                                    std::to_string(analytic::kSamplerMaxK) + "; vgroove-nonsymmetric " +
                                    std::to_string(analytic::kNonsymmetricSamplerMaxK) + ", its pdf costs O(max_k))",
                                1, kMaxSamplerK);
  add_seed(smp, sma.seed, "seed of the uniform numbers")->capture_default_str();
  add_integer(smp, "--cos-bins", sma.cos_bins, "3d: cells over cos theta_o in [0, 1]", 1, kMaxSampleCosBins)
      ->capture_default_str();
  add_integer(smp, "--phi-bins", sma.phi_bins, "3d: cells over phi_o, even", 2, kMaxSamplePhiBins)
      ->capture_default_str();
  add_integer(smp, "--theta-bins", sma.theta_bins, "flatland: cells over theta_o in (-90, 90)", 1, kMaxSampleThetaBins)
      ->capture_default_str();
  add_text(smp, "--out", sma.out, "result JSON to write (the chi-square table, observed and expected per cell)");
  smp->add_flag("--force", sma.force, "overwrite an existing result");
  smp->callback([&sma, smp_max_k]() { sma.max_k_given = smp_max_k->count() > 0; });
}

}  // namespace vgroove::app
