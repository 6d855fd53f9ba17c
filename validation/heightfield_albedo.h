// vgroove validation: the albedo E(mu, alpha) of random heightfields, exactly on the surface, with
// its single- and multiple-scattering parts (suite kind "heightfield_albedo"): per (ndf, alpha)
// `fields` fields (heightfield_lobe.h make_field_surface, F = 1), `rays` rays per field at every
// mu (trace_field, counted per k only), rows E, E_1, E_ms = E - E_1, E_2, E_3+: the mean over the
// fields and its standard error (their spread, at least the rays' binomial error). Models: the 3D
// Smith walk's E_k (analytic/smith_walk_3d.h, Monte Carlo), Smith's exact height-correlated E_ss
// (analytic/albedo_single.h, E_1 only) and the V-groove model's E_k (analytic/albedo_vgroove.h).
// A model is within noise in a row when |traced - model| <= sigmas sqrt(se^2 + var_model) + tolerance
// (a result, not a verdict). Verdict: every ray leaves (so E = 1 exactly), every value finite.
// One work item per (ndf, alpha), streams per (item, field, mu): the same bits for any thread,
// shard or rank count. Tests: tests/validation/heightfield_albedo_test.cpp (HeightfieldAlbedo.*).
// Derivation: docs/derivations/heightfield.md (the albedo section).
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/heightfield_lobe.h"
#include "vgroove/validation/item_work.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

// The rows reported: E, E_1, E_ms = E - E_1, E_2, E_3+.
inline constexpr int kAlbedoRows = 5;
inline constexpr const char* kAlbedoRowNames[kAlbedoRows] = {"E", "E_1", "E_ms", "E_2", "E_3+"};
// The models: the walk (every row), Smith's E_ss (E_1), the V-groove model (every row).
inline constexpr int kAlbedoModels = 3;
inline constexpr const char* kAlbedoModelNames[kAlbedoModels] = {"smith_walk", "smith_ess", "vgroove"};

struct HeightfieldAlbedoSuite {
  std::string file, name, description;
  std::vector<NdfKind> ndfs;
  std::vector<double> alphas;
  std::vector<double> mus;  // (cos 89.9 deg, 1]
  HeightfieldSurfaceKind surface = HeightfieldSurfaceKind::gaussian;
  int field_size = 256;
  double correlation_length = 8.0;
  int fields = 4;
  long rays = 20000;         // per field and mu
  long walk_paths = 100000;  // per (ndf, alpha, mu)
  std::uint64_t seed = 1;
  double sigmas = 5.0;
  double model_tolerance = 1e-4;  // added to every threshold (the models' own accuracy)
  std::size_t items() const { return ndfs.size() * alphas.size(); }
  NdfKind ndf_of(std::size_t item) const { return ndfs[item / alphas.size()]; }  // order: ndf, alpha
  double alpha_of(std::size_t item) const { return alphas[item % alphas.size()]; }
};

// One (ndf, alpha): what is measured and computed, as it travels between processes. Traced rows
// per field: [(field * mus + m) * 4 + r], r: E, E_1, E_2, E_3+ (the fraction of rays, F = 1).
struct HeightfieldAlbedoOutcome {
  std::int64_t rays = 0, lost = 0, bounce_limit = 0, edge_hits = 0, vertex_hits = 0;
  std::vector<double> traced;
  std::vector<std::int64_t> walk_counts;  // [m * 4 + r]: paths left, with k = 1, 2, >= 3
  std::int64_t walk_paths = 0;            // per mu
  std::vector<double> ess, ess_error;     // [m]
  std::vector<double> vgroove;            // [m * 4 + r]
  double field_s = 0.0, trace_s = 0.0, walk_s = 0.0, model_s = 0.0;
};
template <class F>
void fields(HeightfieldAlbedoOutcome& o, F&& f) {
  f("rays", o.rays), f("lost", o.lost), f("bounce_limit", o.bounce_limit), f("edge_hits", o.edge_hits);
  f("vertex_hits", o.vertex_hits), f("traced", o.traced), f("walk_counts", o.walk_counts);
  f("walk_paths", o.walk_paths), f("ess", o.ess), f("ess_error", o.ess_error), f("vgroove", o.vgroove);
  f("field_s", o.field_s), f("trace_s", o.trace_s), f("walk_s", o.walk_s), f("model_s", o.model_s);
}

// One model in one row at one mu (NaN value: the model has no such row).
struct AlbedoComparison {
  double value = 0.0, var = 0.0;  // the model's value and its variance (the walk's Monte Carlo)
  double diff = 0.0;              // traced - model
  double threshold = 0.0;         // sigmas sqrt(se^2 + var) + tolerance (+ E_ss's bound)
  double z = 0.0;                 // diff / sqrt(se^2 + var)
  bool within_noise = false;
};

// One (ndf, alpha, mu): the traced rows over the fields and each model's comparison per row.
struct AlbedoPoint {
  NdfKind ndf = NdfKind::beckmann;
  double alpha = 0.0, mu = 1.0;
  double traced[kAlbedoRows] = {}, traced_se[kAlbedoRows] = {};
  AlbedoComparison models[kAlbedoModels][kAlbedoRows];
};

struct HeightfieldAlbedoRun {
  std::vector<HeightfieldAlbedoOutcome> items;
  std::vector<AlbedoPoint> points;  // order: ndf, alpha, mu (innermost)
  std::vector<bool> item_pass;      // every ray left, every value finite
  int threads = 1;
  double wall_s = 0.0;
  bool pass = false;
};

HeightfieldAlbedoSuite parse_heightfield_albedo_suite(const nlohmann::json& j, const std::string& file);
// One field with its hierarchy per worker (min(threads, items)); throws support::UserError
// ("FILE: /field_size: ...") when a field does not fit this process's share of memory.
double heightfield_albedo_memory_bytes(const HeightfieldAlbedoSuite& suite, int threads);

// One (ndf, alpha): its fields made once, each traced at every mu; the walk and the models. rays
// > 0 overrides the suite's rays per field and mu.
HeightfieldAlbedoOutcome run_heightfield_albedo_item(const HeightfieldAlbedoSuite& suite, std::size_t item, long rays,
                                                     const std::atomic<bool>* cancel = nullptr);
using HeightfieldAlbedoWork = ItemWork<HeightfieldAlbedoOutcome>;
Job<HeightfieldAlbedoWork> heightfield_albedo_job(const HeightfieldAlbedoSuite& suite, long rays,
                                                  nlohmann::json descriptor, const std::atomic<bool>* cancel = nullptr);
// The points and comparisons from the items' outcomes (pure: the same for any split of the work).
HeightfieldAlbedoRun heightfield_albedo_run_from(const HeightfieldAlbedoSuite& suite,
                                                 const std::vector<UnitResult<HeightfieldAlbedoWork>>& results);
HeightfieldAlbedoRun run_heightfield_albedo(const HeightfieldAlbedoSuite& suite, long rays, int threads,
                                            const support::ProgressFn& progress = {},
                                            const std::atomic<bool>* cancel = nullptr);

// Plainly, per point and row: the models within noise, and each other's model - traced (z).
std::string albedo_row_text(const AlbedoPoint& p, int row);
nlohmann::json heightfield_albedo_report_json(const HeightfieldAlbedoSuite& suite, const HeightfieldAlbedoRun& run);
void print_heightfield_albedo_table(std::ostream& os, const HeightfieldAlbedoSuite& suite,
                                    const HeightfieldAlbedoRun& run);

}  // namespace vgroove::validation
