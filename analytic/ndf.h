// vgroove analytic: normal distribution functions in 3D and flatland (Beckmann, GGX, Phong,
// Student-T) and their masking functions (Smith G1 and Lambda, V-cavity G1). Lee et al. 2018,
// Eq. (2), (10); Heitz, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
// JCGT 3(2), 2014, Eq. (5), (10), (24), Sec. 3.2, App. A; Walter, Marschner, Li, Torrance,
// "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, Sec. 5.
// Normalization: 3D 2 pi int D cos sin = 1, flatland int D2 cos = 1. The flatland slope law is the
// marginal of the 3D one along an axis, so the flatland Smith G1 with D2 equals the 3D one with D.
// Angles from n, counter-clockwise positive, a direction at theta is (-sin theta, cos theta).
// Holds: both normalizations and the projected-area constraints by quadrature, hand values (D(0) =
// 1/(pi alpha^2)), Phong -> Beckmann as alpha^2. Tests: tests/analytic/ndf_test.cpp
// (NdfNormalization.ProjectedAreaIsOne3D, NdfNormalization.ProjectedLengthIsOne2D,
// NdfHandValues.*, SmithG1.ProjectedAreaIsConservedIn2D, SmithG1.ProjectedAreaIsConservedIn3D,
// G1VCavity.ProjectedAreaIsConserved, PhongBeckmann.L1DistanceShrinksAsAlphaSquared).
// Derivation: docs/derivations/ndf.md (the Student-T forms: docs/derivations/student_t.md).
#pragma once

#include "vgroove/common/ndf_kind.h"

namespace vgroove::analytic {

using vgroove::ndf_name;
using vgroove::NdfKind;

// Walter et al. 2007, Sec. 5: the Phong exponent alpha_p = 2 / alpha^2 - 2 whose lobe matches
// Beckmann's of width alpha near theta_m = 0 (both D(0) = 1 / (pi alpha^2)). It is negative for
// alpha > 1; D_phong stays normalizable while alpha_p > -2, i.e. for every finite alpha.
double phong_exponent(double alpha);

// 3D isotropic NDFs, D(theta_m; alpha), zero for |theta_m| >= pi/2 (Heaviside chi+(m.n)).
// Depend on |theta_m| only. alpha > 0.
double D_beckmann(double theta_m, double alpha);  // exp(-tan^2/a^2) / (pi a^2 cos^4)
double D_ggx(double theta_m, double alpha);       // a^2 / (pi cos^4 (a^2 + tan^2)^2)
double D_phong(double theta_m, double alpha);     // (p+2)/(2 pi) cos^p, p = phong_exponent(a)
double D(NdfKind kind, double theta_m, double alpha);
// The same from cos(theta_m) and sin(theta_m), theta_m in [0, pi/2) (no chi+ test): saves the
// transcendental calls where the caller has both (the BRDF's and the samplers' sums).
double D_cs(NdfKind kind, double cos_m, double sin_m, double alpha);
// The aperture theta_v = pi - 2 theta_m below which D_cs is exactly 0 in double, because its exp
// or pow underflows (D falls monotonically towards vertical facets): Beckmann, exp(-tan^2/alpha^2)
// = 0 once tan^2/alpha^2 > 745.2, at theta_v < 2 atan(1 / (alpha sqrt(760))); Phong with p > 0,
// cos^p = 0 once p log(cos) < -745.2, at theta_v < 2 asin(exp(-760 / p)); 0 (never) for GGX and
// Phong with p <= 0. The margins make it a lower bound: the sums over apertures (the samplers'
// pdf) stop there and lose only exact zeros.
double D_vanishing_aperture(NdfKind kind, double alpha);

// Flatland NDFs, D2(theta_m; alpha) over (-pi/2, pi/2), zero outside (see the header comment).
double D2_beckmann(double theta_m, double alpha);
double D2_ggx(double theta_m, double alpha);
double D2_phong(double theta_m, double alpha);
double D2(NdfKind kind, double theta_m, double alpha);
// The same from cos(theta_m) >= 0 and sin(theta_m).
double D2_cs(NdfKind kind, double cos_m, double sin_m, double alpha);

// Lee et al. 2018, Eq. (2) (Heitz 2014, Eq. (24)): the V-cavity masking
//   G1(o, h) = H(o.h / o.n) min(1, 2 |h.n| |o.n| / |o.h|),
// from the three dot products.
double G1_vcavity(double o_dot_h, double o_dot_n, double h_dot_n);
// The same when o, h and n lie in one plane (a groove's cross-section, or flatland), from the
// angles of o and h: o.n = cos theta_o, h.n = cos theta_h, o.h = cos(theta_o - theta_h).
double G1_vcavity_inplane(double theta_o, double theta_h);

// Smith's Lambda for Beckmann and GGX (Heitz 2014, Sec. 3.2), with a = 1 / (alpha |tan theta_o|):
//   Beckmann: Lambda = (erf(a) - 1)/2 + exp(-a^2) / (2 a sqrt(pi)),
//   GGX:      Lambda = (-1 + sqrt(1 + 1/a^2)) / 2.
// Lambda(0) = 0. The same in flatland with D2 (see the header comment). Phong has no closed form
// (it is not shape invariant: Heitz 2014, Sec. 3.2) and is left out. Student-T's is in
// ndf_student_t.h.
double Lambda_beckmann(double theta_o, double alpha);
double Lambda_ggx(double theta_o, double alpha);
// Any of them by kind (beckmann, ggx or student_t; not phong). They depend on |tan theta_o| only,
// so the same value serves the direction reversed (theta_o + pi).
double Lambda(NdfKind kind, double theta_o, double alpha);

// Heitz 2014, Eq. (10): Smith's G1(o, m) = chi+(o.m) / (1 + Lambda(o)). These return the value
// for a normal m facing o (o.m > 0); the caller applies chi+(o.m), which needs m.
double G1_smith_beckmann(double theta_o, double alpha);
double G1_smith_ggx(double theta_o, double alpha);

}  // namespace vgroove::analytic
