// vgroove analytic: the share of a lit facet's draws that returns no direction, the integrand's
// factor of the samplers' failure probabilities (sampling_3d.cpp, sampling_flatland.cpp).
//
// The routine (sampling_3d.h) draws among the k - 1 reflections (width f_a - f_k), the k
// reflections (f_k - f_b) and, with the printed strategy only, the rays that meet the other facet
// first (f_b, over the total f_a; the other strategies draw over f_a - f_b). Of these, no direction
// is returned for the shadowed share (printed) and for the outcomes beyond max_k: all of them when
// even the fewer reflections exceed max_k (set exactly: for narrow grooves near grazing light
// f_a, f_k, f_b are all close to 1 and their differences ~ v cos(t) lose their digits, down to 0),
// near Eq. (4)'s boundary K = max_k + 1 only the k-reflection outcome. beyond_only: the part from
// max_k alone.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"

namespace vgroove::analytic {

inline double facet_failure_share(const FacetPrediction& p, int max_k, bool printed, bool beyond_only) {
  const double w_fewer = p.f_a - p.f_k, w_more = p.f_k - p.f_b;
  const bool all_lost = p.fewer.n > max_k, more_lost = p.more.n > max_k;
  if (all_lost) return printed && beyond_only ? (w_fewer + w_more) / p.f_a : 1.0;
  if (printed) return ((beyond_only ? 0.0 : p.f_b) + (more_lost ? w_more : 0.0)) / p.f_a;
  return more_lost && w_fewer + w_more > 0.0 ? w_more / (w_fewer + w_more) : 0.0;
}

}  // namespace vgroove::analytic
