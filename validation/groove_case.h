// vgroove validation: one (theta_v, theta_i) configuration, traced and predicted.
//
// The error follows the paper's normalization of G (Lee et al. 2018, Eq. 6): for each facet the
// light reaches, N rays aimed at it (spread over its projected width f_a) are traced; the error
// is the L1 distance between the traced fractions per bounce count and G, with the shadowed rays
// (blocked by the other facet's rim) a bin of their own. With breakpoint placement the traced
// fractions are the measures of the zones of equal outcome (sim/zones.h, N the grid's rays). Rays the model has no bin
// for (vertex hits, the bounce limit, a different facet hit first) count against it in full. A case's error is the
// larger of its facets'.
#pragma once

#include "vgroove/validation/groove_suite.h"

#include <atomic>
#include <cstdint>

namespace vgroove::validation {

struct FacetOutcome {
  bool compared = false;  // the light reaches this facet
  double l1 = 0.0;
  std::int64_t rays = 0;
  std::int64_t bounces = 0;
  std::int64_t vertex_hits = 0;
  std::int64_t bounce_limit = 0;
  std::int64_t wrong_first = 0;  // aimed at this facet, hit the other one first
  int k = 0;                     // Eq. (4)
  double theta_o_error = 0.0;    // largest |traced - Eq. (5)| over the rays (radians)
  // Rays aimed exactly at the apex and the rims (CaseOptions::probe_vertices), kept out of l1.
  std::int64_t probe_rays = 0, probe_escaped = 0, probe_vertex_hits = 0, probe_blocked = 0, probe_bounce_limit = 0;
  bool non_finite = false;  // a NaN or infinity in any figure or exit direction
  // Breakpoint placement (sim/zones.h): the zones of distinct outcome found (vertex hits, points
  // or a few ulps, not counted), the grid's rays M, the grid cells with equal ends no certificate
  // covers, what may be missing there (their width, a fraction of the beam), and the
  // narrowest zone found, vertex hits left out (a fraction of the beam).
  long zones = 0;
  long grid = 0;
  long uncertified_cells = 0;
  double missed_bound = 0.0;
  double narrowest_zone = 0.0;
};

struct CaseOutcome {
  GrooveParams groove;
  double theta_i = 0.0;   // radians
  FacetOutcome facet[2];  // [left, right]
  double l1 = 0.0;        // max over compared facets
  std::int64_t rays = 0;
  std::int64_t bounces = 0;
  double theta_o_error = 0.0;
  bool non_finite = false;
};

// `stream` names the case's random stream (its index in the suite): with random sampling, the
// rays of facet f come from Rng(seed, stream, f), whichever thread runs the case.
// A degenerate groove (GrooveParams::degenerate) gives an outcome with no facet compared.
// `cancel` (may be null) is read every few million reflections; once set, the case stops early and
// its outcome is incomplete (the caller reports the run as interrupted).
CaseOutcome run_case(const GrooveParams& groove, double theta_i, const CaseOptions& opt, std::uint64_t stream,
                     const std::atomic<bool>* cancel = nullptr);

// The model's side of a case, whichever groove kind: shares of the rays aimed at `side`.
struct ModelShares {
  bool lit = false;
  int k = 0;  // Eq. (4), or k_b of Eq. (7)
  double f_a = 0.0;
  double shadow = 0.0;
  analytic::BounceShare share[4] = {{0, 0.0, 0.0}, {0, 0.0, 0.0}, {0, 0.0, 0.0}, {0, 0.0, 0.0}};
  int shares = 0;
};
ModelShares model_shares(const GrooveParams& groove, double theta_i, sim::Side side, analytic::Eq6Form form);
// The width of the beam that enters the opening, in the units of f_a, from both facets' shares
// ([left, right]): sum over lit facets of f_a times the G of its entering rays. The fraction of the
// entering beam with a share's bounce count is then G f_a / width, and these fractions sum to 1 to
// rounding for every groove and angle (the width is not f_a (1 - shadow): near grazing light the
// shadow is 1 - 1e-9 and the difference would lose the width to cancellation).
double entering_width(const ModelShares (&shares)[2]);
// Eq. (5) or Eq. (8) for n reflections.
double model_exit_angle(const GrooveParams& groove, double theta_i, int n, sim::Side side);
sim::Groove make_groove(const GrooveParams& groove);

}  // namespace vgroove::validation
