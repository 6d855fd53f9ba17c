#include "vgroove/analytic/brdf_model.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/brdf_nonsymmetric.h"
#include "vgroove/analytic/walter.h"

#include <cmath>

namespace vgroove::analytic {

const char* brdf_model_name(BrdfModel m) {
  switch (m) {
    case BrdfModel::vgroove:
      return "vgroove";
    case BrdfModel::cook_torrance:
      return "cook-torrance";
    case BrdfModel::vgroove_nonsymmetric:
      return "vgroove-nonsymmetric";
    case BrdfModel::walter:
      return "walter";
  }
  return "?";
}

std::optional<BrdfModel> brdf_model_from_name(std::string_view name) {
  for (BrdfModel m : {BrdfModel::vgroove, BrdfModel::cook_torrance, BrdfModel::vgroove_nonsymmetric, BrdfModel::walter})
    if (name == brdf_model_name(m)) return m;
  return std::nullopt;
}

int default_max_k(BrdfModel model, bool flatland) {
  if (model == BrdfModel::vgroove_nonsymmetric) return kNonsymmetricDefaultMaxK;
  if (model == BrdfModel::vgroove && flatland) return kFlatlandDefaultMaxK;
  return kAllOrders;
}

namespace {
double flat_angle(const Dir3& d) { return std::atan2(-d.x, d.z); }
// A flatland direction below the interface as walter.h's far-side angle: d = (sin phi, 0, -cos phi).
double far_angle(const Dir3& d) { return std::atan2(d.x, -d.z); }

// Walter et al. 2007, Eq. (20)-(21): single scattering, k = 1 only.
BrdfValue evaluate_walter(const Dir3& i, const Dir3& o, const BrdfEvalOptions& opt) {
  BrdfValue v;
  v.by_k.assign(static_cast<std::size_t>(opt.per_k), 0.0);
  if (!opt.flatland)
    v.value = walter_bsdf(i, o, opt.ndf, opt.alpha, opt.eta, opt.masking);
  else if (o.z >= 0.0)
    v.value = walter_brdf2(flat_angle(i), flat_angle(o), opt.ndf, opt.alpha, opt.eta, opt.masking);
  else
    v.value = walter_btdf2(flat_angle(i), far_angle(o), opt.ndf, opt.alpha, opt.eta, opt.masking);
  if (opt.per_k > 0) v.by_k[0] = v.value;
  return v;
}

// Eq. (23) per k and summed over k = 1..max_k (the sum in the order nonsymmetric_brdf adds it).
BrdfValue evaluate_nonsymmetric(const Dir3& i, const Dir3& o, const BrdfEvalOptions& opt, int max_k) {
  NonsymmetricModel m;
  m.roughness = Roughness{opt.ndf, opt.alpha, opt.alpha_y > 0.0 ? opt.alpha_y : opt.alpha};
  m.partner = opt.symmetric_partner ? PartnerLaw::symmetric : PartnerLaw::independent;
  BrdfValue v;
  v.by_k.assign(static_cast<std::size_t>(opt.per_k), 0.0);
  if (opt.flatland) {
    const double ti = flat_angle(i), to = flat_angle(o);
    v.value = flatland_nonsymmetric_brdf(ti, to, max_k, m);
    for (int k = 1; k <= opt.per_k; ++k)
      v.by_k[static_cast<std::size_t>(k - 1)] = flatland_nonsymmetric_brdf_k(ti, to, k, m);
    return v;
  }
  v.value = nonsymmetric_brdf(i, o, max_k, m, opt.fresnel);
  for (int k = 1; k <= opt.per_k; ++k)
    v.by_k[static_cast<std::size_t>(k - 1)] = nonsymmetric_brdf_k(i, o, k, m, opt.fresnel);
  return v;
}
}  // namespace

BrdfValue evaluate_brdf(BrdfModel model, const Dir3& i, const Dir3& o, const BrdfEvalOptions& opt) {
  const int max_k = opt.max_k > 0 ? opt.max_k : default_max_k(model, opt.flatland);
  if (model == BrdfModel::vgroove_nonsymmetric) return evaluate_nonsymmetric(i, o, opt, max_k);
  if (model == BrdfModel::walter) return evaluate_walter(i, o, opt);
  BrdfValue v;
  v.by_k.assign(static_cast<std::size_t>(opt.per_k), 0.0);
  if (opt.flatland) {
    const double ti = flat_angle(i), to = flat_angle(o);
    if (model == BrdfModel::cook_torrance) {
      v.value = flatland_brdf_single(opt.ndf, opt.alpha, ti, to);
      if (opt.per_k > 0) v.by_k[0] = v.value;
      return v;
    }
    v.value = flatland_brdf(opt.ndf, opt.alpha, ti, to, max_k);
    for (int k = 1; k <= opt.per_k; ++k)
      v.by_k[static_cast<std::size_t>(k - 1)] = flatland_brdf_k(opt.ndf, opt.alpha, ti, to, k);
    return v;
  }
  if (model == BrdfModel::cook_torrance) {
    v.value =
        opt.fresnel ? cook_torrance(i, o, opt.ndf, opt.alpha, opt.fresnel) : cook_torrance(i, o, opt.ndf, opt.alpha);
    if (opt.per_k > 0) v.by_k[0] = v.value;
    return v;
  }
  if (opt.fresnel) {
    v.value = vgroove_brdf(i, o, opt.ndf, opt.alpha, max_k, opt.fresnel);
    for (int k = 1; k <= opt.per_k; ++k)
      v.by_k[static_cast<std::size_t>(k - 1)] = vgroove_brdf_k(i, o, k, opt.ndf, opt.alpha, opt.fresnel);
    return v;
  }
  v.value = vgroove_brdf(i, o, opt.ndf, opt.alpha, max_k);
  for (int k = 1; k <= opt.per_k; ++k)
    v.by_k[static_cast<std::size_t>(k - 1)] = vgroove_brdf_k(i, o, k, opt.ndf, opt.alpha);
  return v;
}

}  // namespace vgroove::analytic
