#include "vgroove/analytic/lobe_nonsymmetric.h"

#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = 0.5 * std::numbers::pi;

bool cancelled(const NonsymmetricLobeOptions& opt) { return opt.cancel && opt.cancel->load(std::memory_order_relaxed); }

// Eq. (9)'s zones for the rays aimed at the left facet of the groove (theta_l, theta_r) at t_i:
// widths (not divided by f_a; the longer facet of unit length) and their counts.
struct Zones {
  int kb = 0;
  double w[4] = {0, 0, 0, 0};
  int n[4] = {0, 0, 0, 0};
  double len_l = 0.0, len_r = 0.0;
};
Zones left_zones(double t_i, double theta_l, double theta_r) {
  Zones z;
  const double theta_v = aperture(theta_l, theta_r);
  const double h_l = std::sin(-theta_l), h_r = std::sin(theta_r), h_max = std::max(h_l, h_r);
  z.len_l = h_max > 0.0 ? h_r / h_max : 1.0;
  z.len_r = h_max > 0.0 ? h_l / h_max : 1.0;
  // f of the fan vertex P_j: len_j sin(phi0 + j theta_v), phi0 = theta_l + pi/2 - t_i; the sines of
  // phi0 + j theta_v by the addition theorem from three sine-cosine pairs.
  const double phi0 = theta_l + kHalfPi - t_i;
  const double s0 = std::sin(phi0), c0 = std::cos(phi0);
  // The counts hold on the whole k_b piece, lit or not (the caller bins by them).
  z.kb = bounce_count_kb(t_i, theta_l, theta_r);
  const int n[4] = {1, z.kb - 1, z.kb, z.kb + 1};
  for (int j = 0; j < 4; ++j) z.n[j] = n[j];
  const double fa = z.len_l * s0;
  if (!(fa > 0.0)) return z;
  const double sv = std::sin(theta_v), cv = std::cos(theta_v);
  const double fb = std::max(0.0, z.len_r * (s0 * cv - c0 * sv));
  const double f2 = std::max(0.0, z.len_r * (s0 * cv + c0 * sv));
  // kb is even: P_{kb - 1} on the right facet's circle, P_kb on the left one's.
  const double a = (z.kb - 1) * theta_v;
  const double sk = std::sin(a), ck = std::cos(a);
  const double s_kb1 = s0 * ck + c0 * sk, c_kb1 = c0 * ck - s0 * sk;
  const double fkb = std::max(0.0, z.len_r * s_kb1);
  const double fka = std::max(0.0, z.len_l * (s_kb1 * cv + c_kb1 * sv));
  // Lee et al. 2018, Eq. (9), times f_a.
  z.w[0] = std::max(0.0, fa - std::max(f2, fb));
  z.w[1] = std::max(0.0, std::min(fa, f2) - fkb);
  z.w[2] = std::max(0.0, std::min(fa, fkb) - std::max(fka, fb));
  z.w[3] = std::max(0.0, std::min(fkb, fka) - fb);
  return z;
}

// d t_o / d theta_l and d t_o / d theta_r of Eq. (8) after n reflections, left facet first.
double dto_dl(int n) { return (n % 2 == 0 ? 1.0 : -1.0) * (-0.5 - n) + 0.5; }
double dto_dr(int n) { return (n % 2 == 0 ? 1.0 : -1.0) * (n - 0.5) + 0.5; }

// Where the deposits go.
struct Accum {
  int bins = 0, rows = 0, max_k = 0;
  std::vector<double> by_k, hist, hist_by_k;
  double below = 0.0, invalid = 0.0;
  Accum(int bins_, int max_k_)
      : bins(bins_),
        rows(max_k_ + 2),
        max_k(max_k_),
        by_k(static_cast<std::size_t>(max_k_) + 2, 0.0),
        hist(static_cast<std::size_t>(bins_), 0.0),
        hist_by_k((static_cast<std::size_t>(max_k_) + 2) * static_cast<std::size_t>(bins_), 0.0) {}
  void add(int n, int bin, double mass) {
    if (n < 1) {
      invalid += mass;
      return;
    }
    if (bin < 0) {
      below += mass;
      return;
    }
    const int row = n > max_k ? max_k + 1 : n;
    by_k[static_cast<std::size_t>(row)] += mass;
    hist[static_cast<std::size_t>(bin)] += mass;
    hist_by_k[static_cast<std::size_t>(row) * bins + bin] += mass;
  }
};

// The laws at one azimuth: the roughness along it, and how the partner follows. The densities
// take the tilt's sine and cosine (analytic/ndf.cpp's formulas written in them; the tests hold
// the lobes to the NDFs' own functions through their albedo and the symmetric lobes).
struct Laws {
  NdfKind ndf;
  double alpha;
  bool flatland;
  PartnerLaw partner;
  double norm_p = 1.0;   // N or N2 of Eq. (20)
  double phong_p = 0.0;  // alpha_p
  double phong_K = 0.0;  // D2 = K cos^p
  Laws(NdfKind n, double a, bool flat, PartnerLaw part) : ndf(n), alpha(a), flatland(flat), partner(part) {
    assert(ndf != NdfKind::student_t);  // no nonsymmetric model for Student-T (partner_law_exists)
    if (partner == PartnerLaw::independent)
      norm_p = flatland ? P2_theta_r_normalization(ndf, alpha) : P_theta_r_normalization(ndf, alpha);
    if (ndf == NdfKind::phong) {
      phong_p = phong_exponent(alpha);
      phong_K = std::exp(std::lgamma(0.5 * (phong_p + 3.0)) - std::lgamma(0.5 * (phong_p + 2.0))) / std::sqrt(kPi);
    }
  }
  // D (3D) or D2 (flatland) at the tilt with sine s and cosine c.
  double ndf_sc(double s, double c) const {
    const double a2 = alpha * alpha;
    switch (ndf) {
      case NdfKind::ggx: {
        const double q = a2 * c * c + s * s;
        return flatland ? a2 / (2.0 * q * std::sqrt(q)) : a2 / (kPi * q * q);
      }
      case NdfKind::beckmann: {
        if (!(c > 0.0)) return 0.0;
        const double t = s / c, e = std::exp(-t * t / a2);
        return flatland ? e / (std::sqrt(kPi) * alpha * c * c * c) : e / (kPi * a2 * c * c * c * c);
      }
      case NdfKind::phong:
        return (flatland ? phong_K : (phong_p + 2.0) / (2.0 * kPi)) * std::pow(c, phong_p);
      case NdfKind::student_t:
        break;  // the nonsymmetric model has no partner law for Student-T (partner_law_exists)
    }
    return 0.0;
  }
  // The groove law q (the tilt under a uniform point) and the partner law P (Eq. 20).
  double q(double s, double c) const { return flatland ? 2.0 * ndf_sc(s, c) * c : 2.0 * kPi * ndf_sc(s, c) * c * s; }
  double p(double s, double c) const { return flatland ? ndf_sc(s, c) * s / norm_p : ndf_sc(s, c) * s * s / norm_p; }
  // v in [0, 1] -> tilt, spreading the nodes over the NDF's width; and its derivative.
  double tilt(double v) const { return std::atan(alpha * std::tan(kHalfPi * v)); }
  double dtilt(double v) const {
    const double c = std::cos(kHalfPi * v), s = std::sin(kHalfPi * v);
    return alpha * kHalfPi / (c * c + alpha * alpha * s * s);
  }
};

// The widths of Eq. (9) as left_zones, at theta_l = -x, from the sines and cosines of x, theta_r and
// t_i (the addition theorem gives the fan's angles; one more sine-cosine pair for P_{kb - 1}).
struct Trig {
  double s, c;
};
Zones zones_from_trig(double t_i, Trig ti, double x, Trig tx, double theta_r, Trig tr) {
  Zones z;
  const double h_max = std::max(tx.s, tr.s);
  z.len_l = h_max > 0.0 ? tr.s / h_max : 1.0;
  z.len_r = h_max > 0.0 ? tx.s / h_max : 1.0;
  // phi0 = theta_l + pi/2 - t_i = pi/2 - (x + t_i); theta_v = pi - (x + theta_r).
  const double s0 = tx.c * ti.c - tx.s * ti.s, c0 = tx.s * ti.c + tx.c * ti.s;
  z.kb = bounce_count_kb(t_i, -x, theta_r);
  const int n[4] = {1, z.kb - 1, z.kb, z.kb + 1};
  for (int j = 0; j < 4; ++j) z.n[j] = n[j];
  const double fa = z.len_l * s0;
  if (!(fa > 0.0)) return z;
  const double sv = tx.s * tr.c + tx.c * tr.s, cv = -(tx.c * tr.c - tx.s * tr.s);
  const double fb = std::max(0.0, z.len_r * (s0 * cv - c0 * sv));
  const double f2 = std::max(0.0, z.len_r * (s0 * cv + c0 * sv));
  const double a = (z.kb - 1) * aperture(-x, theta_r);
  const double sk = std::sin(a), ck = std::cos(a);
  const double s_kb1 = s0 * ck + c0 * sk, c_kb1 = c0 * ck - s0 * sk;
  const double fkb = std::max(0.0, z.len_r * s_kb1);
  const double fka = std::max(0.0, z.len_l * (s_kb1 * cv + c_kb1 * sv));
  // Lee et al. 2018, Eq. (9), times f_a.
  z.w[0] = std::max(0.0, fa - std::max(f2, fb));
  z.w[1] = std::max(0.0, std::min(fa, f2) - fkb);
  z.w[2] = std::max(0.0, std::min(fa, fkb) - std::max(fka, fb));
  z.w[3] = std::max(0.0, std::min(fkb, fka) - fb);
  return z;
}

// A projection: the sorted exit angles `crit` where the bin changes, and the bin of each interval
// between them (interval m lies between crit[m - 1] and crit[m]; -1 below the horizon).
struct Projection {
  std::vector<double> crit;
  std::vector<int> bins;  // crit.size() + 1 entries
  int bin(double t) const {
    return bins[static_cast<std::size_t>(std::upper_bound(crit.begin(), crit.end(), t) - crit.begin())];
  }
  // Fills `bins` from a function of the exit angle, at each interval's middle.
  template <class BinOf>
  void tabulate(BinOf&& bin_of) {
    std::sort(crit.begin(), crit.end());
    bins.clear();
    for (std::size_t m = 0; m <= crit.size(); ++m) {
      const double lo = m == 0 ? -kPi : crit[m - 1], hi = m == crit.size() ? kPi : crit[m];
      bins.push_back(bin_of(0.5 * (lo + hi)));
    }
  }
  // The projection seen through the mirror t -> -t (the outcomes of the right facet hit first are
  // those of the mirrored groove hit on its left facet at -t_i, with their exits mirrored back).
  Projection mirrored() const {
    Projection m;
    for (auto it = crit.rbegin(); it != crit.rend(); ++it) m.crit.push_back(-*it);
    m.bins.assign(bins.rbegin(), bins.rend());
    return m;
  }
};

// The outcomes of the rays that hit the left facet first, for the grooves theta_l = -X,
// theta_r = Y0 + gamma X with X in (0, pi/2) of density qx (gamma = 0: a partner at the fixed tilt
// Y0; gamma = 1: symmetric grooves), deposited through `proj` (the bin of a 2D exit angle, and the
// sorted exit angles where bins change). X is cut where Eq. (7)'s k_b changes and where an
// outcome's exit (linear in X within a k_b piece, with the slope -d t_o / d theta_l + gamma
// d t_o / d theta_r, never 0) crosses a bin edge: each outcome stays in one bin on each piece.
template <class Density, class Tilt>
void integrate_first_facet(const Projection& proj, double t_i, const Density& qx, const Tilt& tilt, double Y0,
                           double gamma, double weight, const NonsymmetricLobeOptions& opt, Accum& acc) {
  const GaussLegendre& gl = gauss_legendre_cached(opt.tilt_order);
  const Trig ti{std::sin(t_i), std::cos(t_i)}, ty{std::sin(Y0), std::cos(Y0)};
  assert(gamma == 0.0 || (gamma == 1.0 && Y0 == 0.0));
  std::vector<double> cuts;
  for (int j = 0; j <= opt.tilt_panels; ++j) cuts.push_back(tilt(static_cast<double>(j) / opt.tilt_panels));
  double x_end = kHalfPi;
  if (gamma > 0.0) x_end = std::min(x_end, (kHalfPi - Y0) / gamma);
  cuts.back() = x_end;
  // Eq. (7)'s k_b changes (r = m - 1/2), X = pi + 2 t_i - theta_l - theta_r = X0 + X1 x and
  // V = pi + theta_l - theta_r = V0 + V1 x: X = (2m - 1) V.
  {
    const double X0 = kPi + 2.0 * t_i - Y0, X1 = 1.0 - gamma;
    const double V0 = kPi - Y0, V1 = -(1.0 + gamma);
    auto r = [&](double x) { return (X0 + X1 * x) / (2.0 * (V0 + V1 * x)); };
    const double r0 = r(0.0), r1 = r(std::nextafter(x_end, 0.0));
    const int m_lo = static_cast<int>(std::max(-1e6, std::floor(std::min(r0, r1) + 0.5))) + 1;
    const int m_hi = static_cast<int>(std::min(1e6, std::floor(std::max(r0, r1) + 0.5)));
    for (int m = std::max(m_lo, -opt.kb_cap); m <= std::min(m_hi, opt.kb_cap / 2 + 1); ++m) {
      const double q = 2.0 * m - 1.0;
      const double den = X1 - q * V1;
      if (den == 0.0) continue;
      const double x = (q * V0 - X0) / den;
      if (x > 0.0 && x < x_end) cuts.push_back(x);
    }
  }
  // The facets' lengths swap roles (the longer has unit length) where the tilts meet: x = Y0.
  if (gamma == 0.0 && Y0 > 0.0 && Y0 < x_end) cuts.push_back(Y0);
  std::sort(cuts.begin(), cuts.end());

  std::vector<double> sub;
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
    const double a = cuts[c], b = cuts[c + 1];
    if (!(b > a)) continue;
    const double mid = 0.5 * (a + b);
    const double tl = -mid, tr = Y0 + gamma * mid;
    sub.assign({a, b});
    const Zones z = left_zones(t_i, tl, tr);
    // Pieces of negligible mass (or beyond kb_cap) are not cut at the bin edges.
    const bool resolve =
        std::abs(z.kb) <= opt.kb_cap && qx(std::sin(mid), std::cos(mid)) * (b - a) * weight > opt.negligible;
    // Each zone's exit on this piece: t_mid + slope (x - mid) (Eq. 8 is linear in theta_l, theta_r).
    double t_mid[4], slope[4];
    for (int j = 0; j < 4; ++j) {
      const int n = z.n[j];
      t_mid[j] = n < 1 ? 0.0 : exit_angle_nonsymmetric(t_i, tl, tr, n);
      slope[j] = n < 1 ? 0.0 : -dto_dl(n) + gamma * dto_dr(n);
    }
    if (resolve) {
      for (int j = 0; j < 4; ++j) {
        const int n = z.n[j];
        if (n < 1 || (j > 0 && n == z.n[j - 1])) continue;
        const double t_a = t_mid[j] + slope[j] * (a - mid), t_b = t_mid[j] + slope[j] * (b - mid);
        const auto lo = std::upper_bound(proj.crit.begin(), proj.crit.end(), std::min(t_a, t_b));
        const auto hi = std::lower_bound(proj.crit.begin(), proj.crit.end(), std::max(t_a, t_b));
        for (auto it = lo; it < hi; ++it) sub.push_back(mid + (*it - t_mid[j]) / slope[j]);
      }
      // Eq. (9)'s clamps max(0, f(P_j)) switch where a fan vertex's offset vanishes: the angle
      // phi0 + j theta_v = (pi/2 - t_i - x) + j (pi - Y0 - (1 + gamma) x) is a multiple of pi, for
      // the vertices Eq. (9) uses, j = -1 (b), 0 (a), 1 (k_2), k_b - 1, k_b.
      for (int j : {-1, 0, 1, z.kb - 1, z.kb}) {
        const double c0 = kHalfPi - t_i + j * (kPi - Y0), c1 = -(1.0 + j * (1.0 + gamma));
        if (c1 == 0.0) continue;
        const double ph_a = c0 + c1 * a, ph_b = c0 + c1 * b;
        const int m_lo = static_cast<int>(std::ceil(std::min(ph_a, ph_b) / kPi));
        const int m_hi = static_cast<int>(std::floor(std::max(ph_a, ph_b) / kPi));
        for (int m = m_lo; m <= m_hi && m - m_lo < 64; ++m) {
          const double x = (m * kPi - c0) / c1;
          if (x > a && x < b) sub.push_back(x);
        }
      }
      std::sort(sub.begin(), sub.end());
    }
    // On each sub-piece every zone keeps its count and its bin (taken at the middle): integrate
    // the zones' shares of the opening, then deposit.
    for (std::size_t s = 0; s + 1 < sub.size(); ++s) {
      const double lo = sub[s], hi = sub[s + 1];
      if (!(hi > lo)) continue;
      const double cen = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
      int bin[4];
      for (int j = 0; j < 4; ++j) {
        const int n = z.n[j];
        bin[j] = n < 1 ? 0 : proj.bin(t_mid[j] + slope[j] * (cen - mid));
      }
      double mass[4] = {0.0, 0.0, 0.0, 0.0};
      for (std::size_t g = 0; g < gl.size(); ++g) {
        const double x = cen + half * gl.x[g];
        const Trig tx{std::sin(x), std::cos(x)};
        const double dens = qx(tx.s, tx.c) * half * gl.w[g];
        if (!(dens > 0.0)) continue;
        const double theta_r = Y0 + gamma * x;
        const Trig trr = gamma == 0.0 ? ty : tx;
        const Zones zz = zones_from_trig(t_i, ti, x, tx, theta_r, trr);
        // The opening's perpendicular width: W cos(t_i), W = l_L cos(theta_l) + l_R cos(theta_r).
        const double open = (zz.len_l * tx.c + zz.len_r * trr.c) * ti.c;
        if (!(open > 0.0)) continue;
        for (int j = 0; j < 4; ++j) mass[j] += dens * zz.w[j] / open;
      }
      for (int j = 0; j < 4; ++j)
        if (mass[j] > 0.0) acc.add(z.n[j], bin[j], weight * mass[j]);
    }
  }
}

// All grooves at one azimuth (or flatland), both facets hit first. The rays that hit the left
// facet first are integrated over its tilt A with the partner B by panels; those that hit the
// right facet first, as the left facet of the mirrored groove (-B, A) at -t_i, over B with A by
// panels: the tilt of the facet hit first is always the variable cut exactly (a single reflection
// on the right facet leaves along 2 B - t_i whatever A is, so A could not carry its bin edges).
void integrate_section(const Projection& proj, double t_i, const Laws& laws, double weight,
                       const NonsymmetricLobeOptions& opt, Accum& acc) {
  const Projection mirrored = proj.mirrored();
  auto q = [&](double s, double c) { return laws.q(s, c); };
  auto p = [&](double s, double c) { return laws.p(s, c); };
  auto tilt = [&](double v) { return laws.tilt(v); };
  if (laws.partner == PartnerLaw::symmetric) {
    integrate_first_facet(proj, t_i, q, tilt, 0.0, 1.0, weight, opt, acc);
    integrate_first_facet(mirrored, -t_i, q, tilt, 0.0, 1.0, weight, opt, acc);
    return;
  }
  const GaussLegendre& gl = gauss_legendre_cached(opt.order);
  const double dv = 1.0 / opt.partner_panels;
  for (int j = 0; j < opt.partner_panels && !cancelled(opt); ++j) {
    for (std::size_t g = 0; g < gl.size(); ++g) {
      const double v = (j + 0.5 + 0.5 * gl.x[g]) * dv;
      const double y = laws.tilt(v);
      const double dy = laws.dtilt(v) * 0.5 * dv * gl.w[g];
      // Left facet first: A cut, partner B = y with P(y).
      const double sy = std::sin(y), cy = std::cos(y);
      const double wb = laws.p(sy, cy) * dy;
      if (wb > 0.0) integrate_first_facet(proj, t_i, q, tilt, y, 0.0, weight * wb, opt, acc);
      // Right facet first: B cut (density P), the other facet A = y with q(y).
      const double wa = laws.q(sy, cy) * dy;
      if (wa > 0.0) integrate_first_facet(mirrored, -t_i, p, tilt, y, 0.0, weight * wa, opt, acc);
    }
  }
}

// Flatland: bins over (-pi/2, pi/2).
Projection flat_projection(int bins) {
  Projection p;
  for (int j = 0; j <= bins; ++j) p.crit.push_back(-kHalfPi + j * kPi / bins);
  p.tabulate([&](double t) {
    if (!(std::abs(t) < kHalfPi)) return -1;
    return std::clamp(static_cast<int>(std::floor((t + kHalfPi) / (kPi / bins))), 0, bins - 1);
  });
  return p;
}

// 3D: the groove at azimuth phi_a sends the 2D exit t to o = c (-sin t a + cos t n) - iu u.
Projection projection_3d(int tb, int pb, double c, double iu, double phi_a) {
  Projection p;
  const double ca = std::cos(phi_a), sa = std::sin(phi_a);
  const double dt = kHalfPi / tb, dp = 2.0 * kPi / pb;
  // theta_o edges and the horizon: o.n = c cos t = cos(theta_e).
  for (int e = 1; e <= tb; ++e) {
    const double v = std::cos(e * dt) / c;
    if (v <= 1.0) {
      const double t = std::acos(std::max(-1.0, v));
      p.crit.push_back(t);
      p.crit.push_back(-t);
    }
  }
  // phi_o edges at (q + 1/2) dp: c sin t sin(phi_e - phi_a) = iu cos(phi_e - phi_a) (the line
  // through the edge; a crossing on its other half only adds a harmless cut).
  for (int q = 0; q < pb; ++q) {
    const double d = (q + 0.5) * dp - phi_a;
    const double s = std::sin(d), co = std::cos(d);
    if (c * std::abs(s) < std::abs(iu * co)) continue;
    p.crit.push_back(std::asin(std::clamp(iu * co / (c * s), -1.0, 1.0)));
  }
  p.tabulate([&](double t) {
    const double oz = c * std::cos(t);
    if (!(oz > 0.0)) return -1;
    const double st = c * std::sin(t);
    const double ox = -st * ca + iu * sa, oy = -st * sa - iu * ca;
    const int ti = std::clamp(static_cast<int>(std::floor(std::acos(std::min(1.0, oz)) / dt)), 0, tb - 1);
    int q = static_cast<int>(std::floor(std::atan2(oy, ox) / dp + 0.5)) % pb;
    if (q < 0) q += pb;
    return ti * pb + q;
  });
  return p;
}

}  // namespace

NonsymmetricLobeOptions flatland_options() {
  NonsymmetricLobeOptions o;
  // The bins' deposits have kinks in B wherever a bin edge of a count meets a zone's kink in A
  // (one per bin edge, feature and count: too many to cut), each leaving an error ~ h_B^3: 128
  // panels bring the bins within ~1e-6 of Eq. (23) integrated (32: 1.5e-5; header).
  o.partner_panels = 128;
  o.tilt_panels = 16;
  return o;
}

FlatlandLobe flatland_nonsymmetric_lobe(const NonsymmetricModel& m, double theta_i, int bins, int max_k,
                                        const NonsymmetricLobeOptions& opt) {
  const Projection proj = flat_projection(bins);
  const Laws laws(m.roughness.ndf, m.roughness.alpha_x, true, m.partner);
  // The first facet on the left (half the grooves) or on the right: the mirror image at -theta_i.
  Accum left(bins, max_k), right(bins, max_k);
  integrate_section(proj, theta_i, laws, 0.5, opt, left);
  integrate_section(proj, -theta_i, laws, 0.5, opt, right);
  FlatlandLobe out;
  out.bins = bins;
  out.max_k = max_k;
  out.by_k = left.by_k;
  out.theta_o.assign(static_cast<std::size_t>(bins), 0.0);
  out.theta_o_by_k = left.hist_by_k;
  for (std::size_t r = 0; r < out.by_k.size(); ++r) out.by_k[r] += right.by_k[r];
  for (int r = 0; r < max_k + 2; ++r)
    for (int b = 0; b < bins; ++b)
      out.theta_o_by_k[static_cast<std::size_t>(r) * bins + b] +=
          right.hist_by_k[static_cast<std::size_t>(r) * bins + (bins - 1 - b)];
  for (int r = 0; r < max_k + 2; ++r)
    for (int b = 0; b < bins; ++b)
      out.theta_o[static_cast<std::size_t>(b)] += out.theta_o_by_k[static_cast<std::size_t>(r) * bins + b];
  for (double v : out.by_k) out.albedo += v;
  out.below = left.below + right.below + left.invalid + right.invalid;
  out.n_resolved = opt.kb_cap;
  return out;
}

Lobe3d nonsymmetric_lobe_3d(const NonsymmetricModel& m, double theta_i, double axes_azimuth, int theta_bins,
                            int phi_bins, int max_k, const NonsymmetricLobeOptions& opt) {
  const int nb = theta_bins * phi_bins;
  Accum acc(nb, max_k);
  const double ix = -std::sin(theta_i), iz = std::cos(theta_i);  // i = dir(theta_i, pi)
  const Roughness& r = m.roughness;
  // The mirror phi_a -> -phi_a holds when alpha(phi_a - axes_azimuth) is even in phi_a.
  const double rem = std::remainder(axes_azimuth, kHalfPi);
  const bool mirror = r.isotropic() || std::abs(rem) < 1e-12;
  const double span = mirror ? kPi : 2.0 * kPi;
  const int panels = mirror ? opt.phi_panels : 2 * opt.phi_panels;
  const GaussLegendre& gl = gauss_legendre_cached(opt.order);
  Accum one(nb, max_k);
  // The azimuths carry the density alpha(phi)^2 / (2 pi alpha_x alpha_y) (phi from the alpha_x
  // axis: the first facet's normal leans towards a, so phi = phi_a - axes_azimuth). With
  // psi = atan2(alpha_x sin phi, alpha_y cos phi), d psi = alpha(phi)^2 / (alpha_x alpha_y) d phi:
  // the quadrature runs in psi (uniform weight d psi / (2 pi)), which follows the density's peak
  // (of width ~ alpha_x / alpha_y) for strongly anisotropic surfaces. Isotropic: psi = phi.
  auto psi_of = [&](double phi_a) {
    const double p = phi_a - axes_azimuth;
    const double psi = std::atan2(r.alpha_x * std::sin(p), r.alpha_y * std::cos(p));
    // Unwrap onto the branch within pi of p (the map is monotone and keeps multiples of pi).
    return psi + 2.0 * kPi * std::round((p - psi) / (2.0 * kPi)) + axes_azimuth;
  };
  auto phi_of = [&](double psi_a) {
    const double q = psi_a - axes_azimuth;
    const double p = std::atan2(r.alpha_y * std::sin(q), r.alpha_x * std::cos(q));
    return p + 2.0 * kPi * std::round((q - p) / (2.0 * kPi)) + axes_azimuth;
  };
  auto node = [&](double psi_a, double dpsi) {
    if (cancelled(opt)) return;
    const double phi_a = phi_of(psi_a);
    const double alpha = alpha_along(r, phi_a - axes_azimuth);
    const double w_phi = dpsi / (2.0 * kPi);
    const double ca = std::cos(phi_a), sa = std::sin(phi_a);
    const double ia = ix * ca, iu = -ix * sa;  // i.a, i.u with u = (-sin, cos, 0)
    const double c = std::sqrt(ia * ia + iz * iz);
    const double t_i = std::atan2(-ia, iz);
    const Projection proj = projection_3d(theta_bins, phi_bins, c, iu, phi_a);
    const Laws laws(r.ndf, alpha, false, m.partner);
    if (!mirror) {
      integrate_section(proj, t_i, laws, w_phi, opt, acc);
      return;
    }
    one = Accum(nb, max_k);
    integrate_section(proj, t_i, laws, w_phi, opt, one);
    // The groove at -phi_a is this one's mirror image (y -> -y): phi bin p -> -p.
    for (int row = 0; row < max_k + 2; ++row)
      for (int t = 0; t < theta_bins; ++t)
        for (int p = 0; p < phi_bins; ++p) {
          const double v = one.hist_by_k[(static_cast<std::size_t>(row) * theta_bins + t) * phi_bins + p];
          if (v == 0.0) continue;
          const int pm = (phi_bins - p) % phi_bins;
          acc.hist_by_k[(static_cast<std::size_t>(row) * theta_bins + t) * phi_bins + p] += v;
          acc.hist_by_k[(static_cast<std::size_t>(row) * theta_bins + t) * phi_bins + pm] += v;
        }
    for (int row = 0; row < max_k + 2; ++row) acc.by_k[static_cast<std::size_t>(row)] += 2.0 * one.by_k[row];
    acc.below += 2.0 * one.below;
    acc.invalid += 2.0 * one.invalid;
  };
  // The phi_a quadrature (as in analytic/lobe_3d.cpp): panels between the azimuths where the
  // per-bin deposits are not smooth, all of which depend on the bins and i only (every groove at
  // phi_a sends its light onto one arc, o.u = -i.u):
  //  - square-root points, where the arc becomes tangent to a theta_o edge (c(phi_a) = cos theta_e,
  //    |sin phi_a| = sin theta_e / sin theta_i): the adjacent pieces are mapped by s^2-type maps;
  //  - kinks where the arc passes through a bin corner o_c: phi_a is the azimuth of i + o_c (mod pi).
  std::vector<std::pair<double, bool>> cuts{{0.0, false}, {span, false}};
  const double si = std::sin(theta_i);
  auto add = [&](double phi, bool sq) {
    for (double p : {phi, phi + kPi, kPi - phi, 2.0 * kPi - phi})
      if (p > 0.0 && p < span) cuts.emplace_back(p, sq);
  };
  for (int b = 1; b < theta_bins; ++b) {
    const double sb = std::sin(b * kHalfPi / theta_bins);
    if (sb < si) add(std::asin(sb / si), true);
  }
  for (int b = 1; b <= theta_bins; ++b)
    for (int q = 0; q < phi_bins; ++q) {
      const Dir3 o_c = dir3(b * kHalfPi / theta_bins, (q + 0.5) * 2.0 * kPi / phi_bins);
      double phi = std::atan2(o_c.y, ix + o_c.x);
      if (phi < 0.0) phi += kPi;
      for (double p : {phi, phi + kPi})
        if (p > 0.0 && p < span) cuts.emplace_back(p, false);
    }
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::pair<double, bool>> merged;
  for (const auto& c : cuts) {
    if (!merged.empty() && c.first - merged.back().first < 1e-12)
      merged.back().second = merged.back().second || c.second;
    else
      merged.push_back(c);
  }
  const double psi_span = psi_of(span) - psi_of(0.0);
  for (std::size_t c = 0; c + 1 < merged.size(); ++c) {
    const double p0 = psi_of(merged[c].first), p1 = psi_of(merged[c + 1].first);
    const bool sq0 = merged[c].second, sq1 = merged[c + 1].second;
    if (!(p1 > p0)) continue;
    const int np_rounded = static_cast<int>(std::lround(panels * (p1 - p0) / psi_span));
    if (np_rounded == 0 && !sq0 && !sq1) {
      node(0.5 * (p0 + p1), p1 - p0);  // a short piece between close cuts: the midpoint rule
      continue;
    }
    const int np = std::max(1, np_rounded);
    for (int pn = 0; pn < np; ++pn)
      for (std::size_t q = 0; q < gl.size(); ++q) {
        const double sv = (pn + 0.5 + 0.5 * gl.x[q]) / np;
        double g, dg;
        flat_end_map(sq0, sq1, sv, g, dg);
        node(p0 + (p1 - p0) * g, (p1 - p0) * dg * 0.5 * gl.w[q] / np);
      }
  }
  Lobe3d out;
  out.theta_bins = theta_bins;
  out.phi_bins = phi_bins;
  out.max_k = max_k;
  out.by_k = acc.by_k;
  out.hist_by_k = acc.hist_by_k;
  out.hist.assign(static_cast<std::size_t>(nb), 0.0);
  for (int row = 0; row < max_k + 2; ++row)
    for (int b = 0; b < nb; ++b)
      out.hist[static_cast<std::size_t>(b)] += out.hist_by_k[static_cast<std::size_t>(row) * nb + b];
  for (double v : out.by_k) out.albedo += v;
  return out;
}

}  // namespace vgroove::analytic
