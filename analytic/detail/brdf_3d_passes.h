// vgroove analytic (internal to brdf_3d*.cpp): the two evaluation passes of Eq. (16)-(17) over the
// solutions of kaleidoscope_solutions.h, for a pair whose groove frame is known (brdf_3d.h).
// brdf_per_solution (brdf_3d.cpp) computes each solution's term on its own (for_each_solution);
// brdf_batched (brdf_3d_batch.cpp) takes the same solutions four at a time without branches and
// is the pass vgroove_brdf runs. Not part of the API: names may change.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 5.1 (Eq. 13-17). The derivation is in brdf_3d.h.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf.h"

namespace vgroove::analytic::brdf_passes {

// groove_frame's fields rounded differently, its angles within a few ulp of groove_frame's
// (brdf_3d.cpp says where it is groove_frame itself): the batched GGX and Beckmann passes' frame.
bool groove_frame_fast(const Dir3& i, const Dir3& o, GrooveFrame& p);

// Eq. (16) summed over k = k_lo..k_hi (k_lo >= 1) for a pair with the frame p, cos_i = i.n,
// cos_o = o.n > 0.
double brdf_per_solution(const GrooveFrame& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf,
                         double alpha, const FresnelFn& F);
// How brdf_batched takes Beckmann's terms (without Fresnel; brdf_3d_batch.cpp): exact, those whose
// exponent tan^2 theta_m / alpha^2 exceeds 32 from std::sin, std::cos and std::exp (any frame);
// vector, every term from the polynomials, for groove_frame_fast, NaN where the pass's bound
// on its deviation from the per-solution pass fails (for exact in groove_frame to take).
enum class BeckmannTails { exact, vector };
// The vector mode's bound on the terms' weighted mean amplification y (brdf_3d_batch.cpp): a
// deviation of up to ~2e-13 from the per-solution pass.
inline constexpr double kBeckmannMeanAmplification = 64.0;
double brdf_batched(const GrooveFrame& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf, double alpha,
                    const FresnelFn& F, BeckmannTails tails = BeckmannTails::exact);

}  // namespace vgroove::analytic::brdf_passes
