#include "vgroove/analytic/brdf_model.h"

#include "vgroove/analytic/brdf_flatland.h"

#include <cmath>

namespace vgroove::analytic {

const char* brdf_model_name(BrdfModel m) { return m == BrdfModel::vgroove ? "vgroove" : "cook-torrance"; }

std::optional<BrdfModel> brdf_model_from_name(std::string_view name) {
  for (BrdfModel m : {BrdfModel::vgroove, BrdfModel::cook_torrance})
    if (name == brdf_model_name(m)) return m;
  return std::nullopt;
}

namespace {
double flat_angle(const Dir3& d) { return std::atan2(-d.x, d.z); }
}  // namespace

BrdfValue evaluate_brdf(BrdfModel model, const Dir3& i, const Dir3& o, const BrdfEvalOptions& opt) {
  BrdfValue v;
  v.by_k.assign(static_cast<std::size_t>(opt.per_k), 0.0);
  if (opt.flatland) {
    const double ti = flat_angle(i), to = flat_angle(o);
    if (model == BrdfModel::cook_torrance) {
      v.value = flatland_brdf_single(opt.ndf, opt.alpha, ti, to);
      if (opt.per_k > 0) v.by_k[0] = v.value;
      return v;
    }
    v.value = flatland_brdf(opt.ndf, opt.alpha, ti, to, opt.max_k);
    for (int k = 1; k <= opt.per_k; ++k)
      v.by_k[static_cast<std::size_t>(k - 1)] = flatland_brdf_k(opt.ndf, opt.alpha, ti, to, k);
    return v;
  }
  if (model == BrdfModel::cook_torrance) {
    v.value = cook_torrance(i, o, opt.ndf, opt.alpha);
    if (opt.per_k > 0) v.by_k[0] = v.value;
    return v;
  }
  v.value = vgroove_brdf(i, o, opt.ndf, opt.alpha, opt.max_k);
  for (int k = 1; k <= opt.per_k; ++k)
    v.by_k[static_cast<std::size_t>(k - 1)] = vgroove_brdf_k(i, o, k, opt.ndf, opt.alpha);
  return v;
}

}  // namespace vgroove::analytic
