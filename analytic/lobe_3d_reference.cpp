// vgroove analytic: the plain reference kernels of the 3D lobe (lobe_3d.h, Lobe3dOptions::
// reference_kernels): at every quadrature node the angle theta_m, its trigonometry and Eq. (6)
// through G_kaleidoscopic, written as the derivation reads. The fast kernels (lobe_3d.cpp) compute
// the same integrand at the same nodes, within rounding (Lobe3d.FastKernelsEqualTheReference);
// Cook-Torrance's bands take these kernels in either mode.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Eq. (1)-(6), Sec. 5.1 (Eq. 10-17).
#include "vgroove/analytic/detail/lobe_3d_run.h"
#include "vgroove/analytic/detail/ndf_visit.h"
#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/ndf.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <type_traits>

namespace vgroove::analytic::lobe_detail {

namespace {

// The weight P(theta_v) per unit CDF and the exit angle for one facet and k.
struct Outcome {
  double P = 0.0;
  double t_o = 0.0;
};

// Cook-Torrance: one reflection off the facet, V-cavity G = min(G1(i), G1(o)) in the
// cross-section (the ratios of Eq. (2) are invariant under the projection); w the opening's width.
Outcome outcome_ct(const Azimuth& az, FacetSide side, double theta_v, double w) {
  Outcome res;
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

// The outcome of exactly k reflections of Eq. (6) for the rays aimed at `side` (G f_a / w), or
// Cook-Torrance's.
Outcome outcome(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double theta_v) {
  Outcome res;
  const double w = opening_width(az.tau, theta_v);
  if (!(w > 0.0)) return res;
  if (r.model == LobeModel::cook_torrance) return outcome_ct(az, side, theta_v, w);
  const FacetPrediction p = G_kaleidoscopic(az.tau, theta_v, side);
  if (!p.lit) return res;
  for (const BounceShare& b : {p.fewer, p.more}) {
    if (b.n != k) continue;
    res.P = b.G * p.f_a / w;
    res.t_o = b.theta_o;
    return res;
  }
  return res;
}

// The same weight without the exit angle, inlined for the quadrature nodes: Eq. (4) and the
// corrected Eq. (6) for the facet with the (mirrored) projected angle tf (see kaleidoscope.cpp).
double weight_k(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double theta_v) {
  if (r.model == LobeModel::cook_torrance) return outcome(r, az, side, k, theta_v).P;
  const double tf = facet_tau(az, side);
  const double f_a = std::sin(0.5 * theta_v - tf);
  if (!(f_a > 0.0)) return 0.0;
  const double f_b = std::max(0.0, -std::sin(0.5 * theta_v + tf));
  const int K = K_at(tf, theta_v);
  if (K != k && K != k + 1) return 0.0;
  const double f_k = std::clamp(std::sin(K * theta_v - 0.5 * theta_v - tf), f_b, f_a);
  const double Gf = K == k ? f_k - f_b : f_a - f_k;  // G f_a of the k-reflection outcome
  return Gf / (2.0 * std::sin(0.5 * theta_v) * std::cos(az.tau));
}

// The Gauss-Legendre sum over one piece [b0, b1] of w = sqrt(CDF) (in_w) or of theta_m: the weight
// at each node's theta_v = pi - 2 theta_m times the density, du = 2 w dw or 2 pi D cos sin d theta_m.
double direct_piece_sum(const LobeRun& r, const Azimuth& az, FacetSide side, int k, const GaussLegendre& rule,
                        double b0, double b1, bool in_w) {
  double sum = 0.0;
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
  return sum;
}

// The half-aperture h = theta_v / 2 = pi/2 - theta_m where the CDF's complement is 1 - u =
// one_minus_u > 0: the library's asin of cos theta_m or atan of cot theta_m, as the NDF's tail
// gives them (tail_arg), formed from 1 - u itself. Not pi - 2 theta_m: its absolute rounding
// (~4e-16, as theta_m nears pi/2) times the k ~ 1 / theta_v reflections of the groove moves
// Eq. (6)'s shares (by 1e-8 relative at theta_v = 1e-4, Phong 2.0 with the bands stopped at k = 5).
double tail_half_aperture(NdfKind ndf, double alpha, double one_minus_u) {
  return visit_ndf(ndf, alpha, [&](const auto& f) {
    const double arg = f.tail_arg(f.tail_variable(one_minus_u));
    return std::remove_cvref_t<decltype(f)>::kTailArgIsCos ? std::asin(arg) : std::atan(arg);
  });
}

}  // namespace

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

int ct_branch(const Azimuth& az, FacetSide side, double theta_v) {
  const double theta_m = 0.5 * (std::numbers::pi - theta_v);
  const double t_s = side == FacetSide::left ? -theta_m : theta_m;
  const double t_o = 2.0 * t_s - az.tau;
  const double gi = 2.0 * std::cos(t_s) * std::cos(az.tau) / std::abs(std::cos(az.tau - t_s));
  const double go = 2.0 * std::cos(t_s) * std::cos(t_o) / std::abs(std::cos(t_o - t_s));
  if (gi >= 1.0 && go >= 1.0) return 0;
  return gi < go ? 1 : 2;
}

// The outcome at the segment's middle gives its bin (the exit crosses no bin edge inside it) and
// whether it holds any flux; its pieces are summed node by node.
void direct_segment(const LobeRun& r, const Azimuth& az, FacetSide side, int k, std::size_t s, double weight,
                    Scratch& sc) {
  const double x_mid = 0.5 * (sc.X[s] + sc.X[s + 1]);
  const Outcome mid = outcome(r, az, side, k, x_mid);
  if (!(mid.P > 0.0)) return;
  const int bin = r.fast ? bin_fast(r, az, mid.t_o) : bin_of(r, az, mid.t_o);
  if (bin < 0) return;
  const int K_piece = K_at(facet_tau(az, side), x_mid);
  // Four nodes where a piece is smooth enough; not for Cook-Torrance, whose V-cavity G has poles
  // near grazing directions.
  const bool smooth_4 = r.model == LobeModel::vgroove && r.four_node_pieces;
  double val = 0.0;
  for_each_gl_piece(r, sc, s, K_piece, smooth_4, [&](double b0, double b1, int order, bool in_w) {
    val += 0.5 * (b1 - b0) * direct_piece_sum(r, az, side, k, gauss_legendre_cached(order), b0, b1, in_w);
  });
  deposit_band(r, row_start(r, k), bin, mirror_of(r, bin), val * weight, sc);
}

// The midpoint rule in the CDF over the tail's mass: the groove of stratum q has 1 - u =
// mass (1 - (q + 1/2) / n), and its outcomes beyond k_cap reflections are deposited.
void tail_reference(const LobeRun& r, const Azimuth& az, FacetSide side, int k_cap, int n, double mass, double weight,
                    Scratch& sc) {
  for (int q = 0; q < n; ++q) {
    const double theta_v = 2.0 * tail_half_aperture(r.ndf, r.alpha, mass * (1.0 - (q + 0.5) / n));
    const FacetPrediction p = G_kaleidoscopic(az.tau, theta_v, side);
    if (!p.lit) continue;
    const double w = opening_width(az.tau, theta_v);
    for (const BounceShare& b : {p.fewer, p.more}) {
      if (!(b.G > 0.0) || b.n <= k_cap) continue;
      const int bin = bin_of(r, az, b.theta_o);
      if (bin < 0) continue;
      deposit_tail(row_start(r, b.n), bin, mirror_of(r, bin), weight * mass / n * (b.G * p.f_a / w), sc);
    }
  }
}

}  // namespace vgroove::analytic::lobe_detail
