// vgroove analytic: the single-scattering directional albedo E_ss(mu, alpha), its cosine-weighted
// average E_avg(alpha) and the split-sum DFG terms of microfacet BRDFs, by deterministic nested
// adaptive Gauss-Kronrod quadrature with an error bound on every value (not Monte Carlo):
//   E_ss(mu) = int f(i, o) (o.n) d omega_o,  f = D G2 / (4 (i.n) (o.n)),  E_avg = 2 int E_ss mu dmu,
// G2 Smith height-correlated or separable (Heitz, "Understanding the Masking-Shadowing Function in
// Microfacet-Based BRDFs", JCGT 3(2), 2014, Eq. 20-21) or the V-cavity (Lee et al. 2018, Eq. 1-3);
// the split sum of Karis 2013 (scale + bias = E_ss); E_avg as Kulla and Conty 2017 read it.
// Accuracy: each value's bound is the summed |K15 - G7| of its final pieces (every kink a cut);
// halving every piece and a 10^4 times tighter tolerance move no value beyond its bound.
// Tests: tests/analytic/albedo_single_test.cpp (Albedo.HalvingTheStepMovesEachValueLessThanItsBound,
// Albedo.GgxAlphaOneAtNormalIncidenceIsOneMinusLn2, Albedo.VcavityIsTheCookTorranceLobesAlbedo,
// Albedo.SplitSumAddsToTheAlbedo, Albedo.ExtremesAreFinite).
// Derivation: docs/derivations/albedo.md.
#pragma once

#include "vgroove/analytic/masking_kind.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/common/ndf_kind.h"

#include <functional>
#include <vector>

namespace vgroove::analytic {

// A microfacet BRDF: the NDF and its G2. Smith's G2 needs Lambda: GGX or Beckmann; the V-cavity
// takes any of the three NDFs.
struct MicrofacetModel {
  NdfKind ndf = NdfKind::ggx;
  MaskingKind masking = MaskingKind::smith_height_correlated;
};
bool model_supported(const MicrofacetModel& m);

struct AlbedoOptions {
  double tol = 1e-9;     // absolute, on each value (E_ss, E_avg, scale, bias)
  int refine = 1;        // every initial piece split in `refine` equal parts (2: the step halved)
  int max_pieces = 400;  // per one-dimensional integral
};

// A value and its error bound; converged: every level met its tolerance before max_pieces.
struct BoundedValue {
  double value = 0.0;
  double error = 0.0;
  bool converged = true;
  long evaluations = 0;  // of the innermost integrand
};

// E_ss(mu, alpha), F = 1. mu in (0, 1], alpha > 0 (no upper limit; GGX at alpha 2 is fine).
BoundedValue albedo_single(const MicrofacetModel& m, double alpha, double mu, const AlbedoOptions& opt = {});

// E_ss with a reflectance: int F(i.h) f cos, F a smooth function of the cosine of the local angle
// of incidence in [0, 1] (an exact conductor's, optics/fresnel.h); the same bound. F = Schlick's
// gives F0 scale + bias (dfg_split_sum).
BoundedValue albedo_single_fresnel(const MicrofacetModel& m, double alpha, double mu,
                                   const std::function<double(double)>& F, const AlbedoOptions& opt = {});

// The split-sum terms (Karis 2013) at (mu, alpha): scale = int (1 - Fc) f cos, bias = int Fc f cos,
// Fc = (1 - i.h)^5; scale + bias = E_ss, and the albedo with Schlick's F is F0 scale + bias.
struct SplitSum {
  BoundedValue scale, bias;
};
SplitSum dfg_split_sum(const MicrofacetModel& m, double alpha, double mu, const AlbedoOptions& opt = {});

// E_avg(alpha) = 2 int_0^1 E_ss(mu) mu dmu (Kulla and Conty 2017), the mu level adaptive too.
BoundedValue albedo_average(const MicrofacetModel& m, double alpha, const AlbedoOptions& opt = {});

// 2 int_0^1 g(mu) mu dmu for a smooth g (Kulla and Conty 2017's Fresnel average F_avg when g = F),
// adaptive Gauss-Kronrod to opt.tol from 4 * opt.refine equal pieces; error as for the albedos.
template <class G>
BoundedValue cosine_weighted_average(G&& g, const AlbedoOptions& opt = {}) {
  AdaptiveOptions o;
  o.abs_tol = opt.tol;
  o.max_pieces = opt.max_pieces;
  std::vector<double> cuts;
  const int n = 4 * opt.refine;
  for (int j = 0; j <= n; ++j) cuts.push_back(static_cast<double>(j) / n);
  const AdaptiveResult r = integrate_adaptive([&](double mu) { return 2.0 * mu * g(mu); }, cuts, o);
  return {r.value, r.error, r.converged, r.evaluations};
}

}  // namespace vgroove::analytic
