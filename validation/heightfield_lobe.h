// vgroove validation: the light of random heightfields (sim/heightfield.h), traced exactly in 3D
// (sim/heightfield_tracer.h) and binned: what the "heightfield" suite (heightfield_suite.h) and
// check_brdf with surface "heightfield" (check_brdf.h) hold their models against.
//
// Fields: Beckmann (a Gaussian field with Gaussian autocorrelation, isotropic alpha), GGX (the
// Gaussian field through the GGX height map) or random-orientation V-grooves of either's tilts,
// field_size^2 cells, correlation length l cells; realization r has its own seed, the same for
// every incidence. Rays land at uniform points of the period from the light at azimuth pi, so that
// the bins are check_brdf's and analytic/lobe_3d.h's: theta_o in [0, pi/2) in theta_bins equal
// bins, phi_o in phi_bins bins centred on the mirror azimuth 0. Memory: heightfield_bytes(n) per
// field held at once (one per worker, either surface), refused before any work in one line when a
// field does not fit this process's share of memory (check_field_fits).
// Tests: tests/validation/heightfield_suite_test.cpp, tests/validation/heightfield_check_brdf_test.cpp.
#pragma once

#include "vgroove/analytic/ndf_anisotropic.h"
#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/heightfield_grooves.h"
#include "vgroove/sim/heightfield_tracer.h"

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace vgroove::validation {

// The kind of field: Gaussian (the Beckmann field, or the Gaussian field through the GGX height
// map) or random-orientation finite V-grooves (sim/heightfield_grooves.h) of the NDF's tilts.
enum class HeightfieldSurfaceKind : unsigned char { gaussian, grooves };
const char* heightfield_surface_name(HeightfieldSurfaceKind k);  // "gaussian", "grooves"

struct HeightfieldFieldSpec {
  NdfKind ndf = NdfKind::beckmann;  // beckmann or ggx
  double alpha = 0.5;
  int field_size = 256;             // cells per side: a power of two in [16, 65536]
  double correlation_length = 8.0;  // cells, in [2, field_size / 8] (grooves: [2, field_size / 12])
  HeightfieldSurfaceKind surface = HeightfieldSurfaceKind::gaussian;
  double aspect = 1.0;  // alpha_y / alpha (Beckmann Gaussian fields only; alpha is alpha_x)
};

// The groove field of correlation length l: grooves 3 l long, 3 l apart (about n^2 / (9 l^2)
// grooves), seeds l / 2 apart along each (at l = 8 the groove field's own defaults).
sim::GrooveFieldOptions groove_field_options(const HeightfieldFieldSpec& spec, std::uint64_t seed);

// The field of realization `seed` (sim::make_gaussian_heightfield / make_ggx_heightfield, or
// sim::make_random_groove_field) with its hierarchy.
sim::HeightfieldSurface make_field_surface(const HeightfieldFieldSpec& spec, std::uint64_t seed);

// Refuses (support::UserError, one line) a field of `field_size` cells per side when `workers`
// of them (one per worker) do not fit this process's memory (support::memory_limit_bytes): `what`
// names the field's key; the message gives its bytes (sim::heightfield_bytes), the budget per
// field and the allowed range [min_size, sim::heightfield_max_n(budget)] of powers of two.
void check_field_fits(int field_size, double workers, const std::string& what, int min_size);

// Independent surface patches of `fields` fields of n^2 cells with correlation length l: fields
// n^2 / (pi l^2), the area over the correlation area of the Gaussian autocorrelation (the
// variance of a field mean over area A is sigma^2 pi l^2 / A). Plays the part of the grooves in
// the noise bound of histogram_metrics.h (a ray picks one of the patches).
double heightfield_patches(int field_size, double correlation_length, int fields);

// One field's rays at theta_i (radians), chunk by chunk (sim::trace_heightfield_chunk), merged
// in chunk order: max_k as sim::HeightfieldTraceOptions (rows k = 0..max_k and one beyond). The
// tally is incomplete when *cancel was set (the caller discards it).
sim::HeightfieldTally trace_field(const sim::HeightfieldSurface& s, double theta_i, long rays, std::uint64_t seed,
                                  int theta_bins, int phi_bins, int max_k, const std::atomic<bool>* cancel = nullptr);

// The Smith random walk (analytic/smith_walk_3d.h) from dir3(theta_i, pi), binned as trace_field
// bins (the same tally type): `paths` walks from `seed` in chunks of sim::kHeightfieldRaysPerChunk.
sim::HeightfieldTally walk_lobe(NdfKind ndf, double alpha, double theta_i, long paths, std::uint64_t seed,
                                int theta_bins, int phi_bins, int max_k, const std::atomic<bool>* cancel = nullptr);

// The same for anisotropic roughness (alpha_x along the x axis, the mirror azimuth 0): the
// Roughness walk of analytic/smith_walk_3d.h (heights log C1, or `heights`).
sim::HeightfieldTally walk_lobe(const analytic::Roughness& r, double theta_i, long paths, std::uint64_t seed,
                                int theta_bins, int phi_bins, int max_k, const std::atomic<bool>* cancel = nullptr);
sim::HeightfieldTally walk_lobe(const analytic::Roughness& r, analytic::WalkHeights heights, double theta_i, long paths,
                                std::uint64_t seed, int theta_bins, int phi_bins, int max_k,
                                const std::atomic<bool>* cancel = nullptr);

// Joint fractions of the tally's rays per (row, bin) for rows k = first_row..last row, row by row.
std::vector<double> joint_fractions(const sim::HeightfieldTally& t, int first_row);

}  // namespace vgroove::validation
