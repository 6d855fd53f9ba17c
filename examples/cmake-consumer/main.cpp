// A renderer developer's view of vgroove: evaluate the validated multiple-scattering BRDF, sample
// it (symmetric and nonsymmetric grooves, Sec. 6) and check the samples' weights against the
// evaluation, then hold two BRDFs against vgroove's exact simulation of a rough V-groove surface:
// vgroove's own (which passes) and Cook-Torrance with the V-cavity G (which loses energy at high
// roughness and fails). Exit status 0 when the sampling checks hold and both verdicts are as
// expected.
#include <vgroove/analytic/brdf_3d.h>
#include <vgroove/analytic/brdf_nonsymmetric.h>
#include <vgroove/analytic/sampling_3d.h>
#include <vgroove/analytic/sampling_nonsymmetric.h>
#include <vgroove/validation/check_brdf.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace va = vgroove::analytic;
namespace vv = vgroove::validation;

int main() {
  const double alpha = 1.0;
  const auto ndf = vgroove::NdfKind::ggx;
  constexpr double deg = std::numbers::pi / 180.0;

  // One evaluation: light 30 deg from the normal, looking back 40 deg on the other side.
  const va::Dir3 wi = va::dir3(30 * deg, std::numbers::pi), wo = va::dir3(40 * deg, 0.0);
  std::printf(
      "GGX alpha %.1f, theta_i 30, theta_o 40, phi_o 0 deg: vgroove %.6f /sr (k = 1: %.6f), "
      "Cook-Torrance %.6f /sr\n",
      alpha, va::vgroove_brdf(wi, wo, ndf, alpha, 1'000'000), va::vgroove_brdf_k(wi, wo, 1, ndf, alpha),
      va::cook_torrance(wi, wo, ndf, alpha));

  // Sampling, as a path tracer calls it: o, its pdf and the weight rho cos / pdf from uniforms.
  // With F = 1 the mean weight is the albedo, 1 up to the light beyond max_k reflections.
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  bool sampling_ok = true;
  {
    const va::SamplerOptions so{va::FacetStrategy::vndf, 256};
    double sum = 0.0;
    const int n = 20000;
    for (int j = 0; j < n; ++j) {
      const va::VgrooveSample3d x = va::sample_vgroove_3d(wi, {U(rng), U(rng), U(rng), U(rng)}, ndf, alpha, so);
      sum += x.weight;
      if (j < 100 && x.k > 0) {  // the weight is the evaluation over the pdf, pointwise
        const double eval = va::vgroove_brdf(wi, x.o, ndf, alpha, so.max_k) * x.o.z;
        sampling_ok = sampling_ok && std::abs(x.weight - eval / va::vgroove_pdf_3d(wi, x.o, ndf, alpha, so)) <=
                                         1e-9 * x.weight;
      }
    }
    std::printf("symmetric, V-cavity VNDF: mean weight over %d samples %.6f (the albedo with F = 1)\n", n, sum / n);
    sampling_ok = sampling_ok && std::abs(sum / n - 1.0) < 1e-3;
  }
  {
    // Nonsymmetric grooves (Eq. 23): the partner's tilt from the tabulated inverse CDF of P(theta_r).
    const va::NonsymmetricSampler ns = va::make_nonsymmetric_sampler(ndf, 0.5, {va::FacetStrategy::vndf, 16}, false);
    double sum = 0.0, sum2 = 0.0;
    const int n = 100;
    for (int j = 0; j < n; ++j) {
      const va::VgrooveSample3d x = va::sample_nonsymmetric_3d(ns, wi, {U(rng), U(rng), U(rng), U(rng), U(rng)});
      sampling_ok = sampling_ok && std::isfinite(x.weight) && (x.k == 0 || x.pdf > 0.0);
      sum += x.weight;
      sum2 += x.weight * x.weight;
    }
    const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
    std::printf("nonsymmetric (alpha 0.5), V-cavity VNDF: mean weight over %d samples %.4f +- %.4f\n", n, mean, se);
    sampling_ok = sampling_ok && std::abs(mean - 1.0) < 5.0 * se + 1e-2;
  }
  std::printf("sampling checks: %s\n", sampling_ok ? "pass" : "FAIL");

  vv::CheckBrdfOptions opt;
  opt.ndf = ndf;
  opt.alpha = alpha;
  opt.theta_i_deg = {0, 45};
  opt.rays = 100'000;
  opt.grooves = 50'000;

  const vv::CheckBrdfResult ours = vv::check_brdf(
      [&](const va::Dir3& i, const va::Dir3& o) { return va::vgroove_brdf(i, o, ndf, alpha, 1'000'000); }, opt);
  const vv::CheckBrdfResult ct =
      vv::check_brdf([&](const va::Dir3& i, const va::Dir3& o) { return va::cook_torrance(i, o, ndf, alpha); }, opt);
  for (const auto* r : {&ours, &ct}) {
    std::printf("%s:\n", r == &ours ? "vgroove multiple scattering" : "Cook-Torrance (V-cavity G)");
    for (const auto& c : r->cases)
      std::printf("  theta_i %4.1f deg: albedo %.4f (traced %.4f, allowed +-%.4f), L1 %.4f (allowed %.4f): %s\n",
                  c.theta_i_deg, c.albedo_model, c.albedo_sim, c.albedo_threshold, c.l1, c.l1_threshold,
                  c.pass ? "pass" : "FAIL");
  }
  const bool expected = ours.pass && !ct.pass;
  std::printf("%s\n", expected ? "as expected: vgroove passes, Cook-Torrance fails" : "UNEXPECTED verdicts");
  return expected && sampling_ok ? 0 : 1;
}
