// vgroove analytic: the BRDFs by name, one entry point for every face (CLI, Python, C++ users):
// vgroove's multiple-scattering V-groove BRDF (Lee et al. 2018, Eq. 16-17; brdf_3d.h and, in
// flatland, brdf_flatland.h) and Cook-Torrance with the V-cavity G (Eq. 1-3), F = 1.
//
// Directions: analytic::Dir3 in the macrosurface frame (n = (0, 0, 1)), i towards the light and o
// towards the viewer, both away from the surface. In flatland both lie in the plane y = 0 and
// their signed 2D angles are atan2(-x, z) (the convention of analytic/ndf.h: the direction at
// angle theta is (-sin theta, cos theta)); the BRDF is then per radian.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/common/ndf_kind.h"

#include <optional>
#include <string_view>
#include <vector>

namespace vgroove::analytic {

enum class BrdfModel : unsigned char { vgroove, cook_torrance };
const char* brdf_model_name(BrdfModel m);  // "vgroove", "cook-torrance"
std::optional<BrdfModel> brdf_model_from_name(std::string_view name);

struct BrdfEvalOptions {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;
  bool flatland = false;
  // Orders summed: all of them by default (the 3D single pass visits only the orders Eq. (4)
  // allows, so the cost does not grow with max_k; the flatland sum costs O(max_k^2)).
  int max_k = 1'000'000;
  // Orders reported one by one, k = 1..per_k (0: none); the total includes every order up to max_k.
  int per_k = 0;
};

struct BrdfValue {
  double value = 0.0;        // 1/sr (3D) or 1/rad (flatland)
  std::vector<double> by_k;  // [k - 1], k = 1..per_k; Cook-Torrance is k = 1 only
};

BrdfValue evaluate_brdf(BrdfModel model, const Dir3& i, const Dir3& o, const BrdfEvalOptions& opt);

}  // namespace vgroove::analytic
