// vgroove sim: exact 2D tracing of light across one V-groove that separates two dielectrics: the
// groove's two facets (sim/groove.h) and the flat rim line on either side, medium 1 (n1) above,
// medium 2 (n2) below, eta = n2 / n1, light from above or below. At every hit the ray splits by the
// exact dielectric Fresnel reflectance at its local angle (optics/fresnel.h), reflected and
// refracted by Snell's law (optics/snell.h), or reflects whole under total internal reflection;
// refracted light is traced on, never dropped. Between the facets a ray follows sim::trace's own
// arithmetic, so with F forced to 1 (DielectricOptions::conductor_limit) every path is sim::trace's
// bit for bit. Conservation: left (both sides) + cut + bounce limit + vertex hits = 1 per ray, to
// rounding. Tests: tests/sim/dielectric_groove_test.cpp (DielectricGroove.EnergyIsConservedToRounding,
// DielectricGroove.ConductorLimitIsTheConductorTracerBitForBit, DielectricGroove.AFlatInterfaceIsFresnelAndSnell,
// DielectricGroove.BeyondTheCriticalAngleEverythingReflects, DielectricGroove.GrazingLightNeverGivesNaN,
// DielectricGroove.RefractedLightMeetsTheInterfaceAgainFromBelow).
// Derivation: docs/derivations/dielectric_groove.md.
#pragma once

#include "vgroove/sim/groove.h"
#include "vgroove/sim/rng.h"
#include "vgroove/sim/tracer.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace vgroove::sim {

// The two media: medium 1 above the interface, medium 2 below.
enum class Medium : unsigned char { above = 0, below = 1 };
const char* medium_name(Medium m);

// The parts of the interface: the two facets (indexed as Side) and the flat parts outside the
// opening on the left and on the right.
enum class Part : unsigned char { left_facet = 0, right_facet = 1, left_flat = 2, right_flat = 3 };

// The Fresnel reflectance each hit uses. In flatland every hit's plane of incidence is the
// cross-section, so s- and p-polarized light stay so through every path, and the exact response to
// unpolarized light is the mean of the s and p traces; `unpolarized` applies the unpolarized F at
// each hit instead (the convention of the conductor tracer and of Lee et al. 2018, Eq. 11).
enum class Polarization : unsigned char { unpolarized, s, p };

// How a hit's two outgoing rays are followed.
enum class Branching : unsigned char {
  split,   // both, weighted F and 1 - F: the exact energy of every path (cut below min_weight)
  random,  // one, reflected with probability F (the weight stays 1), from the caller's stream
};

struct DielectricOptions {
  double eta = 1.5;  // n2 / n1, in (0, inf)
  Branching branching = Branching::split;
  Polarization polarization = Polarization::unpolarized;
  // split: a path whose weight falls below this is cut, its weight reported (DielectricResult::cut);
  // in [0, 1).
  double min_weight = 1e-12;
  // A path still in play after this many interactions ends there (its weight in bounce_limit); >= 0.
  int max_interactions = 100000;
  // F = 1 at every hit: the conductor tracer's mirror groove (a check on the tracer).
  bool conductor_limit = false;
};

// A path that left the interface.
struct DielectricExit {
  Vec2 dir = Vec2::Zero();  // travel direction (unit up to rounding)
  double weight = 0.0;      // its share of the ray's energy (1 in random branching)
  // Bit j set: interaction j (0-based) refracted (T); clear: reflected (R). Kept for j < 64; the
  // bits of longer paths are their first 64 interactions'.
  std::uint64_t path = 0;
  int k = 0;                      // interactions
  Medium side = Medium::above;    // the medium it left into
  Part first = Part::left_facet;  // the part the ray hit first
};

// The exit angle from the normal of the exit side (n above, -n below), counter-clockwise
// positive, in [-pi/2, pi/2]: above, angle_from_normal(dir); below, the angle phi with
// dir = (sin phi, -cos phi). A flat interface lit from above at theta_i (sim/beam.h's direction)
// reflects to -theta_i and refracts to asin(sin theta_i / eta).
double exit_angle(const DielectricExit& e);

namespace detail {
// A path about to interact with a part: at s along a facet, or at x on a flat part.
struct PendingHit {
  Vec2 d;
  double pos;
  double w;
  std::uint64_t path;
  int k;
  Part on;
  Medium in;       // the medium the path travels in
  int groove = 0;  // which groove of a surface (sim/dielectric_microsurface.h)
};
}  // namespace detail

// What one ray became.
struct DielectricResult {
  std::vector<DielectricExit> exits;
  double left[2] = {0.0, 0.0};  // energy that left, by Medium
  double cut = 0.0;             // energy of paths cut below min_weight
  double bounce_limit = 0.0;    // energy of paths still in play after max_interactions
  double vertex = 0.0;          // energy of paths that hit the apex or a rim exactly
  std::int64_t paths_cut = 0;
  std::int64_t interactions = 0;  // hits at which Fresnel and Snell were evaluated, over all paths
  int max_k = 0;                  // most interactions of any path (exits and ends alike)
  double total() const { return left[0] + left[1] + cut + bounce_limit + vertex; }
  // A path that left: recorded, its energy counted on its side, max_k raised to its k.
  void add_exit(const DielectricExit& e) {
    exits.push_back(e);
    left[static_cast<int>(e.side)] += e.weight;
    max_k = std::max(max_k, e.k);
  }
  void clear();
  std::vector<detail::PendingHit> pending;  // the splitting's work list, kept for reuse
};

// The tracer of one groove with one set of options (checked once, here).
class DielectricGrooveTracer {
 public:
  // Throws std::invalid_argument naming the field and its range (eta, min_weight,
  // max_interactions).
  DielectricGrooveTracer(const Groove& g, const DielectricOptions& opt);

  const Groove& groove() const { return g_; }
  const DielectricOptions& options() const { return opt_; }

  // Traces one ray of light arriving from `from`: ray.origin is where its line crosses the rim line
  // (y = rim_height) and ray.dir its unit travel direction, pointing down for light from above and
  // up for light from below (else std::invalid_argument). Light from below is traced from far
  // below: its first hit is the first crossing of its line with the interface. `out` is cleared
  // first (its work list kept); `rng` is drawn from in random branching only. Returns out. Const and
  // without state: one tracer serves any number of threads, each with its own out and rng.
  DielectricResult& trace(const Ray2& ray, Medium from, Rng& rng, DielectricResult& out) const;
  // trace() with another law of one hit: law(d, n, in, t) returns F and sets t as
  // detail::fresnel_split does (instantiated for detail::FlatlandLaw, trace()'s own, and
  // detail::LiftedLaw, sim/dielectric_lifted_law.h).
  template <class Law>
  DielectricResult& trace_with(const Ray2& ray, Medium from, const Law& law, Rng& rng, DielectricResult& out) const;

 private:
  using Pending = detail::PendingHit;
  // Where a path goes after leaving `on` (at pos) along d in `medium`: onto the next part (true,
  // p.on and p.pos filled) or out of the interface (false).
  bool advance(Part on, double pos, const Vec2& d, Medium medium, Pending& p) const;
  // The first part a ray of light from below meets; false when it meets a vertex or nothing.
  bool first_from_below(const Ray2& ray, Pending& p) const;
  bool first_from_above(const Ray2& ray, Pending& p, bool& vertex) const;

  Groove g_;
  DielectricOptions opt_;
};

}  // namespace vgroove::sim
