// vgroove analytic: importance sampling of Walter et al. 2007's rough dielectric BSDF (walter.h) in
// 3D, as Walter Sec. 5.3 does it with the visible normals in place of D(m) |m.n|: a facet normal m
// from the proposal, then reflection with probability F(i.m) and refraction (Snell) otherwise. The
// proposal is the Smith VNDF (GGX and Student-T: vndf.h, detail/smith_vndf.h) or the projected NDF
// |m.n| D(m) (Beckmann and Phong, which have no closed-form VNDF sampler here).
//   pdf(o) = p_m(h_r) F(i.h_r) / (4 |o.h_r|)                                 (o above, Walter Eq. 14)
//   pdf(o) = p_m(h_t) (1 - F(i.h_t)) eta^2 |o.h_t| / (i.h_t + eta o.h_t)^2   (o below, Walter Eq. 17)
// A facet whose reflection leaves below the horizon, or whose refraction leaves above it, gives no
// direction (single scattering has none there): the pdf integrates to 1 less that share. With the
// Smith VNDF and Smith's separable G2, the weight f |o.n| / pdf is G1(o) on both sides (the
// derivation in docs/derivations/walter.md, "Sampling").
// Tests: tests/analytic/walter_sampling_test.cpp (WalterSampling.ChiSquareAgainstItsPdf,
// WalterSampling.AWrongJacobianIsRejected, WalterSampling.SmithWeightIsG1OfTheExit,
// WalterSampling.HardCasesAreFinite).
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/masking_kind.h"
#include "vgroove/common/ndf_kind.h"

namespace vgroove::analytic {

struct WalterSample {
  Dir3 o;                    // unit, away from the surface; o.z < 0: transmitted
  double pdf = 0.0;          // per steradian, of o
  double weight = 0.0;       // f(i, o) |o.z| / pdf with the given G2 (0 when no direction)
  bool ok = false;           // false: the facet gives no direction (o, pdf, weight meaningless)
  bool transmitted = false;  // the refracted branch was taken
};

// i.z > 0 (the light in the near medium), eta = n_far / n_near > 0; u0, u1 choose the facet and
// u2 the branch, each in [0, 1).
WalterSample sample_walter(NdfKind ndf, double alpha, double eta, MaskingKind g, const Dir3& i, double u0, double u1,
                           double u2);
// The density sample_walter draws o with (0 where it never does).
double walter_pdf(NdfKind ndf, double alpha, double eta, const Dir3& i, const Dir3& o);
// The proposal's density of facet normals m (m.z > 0).
double walter_facet_pdf(NdfKind ndf, double alpha, const Dir3& i, const Dir3& m);

}  // namespace vgroove::analytic
