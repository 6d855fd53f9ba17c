// vgroove analytic: the nonsymmetric V-groove BRDF (analytic/brdf_nonsymmetric.h) integrated over
// bins of exit direction, flatland and 3D, isotropic or anisotropic: the lobes the nonsymmetric
// suite compares with the light traced in sim/microsurface_nonsymmetric.h. The symmetric partner
// law gives the symmetric model's lobe by the same code (anisotropic included).
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 4.2 (Eq. 7-9), Sec. 5.2 (Eq. 18-23), Fig. 7-8.
//
// The lobe is the push-forward of the groove population through the kaleidoscope (the change of
// variables that gives Eq. 23 read backwards; tests/analytic/lobe_nonsymmetric_test.cpp checks the
// two against each other). Per unit macro area every groove receives the same flux; the grooves'
// first facet (leaning towards a = (cos phi_a, sin phi_a, 0)) has its azimuth phi_a with the density
// alpha(phi)^2 / (2 pi alpha_x alpha_y) (phi measured from the alpha_x axis; uniform when
// isotropic), its tilt A with the groove law q(A) = 2 pi D_iso(A; alpha(phi)) cos A sin A, and its
// partner the tilt B with P(B; alpha(phi)) (Eq. 20) or B = A (the population of
// sim/microsurface_nonsymmetric.h, which makes every facet's normal follow D in projected area and
// its partner P). In the groove's cross-section (t_i the projected angle) Eq. (9) splits the
// opening, of perpendicular width W cos(t_i) (W the rims' distance), among the outcomes (first facet
// hit, zone): each sends the fraction width / (W cos t_i) of the groove's flux along Eq. (8)'s t_o,
// lifted to o = c (-sin t_o a + cos t_o n) - (i.u) u. Flatland: the first facet on the left
// (theta_l = -A) or, with probability 1/2, on the right (the mirror image: the lobe at -theta_i,
// flipped).
//
// Integration. phi_a (3D) and B by Gauss-Legendre panels (the azimuth over [0, pi] with the mirror
// phi_a -> -phi_a when the roughness axes lie along or across the plane of incidence); A over
// panels uniform in v, A = atan(alpha tan(pi v / 2)), cut where Eq. (7)'s k_b changes for either
// facet (closed forms: theta_l and theta_r are linear in A) and where any outcome's exit crosses a
// bin edge (t_o is linear in A within a k_b piece, and the bin edges are finitely many t in each
// cross-section), so that every outcome stays in one bin on each piece: the deposits are smooth
// functions of (phi_a, B) with kinks, not steps. The remaining errors are the kinks of Eq. (9)'s
// max and min inside the pieces and of the deposits in (phi_a, B), measured by refinement in the
// tests and the report (model_tolerance). Beyond k_b = kb_cap (apertures below ~pi / kb_cap) a
// piece is integrated without cuts.
// The kinks in B bound the flatland bins' accuracy. A bin's deposit of count n is the integral over
// a strip of (A, B) between two lines of constant exit (Eq. 8 is linear in A and B), and it is C^1
// in B with a jump in its second derivative wherever a strip edge crosses a line on which the
// deposit kinks in A: the lit limit and the horizon of the first reflection (A = pi/2 - t_i and
// (pi/2 - t_i) / 2, for the facet hit first), A = 0, Eq. (7)'s k_b changes. These sit one per bin
// edge, feature and count (GGX 0.3 at 80 deg, k = 2, one bin: six, at B0 + 0, 1, 5, 6, 10, 11 deg),
// too many to cut, and the Gauss panels over B leave ~h_B^3 each, alternating from bin to bin. Against
// Eq. (23) integrated over the bins (90 bins, k = 1..4; tests/analytic/lobe_nonsymmetric_test.cpp)
// flatland_options() is within 7e-7 per bin (GGX 1.0 at 80 deg, k = 2; GGX 0.3: 2.2e-7, row L1
// 5e-6; Beckmann 0.3: 5e-8), at 32 partner panels within 1.5e-5 (L1 3e-4). Reaching 1e-8 takes 16
// times the nodes in B (256 panels of 8: 8.8e-9; this comparison's floor ~6e-9), or an outer
// variable along which the bins do not move (the exit angle of each count, as Eq. 23 integrates).
//
// Layouts: FlatlandLobe and Lobe3d (analytic/brdf_flatland.h, analytic/lobe_3d.h), the light at
// azimuth pi in 3D; rows k = 0..max_k, row max_k + 1 for every k > max_k.
#pragma once

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/brdf_nonsymmetric.h"
#include "vgroove/analytic/lobe_3d.h"

#include <atomic>

namespace vgroove::analytic {

// The defaults are the 3D suite's (joint (k, bin) L1 within ~2e-3 of refined runs at 15 x 12 bins,
// 0.2-0.5 s of one core per case); flatland is cheap enough for flatland_options().
struct NonsymmetricLobeOptions {
  int phi_panels = 32;     // 3D: panels over [0, pi] (mirrored) or 2 x over [0, 2 pi), besides the cuts
  int partner_panels = 8;  // panels over B (independent partner law)
  int tilt_panels = 8;     // panels over A before the cuts
  int order = 4;           // Gauss-Legendre nodes per phi and B panel: 2, 4 or 8
  int tilt_order = 2;      // nodes per A piece: 2, 4 or 8
  int kb_cap = 256;
  double negligible = 1e-13;  // a piece of A (or B) carrying less flux is not cut at bin edges
  // Read before each phi_a node and each partner panel (may be null): once set, the rest is skipped
  // and the lobe is incomplete (the caller, stopped by Ctrl-C, discards it).
  const std::atomic<bool>* cancel = nullptr;
};

// The light at theta_i in (-pi/2, pi/2) (flatland, signed) or [0, pi/2) (3D, azimuth pi).
// axes_azimuth: 3D, the azimuth of the alpha_x axis in the lobe's frame (light at pi); a light at
// azimuth phi_i over the roughness axes is axes_azimuth = pi - phi_i.
// Flatland's options: within ~1e-6 per bin of Eq. (23) integrated at 90 bins, ~30-170 ms per case.
NonsymmetricLobeOptions flatland_options();

FlatlandLobe flatland_nonsymmetric_lobe(const NonsymmetricModel& m, double theta_i, int bins, int max_k,
                                        const NonsymmetricLobeOptions& opt = flatland_options());
Lobe3d nonsymmetric_lobe_3d(const NonsymmetricModel& m, double theta_i, double axes_azimuth, int theta_bins,
                            int phi_bins, int max_k, const NonsymmetricLobeOptions& opt = {});

}  // namespace vgroove::analytic
