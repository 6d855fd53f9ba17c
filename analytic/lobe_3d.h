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
// Method, accuracy per bin and what each shortcut costs: docs/derivations/lobe_3d.md.
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
