// vgroove validation: the energy audit (suite kind "energy_audit"; `vgroove energy --audit`): the
// compensation formulas engines ship (validation/energy_formulas.h) held against the exact
// multiple-scattering albedo of references over mu x alpha x reflectance: the 3D V-groove model
// (analytic/albedo_vgroove.h, exact to ~1e-8), the 3D Smith random walk (analytic/smith_walk_3d.h,
// Monte Carlo) and, opt-in (/references), random heightfields traced exactly (sim/heightfield_tracer.h,
// each ray's bounce cosines weighted per channel). Reflectances: grey Schlick, Au, Ag, Cu, Al
// (exact conductors and Schlick), metalness mixes; errors per variant, reference, group, region.
// Verdict (the references, not the formulas): walk and heightfield white channels leave whole, the
// walk's E_1 is Smith's E_ss within `sigmas`, the model sums to 1 and its first row is the V-cavity
// E_ss. Integer tallies: any merge order gives the same bits. Tests: tests/validation/energy_audit_test.cpp
// (EnergyAudit.VgrooveReferenceWithAConductorIsTheTracedGrooves,
// EnergyAudit.SmallAuditChecksPassAndEveryFormulaKeepsTheWhiteFurnace,
// EnergyAudit.HeightfieldChannelsAreTheFresnelTraces, EnergyAudit.HeightfieldTallyIsTheSameForAnyThreadsAndShards,
// EnergyAudit.HeightfieldReferenceInTheReport, Colour.DeltaE2000AtSharmasTestPairs), tests/app/energy_tables_test.cpp
// (EnergyAuditCli.*). Derivation: docs/derivations/energy_compensation.md.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/heightfield_tracer.h"
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

inline constexpr const char* kAuditReferences[] = {"vgroove", "smith_walk", "heightfield"};
inline constexpr std::int64_t kAuditPathsPerChunk = 8192;
inline constexpr std::int64_t kAuditRaysPerChunk = 4096;  // heightfield rays (about a walk chunk's time)
inline constexpr int kAuditMaxFields = 64;

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
  // The heightfield reference (/references has "heightfield"; /heightfield): per (ndf, alpha)
  // `fields` Gaussian fields (Beckmann; GGX through its height map), traced at every mu of the
  // alpha with rays_per_field rays each.
  bool heightfield = false;
  int hf_fields = 4, hf_field_size = 256;
  double hf_correlation_length = 8.0;
  long long hf_rays_per_field = 20000;
  std::int64_t walk_chunks() const { return (walk_paths + kAuditPathsPerChunk - 1) / kAuditPathsPerChunk; }
  std::int64_t hf_chunks_per_field() const { return (hf_rays_per_field + kAuditRaysPerChunk - 1) / kAuditRaysPerChunk; }
  // A cell's chunks: the walk's, then (heightfield) field by field the rays' chunks.
  std::int64_t chunks() const { return walk_chunks() + (heightfield ? hf_fields * hf_chunks_per_field() : 0); }
  std::size_t cells() const { return ndfs.size() * alphas.size() * mus.size(); }
  EnergyAuditCell cell_at(std::size_t c) const;  // order: ndf, alpha, mu (innermost)
};

// The suite from its JSON (strictly: each message names the file and the JSON path).
EnergyAuditSuite parse_energy_audit(const nlohmann::json& j, const std::string& file);
// The suite as its JSON (what `vgroove energy --audit` runs and writes into its report).
nlohmann::json energy_audit_json(const EnergyAuditSuite& s);
// The suite `vgroove energy --audit` and Python's energy_audit run over the grid given: every
// default reflectance, region and threshold, and with `heightfield` the random heightfields (4
// fields of 256^2 cells, correlation length 8, paths / 4 rays each).
nlohmann::json energy_audit_command_suite(const std::vector<std::string>& ndfs, const std::vector<double>& alphas,
                                          const std::vector<double>& mus, long long paths, long long seed, int max_k,
                                          bool heightfield);

// One cell's walks: counts per row (k = 0..max_k, max_k + 1 for k > max_k) and each row's energy
// per channel, [row * C + c], in units of 2^-32.
// The heightfield's (empty without it): rays, lost (HeightfieldFate::lost), bounce_limit (over
// kHeightfieldMaxBounces), hf_by_k and hf_energy as by_k and energy, and per field its rows' counts
// [field * R + row] and its energy per channel [field * C + c] (the spread over fields).
struct AuditTally {
  std::int64_t paths = 0, lost = 0;  // lost: still inside after kWalkMaxBounces reflections
  std::vector<std::int64_t> by_k, energy;
  std::int64_t hf_rays = 0, hf_lost = 0, hf_bounce_limit = 0;
  std::vector<std::int64_t> hf_by_k, hf_energy, hf_field_by_k, hf_field_energy;
};
inline constexpr int kWalkMaxBounces = 100000;
inline constexpr int kHeightfieldMaxBounces = 1000;

// One cell's deterministic part.
struct AuditFixed {
  std::vector<double> vgroove_rows;            // [row * C + c], rows 0..max_k + 1
  SingleScattering smith, vcavity;             // E_avg: NaN but at the cell of mu index 0
  std::vector<double> smith_E_F, vcavity_E_F;  // [C]
  // Smith's separable G2 (MoonRay's lobes, the moonray_table feed's single scattering); E_avg NaN.
  SingleScattering separable;
  std::vector<double> separable_E_F;              // [C]
  double filament_dfg_y, cycles_E, cycles_E_avg;  // NaN when absent
  double seconds = 0.0;
};

struct AuditFields;      // an (ndf, alpha)'s fields, each made on first use (energy_audit.cpp)
struct AuditFieldShare;  // the fields held now, by (ndf, alpha): cells of one share them
struct EnergyAuditWork {
  struct Context {
    std::shared_ptr<AuditFields> fields;  // null without the heightfield reference
  };
  using Tally = AuditTally;
  using Fixed = AuditFixed;
  EnergyAuditSuite suite;
  std::shared_ptr<const ChannelSet> channels;
  std::shared_ptr<const CyclesTables> cycles;  // null without the feed
  // With the heightfield reference: a cell's context takes the fields another cell of its (ndf,
  // alpha) still holds, so they are made once while consecutive cells run (energy_audit_job sets it).
  std::shared_ptr<AuditFieldShare> field_share;
  std::shared_ptr<const Context> prepare(std::size_t cell) const;
  Tally run_chunks(const Context&, std::size_t cell, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t cell) const;
  static void merge(Tally& into, const Tally& from);
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed& f);
  Tally read_tally(support::JsonObject& j, std::size_t cell, const std::vector<ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject& j, std::size_t cell) const;
};

Job<EnergyAuditWork> energy_audit_job(const EnergyAuditSuite& s, nlohmann::json descriptor);
// The memory a run holds: per cell its tally, fixed part and report arrays, and with the heightfield
// reference each of `threads` workers' fields (up to two cells' hf_fields fields, sim::heightfield_bytes)
// and one (ndf, alpha)'s more (the share keeps the group prepared last).
double energy_audit_memory_bytes(const EnergyAuditSuite& s, int threads);

// The heightfield reference's field `field` of a cell (the same fields at every mu of an (ndf,
// alpha)), and the origins of chunk `chunk`'s rays (a cell chunk index, in the heightfield's
// range) with their direction -(sqrt(1 - mu^2), 0, mu): what run_chunks traces.
sim::HeightfieldSurface audit_heightfield_field(const EnergyAuditSuite& s, std::size_t cell, int field);
int audit_heightfield_field_of(const EnergyAuditSuite& s, std::int64_t chunk);
void audit_heightfield_rays(const EnergyAuditSuite& s, const sim::HeightfieldSurface& f, std::size_t cell,
                            std::int64_t chunk, std::vector<Eigen::Vector3d>& origins, Eigen::Vector3d& dir);

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
