// vgroove validation: one case of the dielectric single-groove suite (data/suites/dielectric_grooves.json):
// the kaleidoscopic dielectric model (analytic/kaleidoscope_dielectric.h) against exact split tracing
// of the groove (sim/dielectric_groove.h), to rounding by breakpoint search (sim/zones.h), and the
// light the single-groove model cannot know, measured by path signature: in the groove with flat
// rims, and on the periodic surface of that groove (sim/dielectric_microsurface.h).
//
// A ray's split tree is fixed by the facet (or flat part) it meets first and its chain's hit count n
// in medium 1: every refracted lobe's later fate in one groove does not depend on where the ray
// entered (docs/derivations/kaleidoscope_dielectric.md, KD-4), and its weights depend on directions
// only. So the zones of the conductor search, with the dielectric tracer deciding (first part, n),
// carry the exact traced energy of every path: the width of each zone times the weights of one ray
// traced inside it. Light from below (analytic/kaleidoscope_dielectric_below.h): the same search, every
// path signature's traced energy and exit angle against the model's lobes.
// Tests: tests/analytic/kaleidoscope_dielectric_test.cpp (KaleidoscopeDielectricTracer.*),
// tests/analytic/kaleidoscope_dielectric_below_test.cpp (KaleidoscopeDielectricBelowTracer.*).
#pragma once

#include "vgroove/analytic/kaleidoscope_dielectric.h"
#include "vgroove/analytic/kaleidoscope_dielectric_below.h"
#include "vgroove/common/side.h"

#include <atomic>
#include <cstdint>
#include <map>
#include <tuple>

namespace vgroove::validation {

struct DielectricGrooveCase {
  double theta_v = 0.0;  // aperture, (0, pi]
  double theta_i = 0.0;  // towards the light, (-pi/2, pi/2)
  double eta = 1.5;      // n2 / n1
  bool below = false;    // light from below (medium 2): analytic/kaleidoscope_dielectric_below.h
};

struct DielectricCaseOptions {
  long grid = 64;            // breakpoint search: stratified grid rays per lit facet
  long surface_rays = 2000;  // the periodic surface's measurement: stratified rays over the opening (0: none)
  // The surface's split paths below this weight are cut (reported): re-entering light starts new
  // chains, and without a cut the tree grows without bound.
  double surface_min_weight = 1e-9;
  int max_interactions = 100000;
};

// One facet hit first: everything a share of the rays aimed at it (the model's normalization f_a).
struct DielectricFacetOutcome {
  bool compared = false;
  int k = 0;            // Eq. (4)
  double f_a = 0.0;     // the facet's projected width
  double shadow = 0.0;  // the model's
  long zones = 0;       // of distinct outcome
  long traced = 0;      // rays traced by the search
  std::int64_t interactions = 0;
  long uncertified_cells = 0;
  double missed_bound = 0.0;     // zones the search may have missed, share of the facet's rays
  double l1 = 0.0;               // model against tracer over the model's paths (see run_dielectric_groove_case)
  double direction_error = 0.0;  // largest angle between a model lobe and a traced exit it names, radians
  double conservation = 0.0;     // largest |1 - total| of a traced ray
  double unknown = 0.0;          // traced: refracted at some hit j, then met the interface again
  double unknown_model = 0.0;    // the model's lobes that do not leave at once (KD-4)
  double unknown_recross = 0.0;  // traced: of `unknown`, crossed back into medium 1 at the next hit
  double reflected = 0.0, transmitted = 0.0;  // the model's (of the facet's rays)
};

struct DielectricCaseOutcome {
  DielectricGrooveCase c;
  DielectricFacetOutcome facet[2];  // by Side
  // Over both facets: the largest errors, and the shares of the rays entering the opening.
  double l1 = 0.0, direction_error = 0.0, conservation = 0.0, missed_bound = 0.0;
  // The model's own change when theta_i moves by kRoundingAngle either way (rounding_bound): what the
  // rounding of the inputs' angles alone can make of the comparison (large only where a share is
  // ill-conditioned: grazing light, the critical angle, Eq. 4's integer boundaries).
  double l1_bound = 0.0, direction_bound = 0.0;
  double unknown = 0.0, unknown_model = 0.0, unknown_recross = 0.0;
  double reflected = 0.0, transmitted = 0.0;  // the model's, of the entering rays
  long rays = 0;                              // traced by both searches
  std::int64_t interactions = 0;
  // The periodic surface of this groove: of the rays landing in an opening, refracted at some
  // hit j and meeting the surface again (a neighbouring ridge from below), and of these, the
  // share crossing back at that next hit; its stratification error is below 1 / surface_rays per
  // lobe boundary.
  long surface_rays = 0;
  double surface_unknown = 0.0, surface_recross = 0.0;
  double surface_cut = 0.0;  // cut below surface_min_weight, bounce limit and vertex hits (share of the rays)
  bool non_finite = false;
  double wall_s = 0.0;
};

// What every breakpoint search over the rays aimed at a facet counts, from either side.
struct ZoneSearchCounts {
  bool lit = false;
  double flat = 0.0;  // met a flat part first (from above: the model's shadow; from below: none, KD-5)
  double lost = 0.0;  // vertex hits, cut, bounce limit: no bin in the model
  long zones = 0, traced = 0, uncertified_cells = 0;
  std::int64_t interactions = 0;
  double missed_bound = 0.0, conservation = 0.0;
  bool non_finite = false;
};

// The exact traced energy of the rays aimed at one facet, by path class, as shares of them.
struct TracedFacetEnergy : ZoneSearchCounts {
  std::map<int, double> reflected;          // pure R chains by hit count n
  std::map<int, double> refracted;          // every path refracted first at hit j (prefix R^(j-1) T), by j
  std::map<int, double> direct;             // R^(j-1) T that left downward at once, by j
  std::map<int, double> direct_theta_t;     // their exit angle below (one traced ray's; zones agree to rounding)
  std::map<int, double> reflected_theta_o;  // the R chains' exit angle
  std::map<int, double> recross;            // R^(j-1) T T...: crossed back at hit j + 1, by j
};

// The breakpoint search over the rays aimed at `side` (grid rays + bisection to adjacent doubles).
TracedFacetEnergy trace_facet_energy(const DielectricGrooveCase& c, Side side, long grid, int max_interactions);

// Model against traced for one facet: l1 as run_dielectric_groove_case describes, the largest
// direction error, and the unknown shares.
DielectricFacetOutcome compare_facet(const analytic::DielectricFacetPrediction& model, const TracedFacetEnergy& traced);

// The angle by which rounding may move a traced ray's effective theta_i after up to 64 hits:
// 64 ulps of pi (each reflection rounds the direction by ~1 ulp).
inline constexpr double kRoundingAngle = 64.0 * 2.220446049250313e-16 * 3.141592653589793;

// The narrowest aperture compared: the tracer's path signatures hold 64 interactions, and a chain
// makes up to 2 pi / theta_v + 1 hits (plus one on the rim): 6 deg keeps every path within 62.
inline constexpr double kMinComparedApertureDeg = 6.0;

// The distance between two predictions of the same facet, as compare_facet sums it (shadow, R by
// n, T by j), and the largest change of a lobe's direction (dir, radians).
double prediction_distance(const analytic::DielectricFacetPrediction& a, const analytic::DielectricFacetPrediction& b,
                           double& dir);

// The model's rounding bound for one facet: the largest prediction_distance (and direction change)
// to the model at theta_i -+ kRoundingAngle.
double rounding_bound(const DielectricGrooveCase& c, Side side, double& dir);

// Light from below: a path class by its signature (path bits, interactions, left into medium 1).
using BelowSignature = std::tuple<std::uint64_t, int, bool>;

// Light from below: the exact traced energy of the rays aimed at one facet (the rim-line interval of
// sim::aimed_at: the same lines) per path signature, as shares of them, by the same breakpoint
// search (the outcome: the part met first and the chain's hit count in medium 1).
struct TracedBelowEnergy : ZoneSearchCounts {
  std::map<BelowSignature, double> energy;
  std::map<BelowSignature, double> theta;  // exit angle (sim::exit_angle; one traced ray's)
};
TracedBelowEnergy trace_facet_energy_below(const DielectricGrooveCase& c, Side side, long grid, int max_interactions);

// Light from below, model against traced for one facet: l1 = traced flat + lost + sum over every
// signature of |traced - model|; direction_error over the signatures both have.
DielectricFacetOutcome compare_facet_below(const analytic::DielectricBelowPrediction& model,
                                           const TracedBelowEnergy& traced);

// Light from below: prediction_distance and rounding_bound over the signatures.
double prediction_distance_below(const analytic::DielectricBelowPrediction& a,
                                 const analytic::DielectricBelowPrediction& b, double& dir);
double rounding_bound_below(const DielectricGrooveCase& c, Side side, double& dir);

// Throws std::invalid_argument naming the field and its range.
void check_dielectric_groove_case(const DielectricGrooveCase& c);

// The case. l1 sums over the facet's rays: |traced shadow - model shadow| + what the model has no bin
// for (vertex hits, cut, bounce limit) + sum_n |traced R^n - G_n prod F| + sum_j |traced prefix
// R^(j-1)T - lobe j| + sum_j |traced R^(j-1)T leaving at once - (lobe j if direct else 0)|.
DielectricCaseOutcome run_dielectric_groove_case(const DielectricGrooveCase& c, const DielectricCaseOptions& opt,
                                                 const std::atomic<bool>* cancel = nullptr);

}  // namespace vgroove::validation
