// vgroove analytic (internal to lobe_3d.cpp): the terms of one piece's Gauss-Legendre nodes, four
// nodes at a time. The same arithmetic as the scalar kernels (lobe_3d.cpp, piece_sum), in the same
// order, lane by lane: the same bits, but for Beckmann's and Phong's D at nodes in theta_m and
// their inverse CDFs at nodes in w, whose exp, expm1, log and pow come from the polynomials of
// exp_log_batch.h (within 2 ulp, plus the exponent's rounding) instead of the library's.
#pragma once

#include "vgroove/common/ndf_kind.h"

namespace vgroove::analytic::lobe_nodes {

// One piece of one facet's k-reflection outcome (lobe_3d.cpp, piece_sum).
struct Piece {
  NdfKind ndf;
  double alpha;
  double sin_tau;  // sin of the projected incident angle, negated for the right facet
  double cos_tau;
  int k;      // the outcome's reflections
  int K;      // Eq. (4)'s K on the piece
  bool in_w;  // nodes in w = sqrt(CDF) (else in theta_m)
};

// terms[q] = rule_w[q] * weight(node q) * density(node q) for the nodes v[q], q < n, n a multiple
// of 4: the weight of Eq. (6) per unit CDF (weight_piece) and the density 2 w (in w) or
// 2 pi D cos sin (in theta_m).
void piece_terms(const Piece& p, int n, const double* v, const double* rule_w, double* terms);

}  // namespace vgroove::analytic::lobe_nodes
