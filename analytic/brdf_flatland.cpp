#include "vgroove/analytic/brdf_flatland.h"

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/kaleidoscope_solutions.h"
#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

// Left facet of the groove of aperture theta_v: theta_s = -(pi - theta_v)/2.
double theta_s_left(double theta_v) { return 0.5 * theta_v - kHalfPi; }

// w_n of the header's step (b) for the left facet at incidence theta_i: the projected width
// (unit facet) of the rays aimed at it that leave after n reflections.
double width_left(double theta_i, double theta_v, int n) {
  const FacetPrediction p = G_kaleidoscopic(theta_i, theta_v, FacetSide::left);
  if (!p.lit) return 0.0;
  double w = 0.0;
  // Lee et al. 2018, Eq. (6) times f_a: G(k-1) f_a = f_a - f_k, G(k) f_a = f_k - f_b.
  if (p.fewer.n == n) w += p.f_a - p.f_k;
  if (p.more.n == n) w += p.f_k - p.f_b;
  return w;
}

// rho2 cos(theta_o) cos(theta_i) from the left facets, step (d) of the header.
double left_term(NdfKind ndf, double alpha, double theta_i, double theta_o, int k) {
  const double sign = (k % 2 == 0) ? 1.0 : -1.0;
  // Eq. (5) inverted: k theta_v = theta_i + pi - (-1)^k theta_o + 2 pi m, theta_v in (0, pi].
  const double base = theta_i + std::numbers::pi - sign * theta_o;
  const int m_lo = static_cast<int>(std::ceil(-base / (2.0 * std::numbers::pi)));
  double sum = 0.0;
  for (int m = m_lo;; ++m) {
    const double theta_v = (base + 2.0 * std::numbers::pi * m) / k;
    if (!(theta_v > 0.0)) continue;
    if (theta_v > std::numbers::pi) break;
    const double w = width_left(theta_i, theta_v, k);
    // |d theta_s / d theta_o| = 1 / (2k): the flatland Eq. (13).
    if (w > 0.0) sum += D2(ndf, theta_s_left(theta_v), alpha) * w / (2.0 * k);
  }
  return sum;
}

// ---- The binned lobe ---------------------------------------------------------------------------

struct Accumulator {
  int bins, max_k;
  std::vector<double> hist;  // [row * bins + bin]
  double below = 0.0;
  double tail = 0.0;

  int row_of(int n) const { return std::min(n, max_k + 1); }
  void add(int n, int bin, double v) { hist[static_cast<std::size_t>(row_of(n)) * bins + bin] += v; }
};

struct LobeContext {
  NdfKind ndf;
  double alpha;
  int bins;
  double bin_w;
  GaussLegendre gl_hi, gl_mid, gl_lo;
  std::vector<double> peak_points;  // theta_v values graded around theta_s = 0
};

const GaussLegendre& order_for(const LobeContext& c, int k) {
  // Pieces of Eq. (4) shrink like pi/k^2 and the integrand varies little across them.
  return k <= 8 ? c.gl_hi : (k <= 64 ? c.gl_mid : c.gl_lo);
}

// Flux of the left facets at incidence theta_i (the right facets: mirror = true, called with
// -theta_i; the bin is then flipped) for the k-pieces k = 1..n_res + 1, into the bins.
void add_left_resolved(const LobeContext& c, double theta_i, bool mirror, int n_res, Accumulator& acc,
                       const std::atomic<bool>* cancel) {
  const double lit_lo = std::max(0.0, 2.0 * theta_i);   // f_a = sin(theta_v/2 - theta_i) > 0
  const double cpk = std::numbers::pi + 2.0 * theta_i;  // Eq. (4): k changes at theta_v = cpk / m
  const double inv_cos = 1.0 / std::cos(theta_i);
  std::vector<double> cuts;
  std::size_t subs_done = 0;
  bool stopped = false;  // cancel read set: the rest is skipped
  for (int k = 1; k <= n_res + 1; ++k) {
    if (stopped || (cancel && cancel->load(std::memory_order_relaxed))) return;
    // Eq. (4): k on (cpk / k, cpk / (k - 1)].
    const double hi = std::min(std::numbers::pi, k == 1 ? std::numbers::pi : cpk / (k - 1));
    const double lo = std::max(lit_lo, cpk / k);
    if (hi <= lit_lo) break;
    if (!(hi > lo)) continue;
    cuts.assign({lo, hi});
    auto cut = [&](double v) {
      if (v > lo && v < hi) cuts.push_back(v);
    };
    cut(-2.0 * theta_i);  // f_b = max(0, -sin(theta_v/2 + theta_i)) switches
    // f(k) = sin((k - 1/2) theta_v - theta_i) = 0 (the clamp at 0), and f(k) = f(b) (kth = 2 pi j).
    const double kh = k - 0.5;
    for (int j = static_cast<int>(std::ceil((kh * lo - theta_i) / std::numbers::pi));
         j <= static_cast<int>(std::floor((kh * hi - theta_i) / std::numbers::pi)); ++j)
      cut((theta_i + j * std::numbers::pi) / kh);
    for (int j = static_cast<int>(std::ceil(k * lo / (2.0 * std::numbers::pi)));
         j <= static_cast<int>(std::floor(k * hi / (2.0 * std::numbers::pi))); ++j)
      cut(2.0 * std::numbers::pi * j / k);
    for (double v : c.peak_points) cut(v);
    std::sort(cuts.begin(), cuts.end());
    const GaussLegendre& gl = order_for(c, k);
    for (std::size_t p = 0; p + 1 < cuts.size(); ++p) {
      const double a = cuts[p], b = cuts[p + 1];
      if (!(b > a)) continue;
      // The sub-intervals of [a, b] on which n reflections land in one bin, n = k - 1 and k, each
      // handed to fn.
      struct Sub {
        int n;
        double va, vb;
        long bin;
      };
      auto for_each_sub = [&](auto&& fn) {
        for (int n = std::max(1, k - 1); n <= k; ++n) {  // k = 1: w_0 = f_a - f_k = 0 (f_k = f_a)
          // Eq. (5), unwrapped: y = (-1)^n (theta_i + pi - n theta_v), linear in theta_v.
          const double sgn = (n % 2 == 0) ? 1.0 : -1.0;
          auto y_of = [&](double v) { return sgn * (theta_i + std::numbers::pi - n * v); };
          auto v_of = [&](double y) { return (theta_i + std::numbers::pi - sgn * y) / n; };
          const double ya = std::min(y_of(a), y_of(b)), yb = std::max(y_of(a), y_of(b));
          // Bin edges -pi/2 + j w on the whole circle (2 bins of them per turn).
          const long j0 = static_cast<long>(std::floor((ya + kHalfPi) / c.bin_w));
          const long j1 = static_cast<long>(std::floor((yb + kHalfPi) / c.bin_w));
          for (long j = j0; j <= j1; ++j) {
            const double y_lo = std::max(ya, -kHalfPi + j * c.bin_w);
            const double y_hi = std::min(yb, -kHalfPi + (j + 1) * c.bin_w);
            if (!(y_hi > y_lo)) continue;
            const double v1 = std::clamp(v_of(y_lo), a, b), v2 = std::clamp(v_of(y_hi), a, b);
            const double va = std::min(v1, v2), vb = std::max(v1, v2);
            if (!(vb > va)) continue;
            long bin = j % (2L * c.bins);
            if (bin < 0) bin += 2L * c.bins;
            fn(Sub{n, va, vb, bin});
          }
        }
      };
      Sub subs[2 * 64];
      int count = 0;
      bool overflow = false;
      for_each_sub([&](const Sub& u) {
        if (count == 2 * 64)
          overflow = true;
        else
          subs[count++] = u;
      });
      auto deposit = [&](const Sub& u, double flux) {
        if (u.bin >= c.bins) {
          acc.below += flux;
          return;
        }
        const int b_out = mirror ? c.bins - 1 - static_cast<int>(u.bin) : static_cast<int>(u.bin);
        acc.add(u.n, b_out, flux);
      };
      // d Phi_n = D2 w_n d theta_s / cos theta_i, d theta_s = d theta_v / 2.
      if (!overflow && count == 2 && subs[0].va == a && subs[0].vb == b && subs[1].va == a && subs[1].vb == b) {
        // Both counts stay in one bin each (large k): one evaluation of Eq. (6) per node.
        const double h = 0.5 * (b - a), m = 0.5 * (a + b);
        double s0 = 0.0, s1 = 0.0;
        for (std::size_t q = 0; q < gl.x.size(); ++q) {
          const double v = m - h * gl.x[q];  // nodes from the right end (the rule is symmetric)
          const FacetPrediction pr = G_kaleidoscopic(theta_i, v, FacetSide::left);
          if (!pr.lit) continue;
          const double d = gl.w[q] * D2(c.ndf, theta_s_left(v), c.alpha);
          const double w_fewer = pr.f_a - pr.f_k, w_more = pr.f_k - pr.f_b;
          s0 += d * ((pr.fewer.n == subs[0].n ? w_fewer : 0.0) + (pr.more.n == subs[0].n ? w_more : 0.0));
          s1 += d * ((pr.fewer.n == subs[1].n ? w_fewer : 0.0) + (pr.more.n == subs[1].n ? w_more : 0.0));
        }
        deposit(subs[0], s0 * h * 0.5 * inv_cos);
        deposit(subs[1], s1 * h * 0.5 * inv_cos);
        continue;
      }
      auto one = [&](const Sub& u) {
        // A piece may cross every bin (k = 1 over 10^5 bins: 0.4 s): read `cancel` every 4096.
        if ((++subs_done & 4095) == 0 && cancel && cancel->load(std::memory_order_relaxed)) stopped = true;
        if (stopped) return;
        deposit(u, integrate_mirrored(
                       gl, [&](double v) { return D2(c.ndf, theta_s_left(v), c.alpha) * width_left(theta_i, v, u.n); },
                       u.va, u.vb) *
                       0.5 * inv_cos);
      };
      if (!overflow) {
        for (int q = 0; q < count; ++q) one(subs[q]);
        continue;
      }
      // Many bins crossed on one piece (only with very many bins): each sub-interval as it comes.
      for_each_sub(one);
    }
  }
}

// Flux of the left facets with theta_v in (lit_lo, upper]: all of it leaves (f_a - f_b).
// Graded towards theta_v = 0, where D2 may diverge (Phong, alpha > 1).
double left_flux_below(const LobeContext& c, double theta_i, double upper) {
  const double lit_lo = std::max(0.0, 2.0 * theta_i);
  if (!(upper > lit_lo)) return 0.0;
  const double inv_cos = 1.0 / std::cos(theta_i);
  auto f = [&](double v) {
    const FacetPrediction p = G_kaleidoscopic(theta_i, v, FacetSide::left);
    return p.lit ? D2(c.ndf, theta_s_left(v), c.alpha) * (p.f_a - p.f_b) : 0.0;
  };
  // Below v0 the facet angle theta_s = theta_v/2 - pi/2 is no longer resolved in double (its
  // rounding, ~1e-16, is a relative error 2e-16/theta_v in cos theta_s, the quantity D2 depends
  // on near the horizon): there the integrand is extrapolated as the power law it is, I(v) =
  // I(v0) (v/v0)^e with e fitted on [v0/2, v0] (Phong: D2 ~ cos^p ~ (v/2)^p and f_a - f_b ~ v,
  // e = p + 1 > -1; GGX: e = 1; Beckmann: I = 0), whose integral over (0, v0) is I(v0) v0/(e+1).
  const double v0 = std::ldexp(1.0, -24);
  double s = 0.0;
  double start = lit_lo;
  if (lit_lo < v0 && upper > v0) {
    const double i1 = f(v0), i2 = f(0.5 * v0);
    if (i1 > 0.0 && i2 > 0.0) {
      const double e = std::log2(i1 / i2);
      if (e > -1.0) s += i1 * v0 / (e + 1.0);
    }
    start = v0;
  }
  std::vector<double> cuts{start, upper};
  if (-2.0 * theta_i > start && -2.0 * theta_i < upper) cuts.push_back(-2.0 * theta_i);
  // Dyadic grading towards v0, where D2 may diverge like theta_v^-1.5.
  for (double v = 0.5 * upper; v > start; v *= 0.5) cuts.push_back(v);
  std::sort(cuts.begin(), cuts.end());
  for (std::size_t p = 0; p + 1 < cuts.size(); ++p)
    if (cuts[p + 1] > cuts[p]) s += integrate_mirrored(c.gl_mid, f, cuts[p], cuts[p + 1]);
  return s * 0.5 * inv_cos;
}

int bin_of(double theta, int bins, bool lower_side) {
  const double u = (theta + kHalfPi) / (std::numbers::pi / bins);
  int j = static_cast<int>(std::floor(u));
  if (lower_side && j == u) --j;  // exactly on an edge: the bin below it
  return std::clamp(j, 0, bins - 1);
}

// The lobe's arrays, zeroed. The histogram is zeroed in steps of 2^20 values (8 MB), `cancel` (may
// be null) read before each: 10^5 bins at max_k 300 are 242 MB, 1.4 s of page faults on a loaded
// host. Once the flag is set it stops, the histogram short (the lobe is discarded).
FlatlandLobe make_layout(int bins, int max_k, const std::atomic<bool>* cancel = nullptr) {
  FlatlandLobe lobe;
  lobe.bins = bins;
  lobe.max_k = max_k;
  lobe.by_k.assign(static_cast<std::size_t>(max_k) + 2, 0.0);
  lobe.theta_o.assign(static_cast<std::size_t>(bins), 0.0);
  const std::size_t cells = (static_cast<std::size_t>(max_k) + 2) * static_cast<std::size_t>(bins);
  constexpr std::size_t kStep = std::size_t{1} << 20;
  lobe.theta_o_by_k.reserve(cells);
  while (lobe.theta_o_by_k.size() < cells && !(cancel && cancel->load(std::memory_order_relaxed)))
    lobe.theta_o_by_k.resize(std::min(cells, lobe.theta_o_by_k.size() + kStep), 0.0);
  return lobe;
}

void finish(FlatlandLobe& lobe) {
  for (int r = 0; r < lobe.max_k + 2; ++r)
    for (int b = 0; b < lobe.bins; ++b) {
      const double v = lobe.theta_o_by_k[static_cast<std::size_t>(r) * lobe.bins + b];
      lobe.by_k[static_cast<std::size_t>(r)] += v;
      lobe.theta_o[static_cast<std::size_t>(b)] += v;
    }
  lobe.albedo = 0.0;
  for (double v : lobe.by_k) lobe.albedo += v;
}

std::vector<double> peak_points(double alpha) {
  std::vector<double> pts;
  // theta_s = +-atan(alpha s): geometric grading around the peak of D2 (its poles and its width
  // scale with alpha), so Gauss-Legendre converges on every piece however small alpha is.
  for (double s = 1.0 / 64.0; s <= 64.0; s *= 2.0) pts.push_back(std::numbers::pi - 2.0 * std::atan(alpha * s));
  return pts;
}

}  // namespace

double flatland_brdf_k_reference(NdfKind ndf, double alpha, double theta_i, double theta_o, int k) {
  assert(k >= 1 && alpha > 0.0);
  if (!(std::abs(theta_i) < kHalfPi && std::abs(theta_o) < kHalfPi)) return 0.0;
  // Step (d): left facets at (theta_i, theta_o), right facets by the mirror.
  const double sum = left_term(ndf, alpha, theta_i, theta_o, k) + left_term(ndf, alpha, -theta_i, -theta_o, k);
  return sum / (std::cos(theta_i) * std::cos(theta_o));
}

double flatland_brdf_reference(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k) {
  double s = 0.0;
  for (int k = 1; k <= max_k; ++k) s += flatland_brdf_k_reference(ndf, alpha, theta_i, theta_o, k);
  return s;
}

namespace {

// Step (d), D2(theta_s) w_k / (2k) per solution, over the solutions with k in [k_lo, k_hi], in
// the frame where t_h <= 0 (the profile is mirror symmetric).
double single_pass(NdfKind ndf, double alpha, double theta_i, double theta_o, int k_lo, int k_hi) {
  if (!(std::abs(theta_i) < kHalfPi && std::abs(theta_o) < kHalfPi)) return 0.0;
  const double m = theta_i + theta_o > 0.0 ? -1.0 : 1.0;
  double sum = 0.0;
  for_each_solution(cross_section(m * theta_i, m * theta_o), k_lo, k_hi,
                    [&](const Solution& q) { sum += D2_cs(ndf, q.S, q.C, alpha) * q.W / (2.0 * q.k); });
  return sum / (std::cos(theta_i) * std::cos(theta_o));
}

}  // namespace

double flatland_brdf_k(NdfKind ndf, double alpha, double theta_i, double theta_o, int k) {
  assert(k >= 1 && alpha > 0.0);
  return single_pass(ndf, alpha, theta_i, theta_o, k, k);
}

double flatland_brdf(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k) {
  return single_pass(ndf, alpha, theta_i, theta_o, 1, max_k);
}

double flatland_brdf_fast(NdfKind ndf, double alpha, double theta_i, double theta_o, int max_k) {
  return single_pass(ndf, alpha, theta_i, theta_o, 1, max_k);
}

double flatland_brdf_single(NdfKind ndf, double alpha, double theta_i, double theta_o) {
  if (!(std::abs(theta_i) < kHalfPi && std::abs(theta_o) < kHalfPi)) return 0.0;
  // Lee et al. 2018, Eq. (1) in flatland (header, step e): d theta_h / d theta_o = 1/2.
  const double theta_h = 0.5 * (theta_i + theta_o);
  const double cos_d = std::cos(theta_o - theta_h);
  // Eq. (3): G = min(G1(i, h), G1(o, h)), Eq. (2) for each.
  const double G = std::min(G1_vcavity_inplane(theta_i, theta_h), G1_vcavity_inplane(theta_o, theta_h));
  return D2(ndf, theta_h, alpha) * cos_d * G / (2.0 * std::cos(theta_i) * std::cos(theta_o));
}

FlatlandLobe flatland_lobe(NdfKind ndf, double alpha, double theta_i, int bins, int max_k) {
  return flatland_lobe(ndf, alpha, theta_i, bins, max_k, FlatlandLobeOptions{});
}

FlatlandLobe flatland_lobe(NdfKind ndf, double alpha, double theta_i, int bins, int max_k,
                           const FlatlandLobeOptions& opt) {
  assert(bins > 0 && max_k >= 0 && alpha > 0.0 && std::abs(theta_i) < kHalfPi);
  LobeContext c{ndf,
                alpha,
                bins,
                std::numbers::pi / bins,
                gauss_legendre(opt.quadrature_order),
                gauss_legendre(std::max(4, opt.quadrature_order / 2)),
                gauss_legendre(std::max(3, opt.quadrature_order / 4)),
                peak_points(alpha)};
  // Grooves with k >= n + 2 (theta_v <= (pi + 2 theta)/(n + 1)) only make n + 1 or more
  // reflections; raise n until their flux is negligible.
  auto tail_flux = [&](int n) {
    return left_flux_below(c, theta_i, std::min(std::numbers::pi, (std::numbers::pi + 2.0 * theta_i) / (n + 1))) +
           left_flux_below(c, -theta_i, std::min(std::numbers::pi, (std::numbers::pi - 2.0 * theta_i) / (n + 1)));
  };
  int n_res = max_k + 1;
  double tail = tail_flux(n_res);
  while (tail > 1e-13 && n_res < opt.resolve_cap) {
    n_res = std::min(opt.resolve_cap, 2 * n_res);
    tail = tail_flux(n_res);
  }
  // The layout's zeroed histogram is the accumulator (one allocation: 10^5 bins at max_k 1000 are
  // 800 MB, seconds of page faults to zero, polled).
  FlatlandLobe lobe = make_layout(bins, max_k, opt.cancel);
  if (opt.cancel && opt.cancel->load(std::memory_order_relaxed)) return lobe;  // incomplete: discarded
  Accumulator acc{bins, max_k, std::move(lobe.theta_o_by_k)};
  add_left_resolved(c, theta_i, false, n_res, acc, opt.cancel);
  add_left_resolved(c, -theta_i, true, n_res, acc, opt.cancel);
  // The narrow-groove limit (header, Limits): half the tail at +theta_i, half at -theta_i.
  const double a = std::abs(theta_i);
  acc.add(max_k + 1, bin_of(a, bins, false), 0.5 * tail);
  acc.add(max_k + 1, bin_of(-a, bins, true), 0.5 * tail);

  lobe.theta_o_by_k = std::move(acc.hist);
  lobe.n_resolved = n_res;
  lobe.tail = tail;
  lobe.below = acc.below;
  if (opt.cancel && opt.cancel->load(std::memory_order_relaxed)) return lobe;  // incomplete: not summed
  finish(lobe);
  return lobe;
}

FlatlandLobe flatland_single_lobe(NdfKind ndf, double alpha, double theta_i, int bins) {
  assert(bins > 0 && alpha > 0.0 && std::abs(theta_i) < kHalfPi);
  FlatlandLobe lobe = make_layout(bins, 1);
  const GaussLegendre gl = gauss_legendre(16);
  const double w = std::numbers::pi / bins;
  // Over theta_h: theta_o = 2 theta_h - theta_i covers (-pi/2, pi/2) for theta_h in
  // ((theta_i - pi/2)/2, (theta_i + pi/2)/2). The flux density per d theta_h is
  // rho_CT2 cos(theta_o) d theta_o = D2(h) cos(theta_d) G d theta_h / cos(theta_i) (step e).
  const double inv_cos = 1.0 / std::cos(theta_i);
  auto f = [&](double h) {
    const double theta_o = 2.0 * h - theta_i;
    const double G = std::min(G1_vcavity_inplane(theta_i, h), G1_vcavity_inplane(theta_o, h));
    return D2(ndf, h, alpha) * std::cos(theta_i - h) * G * inv_cos;
  };
  std::vector<double> cuts;
  // Kinks of Eq. (2)-(3): G1(i) = 1 at cos(theta_i + h) = 0, G1(o) = 1 at cos(theta_o + h) = 0,
  // G1(i) = G1(o) at cos(theta_i) = cos(theta_o) (h = 0 or h = theta_i); the peak grading.
  const double extra[] = {
      -theta_i + kHalfPi, -theta_i - kHalfPi, (theta_i + kHalfPi) / 3.0, (theta_i - kHalfPi) / 3.0, 0.0, theta_i};
  std::vector<double> pts(std::begin(extra), std::end(extra));
  for (double s = 1.0 / 64.0; s <= 64.0; s *= 2.0) {
    pts.push_back(std::atan(alpha * s));
    pts.push_back(-std::atan(alpha * s));
  }
  for (int b = 0; b < bins; ++b) {
    const double lo = 0.5 * (-kHalfPi + b * w + theta_i), hi = 0.5 * (-kHalfPi + (b + 1) * w + theta_i);
    cuts.assign({lo, hi});
    for (double v : pts)
      if (v > lo && v < hi) cuts.push_back(v);
    std::sort(cuts.begin(), cuts.end());
    double s = 0.0;
    for (std::size_t p = 0; p + 1 < cuts.size(); ++p) s += integrate_mirrored(gl, f, cuts[p], cuts[p + 1]);
    lobe.theta_o_by_k[static_cast<std::size_t>(bins) + b] = s;
  }
  lobe.n_resolved = 1;
  finish(lobe);
  return lobe;
}

}  // namespace vgroove::analytic
