// check_brdf with surface "heightfield" (validation/check_brdf.h): a user's BRDF against random
// heightfields traced exactly in 3D, by the metric of the V-groove surface. On smooth Beckmann
// fields at normal incidence (masking and multiple scattering nearly absent, heights independent
// of slopes) Cook-Torrance with Smith's height-correlated G, compensated to albedo 1 by Kulla-Conty,
// is the surface's BRDF and passes; Smith's single scattering alone (0.03% short of the field's
// albedo 1), the compensated model with 2% less energy, or at 1.5 alpha, fail. The traced lobe
// does not depend on the thread count, and a field that does not fit memory is refused before any
// work.
#include "vgroove/validation/check_brdf.h"

#include "vgroove/sim/heightfield.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/energy_lobe_shape.h"

#include "tests/user_error_of.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace vgroove::validation {
namespace {

CheckBrdfOptions small() {
  CheckBrdfOptions o;
  o.surface = CheckSurface::heightfield;
  o.ndf = NdfKind::beckmann;
  o.alpha = 0.3;
  o.theta_i_deg = {0};
  o.rays = 20000;
  o.field_size = 64, o.correlation_length = 4, o.fields = 4;
  o.theta_bins = 9, o.phi_bins = 8;
  o.threads = 2;
  return o;
}

const analytic::MicrofacetModel kSmith{NdfKind::beckmann, analytic::MaskingKind::smith_height_correlated};

// Cook-Torrance with Smith's height-correlated G.
BrdfFn smith(double alpha, double scale = 1.0) {
  return [=](const analytic::Dir3& i, const analytic::Dir3& o) {
    return scale * single_scattering_brdf(kSmith, alpha, i, o);
  };
}

// The same with Kulla-Conty's compensation: albedo 1 at every incidence (E(mu) on 17 points, exact
// at mu = 1, where these checks take it; 0.35 s a curve).
BrdfFn smith_kulla_conty(double alpha, const std::shared_ptr<const AlbedoCurve>& curve, double scale = 1.0) {
  return [=](const analytic::Dir3& i, const analytic::Dir3& o) {
    return scale * compensated_brdf(CompensatedLobe::kulla_conty, kSmith, alpha, *curve, i, o);
  };
}

TEST(HeightfieldCheckBrdf, SmithPassesWhereItMustAndWrongModelsFail) {
  // With F = 1 every ray leaves: the traced albedo is 1 exactly, and its threshold is one ray's
  // worth plus the tolerance. Kulla-Conty's Smith passes.
  const auto curve = std::make_shared<const AlbedoCurve>(albedo_curve(kSmith, 0.3, 17));
  const CheckBrdfResult ok = check_brdf(smith_kulla_conty(0.3, curve), small());
  ASSERT_EQ(ok.cases.size(), 1u);
  const CheckBrdfCase& c = ok.cases[0];
  EXPECT_TRUE(ok.pass) << "L1 " << c.l1 << " <= " << c.l1_threshold << ", flux " << c.l1_flux
                       << " <= " << c.l1_flux_threshold << ", albedo " << c.albedo_sim << " vs " << c.albedo_model
                       << " (" << c.albedo_threshold << ")";
  EXPECT_EQ(c.rays, 20000);
  EXPECT_NEAR(c.albedo_sim, 1.0, 1e-15);
  const nlohmann::json j = ok.to_json();
  EXPECT_EQ(j["inputs"]["surface"], "heightfield");
  EXPECT_EQ(j["inputs"]["heightfield"]["field_size"], 64);

  // Smith's single scattering alone lacks the surface's multiple scattering (E_1 0.99971): caught
  // by the albedo at 20000 rays, its shape within noise.
  const CheckBrdfResult single = check_brdf(smith(0.3), small());
  EXPECT_FALSE(single.pass);
  EXPECT_LE(single.cases[0].l1, single.cases[0].l1_threshold);
  EXPECT_GT(std::abs(single.cases[0].albedo_sim - single.cases[0].albedo_model), single.cases[0].albedo_threshold);
  // 2% less energy, or 1.5 times the roughness (on the shape): caught.
  const CheckBrdfResult dim = check_brdf(smith_kulla_conty(0.3, curve, 0.98), small());
  EXPECT_FALSE(dim.pass) << "albedo " << dim.cases[0].albedo_model << " threshold " << dim.cases[0].albedo_threshold;
  const CheckBrdfResult rough = check_brdf(smith(0.45), small());
  EXPECT_FALSE(rough.pass);
  EXPECT_GT(rough.cases[0].l1, rough.cases[0].l1_threshold);
}

TEST(HeightfieldCheckBrdf, ResultsDoNotDependOnThreads) {
  CheckBrdfOptions o = small();
  o.theta_i_deg = {0, 60};
  o.rays = 9001;  // not a multiple of the fields or the chunks
  o.fields = 2;
  o.threads = 1;
  const CheckBrdfResult one = check_brdf(smith(0.3), o);
  o.threads = 2;
  const CheckBrdfResult two = check_brdf(smith(0.3), o);
  ASSERT_EQ(one.cases.size(), 2u);
  for (std::size_t c = 0; c < 2; ++c) {
    EXPECT_EQ(one.cases[c].rays, 9001);
    EXPECT_EQ(one.cases[c].l1, two.cases[c].l1);
    EXPECT_EQ(one.cases[c].l1_flux, two.cases[c].l1_flux);
    EXPECT_EQ(one.cases[c].albedo_sim, two.cases[c].albedo_sim);
  }
}

TEST(HeightfieldCheckBrdf, BadOptionsAndOversizedFieldsAreRefusedInOneLine) {
  CheckBrdfOptions o = small();
  o.dim = SurfaceDim::flatland;
  EXPECT_TRUE(testing_files::user_error_contains([&] { check_options(o); }, "surface heightfield is a 3D surface"));
  o = small();
  o.ndf = NdfKind::phong;
  EXPECT_TRUE(testing_files::user_error_contains([&] { check_options(o); },
                                                 "ndf = phong: surface heightfield takes beckmann or ggx"));
  o = small();
  o.field_size = 100;
  EXPECT_TRUE(testing_files::user_error_contains([&] { check_options(o); },
                                                 "field_size = 100 is out of range [16, 65536], a power of two"));
  o = small();
  o.correlation_length = 9;  // > 64 / 8
  EXPECT_TRUE(
      testing_files::user_error_contains([&] { check_options(o); }, "correlation_length = 9 is out of range [2, 8]"));
  o = small();
  o.fields = 0;
  EXPECT_TRUE(testing_files::user_error_contains([&] { check_options(o); }, "fields = 0 is out of range"));
  o = small();
  o.field_size = 65536;
  o.correlation_length = 8;
  if (support::memory_limit_bytes() >= sim::heightfield_bytes(65536)) GTEST_SKIP() << "this machine holds 126 GB";
  EXPECT_TRUE(testing_files::user_error_contains([&] { check_brdf(smith(0.3), o); },
                                                 "field_size = 65536 needs 126.0 GB with its hierarchy"));
}

}  // namespace
}  // namespace vgroove::validation
