// vgroove analytic: the kaleidoscopic dielectric model over an NDF (kaleidoscope_dielectric_lobe.h).
// Per cross-section (flatland: one; 3D: one per groove azimuth node) and facet, the groove slope
// theta_m is cut into Eq. (4)'s bands of k, then into pieces of a grid graded around theta_m = 0;
// on each piece every lobe's bin and form (Eq. 6's clamps, total internal reflection, the horizon)
// is sampled and each change bisected to rounding, and each segment between changes is integrated
// by Gauss-Legendre (flat-end mapped where total internal reflection starts: 1 - F has a square-root
// corner there). Derivation: docs/derivations/kaleidoscope_dielectric.md, "The BSDF over an NDF".
#include "vgroove/analytic/kaleidoscope_dielectric_lobe.h"

#include "vgroove/analytic/dielectric_section.h"
#include "vgroove/analytic/kaleidoscope_dielectric.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vgroove::analytic {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = 0.5 * std::numbers::pi;

// Codes of a lobe in a signature besides its bin (>= 0).
constexpr int kNotBinned = -1;  // reflected below the horizon, or transmitted travelling back up
constexpr int kEmpty = -3;      // a reflected zone of zero width (Eq. 6's clamps)
constexpr int kTir = -4;        // total internal reflection at this hit

// Where a lobe changes bin is located to this in theta_m: a cut moves at most the density times
// this between two bins (cut_error). In 3D the azimuth quadrature errs by ~1e-6..1e-4 a bin, and
// the bisection is half the cost: 1e-10 there.
constexpr double kCutTolerance = 1e-14;
constexpr double kCutTolerance3d = 1e-10;

// One cross-section problem (flatland: the problem itself; 3D: one groove azimuth).
struct Section : DielectricSection {
  const DielectricLobeOptions* opt = nullptr;
  double cut_tolerance = kCutTolerance;  // in theta_m
  std::function<int(double)> bin_r;      // the 2D exit angle above -> bin, or kNotBinned
  std::function<int(double)> bin_t;      // the 2D angle below (sim::exit_angle's) -> bin, or kNotBinned
  // The density of theta_m (per radian): flatland 2 D2 cos, 3D 2 pi D cos sin.
  std::function<double(double)> pdf;
};

struct Acc {
  int bins = 0, max_k = 0;
  std::vector<double> r, t;  // [row * bins + bin]
  double not_binned_r = 0.0, upward = 0.0, unresolved = 0.0;
  double light = 0.0;  // flux of the light pieces (their mass estimates)
  void add(bool reflected, int k, int bin, double v) {
    const std::size_t at = static_cast<std::size_t>(std::min(k, max_k + 1)) * bins + bin;
    (reflected ? r : t)[at] += v;
  }
};

DielectricFacetPrediction predict(const Section& s, double theta_v, FacetSide side) {
  const DielectricLobeOptions& o = *s.opt;
  auto F = [&](double cos2d) {
    if (s.all_tir) return 1.0;
    // Fresnel's angle is the 3D one: cos = r_1 cos' (dielectric_lifting.md, "The 3D local angle").
    const double c = o.broken_fresnel_at_cross_section_angle ? cos2d : s.c3d * cos2d;
    return o.reflectance ? o.reflectance(c) : optics::fresnel_dielectric(c, s.eta);
  };
  return kaleidoscope_dielectric_with(s.tau, theta_v, s.all_tir ? 1.0 : s.eta_dir, side, F);
}

// Which bins and forms the lobes are in at theta_v: constant on a segment.
void signature(const Section& s, const DielectricFacetPrediction& p, std::vector<int>& sig) {
  sig.clear();
  sig.push_back(p.lit ? p.k : -1);
  if (!p.lit) return;
  sig.push_back(p.shadow > 0.0 ? 1 : 0);
  // A lobe without light (an empty zone, or F = 0 or 1 upstream) has no bin: its direction's
  // changes are no cuts.
  sig.push_back(p.fewer.share > 0.0 ? s.bin_r(p.fewer.theta_o) : kEmpty);
  sig.push_back(p.more.share > 0.0 ? s.bin_r(p.more.theta_o) : kEmpty);
  for (const TransmittedLobe& t : p.transmitted)
    sig.push_back(t.tir ? kTir : (t.share > 0.0 ? s.bin_t(t.theta_t) : kEmpty));
}

// Whether a change between two signatures involves total internal reflection starting or ending.
bool tir_changes(const std::vector<int>& a, const std::vector<int>& b) {
  const std::size_t n = std::max(a.size(), b.size());
  for (std::size_t i = 4; i < n; ++i) {
    const int x = i < a.size() ? a[i] : kEmpty, y = i < b.size() ? b[i] : kEmpty;
    if ((x == kTir) != (y == kTir)) return true;
  }
  return false;
}

double theta_v_of(double theta_m) { return kPi - 2.0 * theta_m; }

// Every change of signature in (a, b) (theta_m), bisected to s.cut_tolerance.
void refine(const Section& s, FacetSide side, double a, const std::vector<int>& sa, double b,
            const std::vector<int>& sb, std::vector<std::pair<double, bool>>& cuts, int depth) {
  if (sa == sb) return;
  const double m = 0.5 * (a + b);
  if (depth > 80 || !(b - a > s.cut_tolerance)) {
    cuts.emplace_back(m, tir_changes(sa, sb));
    return;
  }
  std::vector<int> sm;
  signature(s, predict(s, theta_v_of(m), side), sm);
  refine(s, side, a, sa, m, sm, cuts, depth + 1);
  refine(s, side, m, sm, b, sb, cuts, depth + 1);
}

// The deposits of one facet's lobes at theta_m, weighted by w (quadrature weight times density).
void deposit(const Section& s, FacetSide side, double theta_m, double w, Acc& acc) {
  const double theta_v = theta_v_of(theta_m);
  const DielectricFacetPrediction p = predict(s, theta_v, side);
  if (!p.lit) return;
  // The share of the light entering the groove that is aimed at this facet: f_a over the opening.
  const double scale = w * p.f_a / opening_width(s.tau, theta_v);
  for (const ReflectedLobe* r : {&p.fewer, &p.more}) {
    if (!(r->share > 0.0)) continue;
    const int bin = s.bin_r(r->theta_o);
    if (bin < 0)
      acc.not_binned_r += scale * r->share;
    else
      acc.add(true, r->n, bin, scale * r->share);
  }
  for (const TransmittedLobe& t : p.transmitted) {
    if (!(t.share > 0.0)) continue;
    const int bin = s.bin_t(t.theta_t);
    if (bin < 0)
      acc.upward += scale * t.share;
    else
      acc.add(false, t.j, bin, scale * t.share);
  }
}

// Gauss-Legendre over [a, b] of theta_m, each end flat-mapped when marked.
template <class Fn>
void for_each_node(const GaussLegendre& gl, double a, double b, bool flat_a, bool flat_b, Fn&& fn) {
  for (std::size_t q = 0; q < gl.size(); ++q) {
    double g = 0.0, dg = 0.0;
    flat_end_map(flat_a, flat_b, 0.5 * (gl.x[q] + 1.0), g, dg);
    fn(a + (b - a) * g, 0.5 * gl.w[q] * dg * (b - a));
  }
}

// The grid of theta_m in [0, pi/2]: pieces of at most 0.05, alpha / 4 near 0 (D's peak), growing
// by 25 % beyond (D's tail falls off on the scale of theta_m itself).
std::vector<double> slope_grid(double alpha) {
  std::vector<double> g{0.0};
  while (g.back() < kHalfPi) g.push_back(g.back() + std::min(0.05, std::max(0.25 * alpha, 0.25 * g.back())));
  g.back() = kHalfPi;
  return g;
}

// One facet of one cross-section, weighted by w_section: every band k <= k_cap binned, the rest
// into `unresolved`.
void integrate_facet(const Section& s, FacetSide side, const std::vector<double>& grid, double w_section,
                     const GaussLegendre& gl, int samples, Acc& acc) {
  const DielectricLobeOptions& o = *s.opt;
  const double tf = side == FacetSide::left ? s.tau : -s.tau;
  const double lit_lo = std::max(0.0, 2.0 * tf);  // f_a = sin(theta_v/2 - tf) > 0
  const double cpk = kPi + 2.0 * tf;              // Eq. (4): k changes at theta_v = cpk / m
  std::vector<int> sa, sb;
  std::vector<std::pair<double, bool>> cuts;
  auto pieces = [&](double m_lo, double m_hi, auto&& on_piece) {
    double a = m_lo;
    for (double g : grid) {
      if (g <= a) continue;
      const double b = std::min(g, m_hi);
      on_piece(a, b);
      a = b;
      if (a >= m_hi) break;
    }
  };
  for (int m = 1; m <= o.k_cap; ++m) {
    const double hi = std::min(kPi, m == 1 ? kPi : cpk / (m - 1));
    const double lo = std::max(lit_lo, cpk / m);
    if (hi <= lit_lo) break;
    if (!(hi > lo)) continue;
    pieces(0.5 * (kPi - hi), 0.5 * (kPi - lo), [&](double a, double b) {
      // A light piece (the NDF's tail): node by node, each deposit in its own bin; a bin errs by
      // at most the piece's flux.
      if (s.pdf(0.5 * (a + b)) * (b - a) < o.light_piece) {
        acc.light += w_section * s.pdf(0.5 * (a + b)) * (b - a);
        for_each_node(gl, a, b, false, false,
                      [&](double tm, double wq) { deposit(s, side, tm, w_section * wq * s.pdf(tm), acc); });
        return;
      }
      cuts.assign({{a, false}, {b, false}});
      // Samples strictly inside: the band's ends belong to the neighbouring k.
      double x_prev = a + 1e-13 * (b - a);
      signature(s, predict(s, theta_v_of(x_prev), side), sa);
      for (int q = 1; q <= samples; ++q) {
        const double x = q == samples ? b - 1e-13 * (b - a) : a + (b - a) * q / samples;
        signature(s, predict(s, theta_v_of(x), side), sb);
        refine(s, side, x_prev, sa, x, sb, cuts, 0);
        x_prev = x;
        std::swap(sa, sb);
      }
      std::sort(cuts.begin(), cuts.end());
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const double x0 = cuts[c].first, x1 = cuts[c + 1].first;
        if (!(x1 > x0)) continue;
        for_each_node(gl, x0, x1, cuts[c].second, cuts[c + 1].second,
                      [&](double tm, double wq) { deposit(s, side, tm, w_section * wq * s.pdf(tm), acc); });
      }
    });
  }
  // The grooves beyond k_cap: their flux (f_a - f_b over the opening), not binned.
  const double v_cap = std::min(kPi, cpk / o.k_cap);
  auto unresolved = [&](double a, double b) {
    for_each_node(gl, a, b, false, false, [&](double tm, double wq) {
      const double v = theta_v_of(tm);
      const FacetPrediction p = G_kaleidoscopic(s.tau, v, side);
      if (p.lit) acc.unresolved += w_section * wq * s.pdf(tm) * (p.f_a - p.f_b) / opening_width(s.tau, v);
    });
  };
  // Cut where f_b = max(0, -sin(theta_v/2 + tf)) starts (theta_v = -2 tf): a kink.
  const double v_b = std::clamp(-2.0 * tf, lit_lo, std::max(lit_lo, v_cap));
  if (v_cap > v_b) pieces(0.5 * (kPi - v_cap), 0.5 * (kPi - v_b), unresolved);
  if (v_b > lit_lo) pieces(0.5 * (kPi - v_b), 0.5 * (kPi - lit_lo), unresolved);
}

DielectricLobe make_lobe(const Acc& acc, int theta_bins, int phi_bins) {
  DielectricLobe L;
  L.bins = acc.bins;
  L.theta_bins = theta_bins;
  L.phi_bins = phi_bins;
  L.max_k = acc.max_k;
  L.reflected.assign(acc.bins, 0.0);
  L.transmitted.assign(acc.bins, 0.0);
  for (int row = 0; row < acc.max_k + 2; ++row) {
    const auto b0 = acc.r.begin() + static_cast<std::ptrdiff_t>(row) * acc.bins;
    const auto t0 = acc.t.begin() + static_cast<std::ptrdiff_t>(row) * acc.bins;
    L.reflected_by_k.emplace_back(b0, b0 + acc.bins);
    L.transmitted_by_k.emplace_back(t0, t0 + acc.bins);
    for (int b = 0; b < acc.bins; ++b) {
      L.reflected[b] += L.reflected_by_k.back()[b];
      L.transmitted[b] += L.transmitted_by_k.back()[b];
    }
  }
  for (int b = 0; b < acc.bins; ++b) L.albedo_r += L.reflected[b], L.albedo_t += L.transmitted[b];
  L.upward = acc.upward;
  L.unresolved = acc.unresolved;
  L.light = acc.light;
  L.shadow_or_unknown = acc.upward + acc.unresolved + acc.not_binned_r;
  return L;
}

Acc empty_acc(int bins, int max_k) {
  Acc acc;
  acc.bins = bins;
  acc.max_k = max_k;
  const std::size_t n = static_cast<std::size_t>(max_k + 2) * bins;
  acc.r.assign(n, 0.0);
  acc.t.assign(n, 0.0);
  return acc;
}

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

void check_common(double alpha, double eta, double theta_i, int max_k, const DielectricLobeOptions& o) {
  check(alpha > 0.0 && std::isfinite(alpha), "alpha must be > 0");
  check(eta > 0.0 && std::isfinite(eta), "eta must be in (0, inf)");
  check(std::abs(theta_i) < kHalfPi, "theta_i must be in (-pi/2, pi/2)");
  check(max_k >= 0, "max_k must be >= 0");
  check(o.k_cap >= 1 && o.order >= 1 && o.samples >= 1 && o.phi_panels >= 1 && o.phi_order >= 1,
        "k_cap, order, samples, phi_panels and phi_order must be >= 1");
}

int flat_bin(double t, int bins) {
  const int j = static_cast<int>(std::floor((t + kHalfPi) / (kPi / bins)));
  return std::clamp(j, 0, bins - 1);
}

DielectricLobe flatland_once(NdfKind ndf, double alpha, double eta, double theta_i, int bins, int max_k,
                             const DielectricLobeOptions& o) {
  Section s;
  static_cast<DielectricSection&>(s) = flatland_section(theta_i, eta);
  s.opt = &o;
  s.bin_r = [bins](double t) { return std::cos(t) > 0.0 ? flat_bin(t, bins) : kNotBinned; };
  s.bin_t = [bins](double t) { return std::cos(t) > 0.0 ? flat_bin(t, bins) : kNotBinned; };
  s.pdf = [ndf, alpha](double tm) { return 2.0 * D2(ndf, tm, alpha) * std::cos(tm); };
  Acc acc = empty_acc(bins, max_k);
  const std::vector<double> grid = slope_grid(alpha);
  const GaussLegendre gl = gauss_legendre(o.order);
  for (FacetSide side : {FacetSide::left, FacetSide::right}) integrate_facet(s, side, grid, 1.0, gl, o.samples, acc);
  return make_lobe(acc, 0, 0);
}

// 3D: the groove azimuths phi_a in [0, pi/2] (the rest by the mirror images phi_a -> pi - phi_a,
// phi_o -> -phi_o; phi_a uniform over [0, pi)).
DielectricLobe lobe_3d_once(NdfKind ndf, double alpha, double eta, double theta_i, int tb, int pb, int max_k,
                            const DielectricLobeOptions& o) {
  Acc acc = empty_acc(tb * pb, max_k);
  const std::vector<double> grid = slope_grid(alpha);
  const GaussLegendre gl = gauss_legendre(o.order), gl_phi = gauss_legendre(o.phi_order);
  const double dphi = 2.0 * kPi / pb, dtheta = kHalfPi / tb;
  auto bin3 = [&](double ox, double oy, double oz_from_normal) {
    if (!(oz_from_normal > 0.0)) return kNotBinned;
    const int t = std::min(tb - 1, static_cast<int>(std::atan2(std::hypot(ox, oy), oz_from_normal) / dtheta));
    int p = static_cast<int>(std::floor((std::atan2(oy, ox) + 0.5 * dphi) / dphi));
    p = ((p % pb) + pb) % pb;
    return t * pb + p;
  };
  if (theta_i == 0.0) {
    // Normal incidence: every azimuth shows the same cross-section (tau = 0, q = 0) turned by phi_a,
    // its exits in the plane of a at theta = |t|; phi_a uniform spreads each theta bin's flux
    // uniformly over phi. One cross-section, binned in theta, then spread.
    Section s;
    static_cast<DielectricSection&>(s) = flatland_section(0.0, eta);
    s.opt = &o;
    auto tbin = [&](double t) {
      return std::cos(t) > 0.0 ? std::min(tb - 1, static_cast<int>(std::abs(t) / dtheta)) : kNotBinned;
    };
    s.bin_r = tbin;
    s.bin_t = tbin;
    s.pdf = [ndf, alpha](double tm) { return 2.0 * kPi * D(ndf, tm, alpha) * std::cos(tm) * std::sin(tm); };
    Acc one = empty_acc(tb, max_k);
    for (FacetSide side : {FacetSide::left, FacetSide::right}) integrate_facet(s, side, grid, 1.0, gl, o.samples, one);
    for (int row = 0; row < max_k + 2; ++row)
      for (int t = 0; t < tb; ++t)
        for (int p = 0; p < pb; ++p) {
          const std::size_t from = static_cast<std::size_t>(row) * tb + t,
                            to = (static_cast<std::size_t>(row) * tb + t) * pb + p;
          acc.r[to] = one.r[from] / pb;
          acc.t[to] = one.t[from] / pb;
        }
    acc.not_binned_r = one.not_binned_r, acc.upward = one.upward, acc.unresolved = one.unresolved,
    acc.light = one.light;
    return make_lobe(acc, tb, pb);
  }
  // Panels over [0, pi/2], cut where an exit at normal incidence crosses a phi edge (phi_a = (p + 1/2) dphi).
  std::vector<double> cuts{0.0, kHalfPi};
  for (int p = 0; (p + 0.5) * dphi < kHalfPi; ++p) cuts.push_back((p + 0.5) * dphi);
  std::sort(cuts.begin(), cuts.end());
  std::vector<double> panels;
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
    const int n = std::max(1, static_cast<int>(std::ceil(o.phi_panels * (cuts[c + 1] - cuts[c]) / kHalfPi)));
    for (int j = 0; j < n; ++j) panels.push_back(cuts[c] + (cuts[c + 1] - cuts[c]) * j / n);
  }
  panels.push_back(kHalfPi);
  const double st = std::sin(theta_i), ct = std::cos(theta_i);
  for (std::size_t pn = 0; pn + 1 < panels.size(); ++pn) {
    const double a0 = panels[pn], a1 = panels[pn + 1];
    for (std::size_t q = 0; q < gl_phi.size(); ++q) {
      const double phi_a = 0.5 * (a0 + a1) + 0.5 * (a1 - a0) * gl_phi.x[q];
      const double w_phi = 0.5 * (a1 - a0) * gl_phi.w[q] / kPi;  // phi_a uniform over [0, pi)
      const double ca = std::cos(phi_a), sa = std::sin(phi_a);
      // The light i = (-sin theta_i, 0, cos theta_i); a = (ca, sa, 0), u = (-sa, ca, 0).
      const double i_a = -st * ca, i_u = st * sa;
      Section s;
      static_cast<DielectricSection&>(s) = lifted_section(i_a, i_u, ct, eta);
      s.cut_tolerance = kCutTolerance3d;
      s.opt = &o;
      const double c = s.c3d;
      const double q_1 = -i_u;  // the travel direction's axis component in medium 1 (= p, n1 = 1)
      const double q_2 = q_1 / eta, r_2 = s.all_tir ? 0.0 : std::sqrt((1.0 - q_2) * (1.0 + q_2));
      // Exits lifted: o = r (e_x a + e_y n) + q u, e = (-sin t, cos t) above, (sin t, -cos t) below.
      s.bin_r = [&, c, q_1, ca, sa](double t) {
        const double ex = -c * std::sin(t);
        return bin3(ex * ca - q_1 * sa, ex * sa + q_1 * ca, c * std::cos(t));
      };
      s.bin_t = [&, r_2, q_2, ca, sa](double t) {
        const double ex = r_2 * std::sin(t);
        return bin3(ex * ca - q_2 * sa, ex * sa + q_2 * ca, r_2 * std::cos(t));
      };
      s.pdf = [ndf, alpha](double tm) { return 2.0 * kPi * D(ndf, tm, alpha) * std::cos(tm) * std::sin(tm); };
      Acc node = empty_acc(tb * pb, max_k);
      for (FacetSide side : {FacetSide::left, FacetSide::right})
        integrate_facet(s, side, grid, w_phi, gl, o.samples, node);
      // The node and its mirror image (phi_o -> -phi_o).
      for (std::size_t b = 0; b < node.r.size(); ++b) {
        const std::size_t row = b / (tb * pb), bin = b % (tb * pb);
        const std::size_t t = bin / pb, p = bin % pb;
        const std::size_t mirror = row * tb * pb + t * pb + (pb - p) % pb;
        acc.r[b] += node.r[b], acc.r[mirror] += node.r[b];
        acc.t[b] += node.t[b], acc.t[mirror] += node.t[b];
      }
      acc.not_binned_r += 2.0 * node.not_binned_r;
      acc.upward += 2.0 * node.upward;
      acc.unresolved += 2.0 * node.unresolved;
      acc.light += 2.0 * node.light;
    }
  }
  return make_lobe(acc, tb, pb);
}

double largest_change(const DielectricLobe& a, const DielectricLobe& b) {
  double e = std::max(std::abs(a.albedo_r - b.albedo_r), std::abs(a.albedo_t - b.albedo_t));
  for (std::size_t i = 0; i < a.reflected.size(); ++i)
    e = std::max({e, std::abs(a.reflected[i] - b.reflected[i]), std::abs(a.transmitted[i] - b.transmitted[i])});
  return e;
}

// The flux a bin may gain or lose from the cuts' locations: two ends per segment, each within
// kCutTolerance, times the largest density (sampled on the slope grid, doubled for safety).
double cut_error(NdfKind ndf, double alpha, bool three_d) {
  double pdf_max = 0.0;
  for (double tm : slope_grid(alpha)) {
    const double p =
        three_d ? 2.0 * kPi * D(ndf, tm, alpha) * std::cos(tm) * std::sin(tm) : 2.0 * D2(ndf, tm, alpha) * std::cos(tm);
    if (std::isfinite(p)) pdf_max = std::max(pdf_max, p);
  }
  return 4.0 * (three_d ? kCutTolerance3d : kCutTolerance) * pdf_max;
}

DielectricLobeOptions doubled(const DielectricLobeOptions& o) {
  DielectricLobeOptions d = o;
  d.order *= 2;
  d.samples *= 2;
  d.phi_panels *= 2;
  return d;
}

// Light from below: the model at 1 / eta with the picture mirrored in the macrosurface. Flatland:
// a direction (x, y) becomes (x, -y), so an exit angle t (either side) becomes -t: the bins flip.
void flip_flatland(DielectricLobe& L) {
  auto flip = [](std::vector<double>& v) { std::reverse(v.begin(), v.end()); };
  flip(L.reflected), flip(L.transmitted);
  for (auto& row : L.reflected_by_k) flip(row);
  for (auto& row : L.transmitted_by_k) flip(row);
}

}  // namespace

DielectricLobe kaleidoscope_dielectric_lobe_flatland(NdfKind ndf, double alpha, double eta, double theta_i, int bins,
                                                     int max_k, const DielectricLobeOptions& opt) {
  check_common(alpha, eta, theta_i, max_k, opt);
  check(bins >= 1, "bins must be >= 1");
  const bool below = opt.from == DielectricLightFrom::below;
  const double e = below ? 1.0 / eta : eta;
  DielectricLobe L = flatland_once(ndf, alpha, e, theta_i, bins, max_k, opt);
  if (opt.error_estimate) {
    DielectricLobe fine = flatland_once(ndf, alpha, e, theta_i, bins, max_k, doubled(opt));
    fine.error_estimate = std::max(largest_change(L, fine), fine.light) + cut_error(ndf, alpha, false);
    L = std::move(fine);
  }
  if (below) flip_flatland(L);
  return L;
}

DielectricLobe kaleidoscope_dielectric_lobe_3d(NdfKind ndf, double alpha, double eta, double theta_i, int theta_bins,
                                               int phi_bins, int max_k, const DielectricLobeOptions& opt) {
  check_common(alpha, eta, theta_i, max_k, opt);
  check(theta_i >= 0.0, "theta_i must be in [0, pi/2)");
  check(theta_bins >= 1 && phi_bins >= 2 && phi_bins % 2 == 0, "theta_bins >= 1, phi_bins even >= 2");
  // Light from below, mirrored in z: the angles from the exit side's normal and phi are unchanged.
  const double e = opt.from == DielectricLightFrom::below ? 1.0 / eta : eta;
  DielectricLobe L = lobe_3d_once(ndf, alpha, e, theta_i, theta_bins, phi_bins, max_k, opt);
  if (opt.error_estimate) {
    DielectricLobe fine = lobe_3d_once(ndf, alpha, e, theta_i, theta_bins, phi_bins, max_k, doubled(opt));
    fine.error_estimate = std::max(largest_change(L, fine), fine.light) + cut_error(ndf, alpha, true);
    L = std::move(fine);
  }
  return L;
}

}  // namespace vgroove::analytic
