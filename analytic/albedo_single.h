// vgroove analytic: the single-scattering directional albedo E_ss(mu, alpha), its cosine-weighted
// average E_avg(alpha) and the split-sum DFG terms of microfacet BRDFs, by deterministic nested
// Gauss-Kronrod quadrature with an error bound on every value (not Monte Carlo).
//
// Papers and notes (cited below by first author and year):
//   Heitz. "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs". JCGT 3(2),
//     2014. Eq. (10) (Smith G1), Sec. 3.2 (Lambda of Beckmann and GGX), Eq. (24) (V-cavity G1),
//     Eq. (20) (Smith's separable G2) and Eq. (21) (Smith's height-correlated G2).
//   Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces". ACM
//     TOG 37(6), 2018. Eq. (1)-(3): Cook-Torrance with the V-cavity G.
//   Karis. "Real Shading in Unreal Engine 4". SIGGRAPH 2013 course notes, Physically Based
//     Shading in Theory and Practice: the split sum, whose second factor int f cos with Schlick's
//     F = F0 + (1 - F0) Fc, Fc = (1 - v.h)^5, is F0 * scale + bias (scale with 1 - Fc, bias with
//     Fc). Not in ../shared/papers: cited from the literature; the identity scale + bias = E_ss is
//     what the tests check.
//   Kulla, Conty. "Revisiting Physically Based Shading at Imageworks". SIGGRAPH 2017 course:
//     E(mu) and E_avg = 2 int_0^1 E(mu) mu dmu, the tables energy compensation reads.
//
// Definitions (F = 1 unless a Fresnel weight is named). i = (sin theta_i, 0, mu), mu = cos theta_i;
//   f(i, o) = D(h) G2(i, o, h) / (4 (i.n) (o.n)),   h = (i + o) / |i + o|,
//   E_ss(mu) = int_{o.n > 0} f(i, o) (o.n) d omega_o,   E_avg = 2 int_0^1 E_ss(mu) mu dmu.
// G2 is one of: Smith height-correlated 1 / (1 + Lambda(i) + Lambda(o)) (Heitz 2014, Eq. 21), Smith
// separable G1(i) G1(o) = 1 / ((1 + Lambda(i)) (1 + Lambda(o))) (Eq. 20), or the V-cavity
// min(G1(i, h), G1(o, h)) (Lee et al. 2018, Eq. 2-3; Heitz 2014, Eq. 24): Cook-Torrance.
//
// The quadrature. o = 2 (i.h) h - i and d omega_o = 4 (i.h) d omega_h, so
//   E_ss = int D(h) G2 (i.h) / mu d omega_h = int G2 (1 + tan(theta_i) tan(theta_h) cos(phi_h)) dP(h),
// dP = D cos(theta_h) d omega_h the projected-area measure of the normals (total mass 1). In
// u = CDF(theta_h) (analytic/brdf_3d.h, groove_cdf: t^2 / (alpha^2 + t^2) for GGX, 1 - exp(-t^2 /
// alpha^2) for Beckmann, t = tan theta_h), dP = du d phi / (2 pi): the NDF's peak is absorbed
// and the integrand is bounded and smooth in u, whatever alpha. The exit o is above the horizon
// exactly while theta_h < psi / 2, psi = atan2(cos theta_i, -sin theta_i cos phi) (o.n =
// 2 (i.h) cos theta_h - cos theta_i = 0 solves to tan 2 theta_h = -cos theta_i / (sin theta_i
// cos phi)), so u runs over [0, CDF(psi / 2)], cut where the NDF's scale changes (theta_h =
// alpha 2^j) and, for the V-cavity, at its kinks, which have closed forms too:
//   G1(o, h) = 1 at theta_h = psi / 3   (tan 3 theta_h = -cos theta_i / (sin theta_i cos phi)),
//   G1(i, h) = 1 at theta_h = pi - psi, and G1(i, h) = G1(o, h) (o.n = i.n) at psi - pi / 2.
// phi in [0, pi] (the integrand is even in phi), cut where the V-cavity kinks meet (cos phi =
// k cot theta_i, k = 0, 1/sqrt 3, 1). Both levels are adaptive Gauss-Kronrod (quadrature.h).
//
// The error bound. Each level's estimate is the summed |K15 - G7| of its final pieces, which
// bounds the 15-point value's error where the integrand is smooth on each piece (every kink is
// a cut); the value's bound is the outer estimate plus the largest inner one (the inner errors
// average over phi to at most their maximum). E_avg adds the outer mu level the same way. The
// tests check the bound: halving every initial piece (AlbedoOptions::refine = 2) and a 10^4
// times tighter tolerance move every value by less than its bound.
#pragma once

#include "vgroove/analytic/quadrature.h"
#include "vgroove/common/ndf_kind.h"

#include <functional>
#include <vector>

namespace vgroove::analytic {

// The G2 of the single-scattering BRDF.
enum class MaskingKind : unsigned char {
  smith_height_correlated,  // 1 / (1 + Lambda(i) + Lambda(o))
  smith_separable,          // G1(i) G1(o)
  vcavity,                  // min(G1_vcavity(i, h), G1_vcavity(o, h)): Cook-Torrance, Lee et al. 2018 Eq. (3)
};
const char* masking_name(MaskingKind kind);

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
