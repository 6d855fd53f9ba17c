// vgroove scene: run a scene (scene.h) and report what it asked to record. Only what is asked for
// is computed: the tracer loop is instantiated per (observer, histograms, energy per k) and the
// combination picked once per run; without Fresnel the observer compiles away; with C channels
// one observer carries the C reflectances (Lee et al. 2018, Eq. 11: a path keeps prod_j F).
// Rays: stratified midpoints or uniform draws from Rng(seed, sim::kRayStream, chunk), the same
// landing points for every theta_i (a microsurface scene without Fresnel reproduces
// sim::trace_microsurface). Chunk tallies added in chunk order: bit-identical for any thread
// count, shard or MPI split. Costs: docs/performance.md.
// Tests: tests/scene/scene_test.cpp (Simulate.ConductorGrooveEnergyMatchesTheModelStratified,
// Simulate.ConductorGrooveEnergyMatchesTheModelRandom, Simulate.MicrosurfaceCountsMatchTraceMicrosurface,
// Simulate.BitIdenticalForAnyThreadCount, Simulate.RecordsAreConsistent).
// Derivation: docs/derivations/scene.md.
#pragma once

#include "vgroove/scene/scene.h"
#include "vgroove/sim/ray_fates.h"
#include "vgroove/validation/work_run.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::scene {

// What the rays of one theta_i did. Every ray is in exactly one of escaped, blocked, vertex_hits,
// bounce_limit, not_upward; every escaped ray in one k of by_k.
inline constexpr int kMaxKRow = 4096;

struct ThetaTally : sim::RayFates {
  // [k], escaped rays with k reflections, up to the largest k seen; rays with more than kMaxKRow
  // reflections share the row kMaxKRow + 1 (so that one ray escaping after 10^7 reflections
  // cannot cost a tally 10^7 rows: memory stays bounded for any legal scene).
  std::vector<std::int64_t> by_k;
  // Fresnel: the throughput of the escaped rays summed, per channel [c], and per k [k * C + c]
  // when energy_per_k is asked for.
  std::vector<double> energy;
  std::vector<double> energy_by_k;
  // Histograms (theta_o_bins > 0): exit angles over (-pi/2, pi/2) in equal bins, all escaped rays
  // [bin] and per k row [row * bins + bin], rows k = 0..max_k and one for k > max_k.
  std::vector<std::int64_t> theta_o;
  std::vector<std::int64_t> theta_o_by_k;

  void merge(const ThetaTally& o);
  double mean_k() const { return escaped > 0 ? static_cast<double>(bounces) / static_cast<double>(escaped) : 0.0; }
};

// The kaleidoscopic model's figures for a single groove (Lee et al. 2018, Eq. 4-6 or 7-9, with
// Eq. 11 for the energy): fractions of the beam entering the opening.
struct ModelFigures {
  bool available = false;  // single grooves only
  double mean_k = 0.0;
  std::vector<double> energy;  // [c]
};

struct SimulationResult {
  std::vector<double> theta_i;  // radians, as in the scene
  std::vector<ThetaTally> tallies;
  std::vector<ModelFigures> model;
  int threads = 0;
  double wall_s = 0.0;
  bool interrupted = false;  // cancelled: the tallies are incomplete
  std::int64_t rays = 0, bounces = 0;
};

// An upper bound of the memory simulate needs (support/memory.h): the grooves of each context in
// use, a tally per theta_i (counts per k, histograms, each chunk's energies) and per item in
// flight, and with `result` its JSON.
double simulate_memory_bytes(const Scene& scene, int threads, bool result);

// Runs every theta_i of the scene on `threads` threads (0: all cores).
SimulationResult simulate(const Scene& scene, int threads, const std::atomic<bool>* cancel = nullptr);

// The scene as work items (validation/work_run.h): a unit per theta_i, its rays in chunks. The
// counts merge in any grouping; the energies are sums of doubles, so each chunk's are kept apart
// and added in chunk order when the unit is complete (as simulate() always added them), which
// makes a sharded or MPI run the single-process run bit for bit.
struct ChunkEnergy {
  std::int64_t chunk = 0;
  std::vector<double> energy, energy_by_k;
};
struct SimTally {
  ThetaTally counts;  // its energies empty
  std::vector<ChunkEnergy> energies;
};
struct SimulateWork {
  struct Context;
  struct Fixed {};
  using Tally = SimTally;
  Scene scene;
  // Polled before each ray (a chunk of rays in a narrow groove runs long); a cancelled chunk's
  // tally is incomplete, and so is the run (validation::run_work_items returns nothing).
  const std::atomic<bool>* cancel = nullptr;
  std::shared_ptr<const Context> prepare(std::size_t unit) const;
  Tally run_chunks(const Context& ctx, std::size_t unit, std::int64_t begin, std::int64_t end) const;
  Fixed run_fixed(std::size_t) const { return {}; }
  static void merge(Tally& into, const Tally& from);
  static nlohmann::json tally_json(const Tally& t);
  static nlohmann::json fixed_json(const Fixed&) { return nlohmann::json::object(); }
  Tally read_tally(support::JsonObject& j, std::size_t unit, const std::vector<validation::ChunkRun>& runs) const;
  Fixed read_fixed(support::JsonObject&, std::size_t) const { return {}; }
};
validation::Job<SimulateWork> simulate_job(const Scene& scene, nlohmann::json descriptor);
// The result from every theta_i's merged tally (energies added in chunk order), with the model.
SimulationResult simulation_from(const Scene& scene, const std::vector<validation::UnitResult<SimulateWork>>& results);

// The model's figures for one theta_i of a single-groove scene (available = false otherwise).
ModelFigures model_figures(const Scene& scene, double theta_i);

// The result JSON: provenance, the scene's inputs, and per theta_i what the scene asked for.
// The share of a theta_i's rays a run may lose to vertex hits, blocked entries and exits along
// the horizon (the bounce limit is the scene's own choice and is reported, not counted here):
// each is an exact coincidence of measure zero, so a run that loses more placed its rays on
// vertices systematically and its figures would mislead.
inline constexpr double kMaxLostShare = 1e-3;
// "" when every theta_i lost at most kMaxLostShare of its rays; else the first that lost more.
std::string lost_rays_problem(const SimulationResult& r);
nlohmann::json result_json(const Scene& scene, const SimulationResult& r);
void print_result_table(std::ostream& os, const Scene& scene, const SimulationResult& r);

}  // namespace vgroove::scene
