// vgroove analytic: the single-scattering albedos of Walter et al. 2007's rough dielectric BSDF
// (analytic/walter.h), reflected E_R(mu) = int f_r |o.n| d omega_o and transmitted E_T(mu) =
// int f_t |o.n| d omega_o, and their cosine-weighted averages, by nested adaptive Gauss-Kronrod over
// the microfacet normal h with the measure dP(h) = D(h) (h.n) d omega_h (both Jacobians cancel):
//   E_R = int F(i.h) G2(i, o_r, h) (i.h) / (mu h.n) dP,  E_T = int (1 - F) G2(i, o_t, h) (i.h) / (mu h.n) dP,
// o_r the mirror and o_t the refraction of i at h, each counted where it leaves on its own side.
// Cut at every kink (o.n = 0, i.h = 0, the facet's critical angle when eta < 1); the bound is that
// of analytic/albedo_single.h. T_avg(eta) = eta^2 T_avg(1 / eta) for every G2 symmetric in (i, o).
// Tests: tests/analytic/albedo_glass_test.cpp (AlbedoGlass.SmallRoughnessIsFlatFresnel,
// AlbedoGlass.HalvingTheStepMovesEachValueLessThanItsBound, AlbedoGlass.CriticalAngleIsCut,
// AlbedoGlass.ReflectionIsTheConductorFormWithF, AlbedoGlass.AgreesWithTheBsdfIntegratedOverO,
// AlbedoGlass.TransmittedAveragesObeyReciprocity, AlbedoGlass.SmithLosesEnergy,
// AlbedoGlass.IndexOneIsTheMaskingOfTheStraightPath, AlbedoGlass.ExtremesAreFinite).
// Derivation: the opening comment of albedo_glass.cpp.
#pragma once

#include "vgroove/analytic/albedo_single.h"

namespace vgroove::analytic {

// Light from the near medium, eta = n_far / n_near (> 0; 1 / eta is the same interface lit from
// the other side). The transmitted lobe's Smith height-correlated G2 is B(1 + L(i), 1 + L(o))
// (walter.h). E_R + E_T = 1 - what the masking drops.
struct GlassAlbedo {
  BoundedValue R, T;
};

// E_R(mu) and E_T(mu), mu in (0, 1], alpha > 0, NDF GGX or Beckmann (any MaskingKind); each to
// opt.tol with its own bound.
GlassAlbedo albedo_glass(const MicrofacetModel& m, double alpha, double mu, double eta, const AlbedoOptions& opt = {});

// R_avg = 2 int_0^1 E_R(mu) mu dmu and T_avg likewise (Kulla and Conty 2017's E_avg per lobe).
GlassAlbedo albedo_glass_average(const MicrofacetModel& m, double alpha, double eta, const AlbedoOptions& opt = {});

}  // namespace vgroove::analytic
