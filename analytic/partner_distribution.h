// vgroove analytic: P(theta_r), the law of a nonsymmetric V-groove's second facet, Lee et al.
// 2018, Sec. 5.2, Eq. (18)-(20) and App. C, in 3D and its flatland analogue.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018.
//
// Conventions: analytic/ndf.h (D normalized by 2 pi int_0^{pi/2} D cos sin = 1, D2 by
// int D2 cos = 1). A groove's facets have tilts a = |theta_l| and b = theta_r in [0, pi/2) (the
// angles of their normals from n); both rims lie on the macrosurface, so a groove of depth h has
// the projected widths h / tan a and h / tan b: the ratio tan(theta_l) / tan(theta_r) of Eq. (18).
//
// Derivation (Eq. 18-20). The left facets (normal s_l, azimuth phi_v) cover the projected area
// D(s_l) cos(theta_l) ds_l, ds_l = sin(theta_l) d theta_l d phi_v. If the right tilt is drawn
// independently of the left one with the density P(theta_r), each left facet of projected width w
// brings a right facet of width w tan(theta_l) / tan(theta_r), so the right facets cover
//   [int_0^{pi/2} D(a) cos(a) sin(a) tan(a) da] P(b) / tan(b) db d phi_v.
// They follow D too (D(b) cos(b) sin(b) db d phi_v) exactly when
//   P(b) = D(b) sin^2(b) / N,      N = int_0^{pi/2} D(a) sin^2(a) da,                    (Eq. 20)
// and then the right facets' total projected area equals the left ones': the facets of the
// whole surface, left and right together, have normals distributed by D in projected area, and a
// facet of either side has its partner's tilt distributed by P independently of its own (the
// measure p(a) P(b) (1 + tan a / tan b) of grooves by macro area is symmetric under a <-> b; see
// sim/microsurface_nonsymmetric.h). Written with the groove law p(theta) = 2 pi D cos sin of
// sim/microsurface3d.h (the tilt of a facet under a uniform point of the macrosurface):
//   P(theta) = p(theta) tan(theta) / E_p[tan],
// the tilt law weighted by the facet's depth per width.
//
// Closed forms of N (x = tan a; D sin^2 da = P22(x) x^2 dx, P22 the slope density):
//   Beckmann: N = int x^2 exp(-x^2/alpha^2) dx / (pi alpha^2) = alpha / (4 sqrt(pi)),
//   GGX:      N = (alpha^2/pi) int x^2 / (alpha^2 + x^2)^2 dx = alpha / 4,
//   Phong:    N = (p+2)/(2 pi) int cos^p sin^2 = (p+2) Gamma((p+1)/2) / (8 sqrt(pi) Gamma((p+4)/2)),
//             p = alpha_p = 2/alpha^2 - 2 (Beta function B(3/2, (p+1)/2) / 2).
// App. C prints P = c D sin^2 with c = alpha / (2 sqrt(pi)) (Beckmann), alpha / 4 (GGX) and
// (p+2) / (8 sqrt(pi)) Gamma((p+1)/2) Gamma((p+3)/2) / Gamma((p+4)/2) (Phong): the shape of Eq. (20)
// but a constant that is (up to a factor 2 for Beckmann and Gamma((p+3)/2) for Phong) N itself
// instead of 1/N, so the printed P integrates to N c, not 1 (docs/ERRATA.md, E-NS1).
//
// Phong: N is finite only for p > -1, i.e. alpha < sqrt(2) (cos^p sin^2 is not integrable at pi/2
// otherwise): rougher Phong surfaces have no independent partner law. The functions below throw
// std::domain_error there (the suites reject such specs first).
//
// Flatland. The left facets (normals at -a, a > 0) cover the projected length D2(a) cos(a) da;
// the same argument gives
//   P2(b) = D2(b) sin(b) / N2,     N2 = int_0^{pi/2} D2(a) sin(a) da,
// (= p2(b) tan(b) / E[tan] with p2 = D2 cos, the same rule) and, with the slope marginals of
// analytic/ndf.h (D2 sin da = P(x) x dx),
//   Beckmann: N2 = alpha / (2 sqrt(pi)),   GGX: N2 = alpha / 2,
//   Phong:    N2 = K / (p + 1),  K = Gamma((p+3)/2) / (sqrt(pi) Gamma((p+2)/2)) (D2 = K cos^p).
//
// Anisotropy (analytic/ndf_anisotropic.h): for the elliptical Beckmann and GGX, D(theta, phi) along
// one azimuth is the isotropic D at the effective roughness alpha(phi) times a constant, so the
// partner law of a facet at azimuth phi (Sec. 5.2: "P(theta_r | phi_v)") is P_theta_r(theta_r,
// alpha(phi)).
#pragma once

#include "vgroove/analytic/ndf.h"

namespace vgroove::analytic {

// Whether the partner law exists (N finite): always for Beckmann and GGX, alpha < sqrt(2) for Phong.
bool partner_law_exists(NdfKind ndf, double alpha);

// 3D: N = int_0^{pi/2} D sin^2 (closed form) and Eq. (20), P(theta_r) = D(theta_r) sin^2 / N,
// zero outside [0, pi/2). Integrates to 1 over [0, pi/2).
double P_theta_r_normalization(NdfKind ndf, double alpha);
double P_theta_r(NdfKind ndf, double theta_r, double alpha);
// App. C as printed (E-NS1: not normalized).
double P_theta_r_printed(NdfKind ndf, double theta_r, double alpha);

// Flatland: N2 = int_0^{pi/2} D2 sin and P2(theta_r) = D2(theta_r) sin / N2 on [0, pi/2).
double P2_theta_r_normalization(NdfKind ndf, double alpha);
double P2_theta_r(NdfKind ndf, double theta_r, double alpha);

}  // namespace vgroove::analytic
