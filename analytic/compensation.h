// vgroove analytic: the multiple-scattering energy compensation formulas of the literature and the
// engines (Kulla-Conty 2017, Turquin 2019, Fdez-Aguera 2019, Karis' EnvBRDFApprox, Filament,
// Cycles, three.js, Bevy), as pure functions of the single-scattering values they read (E_ss at
// the directions they use, E_avg, the split-sum scale and bias, F0 or F_avg), so each can be fed
// from its engine's table (analytic/albedo_table.h) or the exact E_ss (analytic/albedo_single.h).
// The sources number no equations; each function names its source's section or listing.
// mu = cos theta in (0, 1]; every factor multiplies a non-negative lobe; E_avg = 1 gives f_ms = 0
// without 0/0. Holds: published constants (three.js 1/21, Karis's fit), Cycles' table, the white
// furnace of Kulla-Conty and Fdez-Aguera, hand-derived points elsewhere.
// Tests: tests/analytic/compensation_test.cpp (KullaConty.WhiteFurnaceByIntegratingTheLobe,
// Turquin.CompensatedAlbedoFromTheViewIsOneAndFromTheLightIsNot,
// EngineForms.FilamentBevyAndCyclesRestateTheirSources, KarisEnvBrdfApprox.*,
// tests/analytic/albedo_glass_test.cpp (CyclesGlass.*),
// Compensation.FiniteAtTheExtremes), tests/analytic/albedo_table_test.cpp.
// Derivation and sources: docs/derivations/energy_compensation.md; tables: docs/albedo_tables.md.
#pragma once

namespace vgroove::analytic {

// ---- Kulla and Conty 2017 ----------------------------------------------------------------------
// The compensation lobe with F = 1: f_ms(mu_o, mu_i) = (1 - E(mu_o)) (1 - E(mu_i)) / (pi (1 -
// E_avg)). Its directional albedo is int f_ms mu_i d omega_i = (1 - E(mu_o)) exactly when E_avg
// = 2 int E mu dmu (so E_ss + E_ms = 1: the white furnace).
double kulla_conty_f_ms(double E_o, double E_i, double E_avg);
// The Fresnel factor of the multiply scattered energy (the "conductor" form of the slides):
// F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)), the lobe being f_ms * F_ms. F_avg = 1 gives 1.
double kulla_conty_fresnel_factor(double F_avg, double E_avg);
// The variant with one F_avg cancelled (Cycles' comment: the lobe it multiplies already carries a
// bounce of Fresnel): F_avg E_avg / (1 - F_avg (1 - E_avg)).
double kulla_conty_fresnel_factor_one_bounce_removed(double F_avg, double E_avg);
// F_avg = 2 int_0^1 F(mu) mu dmu for Schlick's F = F0 + (1 - F0)(1 - mu)^5: F0 + (1 - F0)/21
// (2 int (1 - mu)^5 mu dmu = 2 B(2, 6) = 2/42). For any F curve (an exact conductor):
// albedo_single.h's cosine_weighted_average.
double fresnel_average_schlick(double F0);

// ---- Turquin 2019 ------------------------------------------------------------------------------
// The multiplicative factor 1 + F0 (1 - E_o) / E_o on f_ss (which carries its own Fresnel), E_o =
// E_ss at the view direction mu_o only: with F = F0 = 1 the albedo seen from mu_o is
// E_ss(mu_o) / E_ss(mu_o) = 1 by construction; seen from the light it is not (the factor is not
// reciprocal). F0 is the normal-incidence reflectance (Turquin's approximation of F_avg there).
double turquin_factor(double F0, double E_o);
// Filament's energyCompensation = 1 + f0 (1/dfg.y - 1): the same factor with E_o = dfg.y (its
// DFG LUT's second channel, E_ss with F = 1 at NoV). Bevy's specular_multiscatter is the same with
// dfg.y = F_ab.x + F_ab.y (scale + bias).
double filament_energy_compensation(double F0, double dfg_y);

// ---- Cycles (microfacet_ggx_preserve_energy) --------------------------------------------------
// The net factor on the single-scattering lobe: 1 + Fms (1 - E) / E, Fms the one-bounce-removed
// Kulla-Conty factor of Fss (the Fresnel average; Fss = 1 gives 1/E, the energy_scale alone).
double cycles_energy_factor(double E, double E_avg, double Fss);

// ---- Cycles glass (microfacet_ggx_glass_albedo_scaling, Blender 3.x multi-GGX glass) ----------
// The factor on both lobes of the rough glass, reflected and transmitted: 1 + Fms (1 - E) / E, E =
// E_R + E_T the single-scattering albedo of the glass at the view direction on its own side (light
// from inside reads the table of 1 / eta), Fms = Fss the tint (1 for clear glass: 1 / E). Every
// side's albedo becomes 1, but E differs between the sides, so the transmitted averages lose the
// reciprocity T_avg(eta) = eta^2 T_avg(1 / eta) the exact BSDF keeps
// (CyclesGlass.ScalingBothLobesBreaksTheTransmittedReciprocity).
double cycles_glass_albedo_scaling(double E, double Fss);

// ---- Fdez-Aguera 2019: the split sum with multiple scattering ---------------------------------
// Radiance weights of a prefiltered environment (single, for the specular radiance) and of the
// irradiance (multi), given the split-sum scale and bias at (mu, alpha) (Karis 2013: the albedo
// with Schlick's F is F0 scale + bias):
//   E_ss = scale + bias, E_ms = 1 - E_ss, F_avg = F0 + (1 - F0)/21,
//   single = FssEss = F0 scale + F90 bias, F_ms = FssEss F_avg / (1 - E_ms F_avg), multi = F_ms E_ms.
// F0 = F90 = 1 gives single + multi = 1 exactly.
struct SplitSumScattering {
  double single = 0.0;
  double multi = 0.0;
  double total() const { return single + multi; }
};
// three.js computeMultiscattering (F90 its specularF90; the paper's form has F90 = 1).
SplitSumScattering fdez_aguera(double F0, double scale, double bias, double F90 = 1.0);
// The paper's listing and Bevy's environment_map.wgsl: FssEss = kS scale + bias with the
// roughness-dependent Schlick kS = F0 + (max(1 - r, F0) - F0)(1 - mu)^5, r the perceptual
// roughness (F0 = 1: kS = 1 for every r in [0, 1], so the total is 1 there too).
SplitSumScattering fdez_aguera_roughness_fresnel(double F0, double scale, double bias, double r, double mu);

// three.js DFGApprox = Karis 2014's EnvBRDFApprox: the analytic (scale, bias) of the GGX split
// sum at perceptual roughness r (alpha = r^2) and mu = NoV, constants as published there.
struct ScaleBias {
  double scale = 0.0;
  double bias = 0.0;
};
ScaleBias karis_env_brdf_approx(double r, double mu);

}  // namespace vgroove::analytic
