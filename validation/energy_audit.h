// vgroove validation: the energy audit (suite kind "energy_audit"; `vgroove energy --audit`): the
// energy compensation formulas engines ship (validation/energy_formulas.h) held against the exact
// multiple-scattering albedo of two references, over mu x alpha x reflectance.
//
// References (per cell: NDF, alpha, mu = cos theta_i):
//   vgroove     the 3D V-groove model (Lee et al. 2018), exact to its quadrature (~1e-8;
//               analytic/albedo_vgroove.h), the surface of explicit V-grooves that vgroove traces
//               exactly (`vgroove energy` holds the two together per bounce order with F = 1;
//               tests/validation/energy_audit_test.cpp with a conductor's F). Its formulas are fed
//               with the V-cavity model's single scattering (Cook-Torrance, its k = 1 term).
//   smith_walk  the Smith random walk of Heitz et al. 2016 in 3D (analytic/smith_walk_3d.h), the
//               reference engines fit to, by Monte Carlo: walk_paths paths per cell from their own
//               stream (seed, cell, chunk), each carrying prod_j F(<v_j, m_j>) per channel; standard
//               error at most sqrt(E (1 - E) / N) (every weight lies in [0, 1]). Its formulas are fed
//               with Smith's height-correlated single scattering, and the engine tables only here
//               (GGX).
// The random heightfields (issue 33) and the dielectric tables (issue 32) are not references yet:
// a reference is one more member of the cell's fixed part or tally, and one more name in
// kAuditReferences, with the formulas fed from its own model's single scattering.
//
// Reflectances (validation/energy_materials.h): grey Schlick F0 (1 always: the white furnace;
// 0.04 always: the dielectric of the metalness mixes), Au, Ag, Cu, Al as exact conductors at three
// wavelengths, and the same metals as Schlick's F with their normal reflectance. Groups of errors:
//   grey, conductor, metal_schlick   a formula on a channel against the same channel's exact albedo;
//   engine_metal                     a formula on a metal's Schlick channel (what an engine is given)
//                                    against the metal's exact conductor albedo;
//   metalness_before/_after          metalness m between the dielectric (F0 = 0.04) and a metal's
//                                    Schlick channel: the exact albedo of the mix is (1 - m)
//                                    E(0.04) + m E(metal) (a surface of both); "before" feeds the
//                                    formula F0 = (1 - m) 0.04 + m F0_metal (engines' lerp of F0),
//                                    "after" mixes the formula's two albedos.
// Error = formula albedo - reference albedo. Regions: all; rough (alpha >= rough_alpha); grazing
// (mu <= grazing_mu). Per variant, reference, group and region: the worst |error| (and where), the
// mean |error| and the mean signed error. The colour shift of Au and Cu: the three conductor bands
// read as linear sRGB (R = ~650 nm, G = ~550, B = ~450; an assumption: not a spectral integration),
// converted to CIE L*a*b* (D65) and compared by CIE Delta E 2000, with the per-channel ratios
// formula / reference.
//
// The verdict holds the references, not the formulas: the walk's white channel leaves whole (every
// path left) and its E_1 (Smith height-correlated E_ss) agrees with the exact quadrature within
// sigmas standard errors; the V-groove model's white channel adds up to 1 within vgroove_furnace;
// its first row equals the V-cavity E_ss within vgroove_furnace. The formulas' errors are results.
//
// Work (work_run.h): one unit per cell; the walk in chunks of kAuditPathsPerChunk paths (integer
// tallies: counts per bounce order and each row's Fresnel energy in units of 2^-32 per path, so a
// merge in any order gives the same bits), the model and every quadrature in its fixed part.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/energy_formulas.h"
#include "vgroove/validation/energy_materials.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/work_run.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

inline constexpr const char* kAuditReferences[] = {"vgroove", "smith_walk"};
inline constexpr std::int64_t kAuditPathsPerChunk = 8192;

struct EnergyAuditCell {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5, mu = 1.0;
  std::size_t alpha_index = 0, mu_index = 0;
};

struct EnergyAuditSuite {
  std::string file, name, description;
  std::vector<NdfKind> ndfs;  // ggx, beckmann
  std::vector<double> alphas, mus;
  long long walk_paths = 100000;
  std::uint64_t seed = 1;
  int max_k = 8;
  std::vector<double> grey_F0;  // 1 and 0.04 included
  std::vector<std::string> metals;
  std::vector<double> metalness;
  double rough_alpha = 0.5, grazing_mu = 0.25;
  bool cycles_table = true;  // the cycles_table feed (Cycles' published table, compiled in)
  double sigmas = 5.0, vgroove_furnace = 1e-7;
  std::size_t cells() const { return ndfs.size() * alphas.size() * mus.size(); }
  EnergyAuditCell cell_at(std::size_t c) const;  // order: ndf, alpha, mu (innermost)
};

// The suite from its JSON (strictly: each message names the file and the JSON path).
EnergyAuditSuite parse_energy_audit(const nlohmann::json& j, const std::string& file);
// The suite as its JSON (what `vgroove energy --audit` runs and writes into its report).
nlohmann::json energy_audit_json(const EnergyAuditSuite& s);

// One cell's walks: counts per row (k = 0..max_k, max_k + 1 for k > max_k) and each row's energy
// per channel, [row * C + c], in units of 2^-32.
struct AuditTally {
  std::int64_t paths = 0, lost = 0;  // lost: still inside after kWalkMaxBounces reflections
  std::vector<std::int64_t> by_k, energy;
};
inline constexpr int kWalkMaxBounces = 100000;

// One cell's deterministic part.
struct AuditFixed {
  std::vector<double> vgroove_rows;               // [row * C + c], rows 0..max_k + 1
  SingleScattering smith, vcavity;                // E_avg: NaN but at the cell of mu index 0
  std::vector<double> smith_E_F, vcavity_E_F;     // [C]
  double filament_dfg_y, cycles_E, cycles_E_avg;  // NaN when absent
  double seconds = 0.0;
};

struct EnergyAuditWork {
  struct Context {};
  using Tally = AuditTally;
  using Fixed = AuditFixed;
  EnergyAuditSuite suite;
  std::shared_ptr<const ChannelSet> channels;
  std::shared_ptr<const CyclesTables> cycles;  // null without the feed
  std::shared_ptr<const Context> prepare(std::size_t) const { return std::make_shared<Context>(); }
  Tally run_chunks(const Context&, std::size_t cell, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t cell) const;
  static void merge(Tally& into, const Tally& from);
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed& f);
  Tally read_tally(support::JsonObject& j, std::size_t cell, const std::vector<ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject& j, std::size_t cell) const;
};

Job<EnergyAuditWork> energy_audit_job(const EnergyAuditSuite& s, nlohmann::json descriptor);

// A finished audit: the cells' results with what the report is made of.
struct EnergyAuditRun {
  std::vector<UnitResult<EnergyAuditWork>> cells;
  nlohmann::json body;  // the report's figures (energy_audit.cpp, audit_body)
  std::string table;
  int threads = 1;
  double wall_s = 0.0;
  bool pass = false;
};
EnergyAuditRun energy_audit_run_from(const EnergyAuditSuite& s, const std::vector<UnitResult<EnergyAuditWork>>& r);
nlohmann::json energy_audit_report_json(const EnergyAuditSuite& s, const EnergyAuditRun& run);
void print_energy_audit(std::ostream& os, const EnergyAuditSuite& s, const EnergyAuditRun& run);

// Linear sRGB (IEC 61966-2-1 primaries, D65) to CIE L*a*b* with the D65 white; CIE Delta E 2000
// (Sharma, Wu, Dalal 2005, Eq. 1-22) between two L*a*b* colours, and between two linear-sRGB ones.
void lab_from_linear_srgb(const double rgb[3], double lab[3]);
double delta_e_2000(const double lab1[3], const double lab2[3]);
double delta_e_2000_linear_srgb(const double rgb_a[3], const double rgb_b[3]);

}  // namespace vgroove::validation
