// vgroove analytic: the tabulated inverse CDF of P(theta_r) (Eq. 20, partner_distribution.h), the
// partner law a nonsymmetric V-groove sampler draws the second facet's tilt from (Lee et al. 2018,
// Sec. 6: "we tabulate its inverse CDF, and sample it in runtime using binary search"), in 3D (P)
// and flatland (P2).
//
// The table is a density of its own, so that a sampler's pdf can be exact for what it draws: P_tab
// is piecewise linear in B between the nodes atan(alpha tan(pi j / (2 N))) (dense where D lives,
// for every alpha) merged with the uniform nodes pi j / (2 N), j = 0..N (the heavy tails of GGX at
// small alpha), with P_tab(B_j) = P(B_j), scaled to integrate to 1. Its CDF is
// piecewise quadratic: sample_partner finds the cell by binary search over the CDF at the nodes and
// solves the quadratic in it (one square root). partner_table_pdf(B) is P_tab(B).
//
// The table's error is int |P_tab - P| dB (partner_table_l1_error, per cell by adaptive
// Gauss-Kronrod): the largest change of the expectation of any function bounded by 1 when P_tab
// replaces P. With the default N = 2048 it is below 1e-5 for every NDF with 0.01 <= alpha <= 2
// (Phong: alpha <= 1) (tests/analytic/partner_table_test.cpp; ~h^2, the interpolation error of a
// smooth density).
//
// Phong with alpha > 1 (exponent p < 0) has P ~ (pi/2 - B)^p, singular at pi/2 and, as p -> -1
// (alpha -> sqrt(2)), with nearly all its mass within ulps of pi/2: no table of nodes bounds its
// error, and make_partner_table refuses it (std::domain_error).
#pragma once

#include "vgroove/analytic/ndf.h"

#include <vector>

namespace vgroove::analytic {

struct PartnerTable {
  std::vector<double> B;    // nodes, 0 = B_0 < ... < B_N = pi/2
  std::vector<double> p;    // P_tab at the nodes (linear between)
  std::vector<double> cdf;  // int_0^{B_j} P_tab, cdf[N] = 1
};

inline constexpr int kPartnerTableCells = 2048;

// Throws std::domain_error where the partner law does not exist (Phong, alpha >= sqrt(2)) or is
// not tabulated (Phong, alpha > 1: header).
PartnerTable make_partner_table(NdfKind ndf, double alpha, bool flatland, int cells = kPartnerTableCells);

// B from u in [0, 1): binary search and the quadratic of the cell.
double sample_partner(const PartnerTable& t, double u);
// P_tab(B): 0 outside [0, pi/2].
double partner_table_pdf(const PartnerTable& t, double B);

// int_0^{pi/2} |P_tab - P| dB (P = P_theta_r or P2_theta_r).
double partner_table_l1_error(const PartnerTable& t, NdfKind ndf, double alpha, bool flatland);
// sup over the nodes' cells of |CDF_tab - CDF| at the nodes (the inverse CDF's error in u).
double partner_table_cdf_error(const PartnerTable& t, NdfKind ndf, double alpha, bool flatland);

}  // namespace vgroove::analytic
