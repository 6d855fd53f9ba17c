// vgroove analytic: the Smith visible normals of the Student-T NDF (ndf_student_t.h), sampled by the
// visible-slope method of Heitz and d'Eon 2014 (Sec. 4: stretch to alpha = 1, draw the slope along
// the view from its visible marginal, then the slope across it from its conditional law), with the
// t laws' CDFs of d'Eon 2023 ("Student-T and Beyond") in the incomplete beta function:
//   density  D_i(m) = G1(i) <i.m>+ D(m) / <i.n>,  G1 = 1 / (1 + Lambda(theta_i))   (Heitz 2014, Eq. 10);
//   along:   p = k sinh v (k = sqrt(gamma - 1), stretched slope), F(v) = [C(v) + s |M(v)|] / (1 + Lambda),
//            C = the t CDF I_(sech^2 v)(gamma - 1, 1/2) / 2 (and its complement for v > 0),
//            |M| = k N sech^(2 gamma - 3)(v) / (2 gamma - 3) its first moment, s = alpha tan(theta_i);
//   across:  q = k cosh(v) sinh w, w from the t CDF I_(sech^2 w)(gamma - 1/2, 1/2) / 2.
// Both inverted by Newton's method on log F inside a bracket (bisection when a step leaves it).
// The pdfs below are the formula above with ndf_student_t.h's D and Lambda, not the sampler's F.
// Derivation: docs/derivations/vndf_student_t.md. Held by tests/analytic/vndf_student_t_test.cpp
// (gamma = 2 against GGX's samplers, 1e-12; gamma = 1e4 against Beckmann's, O(1/gamma); chi-square;
// normalization; no NaN over gamma 1.5 + 1e-9 .. 1e4, alpha 0.01 .. 2, theta_i 0 .. 89.9 deg).
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/detail/ndf_student_t.h"

namespace vgroove::analytic {

// 3D, i.z > 0 (returns n otherwise). Increasing in u0 (the slope along i's azimuth, towards i's
// horizontal direction reversed) and in u1 (the slope across it), as sample_visible_normal_3d.
Dir3 sample_student_t_vndf(const StudentT& t, const Dir3& i, double u0, double u1);
double student_t_vndf_pdf(const StudentT& t, const Dir3& i, const Dir3& m);
// 2 <i.n> (1 + Lambda(i)): the pdf is 2 D(m) <i.m> / norm (as ggx_vndf_norm).
double student_t_vndf_norm(const StudentT& t, const Dir3& i);
// Smith's G1 at the angle theta_i: 1 / (1 + Lambda).
double student_t_smith_g1(const StudentT& t, double theta_i);

// Flatland (conventions of vndf.h): G1(theta_i) <i.s>+ D2(theta_s) / cos(theta_i), the x-marginal of
// the 3D law with i in the (x, z) plane. Monotone in u.
double sample_student_t_vndf2(const StudentT& t, double theta_i, double u);
double student_t_vndf2_pdf(const StudentT& t, double theta_i, double theta_s);

// The inversion itself, for the tests: v with F(v) = u for the law of v whose density is
// N sech^(2a) v (1 - s k sinh v)+ / (its integral), N = Gamma(a + 1/2) / (sqrt(pi) Gamma(a)), a > 1/2,
// s >= 0 (the along-slope: a = gamma - 1, k = sqrt(gamma - 1); the across-slope: a = gamma - 1/2, s = 0).
// Clamped to [-760, 760] (beyond, sech v is 0 in double).
double student_t_visible_slope_inverse(double a, double k, double s, double u);

}  // namespace vgroove::analytic
