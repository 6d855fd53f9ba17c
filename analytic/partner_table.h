// vgroove analytic: the tabulated inverse CDF of P(theta_r) (Eq. 20, partner_distribution.h) that
// a nonsymmetric sampler draws the partner's tilt from (Lee et al. 2018, "Practical Multiple
// Scattering for Rough Surfaces", Sec. 6: tabulated inverse CDF, binary search), 3D (P) and
// flatland (P2). The table is a density of its own: P_tab piecewise linear between nodes dense
// where D lives and uniform nodes, scaled to integrate to 1, its CDF piecewise quadratic
// (sample_partner: binary search, one square root); partner_table_pdf(B) = P_tab(B).
// Accuracy: int |P_tab - P| dB (partner_table_l1_error) below 1e-5 at the default N = 2048 for
// every NDF with 0.01 <= alpha <= 2 (Phong: alpha <= 1; Phong above 1 is refused).
// Tests: tests/analytic/partner_table_test.cpp (PartnerTable.ErrorIsBounded,
// PartnerTable.CoarseTableExceedsTheBound, PartnerTable.IsADensity, PartnerTable.SampleInvertsTheCdf,
// PartnerTable.RefusesPhongWithoutAPartnerLaw).
// Derivation: docs/derivations/nonsymmetric.md.
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
