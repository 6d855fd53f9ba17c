// vgroove validation: the energy compensation formulas of analytic/compensation.h as directional
// albedos, each fed from the exact single-scattering values or from its engine's own table as the
// engine reads it: the quantity the energy audit (validation/energy_audit.h) holds against the
// exact multiple-scattering albedo.
//
// A formula's albedo at (mu, alpha) for a reflectance channel (its curve F, F0 = F(1), F_avg = 2
// int F mu dmu) is the integral over the hemisphere of the compensated lobe times the cosine:
//   single         E_F                                 (no compensation; E_F = int F f_ss cos)
//   kulla_conty    E_F + F_ms (1 - E),  F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg))
//                  (Kulla and Conty 2017: int f_ms cos = 1 - E(mu); their conductor Fresnel term)
//   turquin        E_F (1 + F0 (1 - E) / E)           (Turquin 2019; E at the view)
//   filament       E_F (1 + F0 (1 / dfg.y - 1))        (Filament's energyCompensation)
//   bevy_direct    E_F (1 + F0 (1 / (F_ab.x + F_ab.y) - 1))  (Bevy specular_multiscatter)
//   cycles         E_F (1 + Fms (1 - E) / E),  Fms = Fss E_avg / (1 - Fss (1 - E_avg)),
//                  Fss = F0 + (1 - F0) / 21            (Cycles microfacet_ggx_preserve_energy with
//                  its generalized-Schlick Fss; the same factor whatever the channel's curve)
//   fdez_aguera    F0 scale + bias + F_ms (1 - scale - bias), three.js computeMultiscattering (F90 = 1)
//   fdez_aguera_roughness  the same with Bevy's roughness-dependent Schlick kS (environment_map.wgsl)
// E, E_avg, scale and bias are the single-scattering albedo, its average and the split sum with
// F = 1 (analytic/albedo_single.h) of the reference's own microsurface; E_F is exact for every
// formula that evaluates f_ss with the channel's F pointwise (the lobe formulas); the split-sum
// formulas use Schlick's F0 scale + bias, as the engines do, whatever the channel's curve.
//
// Feeds. "exact": every value by quadrature. "cycles_table": E and E_avg read from Blender Cycles'
// published table_ggx_E and table_ggx_Eavg (data/reference/cycles_ggx_albedo.json) as Cycles
// reads them: lookup_table_read_2D, linear in r = sqrt(alpha) and in mu on the 32 x 32 grid of
// texel ends. "filament_lut": dfg.y from Filament's DFG LUT as cmgen --ibl-dfg writes it
// (libs/ibl/src/CubemapIBL.cpp DFG and tools/cmgen iblLutDfg): 128 x 128 RG16F, NoV at the texel
// centres (x + 1/2) / 128, the roughness coordinate of GL row j at min(1, (j + 3/2) / 128) (the
// generator's saturate((h - y + 1/2) / h) with rows written in reverse), alpha = coord^2, each
// value rounded to half precision; the shader samples it bilinearly at (NoV, perceptual
// roughness), clamped to the edge texels. Here its texels hold the exact E_ss where Filament's
// hold a 1024-sample Hammersley estimate. "karis_fit": the split sum from Karis 2014's
// EnvBRDFApprox at r = sqrt(alpha) (three.js DFGApprox, Bevy F_AB without its DFG LUT). The
// engine feeds exist for GGX with Smith's height-correlated G2 only (the engines' model).
#pragma once

#include "vgroove/analytic/compensation.h"

#include <string>
#include <vector>

namespace vgroove::validation {

enum class Feed : unsigned char { exact, cycles_table, filament_lut, karis_fit };
const char* feed_name(Feed f);

struct FormulaVariant {
  std::string id;       // "<formula>" for the exact feed, "<formula>@<feed>" otherwise
  std::string formula;  // single, kulla_conty, turquin, filament, bevy_direct, cycles, fdez_aguera, ...
  Feed feed = Feed::exact;
  std::string source;  // where the formula is published (compensation.h has the details)
};
// Every variant the audit evaluates, in report order.
const std::vector<FormulaVariant>& formula_variants();

// One microfacet model's single-scattering values at a cell (F = 1 but E_F).
struct SingleScattering {
  double E = 0.0, scale = 0.0, bias = 0.0, E_avg = 0.0;
};
// The engine tables' values at a cell (NaN where a feed is absent).
struct EngineValues {
  double cycles_E, cycles_E_avg, filament_dfg_y;
  analytic::ScaleBias karis;
};
// One channel's Fresnel values at a cell.
struct ChannelValues {
  double F0 = 0.0, F_avg = 0.0, E_F = 0.0;
};

// The variant's albedo; NaN when its feed is absent. alpha and mu are the cell's.
double compensated_albedo(const FormulaVariant& v, const SingleScattering& s, const EngineValues& e,
                          const ChannelValues& c, double alpha, double mu);

// Blender Cycles' published tables.
struct CyclesTables {
  std::vector<double> E;      // [mu index][r index], 32 x 32
  std::vector<double> E_avg;  // [r index]
};
// data/reference/cycles_ggx_albedo.json's arrays; a UserError naming the file when they are not there.
CyclesTables read_cycles_tables(const std::string& file);
// The same tables as compiled into vgroove (validation/CMakeLists.txt embeds the file's text).
const CyclesTables& published_cycles_tables();
// lookup_table_read_2D(rough = sqrt(alpha), mu) and lookup_table_read(rough).
double cycles_E(const CyclesTables& t, double alpha, double mu);
double cycles_E_avg(const CyclesTables& t, double alpha);

// Filament's dfg.y at (mu, alpha) as the shader reads the LUT (the header), its texels computed on
// demand from the exact E_ss (tolerance 1e-10) and rounded to half precision.
inline constexpr int kFilamentLutSize = 128;
double filament_dfg_y(double alpha, double mu, int n = kFilamentLutSize);
// The nearest binary16 value (round half to even), as a GPU stores an RG16F texel.
double round_to_half(double v);

}  // namespace vgroove::validation
