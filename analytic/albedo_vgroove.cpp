// vgroove analytic: the V-groove model's directional albedo per bounce order (albedo_vgroove.h).
#include "vgroove/analytic/albedo_vgroove.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <queue>

namespace vgroove::analytic {

namespace {

constexpr double kPi = std::numbers::pi;
// The longest path whose products are followed bounce by bounce (albedo_vgroove.h).
constexpr int kMaxPathBounces = 1 << 20;

struct Run {
  NdfKind ndf;
  double alpha;
  int max_k, C;
  const ChannelReflectance* F;  // null: F = 1
  std::vector<char> unit;       // channels with F = 1 at every cosine (their products stay 1)
  double cutoff;
  std::vector<double>* rows;
  // Scratch: the running product per channel and one bounce's reflectances.
  std::vector<double> prod, f;
};

// One groove (theta_m from cos_m, sin_m), the rays aimed at `side`, with the weight w (its share of
// the light per unit u times the quadrature weight): both outcomes of Eq. (6) into their rows.
void deposit_groove(Run& r, double t_i, double cos_ti, double c, double cos_m, double sin_m, FacetSide side, double w) {
  // theta_v = pi - 2 theta_m, formed from tan(theta_v / 2) = cos_m / sin_m (albedo_vgroove.h).
  const double theta_v = 2.0 * std::atan2(cos_m, sin_m);
  const FacetPrediction p = G_kaleidoscopic(t_i, theta_v, side);
  if (!p.lit) return;
  // Of the light entering the opening 2 sin(theta_v / 2) cos t_i, the facet takes f_a.
  const double to_groove = w * p.f_a / (2.0 * cos_m * cos_ti);
  const double share_fewer = p.fewer.G * to_groove, share_more = p.more.G * to_groove;
  auto row_of = [&](int n) { return static_cast<std::size_t>(std::min(n, r.max_k + 1)); };
  std::vector<double>& rows = *r.rows;
  const int C = r.C;
  if (!r.F) {
    if (p.fewer.n >= 1) rows[row_of(p.fewer.n)] += share_fewer;
    rows[row_of(p.more.n)] += share_more;
    return;
  }
  // The products along the path: bounce j at cos = c |sin((j - 1/2) theta_v - t_f)|, the sine
  // advanced by the rotation through theta_v (re-formed every 32 bounces: rounding stays ~32 ulp).
  const double tf = side == FacetSide::left ? t_i : -t_i;
  const double st = std::sin(theta_v), ct = std::cos(theta_v);
  std::fill(r.prod.begin(), r.prod.end(), 1.0);
  double s = 0.0, co = 0.0;
  auto add = [&](int n, double share) {
    if (share == 0.0) return;
    double* out = &rows[row_of(n) * C];
    for (int ch = 0; ch < C; ++ch) out[ch] += share * r.prod[ch];
  };
  const int K = p.more.n;
  for (int j = 1; j <= K; ++j) {
    if (j == K) add(K - 1, share_fewer);  // the product over K - 1 bounces (G_fewer = 0 when K = 1)
    if ((j - 1) % 32 == 0) {
      const double x = (j - 0.5) * theta_v - tf;
      s = std::sin(x), co = std::cos(x);
    } else {
      const double s1 = s * ct + co * st;
      co = co * ct - s * st;
      s = s1;
    }
    (*r.F)(std::min(1.0, c * std::abs(s)), r.f.data());
    double largest = 0.0;
    for (int ch = 0; ch < C; ++ch)
      if (!r.unit[ch]) largest = std::max(largest, r.prod[ch] *= r.f[ch]);
    // Every channel's product below the cutoff (or the path past kMaxPathBounces): what the path
    // still deposits counts as 0 but in the unit channels, whose products stay 1.
    if (largest < r.cutoff || j == kMaxPathBounces) {
      for (int ch = 0; ch < C; ++ch) r.prod[ch] = r.unit[ch] ? 1.0 : 0.0;
      if (j < K) add(K - 1, share_fewer);  // not yet added (at j = K it was, above)
      add(K, share_more);
      return;
    }
  }
  add(K, share_more);
}

// One facet at one groove azimuth: the pieces of u between the cuts, then the tail.
void integrate_facet(Run& r, const GaussLegendre& rule, int k_bands, int strata, double t_i, double cos_ti, double c,
                     FacetSide side, double w_phi) {
  const double tf = side == FacetSide::left ? t_i : -t_i;
  const double span = kPi + 2.0 * tf;  // Eq. (4): K = floor(span / theta_v) + 1
  const double v_tail = span / (k_bands + 1);
  std::vector<double> X{kPi, v_tail};
  auto cut = [&](double v) {
    if (v > v_tail && v < kPi) X.push_back(v);
  };
  cut(2.0 * tf);
  cut(-2.0 * tf);
  for (int j = 1; j <= k_bands + 1; ++j) {
    cut(span / j);
    cut((kPi + tf) / (j - 0.5));
  }
  // The NDF's scale: theta_m = atan(alpha 2^j), theta_v = 2 atan(1 / (alpha 2^j)) (the density
  // 2 pi D cos sin peaks near theta_m ~ alpha / sqrt 2 and falls over a few such steps).
  for (int j = -4; j <= 8; ++j) cut(2.0 * std::atan(1.0 / std::ldexp(r.alpha, j)));
  std::sort(X.begin(), X.end());
  X.erase(std::unique(X.begin(), X.end()), X.end());
  // In theta_v itself: the grooves' share of the light is 2 pi D cos sin d theta_m = pi D cos sin
  // d theta_v (cos theta_m = sin(theta_v / 2), sin theta_m = cos(theta_v / 2)), smooth in theta_v
  // for every NDF, and so is the weight of Eq. (6) between the cuts.
  for (std::size_t q = 0; q + 1 < X.size(); ++q) {
    const double a = X[q], b = X[q + 1], mid = 0.5 * (a + b), half = 0.5 * (b - a);
    for (std::size_t n = 0; n < rule.size(); ++n) {
      const double h = 0.5 * (mid + half * rule.x[n]);  // theta_v / 2
      const double cos_m = std::sin(h), sin_m = std::cos(h);
      const double density = kPi * D_cs(r.ndf, cos_m, sin_m, r.alpha) * cos_m * sin_m;
      deposit_groove(r, t_i, cos_ti, c, cos_m, sin_m, side, w_phi * density * half * rule.w[n]);
    }
  }
  const double u_tail = groove_cdf(r.ndf, r.alpha, 0.5 * (kPi - v_tail));
  // The tail: midpoints of `strata` equal parts of z = sqrt(1 - u) in [0, sqrt(1 - u_tail)].
  const double z_tail = std::sqrt(1.0 - u_tail);
  if (!(z_tail > 0.0)) return;
  for (int q = 0; q < strata; ++q) {
    const double z = z_tail * (q + 0.5) / strata;
    double cos_m, sin_m;
    groove_cdf_inverse_cos_sin(r.ndf, r.alpha, 1.0 - z * z, cos_m, sin_m);
    if (!(cos_m > 0.0)) continue;
    deposit_groove(r, t_i, cos_ti, c, cos_m, sin_m, side, w_phi * 2.0 * z * z_tail / strata);
  }
}

// int_0^{pi/2} g(phi) d phi * scale into acc, g deposited by node(phi, w) with weight w into *r.rows
// (acc itself): the 15 Kronrod nodes of each piece deposit into a piece-own vector, the 7 Gauss
// ones into another, and their difference is the piece's error.
template <class Node>
void integrate_phi(Node&& node, std::vector<double>& acc, double scale, const VgrooveAlbedoOptions& opt) {
  using detail::kWg;
  using detail::kWk;
  using detail::kXk;
  struct Piece {
    double a, b, error;
    std::vector<double> K, G;
    bool operator<(const Piece& o) const { return error < o.error; }
  };
  const std::size_t n = acc.size();
  std::vector<double> one(n);
  // One piece: node() deposits into acc, so acc is swapped out while it runs.
  auto run = [&](double a, double b) {
    Piece p{a, b, 0.0, std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    auto eval = [&](double x, double wk, double wg) {
      std::fill(one.begin(), one.end(), 0.0);
      acc.swap(one);
      node(x, 1.0);
      acc.swap(one);
      for (std::size_t j = 0; j < n; ++j) {
        p.K[j] += wk * h * scale * one[j];
        p.G[j] += wg * h * scale * one[j];
      }
    };
    eval(c, kWk[7], kWg[3]);
    for (int j = 0; j < 7; ++j) {
      const double wg = j % 2 == 1 ? kWg[j / 2] : 0.0;
      eval(c - h * kXk[j], kWk[j], wg);
      eval(c + h * kXk[j], kWk[j], wg);
    }
    for (std::size_t j = 0; j < n; ++j) p.error = std::max(p.error, std::abs(p.K[j] - p.G[j]));
    return p;
  };
  std::priority_queue<Piece> pieces;
  const int start = 4;
  for (int q = 0; q < start; ++q) pieces.push(run(0.5 * kPi * q / start, 0.5 * kPi * (q + 1) / start));
  auto total_error = [&] {
    auto copy = pieces;
    double e = 0.0;
    while (!copy.empty()) e += copy.top().error, copy.pop();
    return e;
  };
  while (static_cast<int>(pieces.size()) < opt.phi_max_pieces && total_error() > opt.phi_tol) {
    const Piece p = pieces.top();
    pieces.pop();
    const double m = 0.5 * (p.a + p.b);
    pieces.push(run(p.a, m));
    pieces.push(run(m, p.b));
  }
  // Summed from the smallest contributions up (the queue's order does not matter for the value's
  // accuracy at this level; the pieces are summed in order of their left ends for determinism).
  std::vector<Piece> all;
  while (!pieces.empty()) all.push_back(pieces.top()), pieces.pop();
  std::sort(all.begin(), all.end(), [](const Piece& x, const Piece& y) { return x.a < y.a; });
  for (const Piece& p : all)
    for (std::size_t j = 0; j < n; ++j) acc[j] += p.K[j];
}

}  // namespace

VgrooveAlbedo vgroove_albedo(NdfKind ndf, double alpha, double mu, int channels, const ChannelReflectance& F, int max_k,
                             const VgrooveAlbedoOptions& opt) {
  assert(alpha > 0.0 && mu > 0.0 && mu <= 1.0 && max_k >= 1);
  VgrooveAlbedo out;
  out.max_k = max_k;
  out.channels = F ? channels : 1;
  const int C = out.channels;
  out.by_k.assign(static_cast<std::size_t>(max_k + 2) * C, 0.0);
  Run r{ndf,
        alpha,
        max_k,
        C,
        F ? &F : nullptr,
        std::vector<char>(C, 0),
        opt.tail_cutoff,
        &out.by_k,
        std::vector<double>(C),
        std::vector<double>(C)};
  if (F) {
    // A channel whose F is exactly 1 at 0, 1/4, ..., 1 is taken as F = 1 (Schlick's with F0 = 1,
    // the white furnace): no path's product moves it, so it never keeps a path going.
    std::vector<double> f(C);
    std::fill(r.unit.begin(), r.unit.end(), 1);
    for (double cq : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      F(cq, f.data());
      for (int ch = 0; ch < C; ++ch) r.unit[ch] = r.unit[ch] && f[ch] == 1.0;
    }
  }
  const GaussLegendre band_rule = gauss_legendre(opt.band_order);
  // The light at i = dir3(theta_i, pi): i.a = -sin(theta_i) cos(phi_a), i.u = sin(theta_i) sin(phi_a).
  const double ci = mu, si = std::sqrt((1.0 - mu) * (1.0 + mu));
  auto node = [&](double phi_a, double w_phi) {
    const double t_i = std::atan2(si * std::cos(phi_a), ci);
    const double iu = si * std::sin(phi_a);
    const double c = std::sqrt(std::max(0.0, (1.0 - iu) * (1.0 + iu)));
    const double cos_ti = std::cos(t_i);
    for (FacetSide side : {FacetSide::left, FacetSide::right})
      integrate_facet(r, band_rule, opt.k_bands, opt.tail_strata, t_i, cos_ti, c, side, w_phi);
  };
  if (si == 0.0) {
    // Normal incidence: every azimuth shows the same cross-section (t_i = 0, c = 1).
    node(0.0, 1.0);
  } else {
    // (1 / pi) over [0, pi) = (2 / pi) over [0, pi/2] with the mirror image, by globally adaptive
    // Gauss-Kronrod on the vector of rows (the per-row integrands have kinks in phi_a where the
    // cuts in theta_v cross each other): the piece whose largest |K15 - G7| over the rows is
    // largest is halved until their sum is below phi_tol.
    integrate_phi(node, out.by_k, 2.0 / kPi, opt);
  }
  out.total.assign(C, 0.0);
  for (int k = 0; k <= max_k + 1; ++k)
    for (int ch = 0; ch < C; ++ch) out.total[ch] += out.row(k, ch);
  return out;
}

}  // namespace vgroove::analytic
