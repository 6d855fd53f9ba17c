// vgroove validation: tables engines can load (`vgroove energy --export`): E_ss, E_avg and the
// split-sum DFG scale and bias (analytic/albedo_single.h, bounded quadrature) and the exact
// multiple-scattering albedo E_ms with Schlick's F per F0 (the rows k >= 2 of a reference: the
// V-groove model by quadrature or the Smith walk by Monte Carlo), with the exact compensation
// factor (E_F + E_ms) / E_F, E_F = F0 scale + bias, in a chosen layout: "cycles" (Blender Cycles'
// table_ggx_E texel ends) or "centres" (texel centres). Every file (JSON, .npz, C header, PNG,
// OpenEXR) carries its metadata (layout, parametrization, quadrature, reference, version).
// Tests: tests/app/energy_tables_test.cpp (EnergyExport.FilesHoldTheTablesMetadataAndTheWhiteFurnace,
// EnergyExport.SmithWalkMultipleScatteringIsOneMinusTheExactSingleScattering,
// EnergyExport.BadInputNamesTheFlagAndLeavesNoFile, EnergyImages.Png16RoundTripsItsSamplesAndText,
// EnergyImages.ExrRoundTripsItsChannelsAndAttribute). Layouts: docs/albedo_tables.md.
// Derivation: docs/derivations/energy_compensation.md.
#pragma once

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/albedo_table.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/ranges.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace vgroove::validation {

struct EnergyExportOptions {
  analytic::MicrofacetModel model{NdfKind::ggx, analytic::MaskingKind::smith_height_correlated};
  std::string layout = "cycles";      // "cycles" or "centres"
  int size = 32;                      // texels per axis, in [2, kMaxExportSize]
  double tol = 1e-8;                  // the quadrature's tolerance on each value
  std::string ms_reference = "none";  // "none", "vgroove" or "smith_walk"
  std::vector<double> ms_F0{0.04, 0.25, 0.5, 0.75, 1.0};
  long long walk_paths = 100000;  // per texel (smith_walk)
  std::uint64_t seed = 1;
  int threads = 0;
};

// A UserError naming the flag for what is out of range.
void check_energy_export(const EnergyExportOptions& o);
analytic::TableLayout export_layout(const EnergyExportOptions& o);

struct ExportArray {
  std::string name;
  std::string description;
  std::vector<std::string> axes;  // outermost first
  std::vector<std::size_t> shape;
  std::vector<double> values;  // row-major
};

struct EnergyExport {
  nlohmann::json metadata;
  std::vector<ExportArray> arrays;
  double wall_s = 0.0;
};

// The tables; nothing when *cancel was set.
std::optional<EnergyExport> energy_export(const EnergyExportOptions& o, const support::ProgressFn& progress = {},
                                          const std::atomic<bool>* cancel = nullptr);

// The files' contents (bytes).
std::string export_json_text(const EnergyExport& e);
std::string export_npz_bytes(const EnergyExport& e);
// A C/C++ header: the metadata as a comment, each array as `static const float PREFIX_NAME[...]` with
// its dimensions as enumerators (constant expressions in C and C++). prefix: a C identifier.
std::string export_header_text(const EnergyExport& e, const std::string& prefix);
// A C identifier from a file's base name ("tables/ggx-32" -> "ggx_32").
std::string c_identifier(const std::string& base);

}  // namespace vgroove::validation
