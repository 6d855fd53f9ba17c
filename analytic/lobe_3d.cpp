#include "vgroove/analytic/lobe_3d.h"

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/lobe_3d_nodes.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/ndf_visit.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/sin_batch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>
#include <vector>

namespace vgroove::analytic {

namespace {

// The outcome of exactly k reflections of Eq. (6) for the rays aimed at `first`, or G = 0.
struct KShare {
  double G = 0.0;  // fraction of the facet's lit width f_a
  double f_a = 0.0;
  double theta_o = 0.0;  // 2D exit angle
};
KShare share_k(double t_i, double theta_v, FacetSide first, int k) {
  const FacetPrediction p = G_kaleidoscopic(t_i, theta_v, first);
  KShare s;
  if (!p.lit) return s;
  s.f_a = p.f_a;
  if (p.fewer.n == k) {
    s.G = p.fewer.G;
    s.theta_o = p.fewer.theta_o;
  } else if (p.more.n == k) {
    s.G = p.more.G;
    s.theta_o = p.more.theta_o;
  }
  return s;
}

enum class LobeModel { vgroove, cook_torrance };

struct LobeRun {
  NdfKind ndf;
  double alpha;
  double theta_i;
  int tb, pb, max_k;
  LobeModel model;
  std::vector<double>* acc;      // where the deposits go: [row][t][p], as Lobe3d::hist_by_k
  bool fast = true;              // the kernels without per-node trigonometry (below); false: the reference ones
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

// The bin of the 2D exit angle t in the cross-section, or -1 below the horizon.
int bin_of(const LobeRun& r, const Azimuth& az, double t) {
  // o = c (-sin t a + cos t n) - iu u, a = (ca, sa, 0), u = (-sa, ca, 0).
  const double ox = -az.c * std::sin(t) * az.ca + az.iu * az.sa;
  const double oy = -az.c * std::sin(t) * az.sa - az.iu * az.ca;
  const double oz = az.c * std::cos(t);
  if (!(oz > 0.0)) return -1;
  const double theta = std::atan2(std::hypot(ox, oy), oz);
  const double dphi = 2.0 * std::numbers::pi / r.pb;
  int tb = static_cast<int>(theta / (0.5 * std::numbers::pi / r.tb));
  tb = std::min(tb, r.tb - 1);
  int p = static_cast<int>(std::floor((std::atan2(oy, ox) + 0.5 * dphi) / dphi));
  p = ((p % r.pb) + r.pb) % r.pb;
  return tb * r.pb + p;
}

// The 2D exit angles at which the arc of exits crosses a bin edge (theta_o edges, the horizon
// and the phi_o lines), all in (-pi/2, pi/2] (escaping exits have cos t > 0).
void edge_crossings(const LobeRun& r, const Azimuth& az, std::vector<double>& T) {
  T.clear();
  T.push_back(-0.5 * std::numbers::pi);
  T.push_back(0.5 * std::numbers::pi);
  for (int b = 1; b < r.tb; ++b) {
    // o_z = c cos t = cos(theta_b).
    const double q = std::cos(b * 0.5 * std::numbers::pi / r.tb) / az.c;
    if (q < 1.0) {
      const double t = std::acos(q);
      T.push_back(t);
      T.push_back(-t);
    }
  }
  const double dphi = 2.0 * std::numbers::pi / r.pb;
  for (int p = 0; p < r.pb / 2; ++p) {
    // o on the line at azimuth phi_b: c sin t sin(phi_a - phi_b) = -(i.u) cos(phi_a - phi_b).
    const double d = std::atan2(az.sa, az.ca) - (p + 0.5) * dphi;
    const double den = az.c * std::sin(d);
    if (den == 0.0) continue;
    const double v = -az.iu * std::cos(d) / den;
    if (std::abs(v) < 1.0) T.push_back(std::asin(v));
  }
  std::sort(T.begin(), T.end());
}

// The weight P(theta_v) per unit CDF and the exit angle for one facet and k.
struct Outcome {
  double P = 0.0;
  double t_o = 0.0;
};
Outcome outcome_ct(const Azimuth& az, FacetSide side, double theta_v, double w);
Outcome outcome(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double theta_v) {
  Outcome res;
  const double w = opening_width(az.tau, theta_v);
  if (!(w > 0.0)) return res;
  if (r.model == LobeModel::vgroove) {
    const KShare s = share_k(az.tau, theta_v, side, k);
    res.P = s.G * s.f_a / w;
    res.t_o = s.theta_o;
    return res;
  }
  return outcome_ct(az, side, theta_v, w);
}

// The same weight without the exit angle, inlined for the quadrature nodes: Eq. (4) and the
// corrected Eq. (6) for the facet with the (mirrored) projected angle tf (see kaleidoscope.cpp).
double weight_k(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double theta_v) {
  if (r.model == LobeModel::cook_torrance) return outcome(r, az, side, k, theta_v).P;
  const double tf = side == FacetSide::left ? az.tau : -az.tau;
  const double f_a = std::sin(0.5 * theta_v - tf);
  if (!(f_a > 0.0)) return 0.0;
  const double f_b = std::max(0.0, -std::sin(0.5 * theta_v + tf));
  const int K = saturate_to_int(std::floor((std::numbers::pi + 2.0 * tf) / theta_v) + 1.0);
  if (K != k && K != k + 1) return 0.0;
  const double f_k = std::clamp(std::sin(K * theta_v - 0.5 * theta_v - tf), f_b, f_a);
  const double Gf = K == k ? f_k - f_b : f_a - f_k;  // G f_a of the k-reflection outcome
  return Gf / (2.0 * std::sin(0.5 * theta_v) * std::cos(az.tau));
}

Outcome outcome_ct(const Azimuth& az, FacetSide side, double theta_v, double w) {
  Outcome res;
  // Cook-Torrance: one reflection off the facet, V-cavity G = min(G1(i), G1(o)) in the
  // cross-section (the ratios of Eq. (2) are invariant under the projection).
  const double theta_m = 0.5 * (std::numbers::pi - theta_v);
  const double t_s = side == FacetSide::left ? -theta_m : theta_m;
  const double f_a = std::cos(az.tau - t_s);
  if (!(f_a > 0.0)) return res;
  const double t_o = std::remainder(2.0 * t_s - az.tau, 2.0 * std::numbers::pi);
  const double G = std::min(G1_vcavity_inplane(az.tau, t_s), G1_vcavity_inplane(t_o, t_s));
  res.P = G * f_a / w;
  res.t_o = t_o;
  return res;
}

// Which branch of the V-cavity min is active (for the Cook-Torrance breakpoints).
int ct_branch(const Azimuth& az, FacetSide side, double theta_v) {
  const double theta_m = 0.5 * (std::numbers::pi - theta_v);
  const double t_s = side == FacetSide::left ? -theta_m : theta_m;
  const double t_o = 2.0 * t_s - az.tau;
  const double gi = 2.0 * std::cos(t_s) * std::cos(az.tau) / std::abs(std::cos(az.tau - t_s));
  const double go = 2.0 * std::cos(t_s) * std::cos(t_o) / std::abs(std::cos(t_o - t_s));
  if (gi >= 1.0 && go >= 1.0) return 0;
  return gi < go ? 1 : 2;
}

// The kernels without per-node trigonometry (LobeRun::fast). A node's theta_m comes with its
// cosine and sine from the closed form of the CDF's inverse (groove_cdf_inverse), so that with
// h = theta_v / 2 = pi/2 - theta_m, sin h = cos theta_m and cos h = sin theta_m, and the
// offsets of Eq. (6) are angle sums: f_a = sin(h - tf) = cos_m cos tf - sin_m sin tf,
// f_b = -sin(h + tf); only f_k = sin((2K - 1) h - tf) needs one sincos. They differ from the
// reference kernels by rounding only (the same integrand at the same nodes: per bin within 1e-15,
// Lobe3d.FastKernelsEqualTheReference).

// sin x for |x| <= pi, by the polynomial of sin_batch.h (within 2 ulp: the integrand's rounding).
double sin_pi(double x) { return x < 0.0 ? -sin_full(-x) : sin_full(x); }
// cos x for |x| <= pi: sin(pi/2 - |x|).
double cos_pi(double x) { return sin_full(cos_arg(x < 0.0 ? -x : x)); }
// f_k = sin((K - 1/2) theta_v - tf) = -sin((K - 1/2) theta_v - tf - pi), whose argument lies in
// [tf - theta_v/2, tf + theta_v/2) by Eq. (4) ((K - 1) theta_v <= pi + 2 tf < K theta_v).
double f_k_of(int K, double theta_v, double tf) { return -sin_pi((K - 0.5) * theta_v - tf - std::numbers::pi); }
// Eq. (5)'s exit angle for the binning, wrapped into (-pi, pi] without std::remainder.
double exit_angle_fast(double tau, double theta_v, int n, FacetSide side) {
  const double ti = side == FacetSide::left ? tau : -tau;
  double t = ((n % 2 == 0) ? 1.0 : -1.0) * (ti + std::numbers::pi - n * theta_v);
  t -= 2.0 * std::numbers::pi * std::round(t / (2.0 * std::numbers::pi));
  return side == FacetSide::left ? t : -t;
}

// weight_k on a piece where Eq. (4)'s K is known (constant between the piece's breakpoints, as
// are the tests on f_a and f_b): no angle is needed at all. With z = e^{i h} = sin_m + i cos_m
// (h = theta_v / 2), f_k = sin((2K - 1) h - tf) = Im(z^(2K-1)) cos tf - Re(z^(2K-1)) sin tf, the
// power by squaring (its rounding grows like (2K - 1) ulp: far below the quadrature's error).
// N nodes at once (a piece's Gauss-Legendre nodes): the nodes' squarings are independent chains,
// run side by side; each node's value is the same arithmetic as on its own.
template <int N>
void weight_piece(const Azimuth& az, FacetSide side, int k, int K, const double (&cos_m)[N], const double (&sin_m)[N],
                  double (&out)[N]) {
  const double st = side == FacetSide::left ? az.sin_tau : -az.sin_tau, ct = az.cos_tau;
  double re[N], im[N], br[N], bi[N];
  for (int q = 0; q < N; ++q) {
    re[q] = 1.0;
    im[q] = 0.0;
    br[q] = sin_m[q];
    bi[q] = cos_m[q];
  }
  for (unsigned n = static_cast<unsigned>(2 * K - 1);; n >>= 1) {
    if (n & 1u) {
      for (int q = 0; q < N; ++q) {
        const double t = re[q] * br[q] - im[q] * bi[q];
        im[q] = re[q] * bi[q] + im[q] * br[q];
        re[q] = t;
      }
    }
    if (n <= 1u) break;
    for (int q = 0; q < N; ++q) {
      const double t = br[q] * br[q] - bi[q] * bi[q];
      bi[q] = 2.0 * br[q] * bi[q];
      br[q] = t;
    }
  }
  for (int q = 0; q < N; ++q) {
    const double f_a = cos_m[q] * ct - sin_m[q] * st;
    const double f_b = std::max(0.0, -(cos_m[q] * ct + sin_m[q] * st));
    const double f_k = std::clamp(im[q] * ct - re[q] * st, f_b, f_a);
    const double Gf = K == k ? f_k - f_b : f_a - f_k;
    const double w = Gf / (2.0 * cos_m[q] * az.cos_tau);
    out[q] = f_a > 0.0 ? w : 0.0;
  }
}

// weight_k with theta_m's cosine and sine given.
double weight_fast(const Azimuth& az, FacetSide side, int k, double theta_v, double cos_m, double sin_m) {
  const double st = side == FacetSide::left ? az.sin_tau : -az.sin_tau, ct = az.cos_tau;
  const double f_a = cos_m * ct - sin_m * st;  // sin(theta_v/2 - tf)
  if (!(f_a > 0.0)) return 0.0;
  const double f_b = std::max(0.0, -(cos_m * ct + sin_m * st));  // max(0, -sin(theta_v/2 + tf))
  const double tf = side == FacetSide::left ? az.tau : -az.tau;
  const int K = saturate_to_int(std::floor((std::numbers::pi + 2.0 * tf) / theta_v) + 1.0);
  if (K != k && K != k + 1) return 0.0;
  const double f_k = std::clamp(f_k_of(K, theta_v, tf), f_b, f_a);
  const double Gf = K == k ? f_k - f_b : f_a - f_k;
  return Gf / (2.0 * cos_m * az.cos_tau);  // over the opening's width 2 sin(theta_v/2) cos(tau)
}

// bin_of with the theta_o bin found among the cosines of its edges.
int bin_fast(const LobeRun& r, const Azimuth& az, double t) {
  const double st = sin_pi(t), ct = cos_pi(t);
  const double ox = -az.c * st * az.ca + az.iu * az.sa;
  const double oy = -az.c * st * az.sa - az.iu * az.ca;
  const double oz = az.c * ct;
  if (!(oz > 0.0)) return -1;
  // theta_o >= edge b <=> o_z <= cos(edge b): the edges 1..tb-1 with cos >= o_z.
  const auto first = r.cos_edge.begin() + 1, last = r.cos_edge.begin() + r.tb;
  const int tb = static_cast<int>(std::upper_bound(first, last, oz, std::greater<double>()) - first);
  const double dphi = 2.0 * std::numbers::pi / r.pb;
  int p = static_cast<int>(std::floor((std::atan2(oy, ox) + 0.5 * dphi) / dphi));
  p = ((p % r.pb) + r.pb) % r.pb;
  return tb * r.pb + p;
}

// The Gauss-Legendre sum of the weight times the density over one piece [b0, b1] of w (in_w) or
// theta_m, N nodes (LobeRun::fast; the pieces of 4 and 8 nodes go to lobe_nodes::piece_terms in
// runs, integrate_band).
template <int N, typename Ndf>
double piece_sum(const Ndf& ndf, const Azimuth& az, FacetSide side, int k, int K, const GaussLegendre& rule, double b0,
                 double b1, bool in_w) {
  double v[N], cos_m[N], sin_m[N], w[N];
  for (int q = 0; q < N; ++q) v[q] = 0.5 * (b0 + b1) + 0.5 * (b1 - b0) * rule.x[q];
  if (in_w) {
    // groove_cdf_inverse_cos_sin, u = w^2 in (0, 1) at the nodes (w < sqrt(CDF(median))).
    for (int q = 0; q < N; ++q) {
      const double u = v[q] * v[q];
      const double t = ndf.inverse_cdf(u, [u] { return std::log1p(-u); });
      if constexpr (Ndf::kInverseGivesTan) {
        ndf_math::cos_sin_of_atan(t, cos_m[q], sin_m[q]);
      } else {
        ndf_math::cos_sin_of_one_minus_cos(t, cos_m[q], sin_m[q]);
      }
    }
  } else {
    for (int q = 0; q < N; ++q) sin_cos_quadrant(v[q], sin_m[q], cos_m[q]);
  }
  weight_piece<N>(az, side, k, K, cos_m, sin_m, w);
  double sum = 0.0;
  for (int q = 0; q < N; ++q) {
    // The density: du = 2 w dw in w, 2 pi D cos sin d theta_m in theta_m.
    const double density =
        in_w ? 2.0 * v[q] : 2.0 * std::numbers::pi * ndf.D_cs(cos_m[q], sin_m[q]) * cos_m[q] * sin_m[q];
    sum += rule.w[q] * w[q] * density;
  }
  return sum;
}

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
int mirror_of(const LobeRun& r, int bin) {
  const int t = bin / r.pb, p = bin % r.pb;
  return t * r.pb + (r.pb - p) % r.pb;
}

// The bin of the exit angle t (LobeRun::fast): its segment among the crossings, no trigonometry
// but once per segment.
// Also the mirror image's bin (mirror_of), without a division.
// The segment is looked for first where the previous call found its own and beside it (the
// exits of consecutive segments and strata mostly move by less than a segment), else by bisection:
// either way the first crossing above t.
int bin_by_segment(const LobeRun& r, const Azimuth& az, Scratch& sc, double t, int& mirror) {
  const std::vector<double>& T = sc.T;
  const std::size_t h = sc.segment_hint;
  auto holds = [&](std::size_t p) { return p >= 1 && p < T.size() && T[p - 1] <= t && t < T[p]; };
  std::size_t pos;
  if (holds(h)) {
    pos = h;
  } else if (holds(h + 1)) {
    pos = h + 1;
  } else if (h >= 1 && holds(h - 1)) {
    pos = h - 1;
  } else {
    pos = static_cast<std::size_t>(std::upper_bound(T.begin(), T.end(), t) - T.begin());
  }
  sc.segment_hint = pos;
  if (pos == 0 || pos == sc.T.size()) return -1;  // beyond -pi/2 or pi/2: below the horizon
  int& b = sc.segment_bin[pos];
  if (b == -2) {
    b = bin_fast(r, az, 0.5 * (sc.T[pos - 1] + sc.T[pos]));
    sc.segment_mirror[pos] = b < 0 ? -1 : mirror_of(r, b);
  }
  mirror = sc.segment_mirror[pos];
  return b;
}

// The pending pieces of a band (integrate_band, LobeRun::fast): their nodes through
// lobe_nodes::piece_terms, each run of pieces with the same K and variable at once (many nodes
// per call: the kernel's chain of dependent steps overlaps across them), then per segment in order
// the pieces' sums, the segment's flux and its deposits, in the order and with the arithmetic of
// the direct evaluation (piece_sum): the same bits.
void flush_band(const LobeRun& r, const Azimuth& az, FacetSide side, int k, int row, double weight, Scratch& sc) {
  if (sc.node_v.size() < sc.nodes) {
    sc.node_v.resize(sc.nodes);
    sc.node_w.resize(sc.nodes);
    sc.node_terms.resize(sc.nodes);
  }
  // The nodes as piece_sum places them.
  for (const Scratch::Piece& p : sc.pieces) {
    if (p.order < 4) continue;
    const GaussLegendre& rule = gauss_legendre_cached(p.order);
    double* v = sc.node_v.data() + p.node;
    double* w = sc.node_w.data() + p.node;
    for (int q = 0; q < p.order; ++q) {
      v[q] = 0.5 * (p.b0 + p.b1) + 0.5 * (p.b1 - p.b0) * rule.x[q];
      w[q] = rule.w[q];
    }
  }
  const bool left = side == FacetSide::left;
  for (std::size_t a = 0; a < sc.pieces.size();) {
    if (sc.pieces[a].order < 4) {
      ++a;
      continue;
    }
    std::size_t b = a + 1;
    while (b < sc.pieces.size() && sc.pieces[b].order >= 4 && sc.pieces[b].K == sc.pieces[a].K &&
           sc.pieces[b].in_w == sc.pieces[a].in_w)
      ++b;
    const Scratch::Piece& p = sc.pieces[a];
    const std::size_t end = sc.pieces[b - 1].node + static_cast<std::size_t>(sc.pieces[b - 1].order);
    const lobe_nodes::Piece run{r.ndf, r.alpha, left ? az.sin_tau : -az.sin_tau, az.cos_tau, left ? az.tau : -az.tau, k,
                                p.K,   p.in_w};
    lobe_nodes::piece_terms(run, static_cast<int>(end - p.node), sc.node_v.data() + p.node, sc.node_w.data() + p.node,
                            sc.node_terms.data() + p.node);
    a = b;
  }
  std::vector<double>& acc = *r.acc;
  const std::size_t row_start = static_cast<size_t>(row) * r.tb * r.pb;
  for (const Scratch::Segment& g : sc.segments) {
    double val = 0.0;
    for (std::size_t c = g.first; c < g.first + g.count; ++c) {
      const Scratch::Piece& p = sc.pieces[c];
      double sum = p.sum;
      if (p.order >= 4) {
        sum = 0.0;
        for (int q = 0; q < p.order; ++q) sum += sc.node_terms[p.node + static_cast<std::size_t>(q)];
      }
      val += 0.5 * (p.b1 - p.b0) * sum;
    }
    val *= weight;
    // The mirror image pi - phi_a of the groove (y -> -y) sends the same flux to phi_o -> -phi_o.
    acc[row_start + g.bin] += val;
    acc[row_start + g.mirror] += val;
    sc.band_total += 2.0 * val;
  }
}

// Integrate one facet's k-reflection outcomes over theta_v in [x_lo, x_hi] with the weight
// `weight` (the phi_a quadrature weight), depositing into the bins (and their mirror images).
void integrate_band(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double x_lo, double x_hi, double weight,
                    Scratch& sc) {
  if (!(x_hi > x_lo)) return;
  const double tf = side == FacetSide::left ? az.tau : -az.tau;
  std::vector<double>& X = sc.X;
  X.clear();
  X.push_back(x_lo);
  X.push_back(x_hi);
  auto add = [&](double x) {
    if (x > x_lo && x < x_hi) X.push_back(x);
  };
  // Where Eq. (4) or (6) change form: lit (theta_v = 2 tf), f_b clamp (theta_v = -2 tf), K changes
  // ((pi + 2 tf) / j), the f_k clamp at psi = 0 ((pi + tf) / (j - 1/2)).
  add(2.0 * tf);
  add(-2.0 * tf);
  for (int j = std::max(1, k - 1); j <= k + 2; ++j) {
    add((std::numbers::pi + 2.0 * tf) / j);
    add((std::numbers::pi + tf) / (j - 0.5));
  }
  // Between these the outcome's weight is either zero throughout or positive (the fast kernels ask
  // once per form, at its middle, instead of once per segment).
  const bool by_form = r.fast && r.model == LobeModel::vgroove;
  std::vector<double>& F = sc.F;
  std::vector<char>& live = sc.live;
  if (by_form) {
    F = X;
    std::sort(F.begin(), F.end());
    live.assign(F.size(), 0);
    for (std::size_t f = 0; f + 1 < F.size(); ++f) {
      const double x_mid = 0.5 * (F[f] + F[f + 1]);
      double cos_m, sin_m;
      sin_cos_quadrant(0.5 * (std::numbers::pi - x_mid), sin_m, cos_m);
      live[f] = F[f + 1] > F[f] && weight_fast(az, side, k, x_mid, cos_m, sin_m) > 0.0;
    }
  }
  std::size_t form = 0;
  // Four nodes where a piece is smooth enough (gl_pieces, below); not for Cook-Torrance, whose
  // V-cavity G has poles near grazing directions.
  const bool smooth_4 = r.model == LobeModel::vgroove && r.four_node_pieces;
  // Where the exit crosses a bin edge: t = sigma (-1)^k (tf + pi - k theta_v) (mod 2 pi),
  // sigma = +1 for the left facet, -1 for the right (its mirror image).
  const int kk = r.model == LobeModel::vgroove ? k : 1;
  const double sgn = ((kk % 2 == 0) ? 1.0 : -1.0) * (side == FacetSide::left ? 1.0 : -1.0);
  // v = tf + pi - k theta_v sweeps [v_lo, v_hi]; t = sgn (v - 2 pi j) must lie in (-pi/2, pi/2],
  // so only the sorted crossings inside each window sgn [v_lo - 2 pi j, v_hi - 2 pi j] matter.
  const double v_lo = tf + std::numbers::pi - kk * x_hi, v_hi = tf + std::numbers::pi - kk * x_lo;
  const int jj_lo = static_cast<int>(std::floor((v_lo - 0.5 * std::numbers::pi) / (2.0 * std::numbers::pi)));
  const int jj_hi = static_cast<int>(std::ceil((v_hi + 0.5 * std::numbers::pi) / (2.0 * std::numbers::pi)));
  for (int j = jj_lo; j <= jj_hi; ++j) {
    const double a = sgn * (v_lo - 2.0 * std::numbers::pi * j), b = sgn * (v_hi - 2.0 * std::numbers::pi * j);
    const auto first = std::lower_bound(sc.T.begin(), sc.T.end(), std::min(a, b));
    const auto last = std::upper_bound(sc.T.begin(), sc.T.end(), std::max(a, b));
    for (auto it = first; it != last; ++it) add((tf + std::numbers::pi - sgn * *it - 2.0 * std::numbers::pi * j) / kk);
  }
  std::sort(X.begin(), X.end());
  if (r.model == LobeModel::cook_torrance) {
    // The V-cavity min switches branch: located by scanning and bisection.
    const size_t n0 = X.size();
    for (size_t s = 0; s + 1 < n0; ++s) {
      const int m = 16;
      for (int q = 0; q < m; ++q) {
        double a = X[s] + (X[s + 1] - X[s]) * q / m, b = X[s] + (X[s + 1] - X[s]) * (q + 1) / m;
        const int ba = ct_branch(az, side, a), bb = ct_branch(az, side, b);
        if (ba == bb) continue;
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (a + b);
          (ct_branch(az, side, mid) == ba ? a : b) = mid;
        }
        X.push_back(0.5 * (a + b));
      }
    }
    std::sort(X.begin(), X.end());
  }
  const int row = std::min(k, r.max_k + 1);
  std::vector<double>& acc = *r.acc;
  // sqrt(CDF) at the crossing X[j] (theta_m = m), or at the median (j = X.size()): neighbouring
  // segments share their ends.
  std::vector<double>& wX = sc.wX;
  wX.assign(X.size() + 1, -1.0);
  auto w_at = [&](std::size_t j, double m) {
    if (wX[j] < 0.0) wX[j] = std::sqrt(groove_cdf(r.ndf, r.alpha, m));
    return wX[j];
  };
  sc.pieces.clear();
  sc.segments.clear();
  sc.nodes = 0;
  for (size_t s = 0; s + 1 < X.size(); ++s) {
    const double x0 = X[s], x1 = X[s + 1];
    if (!(x1 > x0)) continue;
    int bin, mirror = -1;
    const double x_mid = 0.5 * (x0 + x1);
    if (by_form) {
      // weight_fast > 0 is outcome's P > 0 (the same width over the same opening); the exit is Eq. (5).
      while (form + 2 < F.size() && F[form + 1] <= x_mid) ++form;
      if (!live[form]) continue;
      bin = bin_by_segment(r, az, sc, exit_angle_fast(az.tau, x_mid, k, side), mirror);
    } else {
      const Outcome mid = outcome(r, az, side, k, x_mid);
      if (!(mid.P > 0.0)) continue;
      bin = r.fast ? bin_fast(r, az, mid.t_o) : bin_of(r, az, mid.t_o);
      if (bin >= 0) mirror = mirror_of(r, bin);
    }
    if (bin < 0) continue;
    // The weight is dCDF(theta_m) = 2 pi D cos sin d theta_m. Near theta_m = 0, where D peaks
    // (width alpha), Gauss-Legendre runs in w = sqrt(CDF) (du = 2 w dw, theta_m(w) analytic at
    // w = 0); above the median in theta_m itself, since theta_m(w) is singular at w = 1 (sqrt for
    // GGX, log for Beckmann). Pieces are cut to at most 0.05 in w or theta_m.
    const double m0 = 0.5 * (std::numbers::pi - x1), m1 = 0.5 * (std::numbers::pi - x0);
    const double m_half = r.m_half;
    const bool fast = r.fast && r.model == LobeModel::vgroove;
    // Eq. (4)'s K on this piece (the piece is cut where it changes); outside {k, k + 1} the piece
    // holds no k-reflection outcome.
    const double tf_piece = side == FacetSide::left ? az.tau : -az.tau;
    const int K_piece = saturate_to_int(std::floor((std::numbers::pi + 2.0 * tf_piece) / x_mid) + 1.0);
    if (fast && K_piece != k && K_piece != k + 1) continue;
    double val = 0.0;
    auto gl_pieces = [&](double a0, double a1, bool in_w) {
      if (!(a1 > a0)) return;
      // In theta_m also at most a ratio 1.25 per piece: D's tail above the median falls off on the
      // scale of theta_m itself (a power law for GGX, faster for Beckmann and Phong).
      const double len = in_w ? 0.05 : std::min(0.05, 0.25 * a0);
      const int pieces = static_cast<int>(std::ceil((a1 - a0) / len));
      for (int pc = 0; pc < pieces; ++pc) {
        const double b0 = a0 + (a1 - a0) * pc / pieces, b1 = a0 + (a1 - a0) * (pc + 1) / pieces;
        const double mass_est = in_w ? (b1 - b0) * (b1 + b0) : 1.0;
        // Order by the piece's mass: pieces lighter than 1e-9 (narrow bands of high k) are short.
        int order = mass_est < 1e-9 ? 2 : (mass_est < 1e-6 ? 4 : 8);
        // And by its smoothness (vgroove): f_k = sin((2K - 1) h - tf) turns by at most
        // (2K - 1) (m1 - m0) over the piece, and the nearest singularity lies beyond w = 1 (in w) or
        // beyond theta_m = 0 (GGX's poles at tan theta_m = +-i alpha) and pi/2 (Beckmann's and
        // Phong's) in theta_m. Four nodes err by ~(phase / 2)^8 / 8! < 1e-15 for a phase below 0.1,
        // and by ~(h / 4d)^8 < 1e-17 for a distance d beyond 32 piece lengths h.
        const double d_sing = in_w ? 1.0 - b1 : std::min(b0, 0.5 * std::numbers::pi - b1);
        if (order == 8 && smooth_4 && (2 * K_piece - 1) * (m1 - m0) < 0.1 && 32.0 * (b1 - b0) < d_sing) order = 4;
        const GaussLegendre& rule = gauss_legendre_cached(order);
        double sum = 0.0;
        if (fast) {
          // Pending: the nodes of 4 and 8 (piece_sum's, to the bit) go to lobe_nodes::piece_terms
          // with the band's other pieces (flush_band); 2 nodes are summed here.
          Scratch::Piece pending{b0, b1, order, in_w, K_piece, sc.nodes, 0.0};
          if (order >= 4) {
            sc.nodes += static_cast<std::size_t>(order);
          } else {
            pending.sum = visit_ndf(r.ndf, r.alpha, [&](const auto& ndf) {
              return piece_sum<2>(ndf, az, side, k, K_piece, rule, b0, b1, in_w);
            });
          }
          sc.pieces.push_back(pending);
          continue;
        }
        for (size_t q = 0; q < rule.x.size(); ++q) {
          const double v = 0.5 * (b0 + b1) + 0.5 * (b1 - b0) * rule.x[q];
          if (in_w) {
            const double theta_v = std::numbers::pi - 2.0 * groove_cdf_inverse(r.ndf, r.alpha, v * v);
            sum += rule.w[q] * weight_k(r, az, side, k, theta_v) * 2.0 * v;
          } else {
            const double pdf = 2.0 * std::numbers::pi * D(r.ndf, v, r.alpha) * std::cos(v) * std::sin(v);
            sum += rule.w[q] * weight_k(r, az, side, k, std::numbers::pi - 2.0 * v) * pdf;
          }
        }
        val += 0.5 * (b1 - b0) * sum;
      }
    };
    const std::size_t first_piece = sc.pieces.size();
    if (m0 < m_half) gl_pieces(w_at(s + 1, m0), m1 < m_half ? w_at(s, m1) : w_at(X.size(), m_half), true);
    if (m1 > m_half) gl_pieces(std::max(m0, m_half), m1, false);
    if (fast) {
      sc.segments.push_back({bin, mirror, first_piece, sc.pieces.size() - first_piece});
      continue;
    }
    val *= weight;
    // The mirror image pi - phi_a of the groove (y -> -y) sends the same flux to phi_o -> -phi_o.
    const std::size_t row_start = static_cast<size_t>(row) * r.tb * r.pb;
    acc[row_start + bin] += val;
    acc[row_start + mirror] += val;
    sc.band_total += 2.0 * val;
  }
  if (r.fast && r.model == LobeModel::vgroove) flush_band(r, az, side, k, row, weight, sc);
}

// The tail's strata in the CDF, u_q = u0 + mass (q + 1/2) / n, have 1 - u_q = mass s_q with
// s_q = 1 - (q + 1/2) / n whatever the azimuth. The table holds the NDF's tail variable of s_q
// per stratum (tail_variable: GGX s_q, Beckmann log s_q, Phong s_q^(1/(p+2)), ...), which joins the
// azimuth's variable of the mass (tail_join) into the variable of 1 - u_q.
// Padded to a multiple of 4 entries (lobe_nodes::tail_strata takes four at a time; the padding's
// strata are formed and never read).
std::vector<double> tail_strata_table(NdfKind ndf, double alpha, int n) {
  std::vector<double> t(static_cast<std::size_t>((std::max(n, 0) + 3) / 4 * 4), 0.5);
  visit_ndf(ndf, alpha, [&](const auto& f) {
    for (int q = 0; q < n; ++q) t[q] = f.tail_variable(1.0 - (q + 0.5) / n);
  });
  return t;
}

// The half-aperture h = theta_v / 2 = pi/2 - theta_m where the CDF's complement is 1 - u =
// one_minus_u > 0 (the reference kernels' tail): the library's asin of cos theta_m or atan of
// cot theta_m, as the NDF's tail gives them (tail_arg), formed from 1 - u itself. Not pi - 2 theta_m:
// its absolute rounding (~4e-16, as theta_m nears pi/2) times the k ~ 1 / theta_v reflections of
// the groove moves Eq. (6)'s shares (by 1e-8 relative at theta_v = 1e-4, Phong 2.0 with the bands
// stopped at k = 5).
double tail_half_aperture_reference(NdfKind ndf, double alpha, double one_minus_u) {
  return visit_ndf(ndf, alpha, [&](const auto& f) {
    const double arg = f.tail_arg(f.tail_variable(one_minus_u));
    return std::remove_cvref_t<decltype(f)>::kTailArgIsCos ? std::asin(arg) : std::atan(arg);
  });
}

// The tail beyond the explicit bands: midpoint rule in the CDF.
// The outcomes of more than k_cap reflections come from theta_v < span / k_cap (Eq. 4).
void integrate_tail(const LobeRun& r, const Azimuth& az, FacetSide side, int k_cap, int n, int n_light, double weight,
                    Scratch& sc) {
  const double tf = side == FacetSide::left ? az.tau : -az.tau;
  const double u0 = groove_cdf(r.ndf, r.alpha, 0.5 * (std::numbers::pi - (std::numbers::pi + 2.0 * tf) / k_cap));
  const double mass = 1.0 - u0;
  if (!(mass > 0.0)) return;
  // Whatever the strata, the tail's deposits sum to its exact total (run_lobe), so a bin's error
  // from this node is at most twice the tail's mass times the node's weight, and over all nodes at
  // most twice the largest mass: a tail lighter than kLightTail (lobe_3d.h) takes n_light strata.
  const bool light = mass < kLightTail && n_light < n;
  if (light) n = n_light;
  auto deposit = [&](int k, double Gf_over_w, double theta_o) {
    int mirror = -1;
    const int bin = r.fast ? bin_by_segment(r, az, sc, theta_o, mirror) : bin_of(r, az, theta_o);
    if (bin < 0) return;
    if (!r.fast) mirror = mirror_of(r, bin);
    const int row = std::min(k, r.max_k + 1);
    const std::size_t row_start = static_cast<size_t>(row) * r.tb * r.pb;
    const double val = weight * mass / n * Gf_over_w;
    sc.tail.emplace_back(row_start + bin, val);
    sc.tail.emplace_back(row_start + mirror, val);
  };
  if (r.fast) {
    // The strata four at a time (lobe_nodes::tail_strata) from the table (tail_strata_table) and
    // the azimuth's lead (the NDF's tail variable of the mass), then both
    // outcomes of Eq. (6) as weight_fast forms them: K reflections on [f_b, f_k], K - 1 on [f_k, f_a].
    const std::vector<double>& table = light ? r.light_tail_table : r.tail_table;
    const double lead = visit_ndf(r.ndf, r.alpha, [&](const auto& f) { return f.tail_variable(mass); });
    const int padded = static_cast<int>(table.size());
    sc.strata.resize(6 * static_cast<std::size_t>(padded));
    double *theta_v = sc.strata.data(), *Kd = theta_v + padded, *f_a = Kd + padded, *f_b = f_a + padded,
           *f_k = f_b + padded, *w = f_k + padded;
    const lobe_nodes::TailStrata strata{r.ndf,      r.alpha, lead, side == FacetSide::left ? az.sin_tau : -az.sin_tau,
                                        az.cos_tau, tf};
    lobe_nodes::tail_strata(strata, padded, table.data(), theta_v, Kd, f_a, f_b, f_k, w);
    for (int q = 0; q < n; ++q) {
      if (!(f_a[q] > 0.0)) continue;
      const int K = static_cast<int>(Kd[q]);
      if (K > k_cap && f_k[q] - f_b[q] > 0.0)
        deposit(K, (f_k[q] - f_b[q]) / w[q], exit_angle_fast(az.tau, theta_v[q], K, side));
      if (K - 1 > k_cap && f_a[q] - f_k[q] > 0.0)
        deposit(K - 1, (f_a[q] - f_k[q]) / w[q], exit_angle_fast(az.tau, theta_v[q], K - 1, side));
    }
    return;
  }
  for (int q = 0; q < n; ++q) {
    const double theta_v = 2.0 * tail_half_aperture_reference(r.ndf, r.alpha, mass * (1.0 - (q + 0.5) / n));
    const FacetPrediction p = G_kaleidoscopic(az.tau, theta_v, side);
    if (!p.lit) continue;
    const double w = opening_width(az.tau, theta_v);
    for (const BounceShare& b : {p.fewer, p.more}) {
      if (!(b.G > 0.0) || b.n <= k_cap) continue;
      deposit(b.n, b.G * p.f_a / w, b.theta_o);
    }
  }
}

// by_k, hist and the albedo from hist_by_k.
void add_up(Lobe3d& L) {
  const int rows = L.max_k + 2;
  for (int row = 0; row < rows; ++row) {
    for (int t = 0; t < L.theta_bins; ++t) {
      for (int p = 0; p < L.phi_bins; ++p) {
        const double v = L.hist_by_k[(static_cast<size_t>(row) * L.theta_bins + t) * L.phi_bins + p];
        L.by_k[row] += v;
        L.hist[static_cast<size_t>(t) * L.phi_bins + p] += v;
      }
    }
    L.albedo += L.by_k[row];
  }
}

Lobe3d run_lobe(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k, LobeModel model,
                const Lobe3dOptions& opt) {
  Lobe3d L;
  L.theta_bins = theta_bins;
  L.phi_bins = phi_bins;
  L.max_k = max_k;
  const int rows = max_k + 2;
  L.by_k.assign(rows, 0.0);
  L.hist.assign(static_cast<size_t>(theta_bins) * phi_bins, 0.0);
  L.hist_by_k.assign(static_cast<size_t>(rows) * theta_bins * phi_bins, 0.0);
  if (theta_i == 0.0 && phi_bins > 2 && opt.rotational_symmetry) {
    // Normal incidence: the grooves at every azimuth phi_a show the same cross-section (t_i = 0,
    // i.u = 0) turned by phi_a, whose exits o = -sin t a + cos t n lie at theta_o = |t|,
    // phi_o = phi_a or phi_a + pi. With phi_a uniform the lobe is uniform in phi_o: each (k,
    // theta_o) bin's flux, from one cross-section integrated exactly in theta_v, is shared equally
    // among the phi_o bins. No phi_a quadrature: the bins are exact but for the tail's midpoint
    // rule, given 16 times the strata (two nodes instead of hundreds).
    Lobe3dOptions one_opt = opt;
    one_opt.phi_panels = 1;
    one_opt.corner_cuts = false;
    one_opt.high_k_coarsening = 1;
    one_opt.tail_strata = 16 * opt.tail_strata;
    const Lobe3d one = run_lobe(ndf, alpha, theta_i, theta_bins, 2, max_k, model, one_opt);
    for (int row = 0; row < rows; ++row) {
      for (int t = 0; t < theta_bins; ++t) {
        const std::size_t b = (static_cast<size_t>(row) * theta_bins + t) * 2;
        const double share = (one.hist_by_k[b] + one.hist_by_k[b + 1]) / phi_bins;
        for (int p = 0; p < phi_bins; ++p)
          L.hist_by_k[(static_cast<size_t>(row) * theta_bins + t) * phi_bins + p] = share;
      }
    }
    add_up(L);
    return L;
  }
  LobeRun r{ndf, alpha, theta_i, theta_bins, phi_bins, max_k, model, &L.hist_by_k, true, 0.0, {}, true, {}, {}};
  r.fast = !opt.reference_kernels;
  r.four_node_pieces = opt.four_node_pieces;
  r.m_half = groove_cdf_inverse(ndf, alpha, 0.5);
  if (r.fast && model == LobeModel::vgroove) {
    r.tail_table = tail_strata_table(ndf, alpha, opt.tail_strata);
    r.light_tail_table = tail_strata_table(ndf, alpha, opt.light_tail_strata);
  }
  for (int b = 0; b <= theta_bins; ++b) r.cos_edge.push_back(std::cos(b * 0.5 * std::numbers::pi / theta_bins));
  const GaussLegendre phi_rule = gauss_legendre(opt.phi_order);
  const std::vector<double>&gx = phi_rule.x, &gw = phi_rule.w;
  Scratch sc;
  // The light at i = dir3(theta_i, pi): i.a = -sin(theta_i) cos(phi_a), i.u = sin(theta_i) sin(phi_a).
  const double si = std::sin(theta_i), ci = std::cos(theta_i);
  // k beyond which the bands stop and the tail takes over.
  const int k_cap = std::max(opt.k_bands, max_k + 1);
  // The bands a node integrates (Part): every k; or, with the high k coarsened, k <= k_split and
  // the flux of the rest at the node (exact: what those bands leave of the node's 2 weight); or
  // the bands k > k_split and the tail alone. Every k > k_split lies in the last row (k_split >=
  // max_k).
  enum class Part { all, low_k, high_k };
  const bool coarsen = model == LobeModel::vgroove && opt.high_k_coarsening > 1;
  const int k_split = std::max(max_k, opt.high_k_from);
  double high_k_flux = 0.0;  // Part::low_k: the exact flux of k > k_split, summed over the nodes
  std::vector<double> high_k_acc;
  if (coarsen) high_k_acc.assign(L.hist_by_k.size(), 0.0);
  // The deposits of the grooves at azimuth phi_a (and pi - phi_a) with the quadrature weight
  // dphi, into *r.acc.
  auto node = [&](double phi_a, double dphi, Part part) {
    if (opt.cancel && opt.cancel->load(std::memory_order_relaxed)) return;
    // Area fraction 2 D cos sin d theta_m d phi_a = (1/pi) dCDF d phi_a; phi_a in [0, pi/2] and
    // its mirror image pi - phi_a (y -> -y) cover [0, pi).
    const double weight = dphi / std::numbers::pi;
    Azimuth az;
    az.ca = std::cos(phi_a);
    az.sa = std::sin(phi_a);
    az.tau = std::atan2(si * az.ca, ci);
    az.iu = si * az.sa;
    az.c = std::sqrt(std::max(0.0, 1.0 - az.iu * az.iu));
    az.sin_tau = std::sin(az.tau);
    az.cos_tau = std::cos(az.tau);
    edge_crossings(r, az, sc.T);
    sc.segment_bin.assign(sc.T.size() + 1, -2);
    sc.segment_mirror.assign(sc.T.size() + 1, -1);
    sc.band_total = 0.0;
    sc.tail.clear();
    for (FacetSide side : {FacetSide::left, FacetSide::right}) {
      const double tf = side == FacetSide::left ? az.tau : -az.tau;
      const double span = std::numbers::pi + 2.0 * tf;  // Eq. (4): K = floor(span / theta_v) + 1
      if (model == LobeModel::cook_torrance) {
        integrate_band(r, az, side, 1, 0.0, std::numbers::pi, weight, sc);
        continue;
      }
      // Part::high_k's bands start past k_split, unless the tail starts first (k_bands < k_split:
      // then that part is the tail alone, and Part::low_k's bands end at k_cap).
      int k = part == Part::high_k ? k_split + 1 : 1;
      for (; part != Part::high_k || k <= k_cap; ++k) {
        if (part == Part::low_k && k > k_split) break;
        // K in {k, k + 1} <=> theta_v in [span / (k + 1), span / (k - 1)).
        const double x_lo = span / (k + 1),
                     x_hi = k == 1 ? std::numbers::pi : std::min(std::numbers::pi, span / (k - 1));
        integrate_band(r, az, side, k, x_lo, x_hi, weight, sc);
        if (k >= k_cap) break;
        // Stop once the grooves with outcomes beyond k (theta_v < span / k) weigh nothing.
        if (k >= max_k + 1 && 1.0 - groove_cdf(ndf, alpha, 0.5 * (std::numbers::pi - span / k)) < 1e-16) break;
      }
      // Part::low_k takes the tail's flux from the bands' (below), not its deposits.
      if (k >= k_cap && part != Part::low_k)
        integrate_tail(r, az, side, k_cap, opt.tail_strata, opt.light_tail_strata, weight, sc);
    }
    // What the bands leave of the node's flux is exact: each groove sends all its flux somewhere
    // (Eq. 6 over both facets sums to 1), so k > k_split (Part::low_k), or the tail, carries
    // 2 weight - band_total. The midpoint rule only distributes the tail's.
    if (part == Part::low_k) {
      high_k_flux += 2.0 * weight - sc.band_total;
      return;
    }
    double tail_total = 0.0;
    for (const auto& d : sc.tail) tail_total += d.second;
    // Part::high_k knows only its own bands: the tail keeps its midpoint total (the high k are
    // scaled to their exact flux at the end).
    const double scale =
        part == Part::high_k ? 1.0 : (tail_total > 0.0 ? (2.0 * weight - sc.band_total) / tail_total : 0.0);
    std::vector<double>& acc = *r.acc;
    for (const auto& d : sc.tail) acc[d.first] += scale * d.second;
  };
  // The phi_a quadrature: Gauss-Legendre panels between cuts at the points where the per-bin
  // integrands are not smooth.
  //  - Square-root points: where c(phi_a) = cos(theta_b) a theta_o edge starts to cut the arc of
  //    exits (at t = 0, its crossings move like sqrt(phi_a - phi*)). The pieces next to them are
  //    mapped by phi = phi0 + (phi1 - phi0) g(s), g with a zero slope at each such end (s^2,
  //    1 - (1 - s)^2 or the smoothstep s^2 (3 - 2 s)), which turns sqrt into smooth.
  //  - Kinks at the bin corners (corner_cuts): where the arc passes through a corner o_c the bin's
  //    integrand changes slope (on one side the arc cuts the corner over a length ~ |phi_a - phi*|,
  //    on the other it misses the bin). The arcs of the groove at phi_a lie on the circle
  //    o.u = -i.u, i.e. i + o lies in the cross-section (a, n), so phi* is the azimuth of i + o_c,
  //    folded into [0, pi/2] (the mirror image pi - phi_a serves the mirror corner). These were
  //    the largest error of the lobe: a fixed rule of step h leaves ~|slope jump| h^2 at each
  //    (measured 7e-6 per bin at 384 panels, GGX 0.5 at 30 deg, back-scattering plane).
  // Remaining kinks (an arc's end or a change of form of Eq. 4/6 crossing a bin edge) are weaker.
  std::vector<std::pair<double, bool>> cuts{{0.0, false}, {0.5 * std::numbers::pi, false}};  // (phi_a, sqrt point)
  for (int b = 1; b < theta_bins; ++b) {
    const double sb = std::sin(b * 0.5 * std::numbers::pi / theta_bins);
    if (sb < si) cuts.emplace_back(std::asin(sb / si), true);
  }
  if (opt.corner_cuts) {
    const Dir3 i = dir3(theta_i, std::numbers::pi);
    for (int b = 1; b <= theta_bins; ++b) {
      for (int q = 0; q < phi_bins; ++q) {
        const Dir3 o_c = dir3(b * 0.5 * std::numbers::pi / theta_bins, (q + 0.5) * 2.0 * std::numbers::pi / phi_bins);
        double phi = std::atan2(i.y + o_c.y, i.x + o_c.x);
        if (phi < 0.0) phi += std::numbers::pi;
        if (phi > 0.5 * std::numbers::pi) phi = std::numbers::pi - phi;
        if (phi > 0.0 && phi < 0.5 * std::numbers::pi) cuts.emplace_back(phi, false);
      }
    }
  }
  std::sort(cuts.begin(), cuts.end());
  // Merge coincident cuts (a sqrt point wins).
  std::vector<std::pair<double, bool>> merged;
  for (const auto& c : cuts) {
    if (!merged.empty() && c.first - merged.back().first < 1e-12) {
      merged.back().second = merged.back().second || c.second;
    } else {
      merged.push_back(c);
    }
  }
  auto integrate_phi = [&](int panels, Part part) {
    for (size_t c = 0; c + 1 < merged.size(); ++c) {
      const double p0 = merged[c].first, p1 = merged[c + 1].first;
      const bool sq0 = merged[c].second, sq1 = merged[c + 1].second;
      if (!(p1 > p0)) continue;
      const int np_rounded = static_cast<int>(std::lround(panels * (p1 - p0) / (0.5 * std::numbers::pi)));
      if (np_rounded == 0 && !sq0 && !sq1) {
        // A piece shorter than half a panel (between close corner cuts): the midpoint rule; its
        // O(len^3 f'') is far below the kinks' errors at these lengths.
        node(0.5 * (p0 + p1), p1 - p0, part);
        continue;
      }
      const int np = std::max(1, np_rounded);
      for (int pn = 0; pn < np; ++pn) {
        for (int q = 0; q < opt.phi_order; ++q) {
          const double sv = (pn + 0.5 + 0.5 * gx[q]) / np;
          double g, dg;
          flat_end_map(sq0, sq1, sv, g, dg);
          node(p0 + (p1 - p0) * g, (p1 - p0) * dg * 0.5 * gw[q] / np, part);
        }
      }
    }
  };
  if (!coarsen) {
    integrate_phi(opt.phi_panels, Part::all);
  } else {
    integrate_phi(opt.phi_panels, Part::low_k);
    r.acc = &high_k_acc;
    integrate_phi(std::max(1, opt.phi_panels / opt.high_k_coarsening), Part::high_k);
    r.acc = &L.hist_by_k;
    // The high k: the shape of their coarse bins (all in the last row), scaled to their exact flux.
    const std::size_t bins = static_cast<std::size_t>(theta_bins) * phi_bins, last = (rows - 1) * bins;
    double coarse_flux = 0.0;
    for (std::size_t b = 0; b < bins; ++b) coarse_flux += high_k_acc[last + b];
    const double scale = coarse_flux > 0.0 ? high_k_flux / coarse_flux : 0.0;
    for (std::size_t b = 0; b < bins; ++b) L.hist_by_k[last + b] += scale * high_k_acc[last + b];
  }
  add_up(L);
  return L;
}

}  // namespace

Lobe3d vgroove_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k) {
  return vgroove_lobe_3d(ndf, alpha, theta_i, theta_bins, phi_bins, max_k, Lobe3dOptions{});
}
Lobe3d vgroove_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k,
                       const Lobe3dOptions& opt) {
  return run_lobe(ndf, alpha, theta_i, theta_bins, phi_bins, max_k, LobeModel::vgroove, opt);
}
Lobe3d cook_torrance_lobe_3d_from(const Lobe3d& v) {
  Lobe3d L;
  L.theta_bins = v.theta_bins;
  L.phi_bins = v.phi_bins;
  L.max_k = 1;
  const std::size_t bins = static_cast<std::size_t>(v.theta_bins) * v.phi_bins;
  L.by_k.assign(3, 0.0);
  L.hist.assign(v.hist_by_k.begin() + bins, v.hist_by_k.begin() + 2 * bins);
  L.hist_by_k.assign(3 * bins, 0.0);
  std::copy(L.hist.begin(), L.hist.end(), L.hist_by_k.begin() + bins);
  L.by_k[1] = v.max_k >= 1 ? v.by_k[1] : 0.0;
  L.albedo = L.by_k[1];
  return L;
}

Lobe3d cook_torrance_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins) {
  return cook_torrance_lobe_3d(ndf, alpha, theta_i, theta_bins, phi_bins, Lobe3dOptions{});
}
Lobe3d cook_torrance_lobe_3d(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins,
                             const Lobe3dOptions& opt) {
  return run_lobe(ndf, alpha, theta_i, theta_bins, phi_bins, 1, LobeModel::cook_torrance, opt);
}

}  // namespace vgroove::analytic
