// vgroove validation: check_brdf for BSDFs (CheckBrdfOptions::eta, check_brdf.h): a rough-dielectric
// f(wi, wo) against the exact trace of the procedural V-groove surface between two dielectrics
// (eta = n2 / n1), in 3D lifted (sim/dielectric_lifted.h, patches of parallel grooves of uniform
// azimuth, as validation/glass_energy.h) or in flatland (sim/dielectric_microsurface.h), Fresnel's
// random choice at every hit, lit from `side` (above: wi = dir3(theta_i, pi); below: z negated).
// Each exit hemisphere has its own bins, theta_o from its own normal (flatland: sim::exit_angle's
// signed angle), phi_o centred on phi = 0; a bin's model flux is the integral of f |cos theta_o|.
// f is in flux form (analytic/walter.h): f |cos theta_o| d omega_o is the share of the incident
// flux leaving into d omega_o. Per case: the reflected and the transmitted lobe each (albedo R or
// T against its binomial error, L1 of the normalized lobe and of the flux fractions) and both as
// one lobe; pass = all hold.
// Tests: tests/validation/check_bsdf_test.cpp (CheckBsdf.TabulatedTraceOfAnotherSurfacePasses,
// CheckBsdf.WalterPassesAtSmallRoughness, CheckBsdf.BrokenBsdfsFail, CheckBsdf.BadValuesAndOptionsAreNamed,
// CheckBsdf.ResultsDoNotDependOnThreads, CheckBsdfLong.WalterAgainstTheSurface).
// Derivation: docs/derivations/validation.md (the brdf suite and its thresholds, per hemisphere).
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/validation/check_brdf.h"
#include "vgroove/validation/traced_lobe.h"

#include <vector>

namespace vgroove::validation {

// Throws support::UserError naming eta, or the surface, when o.eta is set and out of its range.
void check_bsdf_options(const CheckBrdfOptions& o);

// The light's direction (towards it) at theta_i (radians) from `side`'s normal, azimuth pi.
analytic::Dir3 bsdf_light(double theta_i, sim::Medium side);

// The traced lobes at every incidence (radians): flux[0, B) the hemisphere above (z > 0), flux[B,
// 2 B) the one below, B = o's bins of one hemisphere; rays that never leave (bounce limit, vertex)
// are in neither. Items (incidence, chunk), counts merged in order: the same for any thread count.
// Empty when *o.cancel was set.
std::vector<TracedLobe> trace_bsdf_lobes(const CheckBrdfOptions& o, const std::vector<double>& theta_i, int threads);

// The case from both hemispheres' traced and model fluxes (as trace_bsdf_lobes lays them out), N
// rays over o.grooves, thresholds widened by `tolerance`.
CheckBrdfCase check_bsdf_lobes(const std::vector<double>& sim, const std::vector<double>& model, double rays,
                               const CheckBrdfOptions& o, double tolerance);

}  // namespace vgroove::validation
