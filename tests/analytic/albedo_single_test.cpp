// Tests of analytic/albedo_single.h: the single-scattering albedos against closed forms derived by
// hand and independent integrals (over the exit hemisphere with ndf.h's D and Lambda; Cook-Torrance
// as validation/energy_table computes it, the k = 1 lobe of analytic/lobe_3d.h), their physics
// (E_ss -> 1 as alpha -> 0, height-correlated >= separable, E <= 1, split sum = E_ss, Schlick's
// F_avg = F0 + (1 - F0) / 21) and the stated error bounds (halving the step and a tighter
// tolerance move each value by less than its bound).
#include "vgroove/analytic/albedo_single.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/analytic/ndf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace va = vgroove::analytic;
using vgroove::NdfKind;

namespace {

constexpr double kPi = std::numbers::pi;

const va::MicrofacetModel kModels[] = {
    {NdfKind::ggx, va::MaskingKind::smith_height_correlated},
    {NdfKind::ggx, va::MaskingKind::smith_separable},
    {NdfKind::ggx, va::MaskingKind::vcavity},
    {NdfKind::beckmann, va::MaskingKind::smith_height_correlated},
    {NdfKind::beckmann, va::MaskingKind::smith_separable},
    {NdfKind::beckmann, va::MaskingKind::vcavity},
};

std::string name(const va::MicrofacetModel& m) {
  return std::string(vgroove::ndf_name(m.ndf)) + "/" + va::masking_name(m.masking);
}

// Smith's G2 from ndf.h (Heitz 2014, Eq. 20-21), at exit angle theta_o, incidence theta_i.
double smith_G2(const va::MicrofacetModel& m, double theta_i, double theta_o, double alpha) {
  const double li = va::Lambda(m.ndf, theta_i, alpha), lo = va::Lambda(m.ndf, theta_o, alpha);
  return m.masking == va::MaskingKind::smith_height_correlated ? 1.0 / (1.0 + li + lo)
                                                               : 1.0 / ((1.0 + li) * (1.0 + lo));
}

}  // namespace

// GGX at alpha = 1 is D = 1/pi; at normal incidence Lambda(i) = 0 and G2 = G1(o) = 2 cos(theta_o) /
// (1 + cos(theta_o)) (Lambda = (1/cos - 1)/2), theta_o = 2 theta_h, so
//   E = 2 int_0^{pi/4} G1(2 t) cos t sin t dt = 2 int_0^{pi/4} (sin 2t - tan t) dt = 1 - ln 2.
TEST(Albedo, GgxAlphaOneAtNormalIncidenceIsOneMinusLn2) {
  for (auto masking : {va::MaskingKind::smith_height_correlated, va::MaskingKind::smith_separable}) {
    const va::BoundedValue e = va::albedo_single({NdfKind::ggx, masking}, 1.0, 1.0);
    EXPECT_NEAR(e.value, 1.0 - std::log(2.0), e.error + 1e-15) << va::masking_name(masking);
    EXPECT_LT(e.error, 1e-9);
  }
}

// At normal incidence (Lambda(i) = 0, both Smith forms G1(o)) against the 1D integral in theta_h
// written from ndf.h's D and G1: 2 pi int_0^{pi/4} D(t) G1(2 t) cos t sin t dt.
TEST(Albedo, NormalIncidenceIsTheOneDimensionalIntegral) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.02, 0.1, 0.35, 0.8, 1.6}) {
      std::vector<double> cuts{0.0, 0.25 * kPi};
      for (double s : {0.25, 0.5, 1.0, 2.0, 4.0})
        if (std::atan(s * alpha) < 0.25 * kPi) cuts.push_back(std::atan(s * alpha));
      std::sort(cuts.begin(), cuts.end());
      va::AdaptiveOptions o;
      o.abs_tol = 1e-13;
      const va::AdaptiveResult ref = va::integrate_adaptive(
          [&](double t) {
            const double G1 =
                ndf == NdfKind::ggx ? va::G1_smith_ggx(2.0 * t, alpha) : va::G1_smith_beckmann(2.0 * t, alpha);
            return 2.0 * kPi * va::D(ndf, t, alpha) * G1 * std::cos(t) * std::sin(t);
          },
          cuts, o);
      for (auto masking : {va::MaskingKind::smith_height_correlated, va::MaskingKind::smith_separable}) {
        const va::BoundedValue e = va::albedo_single({ndf, masking}, alpha, 1.0);
        EXPECT_NEAR(e.value, ref.value, e.error + ref.error + 1e-14)
            << vgroove::ndf_name(ndf) << " " << va::masking_name(masking) << " alpha=" << alpha;
      }
    }
}

// At oblique incidence against the integral over the exit hemisphere (hemisphere_quadrature.h,
// polar about the mirror direction) of D G2 / (4 mu_i) with ndf.h's D and Lambda: other
// coordinates, other code.
TEST(Albedo, ObliqueIncidenceIsTheHemisphereIntegral) {
  for (const va::MicrofacetModel& m : kModels) {
    if (m.masking == va::MaskingKind::vcavity) continue;  // against Cook-Torrance below
    for (auto [alpha, theta_i] : {std::pair{0.2, 0.6}, {0.6, 1.2}, {1.0, 0.3}}) {
      const va::Dir3 i = va::dir3(theta_i, kPi), pole = va::dir3(theta_i, 0.0);
      va::HemisphereOptions ho;
      ho.tol = 1e-9;
      ho.scale = alpha;
      const va::AdaptiveResult ref = va::integrate_hemisphere(
          pole,
          [&](const va::Dir3& o) {
            if (!(o.z > 0.0)) return 0.0;
            va::Dir3 h{i.x + o.x, i.y + o.y, i.z + o.z};
            const double len = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
            const double theta_h = std::acos(std::min(1.0, h.z / len));
            return va::D(m.ndf, theta_h, alpha) * smith_G2(m, theta_i, std::acos(o.z), alpha) / (4.0 * i.z);
          },
          ho);
      const va::BoundedValue e = va::albedo_single(m, alpha, std::cos(theta_i));
      EXPECT_NEAR(e.value, ref.value, e.error + ref.error + 1e-12)
          << name(m) << " alpha=" << alpha << " theta_i=" << theta_i;
    }
  }
}

// Cook-Torrance with the V-cavity G as validation/energy_table computes its albedo: the k = 1 lobe
// of analytic/lobe_3d.h (a push-forward of the grooves, not a quadrature over h).
TEST(Albedo, VcavityIsTheCookTorranceLobesAlbedo) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann, NdfKind::phong})
    for (auto [alpha, theta_i] : {std::pair{0.3, 0.5}, {0.7, 1.1}, {1.0, 0.0}}) {
      const double lobe = va::cook_torrance_lobe_3d(ndf, alpha, theta_i, 1, 2).albedo;
      const va::BoundedValue e = va::albedo_single({ndf, va::MaskingKind::vcavity}, alpha, std::cos(theta_i));
      // The lobe's own accuracy: its phi_a rule (384 panels of 2 nodes, lobe_3d.h).
      EXPECT_NEAR(e.value, lobe, e.error + 1e-7)
          << vgroove::ndf_name(ndf) << " alpha=" << alpha << " theta_i=" << theta_i;
    }
}

// alpha -> 0: a mirror, E_ss -> 1 away from grazing (the loss is the masking, O(alpha^2 tan^2)).
TEST(Albedo, SmoothLimitIsOne) {
  for (const va::MicrofacetModel& m : kModels)
    for (double mu : {0.3, 0.6, 1.0}) {
      double previous = 1.0;
      for (double alpha : {1e-2, 1e-3, 1e-4}) {
        const va::BoundedValue e = va::albedo_single(m, alpha, mu);
        const double loss = 1.0 - e.value;
        EXPECT_LE(std::abs(loss), 20.0 * alpha * alpha / (mu * mu) + e.error)
            << name(m) << " mu=" << mu << " alpha=" << alpha;
        EXPECT_LE(loss, previous + e.error) << name(m) << " mu=" << mu << " alpha=" << alpha;
        previous = loss;
      }
    }
}

// Heitz 2014, Sec. 6: the separable form multiplies what the height-correlated one adds, so
// G1 G1 <= 1 / (1 + Lambda_i + Lambda_o) pointwise and the albedos are ordered.
TEST(Albedo, HeightCorrelatedAtLeastSeparable) {
  for (NdfKind ndf : {NdfKind::ggx, NdfKind::beckmann})
    for (double alpha : {0.05, 0.3, 1.0, 2.0})
      for (double mu : {0.01, 0.3, 0.8, 1.0}) {
        const va::BoundedValue hc = va::albedo_single({ndf, va::MaskingKind::smith_height_correlated}, alpha, mu);
        const va::BoundedValue sep = va::albedo_single({ndf, va::MaskingKind::smith_separable}, alpha, mu);
        EXPECT_GE(hc.value, sep.value - hc.error - sep.error)
            << vgroove::ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu;
        // Strictly where masking matters (Beckmann's Lambda is ~exp(-1 / (alpha tan)^2)).
        if (alpha >= 1.0 && mu < 1.0) {
          EXPECT_GT(hc.value - sep.value, 1e-6) << vgroove::ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu;
        }
      }
}

// Scale + bias = E_ss (1 - Fc + Fc = 1), each within its bound; both in [0, E_ss].
TEST(Albedo, SplitSumAddsToTheAlbedo) {
  for (const va::MicrofacetModel& m : kModels)
    for (auto [alpha, mu] : {std::pair{0.05, 0.9}, {0.4, 0.5}, {1.0, 0.1}, {2.0, 1.0}}) {
      const va::SplitSum s = va::dfg_split_sum(m, alpha, mu);
      const va::BoundedValue e = va::albedo_single(m, alpha, mu);
      EXPECT_NEAR(s.scale.value + s.bias.value, e.value, s.scale.error + s.bias.error + e.error)
          << name(m) << " alpha=" << alpha << " mu=" << mu;
      EXPECT_GT(s.bias.value, 0.0);
      EXPECT_LT(s.bias.value, e.value);
    }
}

// Kulla and Conty 2017: F_avg = 2 int F mu dmu; for Schlick, 2 int mu (1 - mu)^5 dmu = 2 B(2, 6) =
// 1/21, so F_avg = F0 + (1 - F0) / 21.
TEST(Albedo, SchlickFresnelAverageIsF0PlusOneMinusF0Over21) {
  for (double F0 : {0.0, 0.04, 0.5, 0.95, 1.0}) {
    const va::BoundedValue f = va::cosine_weighted_average([&](double mu) {
      const double c = 1.0 - mu;
      return F0 + (1.0 - F0) * c * c * c * c * c;
    });
    EXPECT_NEAR(f.value, F0 + (1.0 - F0) / 21.0, f.error + 1e-15) << "F0=" << F0;
    EXPECT_LT(f.error, 1e-9);
  }
}

// Every value within [0, 1] to its bound; E_avg too.
TEST(Albedo, AlbedosAtMostOne) {
  for (const va::MicrofacetModel& m : kModels)
    for (double alpha : {0.01, 0.2, 0.7, 2.0}) {
      for (double mu : {1e-3, 0.2, 0.6, 1.0}) {
        const va::BoundedValue e = va::albedo_single(m, alpha, mu);
        EXPECT_LE(e.value, 1.0 + e.error) << name(m) << " alpha=" << alpha << " mu=" << mu;
        EXPECT_GT(e.value, 0.0) << name(m) << " alpha=" << alpha << " mu=" << mu;
      }
    }
  va::AlbedoOptions coarse;
  coarse.tol = 1e-5;
  for (const va::MicrofacetModel& m : {kModels[0], kModels[2], kModels[4]})
    for (double alpha : {0.05, 1.0}) {
      const va::BoundedValue a = va::albedo_average(m, alpha, coarse);
      EXPECT_LE(a.value, 1.0 + a.error) << name(m) << " alpha=" << alpha;
      EXPECT_GT(a.value, 0.0);
    }
}

// The bound: halving every initial piece (refine = 2) and a 10^4 times tighter tolerance each
// move the value by less than the bound it was given; the bound meets the tolerance asked for.
TEST(Albedo, HalvingTheStepMovesEachValueLessThanItsBound) {
  va::AlbedoOptions opt, halved, tight;
  opt.tol = 1e-7;
  halved = opt;
  halved.refine = 2;
  tight.tol = 1e-11;
  for (const va::MicrofacetModel& m : kModels)
    for (double alpha : {0.01, 0.15, 0.6, 2.0})
      for (double mu : {2e-3, 0.25, 0.75, 1.0}) {
        const va::BoundedValue e = va::albedo_single(m, alpha, mu, opt);
        EXPECT_TRUE(e.converged) << name(m) << " alpha=" << alpha << " mu=" << mu;
        EXPECT_LE(e.error, opt.tol) << name(m) << " alpha=" << alpha << " mu=" << mu;
        const double d_half = va::albedo_single(m, alpha, mu, halved).value - e.value;
        const double d_tight = va::albedo_single(m, alpha, mu, tight).value - e.value;
        EXPECT_LT(std::abs(d_half), e.error) << name(m) << " alpha=" << alpha << " mu=" << mu;
        EXPECT_LT(std::abs(d_tight), e.error) << name(m) << " alpha=" << alpha << " mu=" << mu;
      }
  // E_avg's bound the same way (one model per masking; a coarse tolerance keeps it quick).
  va::AlbedoOptions a_opt, a_half, a_tight;
  a_opt.tol = 1e-5;
  a_half = a_opt;
  a_half.refine = 2;
  a_tight.tol = 1e-7;
  for (const va::MicrofacetModel& m : {kModels[0], kModels[4], kModels[2]}) {
    const va::BoundedValue e = va::albedo_average(m, 0.5, a_opt);
    EXPECT_LE(e.error, a_opt.tol) << name(m);
    EXPECT_LT(std::abs(va::albedo_average(m, 0.5, a_half).value - e.value), e.error) << name(m);
    EXPECT_LT(std::abs(va::albedo_average(m, 0.5, a_tight).value - e.value), e.error) << name(m);
  }
}

// The corners of the domain: alpha 0.01 and 2, mu from 1e-6 to 1, every NDF the model takes:
// finite, converged, in [0, 1].
TEST(Albedo, ExtremesAreFinite) {
  std::vector<va::MicrofacetModel> models(std::begin(kModels), std::end(kModels));
  models.push_back({NdfKind::phong, va::MaskingKind::vcavity});
  EXPECT_FALSE(va::model_supported({NdfKind::phong, va::MaskingKind::smith_separable}));
  for (const va::MicrofacetModel& m : models)
    for (double alpha : {0.01, 2.0})
      for (double mu : {1e-6, 1e-3, 1.0 - 1e-12, 1.0}) {
        const va::BoundedValue e = va::albedo_single(m, alpha, mu);
        const va::SplitSum s = va::dfg_split_sum(m, alpha, mu);
        for (double v : {e.value, e.error, s.scale.value, s.bias.value}) EXPECT_TRUE(std::isfinite(v)) << name(m);
        EXPECT_TRUE(e.converged) << name(m) << " alpha=" << alpha << " mu=" << mu;
        EXPECT_GE(e.value, 0.0) << name(m) << " alpha=" << alpha << " mu=" << mu;
        EXPECT_LE(e.value, 1.0 + e.error) << name(m) << " alpha=" << alpha << " mu=" << mu;
      }
}

// The albedo with a reflectance: F = 1 is E_ss, Schlick's F is F0 scale + bias (the split sum,
// integrated with its own weights), each within the bounds; a reflectance below 1 lowers it.
TEST(Albedo, WithAReflectanceIsTheSplitSumForSchlicksF) {
  for (const va::MicrofacetModel& m : kModels)
    for (double alpha : {0.05, 0.5, 1.5})
      for (double mu : {0.02, 0.4, 1.0}) {
        const va::BoundedValue e = va::albedo_single(m, alpha, mu);
        const va::BoundedValue one = va::albedo_single_fresnel(m, alpha, mu, [](double) { return 1.0; });
        EXPECT_EQ(one.value, e.value) << name(m);
        const double F0 = 0.3;
        const va::SplitSum s = va::dfg_split_sum(m, alpha, mu);
        const va::BoundedValue f = va::albedo_single_fresnel(m, alpha, mu, [&](double c) {
          const double x = 1.0 - c;
          return F0 + (1.0 - F0) * x * x * x * x * x;
        });
        EXPECT_NEAR(f.value, F0 * s.scale.value + s.bias.value, f.error + s.scale.error + s.bias.error)
            << name(m) << " alpha=" << alpha << " mu=" << mu;
        EXPECT_LT(f.value, e.value) << name(m);
      }
}
