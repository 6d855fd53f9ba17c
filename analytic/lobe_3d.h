// vgroove analytic: the 3D multiple-scattering BRDF of symmetric V-grooves (brdf_3d.h) and
// Cook-Torrance integrated over bins of exit direction: the lobes the suites compare with the
// light traced in procedural surfaces.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 5.1 (Eq. 10-17), Sec. 7.1 (Fig. 11).
#pragma once

#include "vgroove/analytic/brdf_3d.h"

#include <atomic>
#include <vector>

namespace vgroove::analytic {

// The fraction of the incident flux leaving into each (theta_o, phi_o) bin, per k. Layout shared
// with sim::Microsurface3dTally: theta_o in [0, pi/2) in theta_bins equal bins; phi_o in
// phi_bins equal bins centred on phi = 0 (bin 0 covers [-d/2, d/2), d = 2 pi / phi_bins),
// phi_bins even, so that the plane of incidence runs through the centres of bins 0 and
// phi_bins / 2. The light is at i = dir3(theta_i, pi) (its mirror direction at phi = 0).
// Rows k = 0..max_k, row max_k + 1 holds every k > max_k; index [(row * theta_bins + t) * phi_bins + p].
//
// vgroove_lobe_3d is the push-forward of the groove distribution (method (b) of the tests): for
// each groove azimuth (Gauss-Legendre in phi_a, mirror symmetry phi_a -> pi - phi_a), each facet
// and each k, the arc of exits swept by theta_m is cut where it crosses a bin edge or where
// Eq. (4)/(6) change form, and each piece is integrated exactly in smoothness by Gauss-Legendre
// in w = sqrt(CDF(theta_m)) (theta_m above the median). by_k and albedo are exact to rounding
// (albedo - 1 < 3e-14 for F = 1); hist is limited by the phi_a quadrature. Its per-bin integrands
// have square-root points (theta edges tangent to an arc) and kinks where an arc passes through a
// bin corner (at phi_a = the azimuth of i + corner): the phi_a range is cut at both (brdf_3d.cpp,
// run_lobe). Without the corner cuts the kinks leave ~|slope jump| h^2 each: up to 1.6e-5 per bin
// at 384 panels, worst in the back-scattering plane, and the 384 -> 768 change is <= 1e-5.
// With them, at 30 x 24 bins and max_k 16 (GGX 0.5 at 30 deg, GGX 0.3 at 60, 0.7 at 75, Beckmann
// 1.0 at 10): per bin within 1.4e-7..9.6e-7 of 6144 panels, the 384 -> 768 change <= 2.7e-7
// (GGX 0.5 at 30 deg); against Eq. (16) integrated over single bins, < 3.1e-9 at and beside the
// specular peak and 2.5e-8 in the back-scattering bin (45 x 36 bins). Beyond k = k_bands the lobe
// deposits by a midpoint rule in the CDF, scaled to the exact total (per node, or with the bands
// beyond 16 over all nodes, high_k_coarsening); its bins carry the
// rule's error, the same at any phi_a panel count: at 30 x 24 bins, max_k 16, the default 512
// strata against 4096 differ per bin by up to 5.7e-7 (GGX 0.5 at 40 deg), 2.2e-7 (GGX 1.0 at 80),
// 2.1e-7 (GGX 1.5 at 85), 2.5e-8 (GGX 0.1 at 60); Phong 1.0 at 40 deg 1.6e-6, and Phong 1.3, whose
// grooves beyond k = 32 hold 3 % of the flux (cos^(p+2) falls slowly for p + 2 = 2 / alpha^2 near
// 1), 2.7e-4 at 40 deg: the lobe is not accurate to 1e-6 there. Beckmann's tail (and Phong's at
// alpha 0.5) is below 1e-14.
// What makes it cheaper without moving a bin beyond these errors (tests/analytic/lobe_3d_test.cpp):
//  - normal incidence: one cross-section, spread uniformly over phi_o (rotational symmetry): no
//    phi_a quadrature error, the tail with 16 times the strata (GGX 0.3 at 0 deg 4e-10 per bin
//    from 8 times more, Phong 1.3 9.8e-8);
//  - the bands k > max(max_k, 16) and the tail on half the phi_a panels, scaled to their exact
//    flux at the full ones (high_k_coarsening): rows k <= max_k unchanged to the bit;
//  - four Gauss-Legendre nodes where a piece is far from the integrand's singularities
//    (four_node_pieces: bins within 5.3e-15 of eight), a tail lighter than 1e-9 with 16 strata;
//  - the tail's strata from a per-lobe table of 1 - u (lobe_3d.cpp, tail_strata_table), their
//    half-aperture by a series: per bin within 2.6e-15 of the strata from u (which rounded 1 - u);
// and what makes it cheaper at the same integrand, within rounding (lobe_3d_nodes.h; the fast
// kernels against the reference ones, per bin within 1e-15): the pieces' Gauss-Legendre nodes and
// the tail's strata four at a time (AVX2 where the machine has it, the same bits without),
// Beckmann's and Phong's exp, log and pow by polynomials (exp_log_batch.h), the nodes of a band
// evaluated in runs, the deposits indexed without integer divisions, the bin search started at
// the last exit's segment.
// Cost at 30 x 24 bins, max_k 16, over the 60 3D cases of Fig. 11 (one core, one process, idle
// host; `BM_lobe_3d` runs eight of them): median 43 ms, from 2 ms (normal incidence) to 82 ms
// (Phong 0.7 at 20 deg), 2.4 s in all; the scalar kernels of bdf3810 in the same period: median
// 63-70 ms, up to 154-167 ms (Phong 0.7 at 20 deg), 3.75-3.86 s, per bin within 2.6e-15 of these.
// (Before the shortcuts above: median 184 ms, 63-383 ms; per bin within 1.1e-7, per row 6e-15.)
struct Lobe3d {
  int theta_bins = 0;
  int phi_bins = 0;
  int max_k = 0;
  std::vector<double> by_k;  // [row]
  std::vector<double> hist;  // [t * phi_bins + p], all k
  std::vector<double> hist_by_k;
  double albedo = 0.0;
};

// The tail's mass below which it is spread with Lobe3dOptions::light_tail_strata.
inline constexpr double kLightTail = 1e-9;

struct Lobe3dOptions {
  int phi_panels = 384;  // panels over phi_a in [0, pi/2], shared among the pieces between cuts by length
  int phi_order = 2;     // nodes per panel (the integrands have kinks: many low-order panels win)
  int k_bands = 32;      // k beyond which a midpoint rule in the CDF replaces the exact bands
  int tail_strata = 512;
  // Strata for a tail lighter than kLightTail per groove azimuth (of the grooves' area, per facet):
  // it moves no bin by more than 2 kLightTail whatever the strata (the tail's total is exact).
  int light_tail_strata = 16;
  bool corner_cuts = true;  // cut the phi_a range where arcs pass through bin corners (kinks)
  // Four Gauss-Legendre nodes instead of eight on the pieces of theta_m smooth enough for them to
  // agree to rounding (lobe_3d.cpp, integrate_band); false: eight on every piece above 1e-6.
  bool four_node_pieces = true;
  // The bands k > max(max_k, high_k_from) and the tail (all in the last row) on phi_panels /
  // high_k_coarsening panels, scaled to their exact flux from the full ones (lobe_3d.cpp); 1: every
  // k on the same panels.
  int high_k_coarsening = 2;
  int high_k_from = 16;
  // At normal incidence (theta_i == 0) the lobe from one cross-section, spread uniformly over phi_o
  // (rotational symmetry, lobe_3d.cpp); false: the phi_a quadrature as at any other theta_i.
  bool rotational_symmetry = true;
  // The plain per-node kernels in place of the algebraic ones (trigonometry per node, Eq. 6 via
  // G_kaleidoscopic at each piece): the same integrand at the same nodes, for the tests and the
  // benchmark's side-by-side (lobe_3d.cpp, weight_fast).
  bool reference_kernels = false;
  // Read before each phi_a node (may be null): once set, the remaining nodes are skipped and the
  // lobe is incomplete (the caller, stopped by Ctrl-C, discards it).
  const std::atomic<bool>* cancel = nullptr;
};

Lobe3d vgroove_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k);
Lobe3d vgroove_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k,
                       const Lobe3dOptions& opt);
// Single scattering with the V-cavity G (Eq. 1-3), k = 1 only: albedo < 1.
Lobe3d cook_torrance_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins);
// The same from a vgroove lobe: its k = 1 row. Cook-Torrance with the V-cavity G is the k = 1 term
// of Eq. (16) everywhere (Eq. 25; Brdf3d.CookTorranceIsTheK1Term, to 1e-10 relative), so both
// lobes integrate one function over the same bins: per bin within 1e-16 of
// cook_torrance_lobe_3d (Lobe3d.CookTorranceIsTheK1Row), at no cost.
Lobe3d cook_torrance_lobe_3d_from(const Lobe3d& vgroove_lobe);
Lobe3d cook_torrance_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins,
                             const Lobe3dOptions& opt);

}  // namespace vgroove::analytic
