// vgroove analytic: the fast kernels of the 3D lobe (lobe_3d.h, the default; lobe_3d_run.h): no
// trigonometry per node. A node's theta_m comes with its cosine and sine from the closed form of
// the CDF's inverse (the NDF's inverse_cdf, ndf_visit.h), so that with h = theta_v / 2 = pi/2 -
// theta_m, sin h = cos theta_m and cos h = sin theta_m, and the offsets of Eq. (6) are angle sums:
// f_a = sin(h - tf) = cos_m cos tf - sin_m sin tf, f_b = -sin(h + tf); only f_k = sin((2K - 1) h
// - tf) needs a sine. A band's pieces wait until all are known and their nodes run four at a time
// (lobe_nodes::piece_terms), as do the tail's strata (lobe_nodes::tail_strata); the bins come from
// the segments between crossings, found once per segment. They differ from the reference kernels
// (lobe_3d_reference.cpp) by rounding only (the same integrand at the same nodes: per bin within
// 1e-15, LobeKernels.FastKernelsEqualTheReference).
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Eq. (4)-(6), Sec. 5.1 (Eq. 10-17).
#include "vgroove/analytic/detail/lobe_3d_nodes.h"
#include "vgroove/analytic/detail/lobe_3d_run.h"
#include "vgroove/analytic/detail/ndf_visit.h"
#include "vgroove/analytic/detail/sin_batch.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

namespace vgroove::analytic::lobe_detail {

namespace {

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
  const double tf = facet_tau(az, side);
  const int K = K_at(tf, theta_v);
  if (K != k && K != k + 1) return 0.0;
  const double f_k = std::clamp(f_k_of(K, theta_v, tf), f_b, f_a);
  const double Gf = K == k ? f_k - f_b : f_a - f_k;
  return Gf / (2.0 * cos_m * az.cos_tau);  // over the opening's width 2 sin(theta_v/2) cos(tau)
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

// The pending pieces' nodes as piece_sum places them (flush_band).
void place_nodes(Scratch& sc) {
  if (sc.node_v.size() < sc.nodes) {
    sc.node_v.resize(sc.nodes);
    sc.node_w.resize(sc.nodes);
    sc.node_terms.resize(sc.nodes);
  }
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
}

// The pending pieces' terms through lobe_nodes::piece_terms, each run of pieces with the same K
// and variable at once (many nodes per call: the kernel's chain of dependent steps overlaps across
// them).
void evaluate_runs(const LobeRun& r, const Azimuth& az, FacetSide side, int k, Scratch& sc) {
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
}

}  // namespace

// The pending pieces of a band (LobeRun::fast): their nodes evaluated in runs, then per segment in
// order the pieces' sums, the segment's flux and its deposits, in the order and with the
// arithmetic of the direct evaluation (piece_sum): the same bits.
void flush_band(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double weight, Scratch& sc) {
  place_nodes(sc);
  evaluate_runs(r, az, side, k, sc);
  const std::size_t start = row_start(r, k);
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
    deposit_band(r, start, g.bin, g.mirror, val * weight, sc);
  }
}

// Between the form cuts (form_cuts, in sc.X) the outcome's weight is either zero throughout or
// positive: the fast kernels ask once per form, at its middle, instead of once per segment.
void live_forms(const Azimuth& az, FacetSide side, int k, Scratch& sc) {
  std::vector<double>& F = sc.F;
  F = sc.X;
  std::sort(F.begin(), F.end());
  sc.live.assign(F.size(), 0);
  for (std::size_t f = 0; f + 1 < F.size(); ++f) {
    const double x_mid = 0.5 * (F[f] + F[f + 1]);
    double cos_m, sin_m;
    sin_cos_quadrant(0.5 * (std::numbers::pi - x_mid), sin_m, cos_m);
    sc.live[f] = F[f + 1] > F[f] && weight_fast(az, side, k, x_mid, cos_m, sin_m) > 0.0;
  }
}

// Segment s of a band (LobeRun::fast, the vgroove model): its pieces pending, the nodes of 4 and 8
// (piece_sum's, to the bit) for lobe_nodes::piece_terms with the band's other pieces (flush_band),
// 2 nodes summed here. `form` follows the segments through the forms of live_forms.
void fast_segment(const LobeRun& r, const Azimuth& az, FacetSide side, int k, std::size_t s, std::size_t& form,
                  Scratch& sc) {
  const double x_mid = 0.5 * (sc.X[s] + sc.X[s + 1]);
  // weight_fast > 0 is the outcome's P > 0 (the same width over the same opening); the exit is Eq. (5).
  while (form + 2 < sc.F.size() && sc.F[form + 1] <= x_mid) ++form;
  if (!sc.live[form]) return;
  int mirror = -1;
  const int bin = bin_by_segment(r, az, sc, exit_angle_fast(az.tau, x_mid, k, side), mirror);
  if (bin < 0) return;
  // Eq. (4)'s K on this segment (cut where it changes); outside {k, k + 1} it holds no
  // k-reflection outcome.
  const int K_piece = K_at(facet_tau(az, side), x_mid);
  if (K_piece != k && K_piece != k + 1) return;
  const std::size_t first = sc.pieces.size();
  for_each_gl_piece(r, sc, s, K_piece, r.four_node_pieces, [&](double b0, double b1, int order, bool in_w) {
    Scratch::Piece pending{b0, b1, order, in_w, K_piece, sc.nodes, 0.0};
    if (order >= 4) {
      sc.nodes += static_cast<std::size_t>(order);
    } else {
      const GaussLegendre& rule = gauss_legendre_cached(order);
      pending.sum = visit_ndf(
          r.ndf, r.alpha, [&](const auto& ndf) { return piece_sum<2>(ndf, az, side, k, K_piece, rule, b0, b1, in_w); });
    }
    sc.pieces.push_back(pending);
  });
  sc.segments.push_back({bin, mirror, first, sc.pieces.size() - first});
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

// The tail's deposits by the fast kernels: the strata four at a time (lobe_nodes::tail_strata)
// from the table and the azimuth's lead (the NDF's tail variable of the mass), then both outcomes
// of Eq. (6) as weight_fast forms them: K reflections on [f_b, f_k], K - 1 on [f_k, f_a].
void tail_fast(const LobeRun& r, const Azimuth& az, FacetSide side, int k_cap, int n, const std::vector<double>& table,
               double mass, double weight, Scratch& sc) {
  const double lead = visit_ndf(r.ndf, r.alpha, [&](const auto& f) { return f.tail_variable(mass); });
  const int padded = static_cast<int>(table.size());
  sc.strata.resize(6 * static_cast<std::size_t>(padded));
  double *theta_v = sc.strata.data(), *Kd = theta_v + padded, *f_a = Kd + padded, *f_b = f_a + padded,
         *f_k = f_b + padded, *w = f_k + padded;
  const lobe_nodes::TailStrata strata{
      r.ndf, r.alpha, lead, side == FacetSide::left ? az.sin_tau : -az.sin_tau, az.cos_tau, facet_tau(az, side)};
  lobe_nodes::tail_strata(strata, padded, table.data(), theta_v, Kd, f_a, f_b, f_k, w);
  auto deposit = [&](int k, double Gf_over_w, double theta_o) {
    int mirror = -1;
    const int bin = bin_by_segment(r, az, sc, theta_o, mirror);
    if (bin < 0) return;
    deposit_tail(row_start(r, k), bin, mirror, weight * mass / n * Gf_over_w, sc);
  };
  for (int q = 0; q < n; ++q) {
    if (!(f_a[q] > 0.0)) continue;
    const int K = static_cast<int>(Kd[q]);
    if (K > k_cap && f_k[q] - f_b[q] > 0.0)
      deposit(K, (f_k[q] - f_b[q]) / w[q], exit_angle_fast(az.tau, theta_v[q], K, side));
    if (K - 1 > k_cap && f_a[q] - f_k[q] > 0.0)
      deposit(K - 1, (f_a[q] - f_k[q]) / w[q], exit_angle_fast(az.tau, theta_v[q], K - 1, side));
  }
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

}  // namespace vgroove::analytic::lobe_detail
