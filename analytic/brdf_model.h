// vgroove analytic: the BRDFs by name, one entry point for every face (CLI, Python, C++ users):
// vgroove's multiple-scattering V-groove BRDF (Lee et al. 2018, Eq. 16-17; brdf_3d.h and, in
// flatland, brdf_flatland.h), its nonsymmetric form (Eq. 21-23 with P(theta_r) of Eq. 20;
// brdf_nonsymmetric.h), and Cook-Torrance with the V-cavity G (Eq. 1-3), F = 1; Walter et al.
// 2007's rough dielectric BSDF (walter.h), reflection and transmission.
//
// Directions: analytic::Dir3 in the macrosurface frame (n = (0, 0, 1)), i towards the light and o
// towards the viewer, both away from the surface. In flatland both lie in the plane y = 0 and
// their signed 2D angles are atan2(-x, z) (the convention of analytic/ndf.h: the direction at
// angle theta is (-sin theta, cos theta)); the BRDF is then per radian. Walter's BSDF takes o on
// either side (o.z < 0: transmitted into the far medium); the others, o.z >= 0.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/masking_kind.h"
#include "vgroove/common/ndf_kind.h"

#include <optional>
#include <string_view>
#include <vector>

namespace vgroove::analytic {

enum class BrdfModel : unsigned char { vgroove, cook_torrance, vgroove_nonsymmetric, walter };
// "vgroove", "cook-torrance", "vgroove-nonsymmetric", "walter"
const char* brdf_model_name(BrdfModel m);
std::optional<BrdfModel> brdf_model_from_name(std::string_view name);

// The orders a BRDF sums when the caller does not say: the one default of every face (`vgroove
// brdf --max-k`, BrdfEvalOptions::max_k = 0, Python's vgroove.BRDF and vgroove.brdf):
//   vgroove, 3D             kAllOrders: every order (the single pass visits only the orders Eq. (4)
//                           allows, so its cost does not grow with max_k, brdf_3d.h);
//   vgroove, flatland       kFlatlandDefaultMaxK = 4096: one pass over the facet solutions Eq. (4)
//                           allows, whatever max_k (docs/performance.md); the orders beyond it come from grooves
//                           narrower than (pi + 2 |t_i|) / 4097;
//   vgroove-nonsymmetric    kNonsymmetricDefaultMaxK = 64: Eq. (23) integrates over the partner for
//                           each order, O(max_k^2) (GGX alpha 0.5: the values at 64 and 256 differ by
//                           about 6e-8 relative);
//   cook-torrance, walter   single scattering: max_k is not read (kAllOrders is reported).
// The samplers' defaults differ, because a pdf's cost grows with max_k: kSamplerMaxK = 16384
// (sampling_3d.h) and kNonsymmetricSamplerMaxK = 256 (sampling_nonsymmetric.h), on every face too.
inline constexpr int kAllOrders = 1'000'000;
inline constexpr int kFlatlandDefaultMaxK = 4096;
inline constexpr int kNonsymmetricDefaultMaxK = 64;
int default_max_k(BrdfModel model, bool flatland);

struct BrdfEvalOptions {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;
  bool flatland = false;
  // Orders summed, k = 1..max_k; 0: the model's default (default_max_k above). The nonsymmetric
  // model costs O(max_k^2); callers bound max_k there and in flatland (validation/ranges.h).
  int max_k = 0;
  // Orders reported one by one, k = 1..per_k (0: none); the total includes every order up to max_k.
  int per_k = 0;
  // vgroove_nonsymmetric only. The roughness across the alpha axis, 3D, GGX and Beckmann
  // (analytic/ndf_anisotropic.h; 0: alpha, isotropic): alpha is then alpha_x and the azimuths are
  // measured from its axis.
  double alpha_y = 0.0;
  // vgroove_nonsymmetric only: the partner facet's tilt equal to the first's (B = A: the symmetric
  // model, Eq. 24; with alpha_y its anisotropic form) instead of independent (Eq. 20, which for
  // Phong needs alpha < sqrt(2): std::domain_error otherwise).
  bool symmetric_partner = false;
  // Fresnel per reflection (brdf_3d.h: prod_j F(|d_j . s_j|)), 3D only; empty: F = 1. Flatland
  // evaluations ignore it (callers refuse it there).
  FresnelFn fresnel;
  // walter only: eta = n_far / n_near, light in the near medium (eta < 1: from inside the denser
  // one), and the G2 (Walter's own is smith_separable, his Eq. 23).
  double eta = 1.5;
  MaskingKind masking = MaskingKind::smith_separable;
};

struct BrdfValue {
  double value = 0.0;        // 1/sr (3D) or 1/rad (flatland)
  std::vector<double> by_k;  // [k - 1], k = 1..per_k; Cook-Torrance and Walter are k = 1 only
};

BrdfValue evaluate_brdf(BrdfModel model, const Dir3& i, const Dir3& o, const BrdfEvalOptions& opt);

}  // namespace vgroove::analytic
