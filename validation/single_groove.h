// vgroove validation: one groove lit by one parallel beam, as `vgroove trace` and `vgroove
// analytic` report it (and the Python module's trace and kaleidoscope): one row per (facet hit
// first, bounce count k) with the fraction of the beam entering the opening and the exit angle,
// the same shape from the tracer and from the model, so the two can be diffed.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/tally.h"
#include "vgroove/validation/groove_case.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace vgroove::validation {

struct BounceRow {
  sim::Side first = sim::Side::left;
  int k = 0;
  double fraction = 0.0;  // of the beam entering the opening
  double theta_o = 0.0;   // radians
};
// [{"first_facet", "k", "fraction", "theta_o_deg"}, ...]
nlohmann::json rows_json(const std::vector<BounceRow>& rows);

// The model (Eq. 4-6 symmetric, Eq. 7-9 nonsymmetric) for the beam from theta_i (radians). G is
// normalized by each facet's projected width f_a; the beam entering the opening is as wide as the
// zones of the two facets together, sum of f_a G (entering_width), so the fractions sum to 1 for
// every accepted input. Zones that share a bounce count
// (k_b - 1 = 1 when k_b = 2) are one row; rows with G = 0 are left out.
struct ModelFacet {
  bool lit = false;
  int k = 0;  // Eq. (4), or k_b of Eq. (7)
  double f_a = 0.0, shadow = 0.0;
  std::vector<std::pair<int, double>> G;  // (n, G) by n, zones merged
};
struct ModelTable {
  std::vector<BounceRow> rows;
  ModelFacet facet[2];  // [left, right]
};
ModelTable model_table(const GrooveParams& groove, double theta_i, analytic::Eq6Form form);
// `vgroove analytic --json`.
nlohmann::json analytic_json(const GrooveParams& groove, double theta_i_deg, analytic::Eq6Form form);

// The beam's rays: `rays` rays across the opening (sim::sample_position's placement, random
// positions from Rng(seed, 0, 0)), traced with sim::BeamTracer (sim::trace's results bit for bit),
// handed to fn(j0, m, x, results) a block of m rays at a time, in order. Returns false when
// *cancel was set (checked between blocks of sim::BeamTracer::kBlock rays), true when every ray was traced.
using RayBlockFn = std::function<void(long j0, int m, const double* x, const sim::TraceResult* results)>;
bool trace_beam_rays(const GrooveParams& groove, double theta_i, long rays, sim::Sampling sampling, std::uint64_t seed,
                     int max_bounces, const RayBlockFn& fn, const std::atomic<bool>* cancel = nullptr);

// The rows of a tally of `rays` rays (bins with rays), and the largest exit-angle spread in a bin.
std::vector<BounceRow> tally_rows(const sim::Tally& tally, long rays, double* max_spread);
// `vgroove trace --json` for that tally.
nlohmann::json trace_json(const GrooveParams& groove, double theta_i_deg, long rays, sim::Sampling sampling,
                          long long seed, int max_bounces, const sim::Tally& tally);

}  // namespace vgroove::validation
