// vgroove validation: the energy compensation formulas of analytic/compensation.h as directional
// albedos (the compensated lobe times the cosine over the hemisphere) for a reflectance channel
// (its curve F, F0 = F(1), F_avg = 2 int F mu dmu): single, kulla_conty, turquin, filament,
// bevy_direct, cycles, fdez_aguera, fdez_aguera_roughness; the quantity the energy audit
// (validation/energy_audit.h) holds against the exact multiple-scattering albedo. Feeds: "exact"
// (analytic/albedo_single.h quadrature); as each engine reads its table: "cycles_table" (Cycles'
// table_ggx_E, Eavg), "filament_lut" (128 x 128 RG16F DFG LUT layout), "karis_fit" (Karis 2014's
// EnvBRDFApprox), all three GGX with Smith's height-correlated G2, and "moonray_table" (MoonRay's
// 33 x 33 Cook-Torrance tables, GGX and Beckmann); the published tables in data/reference/.
// Tests: tests/validation/energy_audit_test.cpp (EngineTables.CyclesLookupHitsItsNodesAndIsLinearBetween,
// EngineTables.HalfPrecisionRounding, EngineTables.FilamentTexelCentresHoldTheNextRowsRoughness,
// EnergyAudit.SmallAuditChecksPassAndEveryFormulaKeepsTheWhiteFurnace), tests/validation/moonray_tables_test.cpp
// (MoonrayTables.*), tests/analytic/compensation_test.cpp.
// Derivation and sources: docs/derivations/energy_compensation.md.
#pragma once

#include "vgroove/analytic/compensation.h"
#include "vgroove/common/ndf_kind.h"

#include <string>
#include <vector>

namespace vgroove::validation {

enum class Feed : unsigned char { exact, cycles_table, filament_lut, karis_fit, moonray_table };
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
  // MoonRay's E(mu), 1 - E_avg, 2 int (1 - E(x)) x dx of its table, and whether it compensates.
  double moonray_E = 0.0, moonray_one_minus_E_avg = 0.0, moonray_missing_average = 0.0;
  bool moonray_compensates = false;
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

// DreamWorks MoonRay's published tables (ReflectionAlbedo.h), for its Kulla-Conty compensation.
inline constexpr int kMoonrayTableSize = 33;
struct MoonrayTables {
  std::vector<double> ggx_E, beckmann_E;                              // [r index * 33 + mu index]
  std::vector<double> ggx_one_minus_E_avg, beckmann_one_minus_E_avg;  // [r index]
  const std::vector<double>& E(NdfKind ndf) const { return ndf == NdfKind::ggx ? ggx_E : beckmann_E; }
  const std::vector<double>& one_minus_E_avg(NdfKind ndf) const {
    return ndf == NdfKind::ggx ? ggx_one_minus_E_avg : beckmann_one_minus_E_avg;
  }
};
MoonrayTables read_moonray_tables(const std::string& file);  // a UserError naming the file
const MoonrayTables& published_moonray_tables();             // compiled in, as Cycles' are
// ReflectionAlbedo::E(cos = mu, roughness = sqrt(alpha)) in float: rows r = i / 32 linear in r,
// the column ceil(mu * 32) (no interpolation in mu); at r = 1 the last row (MoonRay reads one row
// past its table's end there, with weight 0). ndf: ggx or beckmann.
double moonray_E(const MoonrayTables& t, NdfKind ndf, double alpha, double mu);
double moonray_one_minus_E_avg(const MoonrayTables& t, NdfKind ndf, double alpha);
// 2 int_0^1 (1 - E(x)) x dx of the table as moonray_E reads it: exact, E being constant on each
// column's (j - 1, j] / 32; the Kulla-Conty lobe's albedo is (1 - E(mu)) F_ms this / (1 - E_avg).
double moonray_missing_average(const MoonrayTables& t, NdfKind ndf, double alpha);
// Whether MoonRay adds the compensation lobe at all: CookTorranceEnergyCompensation::weight(r) =
// max(0, r - 0.5) > 0 with r = sqrt(alpha) (BsdfCookTorrance.cc adds it only then).
bool moonray_compensates(double alpha);

// Filament's dfg.y at (mu, alpha) as the shader reads the LUT (the header), its texels computed on
// demand from the exact E_ss (tolerance 1e-10) and rounded to half precision.
inline constexpr int kFilamentLutSize = 128;
double filament_dfg_y(double alpha, double mu, int n = kFilamentLutSize);
// The nearest binary16 value (round half to even), as a GPU stores an RG16F texel.
double round_to_half(double v);

}  // namespace vgroove::validation
