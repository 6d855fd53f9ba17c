// vgroove validation: tables engines can load (`vgroove energy --export`): the single-scattering
// albedo E_ss, its average E_avg, the split-sum DFG scale and bias (analytic/albedo_single.h, by
// bounded quadrature) and the exact multiple-scattering albedo E_ms with Schlick's F per F0
// (the rows k >= 2 of a reference: the V-groove model by quadrature, or the Smith random walk by
// Monte Carlo), with the exact compensation factor (E_F + E_ms) / E_F that turns a single-scattering
// lobe with the same F into the exact albedo (E_F = F0 scale + bias), in a chosen layout.
//
// Layouts (analytic/albedo_table.h names their parts; docs/albedo_tables.md documents them):
//   cycles   Blender Cycles' table_ggx_E: texel ends s = i / (n - 1) clamped to [1e-4, 1], mu = s
//            rows, r = s columns with alpha = r^2, coordinates in float, [mu][r] in memory;
//   centres  texel centres s = (i + 1/2) / n for both (a texture sampled bilinearly at (mu, r) with
//            no half-texel fix), mu rows, r columns, alpha = r^2, [mu][r] in memory.
// The single-scattering model is the reference's (Smith height-correlated for the walk, the
// V-cavity G for the V-groove model; without E_ms, the model asked for).
//
// Every file carries the metadata (layout, parametrization, quadrature, reference, version): the
// JSON and the .npz (its member metadata.json beside the arrays' .npy members: numpy.load(f)
// ["metadata.json"] gives its bytes), the C header (a comment), the PNG (a tEXt chunk) and the
// OpenEXR file (a string attribute) (the image encoders are the command line's: app/).
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
