// vgroove sim: procedural V-groove surfaces between two dielectrics as the rough-glass suites use
// them (validation/dielectric_brdf_suite.h, validation/glass_energy.h): equal-width symmetric grooves,
// flatland with the facet law of make_microsurface, 3D with theta_m from 2 pi D cos sin (the grooves
// lifted, their axis at a uniform azimuth drawn per ray); and one ray's lit point and trace on them.
// Holds: the same draws in the same order for every caller (the lit point, then in 3D the axis), so
// a suite's counts depend only on its seeds.
// Tests: tests/validation/dielectric_brdf_suite_test.cpp (DielectricBrdfSuite.*),
// tests/validation/glass_energy_test.cpp (GlassEnergy.*).
#pragma once

#include "vgroove/sim/dielectric_lifted.h"
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/sim/microsurface.h"

namespace vgroove::sim {

// Flatland: make_microsurface(o). 3D: o.grooves grooves, groove j's theta_m from 2 pi D cos sin with
// the uniform of Rng(o.seed, kGrooveStream, j), the steepest just below pi/2.
Microsurface make_dielectric_vgroove_surface(const MicrosurfaceOptions& o, bool three_d);

// One ray: the lit point a uniform x in [0, grooves) (from above groove floor(x) at the same fraction
// across its opening; from below the place x in the period), the light travelling along flat_dir
// (flatland) or along dir3 with the grooves' axis at azimuth pi u (3D, u the next uniform, the ray
// lifted into the cross-section by lift_ray). The result in r; the 3D frame and lifted ray returned
// (lift_exit(ray, frame, e.dir, e.side) gives an exit's world direction; default in flatland).
struct DielectricVgrooveRay {
  GrooveFrame3d frame;
  LiftedRay ray;
};
DielectricVgrooveRay trace_dielectric_vgroove_ray(const DielectricSurfaceTracer& tracer, const Microsurface& surface,
                                                  bool three_d, Medium from, const Vec2& flat_dir, const Vec3& dir3,
                                                  const DielectricOptions& opt, Rng& rng, DielectricResult& r);

}  // namespace vgroove::sim
