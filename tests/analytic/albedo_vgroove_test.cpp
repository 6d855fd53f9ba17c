// Tests of analytic/albedo_vgroove.h: the 3D V-groove model's directional albedo per bounce order
// with a reflectance per channel.
//
// - F = 1: the rows add up to 1 (the white furnace) and agree with the lobe's (analytic/lobe_3d.h,
//   the same model integrated by its push-forward into bins, another quadrature).
// - The first row is Cook-Torrance's albedo with the V-cavity G (Lee et al. 2018, Eq. 25), computed
//   independently by analytic/albedo_single.h; with Schlick's F it is F0 scale + bias of the
//   V-cavity split sum.
// - A constant reflectance f gives sum_k E_k f^k with the F = 1 rows: the product counts bounces.
// - Doubled resolution (phi panels, band nodes, bands, strata) moves no value by more than the
//   stated accuracy; extremes finite.
#include "vgroove/analytic/albedo_vgroove.h"

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/optics/fresnel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace vgroove::analytic {
namespace {

TEST(AlbedoVgroove, WhiteFurnaceAndTheLobesRows) {
  const int max_k = 8;
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.1, 0.5, 1.0})
      for (double mu : {1.0, 0.5, 0.1}) {
        const VgrooveAlbedo a = vgroove_albedo(ndf, alpha, mu, 1, {}, max_k);
        // Each groove sends all its light out; the facets' integrals, each with its own cuts, add up
        // to 1 within the quadrature's error (measured below 3.3e-10).
        EXPECT_NEAR(a.total[0], 1.0, 1e-9) << ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu;
        EXPECT_EQ(a.row(0, 0), 0.0);
        const Lobe3d lobe = vgroove_lobe_3d(ndf, alpha, std::acos(mu), 1, 2, max_k);
        for (int k = 1; k <= max_k + 1; ++k)
          EXPECT_NEAR(a.row(k, 0), lobe.by_k[k], 2e-7)
              << ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu << " k=" << k;
      }
}

TEST(AlbedoVgroove, FirstRowIsCookTorrancesAlbedoWithTheVcavityG) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann, NdfKind::phong})
    for (double alpha : {0.05, 1.2})
      for (double mu : {1.0, 0.3, 0.05}) {
        const MicrofacetModel ct{ndf, MaskingKind::vcavity};
        const BoundedValue E = albedo_single(ct, alpha, mu);
        const double F0 = 0.2;
        const VgrooveAlbedo a = vgroove_albedo(
            ndf, alpha, mu, 2,
            [&](double c, double* out) {
              out[0] = 1.0;
              out[1] = optics::fresnel_schlick(c, F0);
            },
            4);
        EXPECT_NEAR(a.row(1, 0), E.value, 2e-7 + E.error) << ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu;
        const SplitSum s = dfg_split_sum(ct, alpha, mu);
        EXPECT_NEAR(a.row(1, 1), F0 * s.scale.value + s.bias.value, 2e-7 + s.scale.error + s.bias.error)
            << ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu;
      }
}

// The same with a conductor's F: the first row against albedo_single_fresnel of the V-cavity
// model (the one-bounce integral over h, written independently of the grooves).
TEST(AlbedoVgroove, FirstRowWithAConductorIsAlbedoSingleFresnel) {
  auto F = [](double c) { return optics::fresnel_conductor(c, 0.43, 2.455); };  // gold near 550 nm
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.05, 1.2})
      for (double mu : {1.0, 0.3, 0.05}) {
        const BoundedValue e = albedo_single_fresnel({ndf, MaskingKind::vcavity}, alpha, mu, F);
        const VgrooveAlbedo a = vgroove_albedo(
            ndf, alpha, mu, 1, [&](double c, double* out) { out[0] = F(c); }, 2);
        EXPECT_NEAR(a.row(1, 0), e.value, 2e-7 + e.error) << ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu;
      }
}

TEST(AlbedoVgroove, ConstantReflectanceWeighsOrderKByItsPower) {
  const int max_k = 400;
  for (double alpha : {0.3, 1.5})
    for (double mu : {1.0, 0.4}) {
      const VgrooveAlbedo one = vgroove_albedo(NdfKind::ggx, alpha, mu, 1, {}, max_k);
      const double f = 0.7;
      const VgrooveAlbedo a = vgroove_albedo(
          NdfKind::ggx, alpha, mu, 1, [&](double, double* out) { out[0] = f; }, max_k);
      double want = 0.0;
      for (int k = 1; k <= max_k; ++k) want += one.row(k, 0) * std::pow(f, k);
      // The adaptive phi_a quadrature refines the two runs apart: within its tolerance (1e-8).
      EXPECT_NEAR(a.total[0], want, 1e-8) << "alpha=" << alpha << " mu=" << mu;
      for (int k = 1; k <= 6; ++k)
        EXPECT_NEAR(a.row(k, 0), one.row(k, 0) * std::pow(f, k), 1e-8)
            << "alpha=" << alpha << " mu=" << mu << " k=" << k;
    }
}

// The full grid behind the header's figure is AlbedoVgrooveLong (ctest -L long); here two cells.
void check_doubled_resolution(const std::vector<NdfKind>& ndfs, const std::vector<double>& alphas,
                              const std::vector<double>& mus) {
  auto F = [](double c, double* out) {
    out[0] = 1.0;
    out[1] = optics::fresnel_conductor(c, 0.2, 3.0);
    out[2] = optics::fresnel_schlick(c, 0.04);
  };
  VgrooveAlbedoOptions fine;
  fine.phi_tol /= 100, fine.phi_max_pieces *= 4, fine.band_order *= 2, fine.k_bands *= 2, fine.tail_strata *= 4;
  double worst = 0.0;
  for (NdfKind ndf : ndfs)
    for (double alpha : alphas)
      for (double mu : mus) {
        const VgrooveAlbedo a = vgroove_albedo(ndf, alpha, mu, 3, F, 8);
        const VgrooveAlbedo b = vgroove_albedo(ndf, alpha, mu, 3, F, 8, fine);
        for (std::size_t j = 0; j < a.by_k.size(); ++j) {
          EXPECT_NEAR(a.by_k[j], b.by_k[j], 1e-7) << ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu << " j=" << j;
          worst = std::max(worst, std::abs(a.by_k[j] - b.by_k[j]));
        }
      }
  std::printf("V-groove albedo: largest change at doubled resolution %.2e\n", worst);
}

TEST(AlbedoVgroove, DoubledResolutionMovesNoValueBeyondTheStatedAccuracy) {
  check_doubled_resolution({NdfKind::ggx}, {2.0}, {1.0});
}

TEST(AlbedoVgrooveLong, DoubledResolutionMovesNoValueBeyondTheStatedAccuracy) {
  check_doubled_resolution({NdfKind::ggx, NdfKind::beckmann}, {0.05, 0.5, 2.0}, {1.0, 0.3, 0.05});
}

// Extremes: finite and within [0, 1]; a white channel (Schlick F0 = 1) beside a conductor and a
// dielectric keeps the white furnace. (Phong at alpha 2 with a conductor, whose grooves narrower than 1e-4 rad
// hold 10 % of the light, costs 13 s of one core: left to the long run.)
void check_extremes(const std::vector<NdfKind>& ndfs) {
  for (NdfKind ndf : ndfs)
    for (double alpha : {0.01, 2.0})
      for (double mu : {1.0, 1e-3}) {
        // A dielectric's Schlick F0 = 0.04 ends most long paths (its product falls below the
        // cutoff after ~11 bounces): the white channel beside it must not end with them.
        const VgrooveAlbedo a = vgroove_albedo(
            ndf, alpha, mu, 3,
            [](double c, double* out) {
              out[0] = optics::fresnel_conductor(c, 1.5, 2.0);
              out[1] = optics::fresnel_schlick(c, 1.0);
              out[2] = optics::fresnel_schlick(c, 0.04);
            },
            16);
        for (double v : a.by_k) EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << ndf_name(ndf) << " alpha=" << alpha;
        EXPECT_LE(a.total[0], 1.0);
        EXPECT_GT(a.total[0], 0.0);
        EXPECT_NEAR(a.total[1], 1.0, 1e-9) << ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu;
      }
}

TEST(AlbedoVgroove, ExtremesStayFinite) { check_extremes({NdfKind::ggx, NdfKind::beckmann}); }
TEST(AlbedoVgrooveLong, ExtremesStayFiniteWithPhong) { check_extremes({NdfKind::phong}); }

}  // namespace
}  // namespace vgroove::analytic
