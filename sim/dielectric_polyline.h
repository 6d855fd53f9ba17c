// vgroove sim: exact 2D tracing of light across a periodic polyline profile (sim/polyline.h; the
// random profiles of sim/random_profile.h) that separates two dielectrics: medium 1 (index n1)
// above, medium 2 (n2) below, eta = n2 / n1, light from above or below. At every hit: the exact
// dielectric Fresnel reflectance at the local angle, Snell's law, total internal reflection
// (sim/dielectric_interaction.h, as the groove tracers). Refracted light travels on in medium 2
// and meets the profile again from below (the undersides of neighbouring ridges): traced, never
// dropped; a path that leaves downward (past the lowest vertex) is transmitted into medium 2, one
// that leaves upward is in medium 1. The geometry is the polyline tracer's (sim/polyline_tracer.h:
// first_hit_from_top / first_hit_from above the profile, first_hit_from_bottom /
// first_hit_from_below under it), so with F forced to 1 (DielectricOptions::conductor_limit) every
// path is trace_polyline's bit for bit. Random branching (one path per ray, Fresnel-weighted
// choice from the caller's stream) is what rough profiles need; split branching follows both
// branches with their weights. Conservation: left (both sides) + cut + bounce limit + vertex hits
// = 1 per ray (exactly in random branching, to rounding in split).
// Tests: tests/sim/dielectric_polyline_test.cpp (DielectricPolyline.EnergyIsConservedPerRay,
// DielectricPolyline.AFlatProfileIsFresnelAndSnell, DielectricPolyline.EtaOnePassesStraightThrough,
// DielectricPolyline.ConductorLimitIsThePolylineTracerBitForBit, DielectricPolyline.GrazingLightNeverGivesNaN,
// DielectricPolyline.RaysMeetTheProfileFromBelow, DielectricPolyline.LightFromBelowIsTheMirrorImageOfLightFromAbove,
// DielectricPolyline.SplitAndRandomBranchingAgree,
// DielectricPolyline.BadInputIsRefused).
// Derivation: docs/derivations/smith_walk_dielectric.md (the tracer's section).
#pragma once

#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/sim/polyline.h"
#include "vgroove/sim/polyline_tracer.h"
#include "vgroove/sim/rng.h"

namespace vgroove::sim {

class DielectricPolylineTracer {
 public:
  // Throws std::invalid_argument naming the field and its range (as DielectricGrooveTracer). The
  // profile is referenced, not copied: it must outlive the tracer.
  DielectricPolylineTracer(const Polyline& p, const DielectricOptions& opt);

  const Polyline& profile() const { return p_; }
  const DielectricOptions& options() const { return opt_; }

  // Traces one ray of light arriving from `from`: from above it crosses the top line y = y_max at
  // x, travelling along dir (unit, dir.y < 0); from below it crosses the bottom line y = y_min at x
  // (dir.y > 0). x in [x_0, x_0 + period) (else std::invalid_argument, as for a direction on the
  // wrong side). `out` is cleared first (its work list kept); `rng` is drawn from in random
  // branching only, once per hit with F < 1. Exits' `first` is the orientation of the segment
  // hit first: left_facet when its normal leans right (n.x > 0, a V-groove's left facet), else
  // right_facet. Exits' PendingHit::groove is the segment index. Const and without state.
  DielectricResult& trace(double x, const Vec2& dir, Medium from, Rng& rng, DielectricResult& out) const;

 private:
  const Polyline& p_;
  PolylineLows lows_;  // the pyramid of lowest vertices, for paths under the profile
  DielectricOptions opt_;
};

}  // namespace vgroove::sim
