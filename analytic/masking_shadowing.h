// vgroove analytic: the joint masking-shadowing G2(i, o) of Smith's three forms and of the
// V-cavity, and the V-cavity's G1 and G2 averaged over a bin of facet normals. Heitz,
// "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), 2014:
// separable Eq. (20), height-correlated Eq. (21), height-direction-correlated Eq. (23) with van
// Ginneken et al.'s (1998) lambda(phi) = 4.41 phi / (4.41 phi + 1) (quoted there); V-cavity G1 Eq.
// (24) (analytic/ndf.h G1_vcavity), its G2 the minimum of the two (Lee et al. 2018 Eq. 3: in a
// V-cavity the part of a facet in view from any direction is a segment from its ridge). The bin
// averages weight a normal m as the microfacet BRDF does, D(m) (o.m)+ for G1 and D(m) (i.m)+
// (o.m)+ for G2 (Heitz 2014 Eq. 13, 15, 18), as sim/heightfield_masking.h weights its points.
// Smith's forms are one number for every m facing both directions (chi+ is the caller's).
// Tests: tests/analytic/masking_shadowing_test.cpp (MaskingShadowing.*).
// Derivation: docs/derivations/heightfield.md (traced masking-shadowing).
#pragma once

#include "vgroove/analytic/ndf.h"

namespace vgroove::analytic {

// From Smith's Lambda of each direction (analytic/ndf.h Lambda). phi: the azimuth difference of
// i and o in radians, any value (folded onto [0, pi]); 0 is the hotspot (masking and shadowing
// fully correlated: G2 = min(G1_i, G1_o)).
double G2_smith_separable(double lambda_i, double lambda_o);                                // Eq. (20)
double G2_smith_height_correlated(double lambda_i, double lambda_o);                        // Eq. (21)
double van_ginneken_lambda(double phi);                                                     // 4.41 phi / (4.41 phi + 1)
double G2_smith_height_direction_correlated(double lambda_i, double lambda_o, double phi);  // Eq. (23)

// The V-cavity's G2 at a normal m (unit vectors, n = (0, 0, 1)): min(G1_vcavity(i, m),
// G1_vcavity(o, m)); 0 when m faces away from i or o.
double G2_vcavity(double ix, double iy, double iz, double ox, double oy, double oz, double mx, double my, double mz);

// A bin of facet normals: theta_m in [theta_lo, theta_hi] within [0, pi/2], azimuth phi_m in
// [phi_lo, phi_hi] (absolute, radians, phi_hi - phi_lo <= 2 pi).
struct NormalBin {
  double theta_lo = 0.0, theta_hi = 0.0, phi_lo = 0.0, phi_hi = 0.0;
};
// int_bin G D(m) w(m) dm / int_bin D(m) w(m) dm with w = (o.m)+ (G1) or (i.m)+ (o.m)+ (G2),
// by Gauss-Legendre on `panels` x `panels` panels of 16 x 16 nodes over the bin (the integrand's
// kinks, min and the facing cut, converge slowly; NaN where the bin has no weight). Beckmann or
// GGX (any kind D takes).
double vcavity_g1_bin_average(NdfKind ndf, double alpha, double theta_o, double phi_o, const NormalBin& bin,
                              int panels = 8);
double vcavity_g2_bin_average(NdfKind ndf, double alpha, double theta_i, double phi_i, double theta_o, double phi_o,
                              const NormalBin& bin, int panels = 8);

}  // namespace vgroove::analytic
