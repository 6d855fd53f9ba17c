// vgroove analytic: normal distribution functions (NDFs) in 3D and in flatland, and the masking
// functions that go with them.
//
// Papers (cited below by first author and year):
//   Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
//     ACM TOG 37(6), 2018. Sec. 3, Eq. (2); Sec. 5.1, Eq. (10) (D weighted by projected area);
//     App. C builds P(theta_r) on these D (analytic/partner_distribution.h).
//   Heitz. "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs".
//     JCGT 3(2), 2014. Eq. (5) (projected-area constraint), Eq. (10) (Smith G1), Sec. 3.2
//     (Beckmann and GGX D and Lambda), Eq. (24) (V-cavity G1), App. A (Lambda from the slopes).
//   Walter, Marschner, Li, Torrance. "Microfacet Models for Refraction through Rough Surfaces".
//     EGSR 2007. Sec. 5: Beckmann, Phong and GGX D, and the Phong exponent for a Beckmann width,
//     alpha_p = 2 alpha^-2 - 2. This paper is not in ../shared/papers: its section is cited from
//     the literature, not re-read; the formulas are checked by the tests instead (normalization,
//     D(0) = 1/(pi alpha^2) for all three, Phong -> Beckmann as alpha -> 0). Beckmann's and GGX's
//     D are also printed in Heitz 2014, Sec. 3.2.
//
// Sign convention (the same as sim/geometry.h, written again because analytic/ must not include
// sim/): angles from the macrosurface normal n, counter-clockwise positive; a direction at angle
// theta is (-sin theta, cos theta). A facet of slope s = dh/dx has the normal (-s, 1)/|.|, which
// is the direction at theta_m = atan(s): slope and normal angle are related by s = tan(theta_m).
//
// Normalization.
//   3D: integral over the hemisphere of D(m) cos(theta_m) dm = 1 (Heitz 2014, Eq. (5) with
//       theta_o = 0: the microfacets' projected area is the macrosurface's), i.e.
//       2 pi int_0^{pi/2} D(theta) cos(theta) sin(theta) dtheta = 1.
//   2D: int_{-pi/2}^{pi/2} D2(theta) cos(theta) dtheta = 1: D2(theta) dtheta is the length of
//       profile with normals in dtheta per unit length of macrosurface, and cos(theta) projects it.
//
// From slopes to normals. Let P(s) be the density of the slope s over the macrosurface length
// (a 1D profile) or P22(sx, sy) over its area (3D). Since dx = cos(theta) dl and ds = dtheta /
// cos^2(theta),
//   2D: D2(theta) = P(tan theta) / cos^3(theta),
//   3D: D(m)      = P22(tan theta_m, phi) / cos^4(theta_m)   (Heitz 2014, Sec. 3.2).
//
// The flatland forms chosen here. A 2D profile is taken to be a straight cut through the
// isotropic 3D surface; its slopes along the cut are distributed as the marginal of P22 along one
// axis, P(s) = int P22(s, t) dt. This choice has two properties the tests check:
//   - it is one rule for the three NDFs (no form is picked per NDF), and Beckmann's marginal is
//     the 1D Gaussian in tan(theta);
//   - Smith's Lambda depends on P22 only through this marginal along the view's azimuth (Heitz
//     2014, App. A), so the flatland Smith G1 with D2 equals the 3D Smith G1 with D: the 2D
//     projected-area constraint int G1 <o, m> D2 dtheta_m = cos(theta_o) holds with Heitz's
//     closed-form Lambda.
// The marginals (s = tan theta):
//   Beckmann: P22 = exp(-|s|^2/a^2) / (pi a^2)        -> P(s) = exp(-s^2/a^2) / (sqrt(pi) a),
//             a Gaussian of standard deviation a/sqrt(2).
//   GGX:      P22 = 1 / (pi a^2 (1 + |s|^2/a^2)^2)    -> P(s) = (1 + s^2/a^2)^(-3/2) / (2 a),
//             from int (c^2 + t^2/a^2)^-2 dt = pi a / (2 c^3), c^2 = 1 + s^2/a^2: a Student-t
//             with 2 degrees of freedom scaled by a/sqrt(2). (Not the 1D Cauchy density: that
//             is the marginal of the radial law (1 + |s|^2/a^2)^(-3/2), not of GGX's power -2.)
//   Phong:    P22 = (p+2)/(2 pi) (1 + |s|^2)^(-(p+4)/2) -> P(s) = K (1 + s^2)^(-(p+3)/2),
//             K = Gamma((p+3)/2) / (sqrt(pi) Gamma((p+2)/2)), p = alpha_p: a Student-t with
//             nu = p + 2 = 2/a^2 degrees of freedom scaled by 1/sqrt(nu) = a/sqrt(2).
// So all three 2D slope laws are (a/sqrt(2)) t_nu, with nu = 2 (GGX), nu = 2/a^2 (Phong) and
// nu -> infinity (Beckmann); Phong tends to Beckmann as a -> 0 and equals GGX at a = 1. Student-T
// (ndf_student_t.h), whose 3D slopes are a bivariate t of tail gamma, has nu = 2 gamma - 2.
// In angles:
//   D2_beckmann = exp(-tan^2/a^2) / (sqrt(pi) a cos^3),
//   D2_ggx      = a^2 / (2 (a^2 cos^2 + sin^2)^(3/2)),
//   D2_phong    = K cos^p(theta)    (the 2D Phong lobe is again a power of the cosine).
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
