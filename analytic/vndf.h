// vgroove analytic: distributions of facet normals to sample from, in 3D and in flatland, each a
// matched pair sample_x(u) / x_pdf(x): |s.n| D(s) (Lee et al. 2018, Sec. 6), the V-cavity's
// visible normals (Heitz and d'Eon, "Importance Sampling Microfacet-Based BSDFs using the
// Distribution of Visible Normals", CGF 33(4), 2014), the Smith-GGX VNDF by spherical caps (Dupuy
// and Benyoub, CGF 42(8), 2023) and its bounded cap (Tokuyoshi and Eto, "Bounded VNDF Sampling for
// the Smith-GGX BRDF", PACMCGIT 7(1), 2024, Eq. 5-6, 10). The symmetric V-groove surface is a
// V-cavity surface, so its first-hit facets follow the V-cavity VNDF exactly; the Smith VNDF is a
// proposal here. Conventions: 3D as brdf_3d.h, flatland as ndf.h (the marginals along x).
// Holds: every density integrates to 1; the V-cavity VNDF is the grooves' lit widths; the bounded
// cap keeps every reflection above the horizon.
// Tests: tests/analytic/vndf_test.cpp (Vndf.DensitiesIntegrateToOne, Vndf.FlatlandDensitiesIntegrateToOne,
// Vndf.VcavityVisibleNormalsAreTheLitWidths, Vndf.BoundedCapHoldsEveryReflectionAboveTheHorizon,
// Vndf.BoundedLowerBoundHandValues), tests/analytic/sampling_chi2_test.cpp.
// Derivation: docs/derivations/sampling.md.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf.h"

namespace vgroove::analytic {

// ---- 3D -----------------------------------------------------------------------------------------

// |s.n| D(s) over the hemisphere of s (Lee et al. 2018, Sec. 6): theta_m by the inverse of the
// closed-form CDF (groove_cdf_inverse), phi = 2 pi u1.
Dir3 sample_projected_ndf(NdfKind ndf, double alpha, double u0, double u1);
double projected_ndf_pdf(NdfKind ndf, double alpha, const Dir3& s);

// The V-cavity VNDF D(s) <i.s> G1_vcavity(i, s) / <i.n> (Heitz and d'Eon 2014), u2 choosing
// between s and its mirror image. i.z > 0. Returns n when both facets are seen edge-on (i.z = 0).
Dir3 sample_vcavity_vndf(NdfKind ndf, double alpha, const Dir3& i, double u0, double u1, double u2);
double vcavity_vndf_pdf(NdfKind ndf, double alpha, const Dir3& i, const Dir3& s);

// The Smith-GGX VNDF (Heitz 2018; spherical caps, Dupuy and Benyoub 2023):
//   p(m) = G1(i) <i.m> D(m) / <i.n> = 2 D(m) <i.m> / (i_z + sqrt(alpha^2 (i_x^2 + i_y^2) + i_z^2)).
Dir3 sample_ggx_vndf(double alpha, const Dir3& i, double u0, double u1);
double ggx_vndf_pdf(double alpha, const Dir3& i, const Dir3& m);

// The bounded Smith-GGX VNDF (Tokuyoshi and Eto 2024): the cap in the unit-roughness space cut at
// o_z > -k i_z (Eq. 6, isotropic: k = (1 - alpha^2) s^2 / (s^2 + alpha^2 i_z^2),
// s = 1 + sgn(1 - alpha) |i_xy|), so that fewer single reflections fall below the horizon; pdf
// Eq. (10): 2 D(m) <i.m> / (k i_z + sqrt(alpha^2 |i_xy|^2 + i_z^2)) where the cap holds m's
// reflection, 0 elsewhere. Facets whose single reflection leaves below the horizon, which the
// V-groove needs for k >= 2, are partly outside the cap.
Dir3 sample_ggx_bounded_vndf(double alpha, const Dir3& i, double u0, double u1);
double ggx_bounded_vndf_pdf(double alpha, const Dir3& i, const Dir3& m);
// The cap's lower bound -k i_z of Eq. (6) (the unit-roughness cosine).
double ggx_bounded_vndf_lower_bound(double alpha, const Dir3& i);
// The pieces of Eq. (8) and (10), for callers that have D(m) and <i.m> already:
// p(m) = 2 D(m) <i.m> / norm, and whether the bounded cap holds m's reflection.
double ggx_vndf_norm(double alpha, const Dir3& i);
double ggx_bounded_vndf_norm(double alpha, const Dir3& i);
bool ggx_bounded_vndf_covers(double alpha, const Dir3& i, const Dir3& m);

// Smith's G1 for GGX at the direction i (Heitz 2014, Eq. 10 with Lambda of Sec. 3.2).
double ggx_smith_g1(double alpha, const Dir3& i);

// ---- Flatland -----------------------------------------------------------------------------------

// D2(theta_s) cos(theta_s) over (-pi/2, pi/2): the x-marginal of sample_projected_ndf.
double sample_projected_ndf2(NdfKind ndf, double alpha, double u0, double u1);
double projected_ndf2_pdf(NdfKind ndf, double alpha, double theta_s);

// The flatland V-cavity VNDF D2(theta_s) <i.s> G1_vcavity(i, s) / cos(theta_i): theta_s from
// D2 cos, replaced by -theta_s with probability <i.s'> / (<i.s> + <i.s'>).
double sample_vcavity_vndf2(NdfKind ndf, double alpha, double theta_i, double u0, double u1, double u2);
double vcavity_vndf2_pdf(NdfKind ndf, double alpha, double theta_i, double theta_s);

// The flatland Smith-GGX VNDF G1(theta_i) <i.s> D2(theta_s) / cos(theta_i): the x-marginal of
// sample_ggx_vndf with i in the (x, z) plane.
double sample_ggx_vndf2(double alpha, double theta_i, double u0, double u1);
double ggx_vndf2_pdf(double alpha, double theta_i, double theta_s);

}  // namespace vgroove::analytic
