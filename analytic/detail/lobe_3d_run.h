// vgroove analytic (internal to lobe_3d*.cpp): what the 3D lobe's integration (lobe_3d.h) shares
// between its parts: the cut points both paths use (lobe_3d_cuts.cpp), the plain reference kernels
// (lobe_3d_reference.cpp), the fast kernels (lobe_3d_fast.cpp) and the driver (lobe_3d.cpp). The run's
// constants, one groove azimuth's cross-section, a node's scratch, the bins and the deposits. Not
// part of the API: names may change.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 5.1 (Eq. 10-17).
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <utility>
#include <vector>

namespace vgroove::analytic::lobe_detail {

enum class LobeModel { vgroove, cook_torrance };

struct LobeRun {
  NdfKind ndf;
  double alpha;
  double theta_i;
  int tb, pb, max_k;
  LobeModel model;
  std::vector<double>* acc;      // where the deposits go: [row][t][p], as Lobe3d::hist_by_k
  bool fast = true;              // the kernels without per-node trigonometry (lobe_3d.cpp); false: the reference ones
  double m_half = 0.0;           // the median of theta_m over the grooves' area
  std::vector<double> cos_edge;  // cos of the theta_o bin edges, b = 0..tb (decreasing)
  bool four_node_pieces = true;  // Lobe3dOptions::four_node_pieces
  // The fast kernels' tail strata (tail_strata_table) for Lobe3dOptions::tail_strata and light_tail_strata.
  std::vector<double> tail_table, light_tail_table;
};

// One groove azimuth: the geometry of the cross-section.
struct Azimuth {
  double tau;               // projected incident angle t_i
  double iu;                // i.u
  double c;                 // sqrt(1 - iu^2)
  double ca, sa;            // cos, sin phi_a
  double sin_tau, cos_tau;  // of tau
};

// The facet's projected incident angle: tau for the left facet, -tau for the right (its mirror image).
inline double facet_tau(const Azimuth& az, FacetSide side) { return side == FacetSide::left ? az.tau : -az.tau; }

// What one phi_a node computes, kept between its bands.
struct Scratch {
  std::vector<double> T, X;
  std::vector<double> F;    // integrate_band: where the outcome changes form (X without the crossings)
  std::vector<char> live;   // integrate_band: whether the outcome's weight is positive from F[f] to F[f + 1]
  std::vector<double> wX;   // integrate_band: sqrt(CDF) at the crossings X, -1 not yet known
  double band_total = 0.0;  // flux deposited by the bands at this node
  std::vector<std::pair<size_t, double>> tail;  // the tail's deposits at this node
  // The bin of each segment between consecutive crossings T (constant there: T holds every exit
  // angle where a bin edge or the horizon is crossed), found at the segment's middle when first
  // asked for; -2 not yet known. With it, its mirror image's (mirror_of).
  std::vector<int> segment_bin, segment_mirror;
  std::size_t segment_hint = 0;  // where bin_by_segment found the last exit
  // integrate_tail: the strata's theta_v, K, f_a, f_b, f_k and w (lobe_nodes::tail_strata).
  std::vector<double> strata;
  // integrate_band (LobeRun::fast): the band's pieces of theta_m and w, their nodes, and the
  // segments they make up, summed once every piece's nodes are evaluated (flush_band).
  struct Piece {
    double b0, b1;
    int order;
    bool in_w;
    int K;
    std::size_t node;  // its first node in node_v (order >= 4), placed by flush_band
    double sum;        // order 2: its sum (piece_sum)
  };
  struct Segment {
    int bin, mirror;
    std::size_t first, count;  // its pieces
  };
  std::vector<Piece> pieces;
  std::vector<Segment> segments;
  std::size_t nodes = 0;                           // the pieces' nodes (order >= 4)
  std::vector<double> node_v, node_w, node_terms;  // sized to the most nodes a band has had
};

// The bin of the mirror image phi_o -> -phi_o of the exit in bin `bin`: (t, p) -> (t, -p mod phi_bins).
inline int mirror_of(const LobeRun& r, int bin) {
  const int t = bin / r.pb, p = bin % r.pb;
  return t * r.pb + (r.pb - p) % r.pb;
}

// The first index of row k's bins (every k > max_k in the last row).
inline std::size_t row_start(const LobeRun& r, int k) {
  const int row = std::min(k, r.max_k + 1);
  return static_cast<size_t>(row) * r.tb * r.pb;
}

// A segment's flux val (the phi_a weight applied) into its bin and the mirror image's: the mirror
// image pi - phi_a of the groove (y -> -y) sends the same flux to phi_o -> -phi_o.
inline void deposit_band(const LobeRun& r, std::size_t start, int bin, int mirror, double val, Scratch& sc) {
  std::vector<double>& acc = *r.acc;
  acc[start + bin] += val;
  acc[start + mirror] += val;
  sc.band_total += 2.0 * val;
}

// A tail deposit of val into bin and its mirror image's, kept until the node's tail is scaled.
inline void deposit_tail(std::size_t start, int bin, int mirror, double val, Scratch& sc) {
  sc.tail.emplace_back(start + bin, val);
  sc.tail.emplace_back(start + mirror, val);
}

// ---- Cut points (lobe_3d_cuts.cpp) ------------------------------------------------------------

// The 2D exit angles at which the arc of exits crosses a bin edge (theta_o edges, the horizon and
// the phi_o lines), sorted, all in (-pi/2, pi/2] (escaping exits have cos t > 0).
void edge_crossings(const LobeRun& r, const Azimuth& az, std::vector<double>& T);
// The band [x_lo, x_hi] of theta_v cut where Eq. (4) or (6) change form (X, unsorted).
void form_cuts(const Azimuth& az, FacetSide side, int k, double x_lo, double x_hi, std::vector<double>& X);
// X with the apertures where the band's exit crosses one of the crossings T added, then sorted;
// for Cook-Torrance also where the V-cavity min switches branch.
void crossing_cuts(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double x_lo, double x_hi,
                   const std::vector<double>& T, std::vector<double>& X);
// The phi_a range [0, pi/2] cut where the per-bin integrands are not smooth: (phi_a, whether it is
// a square-root point), sorted, coincident cuts merged (run_lobe).
std::vector<std::pair<double, bool>> phi_cuts(double theta_i, int theta_bins, int phi_bins, bool corner_cuts);

// sqrt(CDF) at the crossing X[j] (theta_m = m), or at the median (j = X.size()), once per band:
// neighbouring segments share their ends.
inline double w_at(const LobeRun& r, Scratch& sc, std::size_t j, double m) {
  if (sc.wX[j] < 0.0) sc.wX[j] = std::sqrt(groove_cdf(r.ndf, r.alpha, m));
  return sc.wX[j];
}

// The Gauss-Legendre pieces of segment s = [X[s], X[s + 1]] of theta_v: f(b0, b1, order, in_w) for
// each. The weight is dCDF(theta_m) = 2 pi D cos sin d theta_m. Near theta_m = 0, where D peaks
// (width alpha), the rule runs in w = sqrt(CDF) (du = 2 w dw, theta_m(w) analytic at w = 0); above
// the median in theta_m itself, since theta_m(w) is singular at w = 1 (sqrt for GGX, log for
// Beckmann). Pieces are cut to at most 0.05 in w or theta_m, in theta_m also to a ratio 1.25: D's
// tail above the median falls off on the scale of theta_m itself (a power law for GGX, faster for
// Beckmann and Phong). Order by the piece's mass: pieces lighter than 1e-9 (narrow bands of high k)
// take 2 nodes, lighter than 1e-6 four, others eight; and by its smoothness where smooth_4 (the
// vgroove model with four_node_pieces): f_k = sin((2K - 1) h - tf) turns by at most (2K - 1)
// (m1 - m0) over the piece, and the nearest singularity lies beyond w = 1 (in w) or beyond
// theta_m = 0 (GGX's poles at tan theta_m = +-i alpha) and pi/2 (Beckmann's and Phong's) in
// theta_m. Four nodes err by ~(phase / 2)^8 / 8! < 1e-15 for a phase below 0.1, and by
// ~(h / 4d)^8 < 1e-17 for a distance d beyond 32 piece lengths h.
template <typename F>
void for_each_gl_piece(const LobeRun& r, Scratch& sc, std::size_t s, int K_piece, bool smooth_4, F&& f) {
  const std::vector<double>& X = sc.X;
  const double m0 = 0.5 * (std::numbers::pi - X[s + 1]), m1 = 0.5 * (std::numbers::pi - X[s]);
  auto pieces = [&](double a0, double a1, bool in_w) {
    if (!(a1 > a0)) return;
    const double len = in_w ? 0.05 : std::min(0.05, 0.25 * a0);
    const int n = static_cast<int>(std::ceil((a1 - a0) / len));
    for (int pc = 0; pc < n; ++pc) {
      const double b0 = a0 + (a1 - a0) * pc / n, b1 = a0 + (a1 - a0) * (pc + 1) / n;
      const double mass_est = in_w ? (b1 - b0) * (b1 + b0) : 1.0;
      int order = mass_est < 1e-9 ? 2 : (mass_est < 1e-6 ? 4 : 8);
      const double d_sing = in_w ? 1.0 - b1 : std::min(b0, 0.5 * std::numbers::pi - b1);
      if (order == 8 && smooth_4 && (2 * K_piece - 1) * (m1 - m0) < 0.1 && 32.0 * (b1 - b0) < d_sing) order = 4;
      f(b0, b1, order, in_w);
    }
  };
  const double m_half = r.m_half;
  if (m0 < m_half)
    pieces(w_at(r, sc, s + 1, m0), m1 < m_half ? w_at(r, sc, s, m1) : w_at(r, sc, X.size(), m_half), true);
  if (m1 > m_half) pieces(std::max(m0, m_half), m1, false);
}

// Eq. (4)'s K at the aperture theta_v for the facet with the projected angle tf.
inline int K_at(double tf, double theta_v) {
  return saturate_to_int(std::floor((std::numbers::pi + 2.0 * tf) / theta_v) + 1.0);
}

// ---- Reference kernels (lobe_3d_reference.cpp) -------------------------------------------------

// The bin of the 2D exit angle t in the cross-section, or -1 below the horizon.
int bin_of(const LobeRun& r, const Azimuth& az, double t);
// Which branch of the V-cavity min is active (for the Cook-Torrance cut points).
int ct_branch(const Azimuth& az, FacetSide side, double theta_v);
// Segment s of a band by the direct evaluation (per node theta_m, Eq. 6 through G_kaleidoscopic):
// the reference kernels, and Cook-Torrance's bands in either mode (bins by bin_fast when r.fast).
void direct_segment(const LobeRun& r, const Azimuth& az, FacetSide side, int k, std::size_t s, double weight,
                    Scratch& sc);
// The tail's deposits by the reference kernels: n strata of the mass beyond k_cap.
void tail_reference(const LobeRun& r, const Azimuth& az, FacetSide side, int k_cap, int n, double mass, double weight,
                    Scratch& sc);

// ---- Fast kernels (lobe_3d_fast.cpp) ------------------------------------------------------------

// bin_of with the theta_o bin found among the cosines of its edges.
int bin_fast(const LobeRun& r, const Azimuth& az, double t);
// Where the band's outcome holds flux, per form of Eq. (4)/(6) (the cuts of form_cuts, in sc.X).
void live_forms(const Azimuth& az, FacetSide side, int k, Scratch& sc);
// Segment s of a band: its pieces pending until flush_band; `form` follows the segments through
// the forms of live_forms.
void fast_segment(const LobeRun& r, const Azimuth& az, FacetSide side, int k, std::size_t s, std::size_t& form,
                  Scratch& sc);
// The band's pending pieces evaluated, summed per segment and deposited.
void flush_band(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double weight, Scratch& sc);
// The tail's strata per NDF (n entries padded to a multiple of 4), and its deposits by the fast
// kernels: n strata of the mass beyond k_cap.
std::vector<double> tail_strata_table(NdfKind ndf, double alpha, int n);
void tail_fast(const LobeRun& r, const Azimuth& az, FacetSide side, int k_cap, int n, const std::vector<double>& table,
               double mass, double weight, Scratch& sc);

}  // namespace vgroove::analytic::lobe_detail
