// vgroove analytic: the nonsymmetric V-groove BRDF (analytic/brdf_nonsymmetric.h) integrated over
// bins of exit direction, flatland and 3D, isotropic or anisotropic: the lobes the nonsymmetric
// suite compares with sim/microsurface_nonsymmetric.h. The symmetric partner law gives the
// symmetric model's lobe by the same code. Lee et al. 2018 ("Practical Multiple Scattering for
// Rough Surfaces", ACM TOG 37(6)), Eq. (7)-(9), (18)-(23), Fig. 7-8: the push-forward of the
// groove population through the kaleidoscope, by Gauss-Legendre panels cut where Eq. (7)'s k_b
// changes and where an exit crosses a bin edge. Layouts: FlatlandLobe and Lobe3d, rows k =
// 0..max_k and max_k + 1. Accuracy: flatland_options() within 7e-7 per bin of Eq. (23) integrated
// over the bins (90 bins, k = 1..4); the remaining kinks are measured by refinement
// (model_tolerance in the report). Tests: tests/analytic/lobe_nonsymmetric_test.cpp
// (NonsymmetricLobe.FlatlandBinsAreEq23Integrated, NonsymmetricLobe.FlatlandBinsMatchEq23PerBinAtTheSuitesOptions,
// NonsymmetricLobe.SymmetricPartnerIsTheSymmetricLobe, NonsymmetricLobe.WhiteFurnace,
// NonsymmetricLobe.HardCasesStayFinite), tests/analytic/lobe_nonsymmetric_long_test.cpp.
// Derivation: docs/derivations/nonsymmetric.md.
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
// Flatland's options: within ~1e-6 per bin of Eq. (23) integrated at 90 bins (cost: docs/performance.md).
NonsymmetricLobeOptions flatland_options();

FlatlandLobe flatland_nonsymmetric_lobe(const NonsymmetricModel& m, double theta_i, int bins, int max_k,
                                        const NonsymmetricLobeOptions& opt = flatland_options());
Lobe3d nonsymmetric_lobe_3d(const NonsymmetricModel& m, double theta_i, double axes_azimuth, int theta_bins,
                            int phi_bins, int max_k, const NonsymmetricLobeOptions& opt = {});

}  // namespace vgroove::analytic
