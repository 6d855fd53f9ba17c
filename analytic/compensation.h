// vgroove analytic: multiple-scattering energy compensation formulas of the literature and of the
// engines, as pure functions of the single-scattering values they read (E_ss at the directions
// they use, E_avg, the split-sum scale and bias, F0 or F_avg), so each can be fed from its own
// table (analytic/albedo_table.h, in the engine's layout) or from the exact E_ss
// (analytic/albedo_single.h). docs/albedo_tables.md has the table of them and what is tested.
//
// Papers and sources (cited below by first author and year, or by engine):
//   Kulla, Conty. "Revisiting Physically Based Shading at Imageworks". SIGGRAPH 2017 course,
//     Physically Based Shading in Theory and Practice (slides "Energy compensation"): the lobe
//     f_ms, E_avg, and the Fresnel factor of the multiply scattered energy with F_avg. Not in
//     ../shared/papers; cited from the published slides (the slides number no equations).
//   Turquin. "Practical multiple scattering compensation for microfacet models". Industrial Light
//     & Magic technical report, 2019: f = f_ss (1 + F0 (1 - E_ss) / E_ss), E_ss at the view
//     direction (his Eq. (11)-(12) as numbered in the report; not in ../shared/papers).
//   Fdez-Aguera. "A Multiple-Scattering Microfacet Model for Real-Time Image-based Lighting".
//     JCGT 8(1), 2019: the split-sum form (Sec. 3-4, and the listing that closes the paper).
//     Not in ../shared/papers; restated from the paper and from the engines that port it.
//   Karis. "Real Shading in Unreal Engine 4" (SIGGRAPH 2013) for the split sum, and "Physically
//     Based Shading on Mobile" (Unreal Engine blog, 2014) for EnvBRDFApprox, the analytic fit
//     three.js reads as its DFG "table" (DFGApprox).
//   Filament: google/filament, docs "Physically Based Rendering in Filament", Sec. 4.7.2 "Energy
//     compensation" (listing "energyCompensationImpl": energyCompensation = 1 + f0 (1/dfg.y - 1),
//     dfg.y = int f_ss cos with F = 1, its DFG LUT indexed (NoV, perceptual roughness), alpha = r^2).
//   Cycles: blender/blender intern/cycles/kernel/closure/bsdf_microfacet.h,
//     microfacet_ggx_preserve_energy (read through the project's source index; the commit of the
//     stored copy was not recorded): energy_scale = 1 + (1 - E) / E, and with a Fresnel average
//     Fss, weight darkening (1 + Fms (1 - E) / E) / energy_scale, Fms = Fss E_avg / (1 - Fss
//     (1 - E_avg)); E = table_ggx_E at (r = alpha^(1/2), mu = dot(wi, N)), wi the direction toward
//     the viewer (Cycles' convention), E_avg = table_ggx_Eavg(r).
//   three.js: mrdoob/three.js src/renderers/shaders/ShaderChunk/lights_physical_pars_fragment
//     .glsl.js, computeMultiscattering (Fdez-Aguera with F90: FssEss = F0 fab.x + F90 fab.y, Ess =
//     fab.x + fab.y, Ems = 1 - Ess, Favg = F0 + (1 - F0) 0.047619, Fms = FssEss Favg / (1 - Ems
//     Favg); single FssEss, multi Fms Ems); fab from DFGApprox (older releases) or a DFG LUT at
//     (roughness, dotNV) (newer). Commit of the stored copies not recorded.
//   Bevy: bevyengine/bevy crates/bevy_pbr/src/render/pbr_lighting.wgsl, specular_multiscatter
//     (direct lights: Fr *= 1 + F0 (1 / (F_ab.x + F_ab.y) - 1), Filament's form; an older release
//     has 1 / F_ab.x, which its later comment "F_ab.x + F_ab.y is dfg.y in Filament" corrects), and
//     environment_map.wgsl (Fdez-Aguera with the paper's roughness-dependent Fresnel kS = F0 +
//     (max(1 - r, F0) - F0) (1 - NdotV)^5; FssEss = kS f_ab.x + f_ab.y in the releases read, kS Ess
//     in a later one). Commit of the stored copies not recorded.
//   Unreal Engine: not implemented. What is documented publicly is a project setting ("Enable
//     Energy Conservation on Material", r.Material.EnergyConservation) and the API stub
//     FViewUniformShaderParameters::bShadingEnergyConservation ("Energy conservation."); the
//     shaders that compute it (Engine/Shaders/Private/ShadingEnergyConservation.ush) are in Epic's
//     access-restricted repository, not in a published source this project can cite.
// Equation numbers: the slides, docs and engine sources above number none; Filament's is its
// documentation's section, Fdez-Aguera's the paper's sections; Turquin's as cited, not re-read.
// Published numbers to test against: three.js's 0.047619 (= 1/21) and Karis's constants
// (tests/analytic/compensation_test.cpp), Cycles' table (tests/analytic/albedo_table_test.cpp);
// the other sources print none, so their tests use values derived by hand from the printed forms.
//
// Conventions. mu = cos theta, in (0, 1]. E_o = E_ss(mu_o) is the albedo at the direction the
// formula names (for the split-sum forms, the view direction, mu = NoV). alpha is the GGX/Beckmann
// width (alpha = r^2 in Filament, three.js, Bevy and Cycles, r their "roughness"); the functions
// here take table values, not alpha, except the three.js fit, which takes r. Signs: every factor
// here multiplies (or adds to) a non-negative lobe; 1 - E >= 0 for a tabulated E <= 1.
// Guards: 1/E is finite for E > 0 (every microfacet E_ss is > 0 for mu > 0); E_avg = 1 (alpha -> 0)
// gives f_ms = 0 by the numerator's (1 - E) factors, computed as 0 without dividing 0 by 0.
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
