// vgroove analytic: the cut points of the 3D lobe's integration (lobe_3d_run.h), shared by the
// reference and the fast kernels: between consecutive cuts each integrand is smooth, so that
// Gauss-Legendre converges at its order. In theta_v per band (one facet, one k): where Eq. (4) or
// (6) change form and where the exit crosses a bin edge (and, for Cook-Torrance, where the V-cavity
// min switches branch); in phi_a: square-root points and the kinks at the bins' corners.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces".
// ACM TOG 37(6), 2018. Eq. (4)-(6).
#include "vgroove/analytic/detail/lobe_3d_run.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic::lobe_detail {

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

void form_cuts(const Azimuth& az, FacetSide side, int k, double x_lo, double x_hi, std::vector<double>& X) {
  const double tf = facet_tau(az, side);
  X.clear();
  X.push_back(x_lo);
  X.push_back(x_hi);
  auto add = [&](double x) {
    if (x > x_lo && x < x_hi) X.push_back(x);
  };
  // Lit (theta_v = 2 tf), f_b clamp (theta_v = -2 tf), K changes ((pi + 2 tf) / j), the f_k clamp
  // at psi = 0 ((pi + tf) / (j - 1/2)).
  add(2.0 * tf);
  add(-2.0 * tf);
  for (int j = std::max(1, k - 1); j <= k + 2; ++j) {
    add((std::numbers::pi + 2.0 * tf) / j);
    add((std::numbers::pi + tf) / (j - 0.5));
  }
}

void crossing_cuts(const LobeRun& r, const Azimuth& az, FacetSide side, int k, double x_lo, double x_hi,
                   const std::vector<double>& T, std::vector<double>& X) {
  const double tf = facet_tau(az, side);
  auto add = [&](double x) {
    if (x > x_lo && x < x_hi) X.push_back(x);
  };
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
    const auto first = std::lower_bound(T.begin(), T.end(), std::min(a, b));
    const auto last = std::upper_bound(T.begin(), T.end(), std::max(a, b));
    for (auto it = first; it != last; ++it) add((tf + std::numbers::pi - sgn * *it - 2.0 * std::numbers::pi * j) / kk);
  }
  std::sort(X.begin(), X.end());
  if (r.model != LobeModel::cook_torrance) return;
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

// The points where the per-bin integrands in phi_a are not smooth:
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
std::vector<std::pair<double, bool>> phi_cuts(double theta_i, int theta_bins, int phi_bins, bool corner_cuts) {
  const double si = std::sin(theta_i);
  std::vector<std::pair<double, bool>> cuts{{0.0, false}, {0.5 * std::numbers::pi, false}};  // (phi_a, sqrt point)
  for (int b = 1; b < theta_bins; ++b) {
    const double sb = std::sin(b * 0.5 * std::numbers::pi / theta_bins);
    if (sb < si) cuts.emplace_back(std::asin(sb / si), true);
  }
  if (corner_cuts) {
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
  return merged;
}

}  // namespace vgroove::analytic::lobe_detail
