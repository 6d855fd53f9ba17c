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

// Eq. (16) summed over k = k_lo..k_hi (k_lo >= 1) for a pair with the frame p, cos_i = i.n,
// cos_o = o.n > 0.
double brdf_per_solution(const GrooveFrame& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf,
                         double alpha, const FresnelFn& F);
double brdf_batched(const GrooveFrame& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf, double alpha,
                    const FresnelFn& F);

}  // namespace vgroove::analytic::brdf_passes
