// vgroove analytic: the single-scattering rough dielectric BSDF of Walter, Marschner, Li, Torrance,
// "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, Eq. (13)-(21) (reflection
// and transmission), in 3D and its flatland analogue, with V-cavity or Smith (separable, height-
// correlated) masking. Light arrives along i in the near medium; eta = n_far / n_near. Flux form:
// f(i, o) |o.n| d omega_o is the share of the flux from i leaving into d omega_o (Walter's Eq. 21 as
// printed, i the light), so f_t(i, o) / n_o^2 = f_t(o, i) / n_i^2 (flatland: n^1). Holds: normal-
// incidence hand values, that generalized reciprocity, flat Fresnel R and T as alpha -> 0, finite
// at 89.9 deg for alpha 0.01..2, TIR; against the tracer (k = 1 exits), reflection from above exact
// with the V-cavity G. Tests: tests/analytic/walter_test.cpp (Walter.NormalIncidenceHandValues,
// Walter.GeneralizedReciprocity, Walter.SmallRoughnessIsFlatFresnel, Walter.GrazingIsFinite,
// Walter.TotalInternalReflection, Walter.ArticleEq21dBreaksReciprocity), tests/validation/
// walter_sim_test.cpp (WalterSim.ReflectionFromAboveMatchesTheTracer, WalterSim.TransmittedFluxSettlesEta).
// Derivation: docs/derivations/walter.md.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/masking_kind.h"
#include "vgroove/analytic/ndf.h"

namespace vgroove::analytic {

// The G2(i, o, h) (analytic/masking_kind.h). Smith height-correlated transmission is
// B(1 + L(i), 1 + L(o)) (docs/derivations/walter.md); V-cavity G1v is Lee et al. 2018 Eq. (2)
// (Heitz 2014 Eq. 24).

// 3D. n = (0, 0, 1) on the near side: i.z > 0; o.z > 0 reflects, o.z < 0 transmits. Unit vectors
// pointing away from the surface. Smith needs beckmann, ggx or student_t (not phong).
// Walter Eq. (13): h_r = (i + o) / |i + o|; Eq. (16): h_t = -(n_i i + n_o o) / |.|, oriented to n.
Dir3 walter_half_vector(const Dir3& i, const Dir3& o, double eta);
// Walter Eq. (17): |d omega_h / d omega_o| = n_o^2 |o.h_t| / (n_i i.h_t + n_o o.h_t)^2 (n_i = 1, n_o = eta).
double walter_jacobian_t(const Dir3& i, const Dir3& o, double eta);
// Walter Eq. (20) (reflection) and Eq. (21) (transmission), unpolarized dielectric F(i.h, eta).
// 0 where o is on neither lobe's valid side (i.h <= 0, or transmission with o.h >= 0).
double walter_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, double eta, MaskingKind g);
double walter_btdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, double eta, MaskingKind g);
// Either, by the side of o.
double walter_bsdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, double eta, MaskingKind g);

// Flatland (angles in (-pi/2, pi/2), radians). Near side: the direction at theta is (-sin, cos)
// (analytic/ndf.h). Far side: the direction at phi is (sin phi, -cos phi), sim::exit_angle's
// convention below the interface (a ray going straight through keeps its angle). D2 for D.
// |d theta_h / d theta_t| = n_o |o.h_t| / |n_i i.h_t + n_o o.h_t| (docs/derivations/walter.md).
double walter_half_angle_t2(double theta_i, double theta_t, double eta);
double walter_jacobian_t2(double theta_i, double theta_t, double eta);
// f_r2 = F G D2(h) |i.h| / (2 |i.n| |o.n|); f_t2 = |i.h||o.h| n_o (1 - F) G D2(h) / (|i.n||o.n| |n_i i.h + n_o o.h|).
double walter_brdf2(double theta_i, double theta_o, NdfKind ndf, double alpha, double eta, MaskingKind g);
double walter_btdf2(double theta_i, double theta_t, NdfKind ndf, double alpha, double eta, MaskingKind g);

}  // namespace vgroove::analytic
