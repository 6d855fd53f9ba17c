// vgroove sim: exact 3D tracing across dielectric V-grooves extruded along their axis u, by lifting
// the flatland tracers (sim/dielectric_groove.h, sim/dielectric_microsurface.h): a 3D direction is
// d = r e + q u (e the unit cross-section direction), n d.u is conserved at every hit, and the
// cross-section traces e with detail::LiftedLaw (sim/dielectric_lifted_law.h: Fresnel and total
// internal reflection at the 3D local angle, Snell with the effective index). Exits lift back as
// r_s e + q_s u in the medium s they left into. Unpolarized Fresnel only (the plane of incidence
// turns from hit to hit). Weights, k, R/T signatures, sides and the energy accounts are the
// cross-section's: left + cut + bounce limit + vertex = 1 per ray to rounding.
// Holds: a direct 3D tracer of the extruded groove as a triangle mesh to rounding; a flat interface
// is 3D Fresnel and Snell; eta = 1 passes straight; the conductor limit is trace_groove3d bit for bit.
// Tests: tests/sim/dielectric_lifted_test.cpp (DielectricLifted.AgreesWithTheExtrudedMeshTracer,
// DielectricLifted.ConductorLimitIsTheLiftedConductorTallyBitForBit,
// DielectricLifted.AFlatInterfaceIsFresnelAndSnellIn3d, DielectricLifted.NoAxisComponentIsTheFlatlandTracer,
// DielectricLifted.EnergyIsConservedToRounding). Derivation: docs/derivations/dielectric_lifting.md.
#pragma once

#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/sim/dielectric_lifted_law.h"
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/sim/microsurface3d.h"

#include <vector>

namespace vgroove::sim {

// What one 3D ray became: the cross-section's paths and their 3D exit directions.
struct LiftedResult {
  DielectricResult flat;   // weights, k, signatures, sides, energy accounts (exits' dir: e)
  std::vector<Vec3> dirs;  // dirs[i]: flat.exits[i]'s 3D travel direction (world frame)
};

// A 3D ray in a groove frame's cross-section: its unit cross-section direction e, and the law of
// its hits (the lengths r and axis components q of a unit direction in each medium).
struct LiftedRay {
  Vec2 e = Vec2::Zero();
  double q[2] = {0.0, 0.0};  // d.u, by Medium
  detail::LiftedLaw law;
};

// The cross-section of the unit world direction d (macro normal +z) of light travelling in medium
// `from`: r and e from (d.a, d.n) as trace_groove3d forms them; the other medium's q = p / n_k, its
// r = sqrt((1 - q)(1 + q)) (0 when |q| >= 1: that medium cannot be reached).
LiftedRay lift_ray(const Vec3& d, const GrooveFrame3d& frame, Medium from, const DielectricOptions& opt);
// The 3D direction r_s e + q_s u of a cross-section exit into medium `side`.
Vec3 lift_exit(const LiftedRay& ray, const GrooveFrame3d& frame, const Vec2& e, Medium side);

// One groove in a flat interface (sim/dielectric_groove.h's), extruded along frame.u().
class LiftedGrooveTracer {
 public:
  // Throws std::invalid_argument naming the field and its range (as DielectricGrooveTracer, and
  // polarization: unpolarized only).
  LiftedGrooveTracer(const Groove& g, const GrooveFrame3d& frame, const DielectricOptions& opt);

  // Light from `from` travelling along the unit direction d (d.z < 0 from above, > 0 from below,
  // else std::invalid_argument), its line crossing the rim plane at x across the groove (the
  // groove's cross-section coordinate along frame.a(), apex at x = 0). Const, without state.
  LiftedResult& trace(const Vec3& d, double x, Medium from, Rng& rng, LiftedResult& out) const;

 private:
  DielectricGrooveTracer flat_;
  GrooveFrame3d frame_;
};

// A procedural surface (sim/dielectric_microsurface.h's) extruded along frame.u().
class LiftedSurfaceTracer {
 public:
  // As LiftedGrooveTracer's; the surface must outlive the tracer.
  LiftedSurfaceTracer(const Microsurface& surface, const GrooveFrame3d& frame, const DielectricOptions& opt);

  const DielectricSurfaceTracer& flatland() const { return flat_; }
  // Light from above landing in groove `groove` at x on its rim line (its own frame), d.z < 0.
  LiftedResult& trace_from_above(int groove, double x, const Vec3& d, Rng& rng, LiftedResult& out) const;
  // Light from below whose line crosses z = -depth_max() at x (groove widths), d.z > 0.
  LiftedResult& trace_from_below(double x, const Vec3& d, Rng& rng, LiftedResult& out) const;

 private:
  const Microsurface& surface_;
  DielectricSurfaceTracer flat_;
  GrooveFrame3d frame_;
};

}  // namespace vgroove::sim
