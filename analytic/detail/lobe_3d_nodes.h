// vgroove analytic (internal to lobe_3d.cpp): the terms of the Gauss-Legendre nodes of a run of
// pieces, and the tail's strata, four at a time. The same integrand as the scalar kernels
// (lobe_3d.cpp, piece_sum and weight_fast), lane by lane, within rounding: at nodes in theta_m
// Eq. (6)'s f_k from one polynomial sine of the angle (weight_fast's f_k_of) instead of the complex
// power, Beckmann's and Phong's D by exp and pow, and at nodes in w their inverse CDFs by log and
// expm1, from the polynomials of exp_log_batch.h (within 2 ulp, plus the exponent's rounding)
// instead of the library's; the rest is the scalar arithmetic in its order (GGX's nodes in w: the
// same bits). Each NDF's D and inverse CDF are its own templates (ndf_visit.h), the same code as
// the scalar kernels' at double.
#pragma once

#include "vgroove/common/ndf_kind.h"

namespace vgroove::analytic::lobe_nodes {

// One piece of one facet's k-reflection outcome (lobe_3d.cpp, piece_sum).
struct Piece {
  NdfKind ndf;
  double alpha;
  double sin_tau;  // sin of the projected incident angle, negated for the right facet
  double cos_tau;
  double tf;  // the facet's projected incident angle (tau, or -tau for the right facet)
  int k;      // the outcome's reflections
  int K;      // Eq. (4)'s K on the piece
  bool in_w;  // nodes in w = sqrt(CDF) (else in theta_m)
};

// terms[q] = rule_w[q] * weight(node q) * density(node q) for the nodes v[q], q < n, n a multiple
// of 4 (the pieces of a run share k, K and the variable): the weight of Eq. (6) per unit CDF (weight_piece) and the
// density 2 w (in w) or 2 pi D cos sin (in theta_m).
void piece_terms(const Piece& p, int n, const double* v, const double* rule_w, double* terms);

// The tail's strata of one groove azimuth and facet (lobe_3d.cpp, integrate_tail): 1 - u = lead
// entry (Phong cos theta_m = lead entry, Beckmann log(1 - u) = lead + entry; tail_strata_table).
struct TailStrata {
  NdfKind ndf;
  double alpha;
  double lead;
  double sin_tau;  // as Piece::sin_tau
  double cos_tau;
  double tf;  // the facet's projected incident angle (tau, or -tau for the right facet)
};

// Per stratum q < n (n a multiple of 4; table holds n entries): the aperture theta_v, Eq. (4)'s K
// (saturated as saturate_to_int, as a double), the offsets f_a, f_b and the clamped f_k of
// Eq. (6), and the opening's width w = 2 cos theta_m cos tau, by weight_fast's arithmetic lane by
// lane (floor exact; no value depends on the lane width).
void tail_strata(const TailStrata& t, int n, const double* table, double* theta_v, double* K, double* f_a, double* f_b,
                 double* f_k, double* w);

}  // namespace vgroove::analytic::lobe_nodes
