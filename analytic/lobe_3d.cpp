// vgroove analytic: the 3D lobe (lobe_3d.h), its driver: the phi_a quadrature (run_lobe); per
// node, per facet and per k, a band of theta_v cut at the points of lobe_3d_cuts.cpp into segments
// of one bin, each integrated by Gauss-Legendre pieces, then the tail beyond k_cap by a midpoint
// rule in the CDF scaled to its exact flux. The kernels are the fast ones (lobe_3d_fast.cpp) or the
// plain reference ones (lobe_3d_reference.cpp); what they share is in lobe_3d_run.h.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Sec. 5.1 (Eq. 10-17), Sec. 7.1 (Fig. 11).
#include "vgroove/analytic/lobe_3d.h"

#include "vgroove/analytic/detail/lobe_3d_run.h"
#include "vgroove/analytic/detail/ndf_visit.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

namespace {

using namespace lobe_detail;

// Integrate one facet's k-reflection outcomes over theta_v in [x_lo, x_hi] with the weight
// `weight` (the phi_a quadrature weight), depositing into the bins (and their mirror images):
// the band cut at the points where the integrand is not smooth, each segment between them by the
// fast or the direct kernels.
void integrate_band(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double x_lo, double x_hi, double weight,
                    Scratch& sc) {
  if (!(x_hi > x_lo)) return;
  form_cuts(az, side, k, x_lo, x_hi, sc.X);
  const bool fast = r.fast && r.model == LobeModel::vgroove;
  if (fast) live_forms(az, side, k, sc);
  crossing_cuts(r, az, side, k, x_lo, x_hi, sc.T, sc.X);
  sc.wX.assign(sc.X.size() + 1, -1.0);
  sc.pieces.clear();
  sc.segments.clear();
  sc.nodes = 0;
  std::size_t form = 0;
  for (size_t s = 0; s + 1 < sc.X.size(); ++s) {
    if (!(sc.X[s + 1] > sc.X[s])) continue;
    if (fast) {
      fast_segment(r, az, side, k, s, form, sc);
    } else {
      direct_segment(r, az, side, k, s, weight, sc);
    }
  }
  if (fast) flush_band(r, az, side, k, weight, sc);
}

// The tail beyond the explicit bands: midpoint rule in the CDF.
// The outcomes of more than k_cap reflections come from theta_v < span / k_cap (Eq. 4).
void integrate_tail(const LobeRun& r, const Azimuth& az, FacetSide side, int k_cap, int n, int n_light, double weight,
                    Scratch& sc) {
  const double tf = facet_tau(az, side);
  const double u0 = groove_cdf(r.ndf, r.alpha, 0.5 * (std::numbers::pi - (std::numbers::pi + 2.0 * tf) / k_cap));
  const double mass = 1.0 - u0;
  if (!(mass > 0.0)) return;
  // Whatever the strata, the tail's deposits sum to its exact total (run_lobe), so a bin's error
  // from this node is at most twice the tail's mass times the node's weight, and over all nodes at
  // most twice the largest mass: a tail lighter than kLightTail (lobe_3d.h) takes n_light strata.
  const bool light = mass < kLightTail && n_light < n;
  if (light) n = n_light;
  if (r.fast) {
    tail_fast(r, az, side, k_cap, n, light ? r.light_tail_table : r.tail_table, mass, weight, sc);
  } else {
    tail_reference(r, az, side, k_cap, n, mass, weight, sc);
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

// The bands a node integrates: every k; or, with the high k coarsened (Lobe3dOptions::
// high_k_coarsening), k <= k_split and the flux of the rest at the node (exact: what those bands
// leave of the node's 2 weight); or the bands k > k_split and the tail alone. Every k > k_split
// lies in the last row (k_split >= max_k).
enum class Part { all, low_k, high_k };

// What the phi_a nodes of one lobe share.
struct PhiRun {
  LobeRun& r;
  const Lobe3dOptions& opt;
  double si, ci;  // sin and cos theta_i
  int k_cap;      // k beyond which the bands stop and the tail takes over
  int k_split;
  double high_k_flux = 0.0;  // Part::low_k: the exact flux of k > k_split, summed over the nodes
  Scratch sc;
};

// The groove at azimuth phi_a under the light at i = dir3(theta_i, pi): i.a = -sin(theta_i)
// cos(phi_a), i.u = sin(theta_i) sin(phi_a).
Azimuth azimuth_at(double phi_a, double si, double ci) {
  Azimuth az;
  az.ca = std::cos(phi_a);
  az.sa = std::sin(phi_a);
  az.tau = std::atan2(si * az.ca, ci);
  az.iu = si * az.sa;
  az.c = std::sqrt(std::max(0.0, 1.0 - az.iu * az.iu));
  az.sin_tau = std::sin(az.tau);
  az.cos_tau = std::cos(az.tau);
  return az;
}

// One facet's bands at a node, then its tail.
void facet_bands(PhiRun& pr, const Azimuth& az, FacetSide side, double weight, Part part) {
  const LobeRun& r = pr.r;
  const double span = std::numbers::pi + 2.0 * facet_tau(az, side);  // Eq. (4): K = floor(span / theta_v) + 1
  if (r.model == LobeModel::cook_torrance) {
    integrate_band(r, az, side, 1, 0.0, std::numbers::pi, weight, pr.sc);
    return;
  }
  // Part::high_k's bands start past k_split, unless the tail starts first (k_bands < k_split:
  // then that part is the tail alone, and Part::low_k's bands end at k_cap).
  int k = part == Part::high_k ? pr.k_split + 1 : 1;
  for (; part != Part::high_k || k <= pr.k_cap; ++k) {
    if (part == Part::low_k && k > pr.k_split) break;
    // K in {k, k + 1} <=> theta_v in [span / (k + 1), span / (k - 1)).
    const double x_lo = span / (k + 1), x_hi = k == 1 ? std::numbers::pi : std::min(std::numbers::pi, span / (k - 1));
    integrate_band(r, az, side, k, x_lo, x_hi, weight, pr.sc);
    if (k >= pr.k_cap) break;
    // Stop once the grooves with outcomes beyond k (theta_v < span / k) weigh nothing.
    if (k >= r.max_k + 1 && 1.0 - groove_cdf(r.ndf, r.alpha, 0.5 * (std::numbers::pi - span / k)) < 1e-16) break;
  }
  // Part::low_k takes the tail's flux from the bands' (integrate_node), not its deposits.
  if (k >= pr.k_cap && part != Part::low_k)
    integrate_tail(r, az, side, pr.k_cap, pr.opt.tail_strata, pr.opt.light_tail_strata, weight, pr.sc);
}

// The deposits of the grooves at azimuth phi_a (and pi - phi_a) with the quadrature weight dphi,
// into *r.acc.
void integrate_node(PhiRun& pr, double phi_a, double dphi, Part part) {
  if (pr.opt.cancel && pr.opt.cancel->load(std::memory_order_relaxed)) return;
  Scratch& sc = pr.sc;
  // Area fraction 2 D cos sin d theta_m d phi_a = (1/pi) dCDF d phi_a; phi_a in [0, pi/2] and
  // its mirror image pi - phi_a (y -> -y) cover [0, pi).
  const double weight = dphi / std::numbers::pi;
  const Azimuth az = azimuth_at(phi_a, pr.si, pr.ci);
  edge_crossings(pr.r, az, sc.T);
  sc.segment_bin.assign(sc.T.size() + 1, -2);
  sc.segment_mirror.assign(sc.T.size() + 1, -1);
  sc.band_total = 0.0;
  sc.tail.clear();
  for (FacetSide side : {FacetSide::left, FacetSide::right}) facet_bands(pr, az, side, weight, part);
  // What the bands leave of the node's flux is exact: each groove sends all its flux somewhere
  // (Eq. 6 over both facets sums to 1), so k > k_split (Part::low_k), or the tail, carries
  // 2 weight - band_total. The midpoint rule only distributes the tail's.
  if (part == Part::low_k) {
    pr.high_k_flux += 2.0 * weight - sc.band_total;
    return;
  }
  double tail_total = 0.0;
  for (const auto& d : sc.tail) tail_total += d.second;
  // Part::high_k knows only its own bands: the tail keeps its midpoint total (the high k are
  // scaled to their exact flux at the end).
  const double scale =
      part == Part::high_k ? 1.0 : (tail_total > 0.0 ? (2.0 * weight - sc.band_total) / tail_total : 0.0);
  std::vector<double>& acc = *pr.r.acc;
  for (const auto& d : sc.tail) acc[d.first] += scale * d.second;
}

// The phi_a quadrature: Gauss-Legendre panels between the cuts (phi_cuts), shared among the
// pieces by length, mapped flat at square-root points (flat_end_map).
void integrate_phi(PhiRun& pr, const std::vector<std::pair<double, bool>>& cuts, int panels, Part part) {
  const GaussLegendre phi_rule = gauss_legendre(pr.opt.phi_order);
  const std::vector<double>&gx = phi_rule.x, &gw = phi_rule.w;
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    const double p0 = cuts[c].first, p1 = cuts[c + 1].first;
    const bool sq0 = cuts[c].second, sq1 = cuts[c + 1].second;
    if (!(p1 > p0)) continue;
    const int np_rounded = static_cast<int>(std::lround(panels * (p1 - p0) / (0.5 * std::numbers::pi)));
    if (np_rounded == 0 && !sq0 && !sq1) {
      // A piece shorter than half a panel (between close corner cuts): the midpoint rule; its
      // O(len^3 f'') is far below the kinks' errors at these lengths.
      integrate_node(pr, 0.5 * (p0 + p1), p1 - p0, part);
      continue;
    }
    const int np = std::max(1, np_rounded);
    for (int pn = 0; pn < np; ++pn) {
      for (int q = 0; q < pr.opt.phi_order; ++q) {
        const double sv = (pn + 0.5 + 0.5 * gx[q]) / np;
        double g, dg;
        flat_end_map(sq0, sq1, sv, g, dg);
        integrate_node(pr, p0 + (p1 - p0) * g, (p1 - p0) * dg * 0.5 * gw[q] / np, part);
      }
    }
  }
}

// A lobe with its bins sized and zero.
Lobe3d empty_lobe(int theta_bins, int phi_bins, int max_k) {
  Lobe3d L;
  L.theta_bins = theta_bins;
  L.phi_bins = phi_bins;
  L.max_k = max_k;
  const int rows = max_k + 2;
  L.by_k.assign(rows, 0.0);
  L.hist.assign(static_cast<size_t>(theta_bins) * phi_bins, 0.0);
  L.hist_by_k.assign(static_cast<size_t>(rows) * theta_bins * phi_bins, 0.0);
  return L;
}

Lobe3d run_lobe(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k, LobeModel model,
                const Lobe3dOptions& opt);

// Normal incidence: the grooves at every azimuth phi_a show the same cross-section (t_i = 0,
// i.u = 0) turned by phi_a, whose exits o = -sin t a + cos t n lie at theta_o = |t|, phi_o = phi_a
// or phi_a + pi. With phi_a uniform the lobe is uniform in phi_o: each (k, theta_o) bin's flux,
// from one cross-section integrated exactly in theta_v, is shared equally among the phi_o bins. No
// phi_a quadrature: the bins are exact but for the tail's midpoint rule, given 16 times the strata
// (two nodes instead of hundreds).
Lobe3d normal_incidence_lobe(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k,
                             LobeModel model, const Lobe3dOptions& opt) {
  Lobe3d L = empty_lobe(theta_bins, phi_bins, max_k);
  Lobe3dOptions one_opt = opt;
  one_opt.phi_panels = 1;
  one_opt.corner_cuts = false;
  one_opt.high_k_coarsening = 1;
  one_opt.tail_strata = 16 * opt.tail_strata;
  const Lobe3d one = run_lobe(ndf, alpha, theta_i, theta_bins, 2, max_k, model, one_opt);
  for (int row = 0; row < max_k + 2; ++row) {
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

// The run's constants: the kernels, the median, the tail's tables and the bins' edges.
LobeRun lobe_run(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k, LobeModel model,
                 const Lobe3dOptions& opt, std::vector<double>* acc) {
  LobeRun r{ndf, alpha, theta_i, theta_bins, phi_bins, max_k, model, acc, true, 0.0, {}, true, {}, {}};
  r.fast = !opt.reference_kernels;
  r.four_node_pieces = opt.four_node_pieces;
  r.m_half = groove_cdf_inverse(ndf, alpha, 0.5);
  if (r.fast && model == LobeModel::vgroove) {
    r.tail_table = tail_strata_table(ndf, alpha, opt.tail_strata);
    r.light_tail_table = tail_strata_table(ndf, alpha, opt.light_tail_strata);
  }
  for (int b = 0; b <= theta_bins; ++b) r.cos_edge.push_back(std::cos(b * 0.5 * std::numbers::pi / theta_bins));
  return r;
}

Lobe3d run_lobe(NdfKind ndf, double alpha, double theta_i, int theta_bins, int phi_bins, int max_k, LobeModel model,
                const Lobe3dOptions& opt) {
  if (theta_i == 0.0 && phi_bins > 2 && opt.rotational_symmetry)
    return normal_incidence_lobe(ndf, alpha, theta_i, theta_bins, phi_bins, max_k, model, opt);
  Lobe3d L = empty_lobe(theta_bins, phi_bins, max_k);
  LobeRun r = lobe_run(ndf, alpha, theta_i, theta_bins, phi_bins, max_k, model, opt, &L.hist_by_k);
  PhiRun pr{r,
            opt,
            std::sin(theta_i),
            std::cos(theta_i),
            std::max(opt.k_bands, max_k + 1),
            std::max(max_k, opt.high_k_from),
            0.0,
            {}};
  const std::vector<std::pair<double, bool>> cuts = phi_cuts(theta_i, theta_bins, phi_bins, opt.corner_cuts);
  if (!(model == LobeModel::vgroove && opt.high_k_coarsening > 1)) {
    integrate_phi(pr, cuts, opt.phi_panels, Part::all);
    add_up(L);
    return L;
  }
  integrate_phi(pr, cuts, opt.phi_panels, Part::low_k);
  std::vector<double> high_k_acc(L.hist_by_k.size(), 0.0);
  r.acc = &high_k_acc;
  integrate_phi(pr, cuts, std::max(1, opt.phi_panels / opt.high_k_coarsening), Part::high_k);
  // The high k: the shape of their coarse bins (all in the last row), scaled to their exact flux.
  const std::size_t bins = static_cast<std::size_t>(theta_bins) * phi_bins, last = (max_k + 1) * bins;
  double coarse_flux = 0.0;
  for (std::size_t b = 0; b < bins; ++b) coarse_flux += high_k_acc[last + b];
  const double scale = coarse_flux > 0.0 ? pr.high_k_flux / coarse_flux : 0.0;
  for (std::size_t b = 0; b < bins; ++b) L.hist_by_k[last + b] += scale * high_k_acc[last + b];
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
