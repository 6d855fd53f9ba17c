// analytic/brdf_model.h: the one table of default orders (BrdfEvalOptions::max_k = 0 sums the
// model's default_max_k, the value `vgroove brdf` and Python use when max_k is not given) and the
// Fresnel plug-in of evaluate_brdf against the per-model functions it calls.
#include "vgroove/analytic/brdf_model.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/brdf_nonsymmetric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace vgroove::analytic {
namespace {

TEST(BrdfModel, DefaultMaxKIsTheTable) {
  EXPECT_EQ(default_max_k(BrdfModel::vgroove, false), kAllOrders);
  EXPECT_EQ(default_max_k(BrdfModel::vgroove, true), kFlatlandDefaultMaxK);
  EXPECT_EQ(default_max_k(BrdfModel::vgroove_nonsymmetric, false), kNonsymmetricDefaultMaxK);
  EXPECT_EQ(default_max_k(BrdfModel::vgroove_nonsymmetric, true), kNonsymmetricDefaultMaxK);
  EXPECT_EQ(default_max_k(BrdfModel::cook_torrance, false), kAllOrders);
  EXPECT_EQ(kAllOrders, 1'000'000);
  EXPECT_EQ(kFlatlandDefaultMaxK, 4096);
  EXPECT_EQ(kNonsymmetricDefaultMaxK, 64);
}

TEST(BrdfModel, MaxKZeroSumsTheDefaultOrders) {
  // Phong alpha 1.3 near the mirror direction, where narrow grooves send light after many
  // reflections: the default's value differs from a short sum's (power) and equals the explicit
  // default's.
  const Dir3 i = dir3(0.5, 0.0), o = dir3(0.52, std::numbers::pi);
  BrdfEvalOptions opt;
  opt.ndf = NdfKind::phong, opt.alpha = 1.3;
  const double by_default = evaluate_brdf(BrdfModel::vgroove, i, o, opt).value;
  EXPECT_EQ(by_default, vgroove_brdf(i, o, NdfKind::phong, 1.3, kAllOrders));
  EXPECT_NE(by_default, vgroove_brdf(i, o, NdfKind::phong, 1.3, 16));
  opt.max_k = 16;
  EXPECT_EQ(evaluate_brdf(BrdfModel::vgroove, i, o, opt).value, vgroove_brdf(i, o, NdfKind::phong, 1.3, 16));

  BrdfEvalOptions flat;
  flat.ndf = NdfKind::phong, flat.alpha = 1.3, flat.flatland = true;
  const double ti = 0.5, to = -0.52;
  const Dir3 fi{-std::sin(ti), 0.0, std::cos(ti)}, fo{-std::sin(to), 0.0, std::cos(to)};
  const double flat_default = evaluate_brdf(BrdfModel::vgroove, fi, fo, flat).value;
  EXPECT_EQ(flat_default, flatland_brdf(NdfKind::phong, 1.3, ti, to, kFlatlandDefaultMaxK));
  EXPECT_NE(flat_default, flatland_brdf(NdfKind::phong, 1.3, ti, to, 64));

  BrdfEvalOptions ns;
  ns.ndf = NdfKind::ggx, ns.alpha = 0.5;
  EXPECT_EQ(evaluate_brdf(BrdfModel::vgroove_nonsymmetric, i, o, ns).value,
            vgroove_nonsymmetric_brdf(i, o, NdfKind::ggx, 0.5, kNonsymmetricDefaultMaxK));
}

TEST(BrdfModel, FresnelIsThePerModelFunctionsPlugIn) {
  const Dir3 i = dir3(0.6, 3.1), o = dir3(0.9, 0.4);
  // Schlick's F with F0 = 0.5 (any reflectance below 1 at every angle will do).
  const FresnelFn F = [](double c) { return 0.5 + 0.5 * std::pow(1.0 - c, 5.0); };
  BrdfEvalOptions opt;
  opt.ndf = NdfKind::ggx, opt.alpha = 0.6, opt.fresnel = F, opt.per_k = 3;
  const BrdfValue v = evaluate_brdf(BrdfModel::vgroove, i, o, opt);
  EXPECT_EQ(v.value, vgroove_brdf(i, o, NdfKind::ggx, 0.6, kAllOrders, F));
  for (int k = 1; k <= 3; ++k) EXPECT_EQ(v.by_k[k - 1], vgroove_brdf_k(i, o, k, NdfKind::ggx, 0.6, F)) << k;
  EXPECT_EQ(evaluate_brdf(BrdfModel::cook_torrance, i, o, opt).value, cook_torrance(i, o, NdfKind::ggx, 0.6, F));
  // A conductor reflects less than the perfect mirror, per order and in all.
  BrdfEvalOptions mirror = opt;
  mirror.fresnel = {};
  const BrdfValue m = evaluate_brdf(BrdfModel::vgroove, i, o, mirror);
  EXPECT_LT(v.value, m.value);
  for (int k = 1; k <= 3; ++k) {
    if (m.by_k[k - 1] > 0) {
      EXPECT_LT(v.by_k[k - 1], m.by_k[k - 1]) << k;
    }
  }
  NonsymmetricModel model;
  model.roughness = Roughness{NdfKind::ggx, 0.6, 0.6};
  EXPECT_EQ(evaluate_brdf(BrdfModel::vgroove_nonsymmetric, i, o, opt).value,
            nonsymmetric_brdf(i, o, kNonsymmetricDefaultMaxK, model, F));
}

}  // namespace
}  // namespace vgroove::analytic
