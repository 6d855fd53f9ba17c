// vgroove validation: exact energy tables of rough glass: E_R(mu, alpha, eta) and E_T per number of
// interactions k of V-groove surfaces between two dielectrics, light from either side, traced with
// Fresnel's random choice at every hit (sim/dielectric_microsurface.h; in 3D lifted,
// sim/dielectric_lifted.h, on patches of parallel grooves with uniform azimuth), or (reference
// smith_walk) the dielectric Smith walk. mu: the cosine from the light side's normal, eta = n2 / n1.
// Nothing is absorbed: E_R + E_T + limit + vertex = 1 per cell. Hemispherical averages obey
// T_avg(above) = eta^2 T_avg(below) (flatland: eta). The glass compensation forms (MoonRay's
// Kulla-Conty, its inside scale one, Cycles') beside the traced totals, summarized over the grid.
// Tests: tests/validation/glass_energy_test.cpp (GlassEnergy.NearlyFlatIsFresnel,
// GlassEnergy.ReciprocityOfTheAverages, GlassEnergy.ConductorLimitIsTheConductorTable,
// GlassEnergy.EnergyIsAccountedAndTheCountsDoNotDependOnThreads,
// GlassEnergy.SmithWalkFirstOrderIsWaltersAndItsAveragesAreReciprocal,
// GlassEnergy.CompensationAuditBesideTheWalk, GlassEnergy.FormSummaryIsTheHandComputation,
// GlassEnergy.BrokenFormIsTheWorstOverTheGrid).
// Derivation: docs/derivations/dielectric_lifting.md ("Energy tables"), energy_compensation.md.
#pragma once

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/compensation_glass.h"
#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/work_run.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

struct GlassCell {
  NdfKind ndf = NdfKind::ggx;
  SurfaceDim dim = SurfaceDim::three_d;
  sim::Medium from = sim::Medium::above;
  double eta = 1.5;  // n2 / n1
  double alpha = 0.5;
  double mu = 1.0;  // cos of the light's angle from its side's normal; kHemisphere: cosine-weighted
};
inline constexpr double kHemisphere = -1.0;

// What the table measures: the traced V-groove surfaces, or Heitz et al. 2016's dielectric Smith
// walk (analytic/smith_walk_3d_dielectric.h in 3D, smith_walk_flatland_dielectric.h in flatland),
// whose k = 1 is Walter's BSDF with the height-correlated G2 and whose orders are Smith's.
enum class GlassReference : unsigned char { vgroove, smith_walk };
const char* glass_reference_name(GlassReference r);  // "vgroove", "smith_walk"
// The reference by name; one line naming `prefix` + reference and the names otherwise.
GlassReference glass_reference_from(const std::string& name, const std::string& prefix = "--");

struct GlassGrid {
  std::vector<NdfKind> ndfs{NdfKind::ggx};
  std::vector<SurfaceDim> dims{SurfaceDim::three_d};
  std::vector<sim::Medium> sides{sim::Medium::above, sim::Medium::below};
  std::vector<double> etas;    // each in [kMinGlassEta, kMaxGlassEta], not 1
  std::vector<double> alphas;  // each in [kMinAlpha, kMaxAlpha]
  std::vector<double> mus;     // each in [kMinMu, 1]
  long long rays = 100000;     // per cell
  std::uint64_t seed = 1;
  int max_k = 16;
  int grooves = 10000;  // per surface (one surface per ndf, dimension and alpha)
  int max_interactions = 100000;
  bool conductor_limit = false;  // F = 1 at every hit (a check: the conductor tables' E_k)
  GlassReference reference = GlassReference::vgroove;
  std::size_t cells() const { return average_cells() * mus.size(); }
  // The hemispherical cells, after the grid's: one per (ndf, dimension, side, eta, alpha).
  std::size_t average_cells() const { return ndfs.size() * dims.size() * sides.size() * etas.size() * alphas.size(); }
  // Order: ndf, dimension, side, eta, alpha, mu (innermost); then the hemispherical cells in the
  // same order without mu.
  GlassCell cell_at(std::size_t c) const;
};

// The axes by name: ndf (ggx, beckmann), dim (flatland, 3d), side (above, below); a bad name is one
// line naming `prefix` + the field.
void set_glass_axes(GlassGrid& g, const std::vector<std::string>& ndfs, const std::vector<std::string>& dims,
                    const std::vector<std::string>& sides, const std::string& prefix = "--");
// One line naming the field and its range: `prefix` + eta, ndf (ggx, beckmann), grooves, ... (the
// command line's flags with "--", Python's arguments with "").
void check_glass_grid(const GlassGrid& g, const std::string& prefix = "--");

struct GlassCounts {
  long long rays = 0;
  std::vector<long long> reflected, transmitted;  // rows k = 1..max_k, then k > max_k
  long long bounce_limit = 0, vertex = 0;
  long long interactions = 0;
  void merge(const GlassCounts& o);
};

struct GlassTable {
  GlassGrid grid;
  std::vector<GlassCounts> cells;  // the grid's, then the hemispherical ones
  int threads = 1;
  double wall_s = 0.0;
};

// The work of a table (work_run.h): a unit per cell (the grid's, then the hemispherical ones), its
// rays in chunks of sim::kRaysPerChunk, chunk c of cell k from the stream (seed, glass rays + k, c);
// the context is the cell's surface. One process, shards (`--shard`, `vgroove merge`) and MPI ranks
// give the same counts.
struct GlassWork {
  struct Context {
    sim::Microsurface surface;
  };
  using Tally = GlassCounts;
  struct Fixed {};
  GlassGrid grid;
  const std::atomic<bool>* cancel = nullptr;
  std::shared_ptr<const Context> prepare(std::size_t cell) const;
  Tally run_chunks(const Context& ctx, std::size_t cell, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t) const { return {}; }
  static void merge(Tally& into, const Tally& from) { into.merge(from); }
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed&) { return nlohmann::json::object(); }
  // As strictly as a suite: the chunks' ray count, every bucket within it and the buckets adding up
  // to it (every ray ends in exactly one).
  Tally read_tally(support::JsonObject& j, std::size_t cell, const std::vector<ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject& j, std::size_t cell) const;  // throws: glass cells have none
};

// The grid as the job's input (every field the counts depend on) and back, checked as the command
// line checks it (`where` names the file).
nlohmann::json glass_grid_json(const GlassGrid& g);
GlassGrid glass_grid_from_json(const nlohmann::json& j, const std::string& where);
Job<GlassWork> glass_job(const GlassGrid& g, const std::atomic<bool>* cancel = nullptr);
GlassTable glass_table_from(const GlassGrid& g, std::vector<UnitResult<GlassWork>> results);

// Every cell in this process (deterministic: the same counts for any thread count); nothing when
// *cancel was set.
std::optional<GlassTable> run_glass_table(const GlassGrid& g, int threads, const support::ProgressFn& progress = {},
                                          const std::atomic<bool>* cancel = nullptr);

// The reciprocity of the hemispherical averages for each (ndf, dim, eta, alpha) with both sides:
// T_avg(above) against eta^p T_avg(below), p = 2 in 3D and 1 in flatland.
struct GlassReciprocity {
  GlassCell cell;  // its side and mu not meaningful
  double above = 0.0, below = 0.0, scaled_below = 0.0, se = 0.0;
  double z() const { return se > 0.0 ? (above - scaled_below) / se : 0.0; }
};
std::vector<GlassReciprocity> glass_reciprocity(const GlassTable& t);

nlohmann::json glass_table_json(const GlassTable& t);
void print_glass_table(std::ostream& os, const GlassTable& t);

// The audit columns (glass_compensation_audit): Kulla and Conty's rough-glass compensation as
// MoonRay ships it (analytic/compensation_glass.h) and with the inside transmitted weight unscaled,
// fed with the exact single scattering of the reference's own model (Smith walk: Walter with the
// height-correlated G2, its exact first order; V-groove: Walter with the V-cavity G, exact for the
// reflected first order only) and the exact F_avg, averages by the 8-point rule in mu; 3D cells,
// not the conductor limit. Formula minus traced, with the traced se.
struct GlassCompensationRow {
  GlassCell cell;                                         // 3D; mu = kHemisphere: the hemispherical averages
  double E_R = 0.0, E_T = 0.0;                            // the single scattering fed to the form (quadrature)
  double eta_rel = 1.5;                                   // n_far / n_near of the lit side (eta above, 1 / eta below)
  analytic::KullaContyGlassAverages averages;             // what the Kulla-Conty forms read (exact E_avg, F_avg)
  analytic::CompensatedGlass moonray, scale_one, cycles;  // cycles: both lobes times 1 / (E_R + E_T)
  double R = 0.0, T = 0.0, se_R = 0.0, se_T = 0.0;        // traced totals (all orders)
  long long rays = 0, left = 0;                           // rays traced, rays that left (R + T)
};

// The single-scattering model whose E feeds the form for a reference.
analytic::MicrofacetModel glass_single_scattering_model(GlassReference r, NdfKind ndf);

std::vector<GlassCompensationRow> glass_compensation_audit(const GlassTable& t);
void print_glass_compensation_audit(std::ostream& os, const std::vector<GlassCompensationRow>& rows);
nlohmann::json glass_compensation_audit_json(const std::vector<GlassCompensationRow>& rows);
// The table's JSON and printout from the audit rows glass_compensation_audit(t) gave (a caller that
// prints and writes computes them once; the one-argument forms compute them).
nlohmann::json glass_table_json(const GlassTable& t, const std::vector<GlassCompensationRow>& audit);
void print_glass_table(std::ostream& os, const GlassTable& t, const std::vector<GlassCompensationRow>& audit);

// ---- The forms over the grid (the summary and error maps of `kulla_conty_glass`) ------------------
// A form: R', T' of a row. glass_forms(): moonray, scale_one, cycles_glass (the rows' values).
struct GlassForm {
  std::string id, formula;
  analytic::CompensatedGlass (*of)(const GlassCompensationRow&) = nullptr;
};
const std::vector<GlassForm>& glass_forms();

// The conductor audit's regions (EnergyAuditSuite's rough_alpha, grazing_mu, as `vgroove energy
// --audit` runs them): all; rough alpha >= rough_alpha; grazing mu <= grazing_mu.
struct GlassRegions {
  double rough_alpha = 0.5, grazing_mu = 0.25;
};
GlassRegions glass_regions();
inline constexpr const char* kGlassSides[] = {"both", "above", "below"};
inline constexpr const char* kGlassRegionNames[] = {"all", "rough", "grazing"};
inline constexpr const char* kGlassQuantities[] = {"R", "T", "R+T"};

// The noise of a traced share p of n rays, for z: sqrt(max(p (1 - p), 1 / n) / n) (at least one
// ray's worth: a share that is exactly 0 or 1, as R + T of the walk, still has a finite z).
double glass_share_se(double p, long long n);
// Within noise: max |z| over a family of m cells <= z with m P(|Z| > z) = 0.01 (Bonferroni, 1 %).
double glass_noise_threshold(std::size_t m);

// One (form, side, region, quantity): the grid's cells (mu != kHemisphere), errors formula - traced.
struct GlassErrorStat {
  long n = 0;
  double worst = 0.0, worst_z = 0.0;  // the largest |error| (signed) and its z, at `at`
  double max_z = 0.0;                 // the largest |z| (signed), at `z_at`
  double sum_abs = 0.0, sum = 0.0, sum_abs_z = 0.0;
  std::string at, z_at;
  void add(double e, double z, const std::string& where);
  double mean_abs() const;
  double mean() const;
  double mean_abs_z() const;
  double threshold() const { return glass_noise_threshold(static_cast<std::size_t>(n)); }
  bool within_noise() const { return n > 0 && std::abs(max_z) <= threshold(); }
};
struct GlassFormSummary {
  std::vector<std::string> forms;
  GlassRegions regions;
  std::vector<GlassErrorStat> stats;  // [form][side 3][region 3][quantity 3]
  const GlassErrorStat& at(std::size_t form, int side, int region, int quantity) const {
    return stats[((form * 3 + side) * 3 + region) * 3 + quantity];
  }
  // The form of the least (closest) and largest (farthest) mean |error|; -1 when no cell.
  int closest(int side, int region, int quantity, bool farthest = false) const;
};
GlassFormSummary glass_form_summary(const std::vector<GlassCompensationRow>& rows, const std::vector<GlassForm>& forms,
                                    const GlassRegions& regions = glass_regions());
void print_glass_form_summary(std::ostream& os, const GlassFormSummary& s, GlassReference reference);
// The summary, the closest forms and the error maps [ndf][side][eta][alpha][mu] per form and quantity.
nlohmann::json glass_form_summary_json(const GlassTable& t, const std::vector<GlassCompensationRow>& rows,
                                       const std::vector<GlassForm>& forms, const GlassFormSummary& s);

}  // namespace vgroove::validation
