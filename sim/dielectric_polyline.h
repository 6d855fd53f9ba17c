// vgroove sim: exact 2D tracing of light across a periodic polyline profile (sim/polyline.h, the
// random profiles of sim/random_profile.h) between two dielectrics: medium 1 above, medium 2 below,
// eta = n2 / n1, light from either side. Each hit: exact Fresnel at the local angle, Snell, total
// internal reflection (sim/dielectric_interaction.h). Refracted light travels on under the profile
// and meets it again from below (traced, never dropped); a path leaving downward is in medium 2,
// upward in medium 1. Geometry: sim/polyline_tracer.h (above and under the profile), so the
// conductor limit is trace_polyline bit for bit. Random or split branching; left + cut + limit +
// vertex = 1 per ray. Tests: tests/sim/dielectric_polyline_test.cpp (DielectricPolyline.EnergyIsConservedPerRay,
// DielectricPolyline.AFlatProfileIsFresnelAndSnell, DielectricPolyline.EtaOnePassesStraightThrough,
// DielectricPolyline.ConductorLimitIsThePolylineTracerBitForBit, DielectricPolyline.GrazingLightNeverGivesNaN,
// DielectricPolyline.RaysMeetTheProfileFromBelow, DielectricPolyline.LightFromBelowIsTheMirrorImageOfLightFromAbove,
// DielectricPolyline.SplitAndRandomBranchingAgree, DielectricPolyline.BadInputIsRefused,
// DielectricPolyline.ADownwardRayJustAboveTheFloorMeetsTheNextValley).
// Derivation: docs/derivations/smith_walk_dielectric.md.
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
