// vgroove analytic: the rough dielectric's single-scattering albedos (albedo_glass.h).
//
// Derivation. Walter Eq. (20): f_r = F G D / (4 |i.n| |o.n|) and d omega_h = d omega_o / (4 |o.h|), so
// f_r |o.n| d omega_o = F G D (i.h) / (i.n) d omega_h (i.h = o.h). Walter Eq. (21) with Eq. (17):
// f_t = (i.h) |o.h| eta^2 (1 - F) G D / (|i.n| |o.n| (i.h + eta o.h)^2) and d omega_h = eta^2 |o.h|
// d omega_o / (i.h + eta o.h)^2, so f_t |o.n| d omega_o = (1 - F) G D (i.h) / (i.n) d omega_h. With
// dP = D (h.n) d omega_h both albedos are int w G2 (i.h) / (mu h.n) dP over the normals with i.h > 0,
// w = F or 1 - F, each where its o leaves on its side (o_r.n > 0, o_t.n < 0; TIR: w = 1 - F = 0).
// Without G the sum is int (i.h) D d omega_h / mu >= 1; Smith's G2 <= G1(i) = mu / int (i.h)+ D
// (G1's normalization, Heitz 2014 Eq. 8) and B(1 + a, 1 + b) <= 1 / (1 + a), so E_R + E_T <= 1.
// Reciprocity of the averages. T_avg(eta) = (1 / pi) int int f_t(i, o) |i.n| |o.n| d omega_o d omega_i.
// Generalized reciprocity (walter.h) f_t(i, o) / eta^2 = f'_t(o, i) / 1, f' the BSDF lit from the far
// side (index ratio 1 / eta): swapping the integration variables gives T_avg(eta) = eta^2 T_avg(1/eta).
// Eta = 1: F = 0 and o_t = -i at every h: E_R = 0, E_T = G2(i, -i) / G1(i) (the test's hand values).
#include "vgroove/analytic/albedo_glass.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

namespace vgroove::analytic {
namespace {

constexpr double kPi = std::numbers::pi;

double rounding(double value) { return 64.0 * std::numeric_limits<double>::epsilon() * std::abs(value); }

double log_gamma(double x) {
  int sign = 0;
  return ::lgamma_r(x, &sign);
}

// Lambda of a direction with |z| = c, from tan^2 (ndf.h's forms through its angle).
double lambda_of(NdfKind ndf, double alpha, double x, double y, double z) {
  return Lambda(ndf, std::atan2(std::hypot(x, y), std::abs(z)), alpha);
}

enum class Lobe { reflect, transmit };

struct Setup {
  MicrofacetModel m;
  double alpha, mu, sin_i, eta, lambda_i;
  Lobe lobe;
};

// The exit direction at the normal h = (sin_h cos_phi, sin_h sin_phi, cos_h), i = (sin_i, 0, mu);
// false where h is not lit (i.h <= 0) or the facet reflects totally (transmission).
struct Exit {
  double ih = 0.0, ox = 0.0, oy = 0.0, oz = 0.0, oh = 0.0, w = 0.0;
};
bool exit_at(const Setup& s, double cos_h, double sin_h, double cos_phi, double sin_phi, Exit& e) {
  const double hx = sin_h * cos_phi, hy = sin_h * sin_phi, hz = cos_h;
  e.ih = s.sin_i * hx + s.mu * hz;
  if (!(e.ih > 0.0)) return false;
  const double F = optics::fresnel_dielectric(e.ih, s.eta);
  if (s.lobe == Lobe::reflect) {
    // Walter Eq. (13) inverted: o_r = 2 (i.h) h - i.
    e.ox = 2.0 * e.ih * hx - s.sin_i, e.oy = 2.0 * e.ih * hy, e.oz = 2.0 * e.ih * hz - s.mu;
    e.oh = e.ih;
    e.w = F;
    return e.oz > 0.0;
  }
  // Snell at h (Walter Eq. 40 with n_i / n_o = 1 / eta): o_t = -i / eta + (i.h / eta - cos_t) h.
  const double sin2_t = (1.0 - e.ih) * (1.0 + e.ih) / (s.eta * s.eta);
  if (!(sin2_t < 1.0) || !(F < 1.0)) return false;
  const double cos_t = std::sqrt(1.0 - sin2_t), k = e.ih / s.eta - cos_t;
  e.ox = -s.sin_i / s.eta + k * hx, e.oy = k * hy, e.oz = -s.mu / s.eta + k * hz;
  e.oh = -cos_t;
  e.w = 1.0 - F;
  return e.oz < 0.0;
}

// w G2 (i.h) / (mu h.n): the integrand against dP(h).
double integrand(const Setup& s, double cos_h, double sin_h, double cos_phi, double sin_phi) {
  Exit e;
  if (!exit_at(s, cos_h, sin_h, cos_phi, sin_phi, e)) return 0.0;
  double G2 = 0.0;
  if (s.m.masking == MaskingKind::vcavity) {
    // Lee et al. 2018, Eq. (2)-(3), as walter.cpp takes it.
    G2 = std::min(G1_vcavity(e.ih, s.mu, cos_h), G1_vcavity(e.oh, e.oz, cos_h));
  } else {
    const double lo = lambda_of(s.m.ndf, s.alpha, e.ox, e.oy, e.oz), li = s.lambda_i;
    if (!std::isfinite(lo)) return 0.0;  // o on the horizon: G1(o) = 0
    if (s.m.masking == MaskingKind::smith_separable)
      G2 = 1.0 / ((1.0 + li) * (1.0 + lo));  // Heitz 2014, Eq. (20)
    else if (s.lobe == Lobe::reflect)
      G2 = 1.0 / (1.0 + li + lo);  // Heitz 2014, Eq. (21)
    else
      G2 = std::exp(log_gamma(1.0 + li) + log_gamma(1.0 + lo) - log_gamma(2.0 + li + lo));  // walter.h
  }
  return e.w * G2 * e.ih / (s.mu * cos_h);
}

std::vector<double> refined(std::vector<double> cuts, int refine) {
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  if (refine <= 1 || cuts.size() < 2) return cuts;
  std::vector<double> out;
  for (std::size_t j = 0; j + 1 < cuts.size(); ++j)
    for (int r = 0; r < refine; ++r) out.push_back(cuts[j] + (cuts[j + 1] - cuts[j]) * r / refine);
  out.push_back(cuts.back());
  return out;
}

// Where along theta_h in (lo, hi) the sign of g changes: a scan of n steps, then bisection.
template <class G>
void sign_changes(G&& g, double lo, double hi, int n, std::vector<double>& out) {
  double a = lo, ga = g(lo);
  for (int j = 1; j <= n; ++j) {
    const double b = lo + (hi - lo) * j / n, gb = g(b);
    if ((ga > 0.0) != (gb > 0.0)) {
      double x0 = a, x1 = b;
      const bool pos0 = ga > 0.0;
      for (int it = 0; it < 80 && x1 - x0 > 1e-15; ++it) {
        const double x = 0.5 * (x0 + x1);
        ((g(x) > 0.0) == pos0 ? x0 : x1) = x;
      }
      out.push_back(0.5 * (x0 + x1));
    }
    a = b, ga = gb;
  }
}

// The measure's complement w = 1 - P(theta_h) (brdf_3d.h's groove_cdf), integrated in v = sqrt(w):
// transmission reaches theta_h = pi/2, where (i.h) / (mu h.n) ~ 1 / sqrt(w) for GGX; in v the
// integrand 2 v (.) is finite, and h is formed from w without the rounding of 1 - u.
//   GGX: w = alpha^2 / (alpha^2 + tan^2), tan^2 = alpha^2 (1 - w) / w; Beckmann: w = exp(-tan^2 / alpha^2).
double w_of(NdfKind ndf, double alpha, double theta) {
  if (!(theta > 0.0)) return 1.0;
  if (!(theta < 0.5 * kPi)) return 0.0;
  const double c = std::cos(theta), s = std::sin(theta), a2c2 = alpha * alpha * c * c;
  if (ndf == NdfKind::ggx) return a2c2 / (a2c2 + s * s);
  const double t = s / (alpha * c);
  return std::exp(-t * t);
}
void h_of(NdfKind ndf, double alpha, double v, double& cos_h, double& sin_h) {
  const double w = v * v;
  if (!(w > 0.0)) {
    cos_h = 0.0, sin_h = 1.0;
    return;
  }
  if (ndf == NdfKind::ggx) {
    const double a2 = alpha * alpha * (1.0 - w), den = std::sqrt(w + a2);
    cos_h = std::sqrt(w) / den, sin_h = std::sqrt(a2) / den;
    return;
  }
  const double t = alpha * std::sqrt(-2.0 * std::log(v));
  cos_h = 1.0 / std::sqrt(1.0 + t * t), sin_h = t * cos_h;
}
double v_of(NdfKind ndf, double alpha, double theta) { return std::sqrt(w_of(ndf, alpha, theta)); }
double theta_of_v(NdfKind ndf, double alpha, double v) {
  double c = 1.0, s = 0.0;
  h_of(ndf, alpha, v, c, s);
  return std::atan2(s, c);
}

double g1v_ratio(double ih_or_oh, double n_dot, double cos_h) {
  return 2.0 * cos_h * std::abs(n_dot) / std::abs(ih_or_oh);
}

BoundedValue integrate_lobe(const Setup& s, const AlbedoOptions& opt) {
  const bool vcavity = s.m.masking == MaskingKind::vcavity;
  const NdfKind ndf = s.m.ndf;
  AdaptiveOptions inner;
  inner.abs_tol = 0.5 * opt.tol;
  inner.max_pieces = opt.max_pieces;
  double inner_error = 0.0;
  bool converged = true;
  long evaluations = 0;
  auto along = [&](double phi) {
    const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
    // i.h = 0 at theta_h = psi (albedo_single.cpp); o_r.n = 0 at psi / 2.
    const double psi = std::atan2(s.mu, -s.sin_i * cos_phi);
    const double theta_end = s.lobe == Lobe::reflect ? 0.5 * psi : std::min(psi, 0.5 * kPi);
    const double v_end = v_of(ndf, s.alpha, theta_end);
    // The kinks inside, found in v by a scan and bisection: the facet's critical angle i.h =
    // sqrt(1 - eta^2) and o_t.n = 0 (eta < 1); the V-cavity's G1(i) = 1, G1(o) = 1, G1(i) = G1(o).
    std::vector<std::function<double(const Exit&, double)>> kink_fns;
    if (s.eta < 1.0) {
      if (s.lobe == Lobe::transmit) kink_fns.push_back([](const Exit& e, double) { return e.ih > 0.0 ? e.oz : 1.0; });
    }
    if (vcavity) {
      const double mu = s.mu;
      kink_fns.push_back([mu](const Exit& e, double ch) { return g1v_ratio(e.ih, mu, ch) - 1.0; });
      kink_fns.push_back([](const Exit& e, double ch) { return g1v_ratio(e.oh, e.oz, ch) - 1.0; });
      kink_fns.push_back(
          [mu](const Exit& e, double ch) { return g1v_ratio(e.ih, mu, ch) - g1v_ratio(e.oh, e.oz, ch); });
    }
    std::vector<double> kinks_v;
    for (const auto& fn : kink_fns)
      sign_changes(
          [&](double v) {
            double ch = 1.0, sh = 0.0;
            h_of(ndf, s.alpha, v, ch, sh);
            Exit e;
            exit_at(s, ch, sh, cos_phi, sin_phi, e);
            return fn(e, ch);
          },
          v_end, 1.0, 64, kinks_v);
    std::vector<double> thetas{theta_end};
    if (s.eta < 1.0) {
      // i.h = A sin + B cos = R cos(theta - delta) = sqrt(1 - eta^2) at theta = delta +- acos(c / R).
      const double c_crit = std::sqrt((1.0 - s.eta) * (1.0 + s.eta));
      const double A = s.sin_i * cos_phi, B = s.mu, R = std::hypot(A, B), delta = std::atan2(A, B);
      if (R > c_crit)
        for (double t : {delta - std::acos(c_crit / R), delta + std::acos(c_crit / R)})
          if (t > 0.0 && t < theta_end) kinks_v.push_back(v_of(ndf, s.alpha, t));
    }
    const double negligible = 1e-3 * opt.tol;
    for (int j = -1; j < 64; ++j) {
      const double t = std::atan(s.alpha * std::ldexp(1.0, j));
      if (!(t < theta_end)) break;
      thetas.push_back(t);
      if (w_of(ndf, s.alpha, t) - v_end * v_end < negligible) break;
    }
    // Graded towards the end where o grazes (Smith's layer, albedo_single.cpp) and both sides of
    // each kink (the square-root point of 1 - F at the critical angle; Smith's layer at o_t.n = 0).
    const double layer = 0.01 * std::min(s.alpha, s.mu);
    std::vector<double> ends;
    for (double v : kinks_v) ends.push_back(theta_of_v(ndf, s.alpha, v));
    if (s.lobe == Lobe::reflect && !vcavity) ends.push_back(theta_end);
    for (double c : ends) {
      thetas.push_back(c);
      for (double d = 0.25 * theta_end; d > 1e-3 * layer; d *= 0.25)
        for (double t : {c - d, c + d})
          if (t > 0.0 && t < theta_end) thetas.push_back(t);
    }
    std::vector<double> cuts{1.0, v_end};
    for (double t : thetas) cuts.push_back(v_of(ndf, s.alpha, t));
    for (double v : kinks_v) cuts.push_back(v);
    for (double& v : cuts) v = std::clamp(v, v_end, 1.0);
    const AdaptiveResult r = integrate_adaptive(
        [&](double v) {
          double cos_h = 1.0, sin_h = 0.0;
          h_of(ndf, s.alpha, v, cos_h, sin_h);
          if (!(cos_h > 0.0)) return 0.0;
          return 2.0 * v * integrand(s, cos_h, sin_h, cos_phi, sin_phi);
        },
        refined(cuts, opt.refine), inner);
    inner_error = std::max(inner_error, r.error);
    converged = converged && r.converged;
    evaluations += r.evaluations;
    return r.value;
  };
  std::vector<double> phis{0.0, 0.25 * kPi, 0.5 * kPi, 0.75 * kPi, kPi};
  for (double d = 0.25 * s.mu; d < 0.1; d *= 4.0) {
    phis.push_back(0.5 * kPi - d);
    phis.push_back(0.5 * kPi + d);
  }
  // The V-cavity reflection's kinks meet at cos phi = k cot theta_i (albedo_single.cpp).
  if (vcavity && s.sin_i > 0.0)
    for (double k : {1.0 / std::sqrt(3.0), 1.0}) {
      const double c = k * s.mu / s.sin_i;
      if (c < 1.0) phis.push_back(std::acos(c));
    }
  // Where the critical angle's crossings appear (R(phi) = sqrt(1 - eta^2) above): a square-root
  // point of the inner integral in phi, graded about.
  if (s.eta < 1.0 && s.sin_i > 0.0) {
    const double c = std::sqrt(std::max(0.0, (1.0 - s.eta) * (1.0 + s.eta) - s.mu * s.mu)) / s.sin_i;
    if (c > 0.0 && c < 1.0)
      for (double p0 : {std::acos(c), kPi - std::acos(c)}) {
        phis.push_back(p0);
        for (double d = 0.1; d > 1e-7; d *= 0.25)
          for (double p : {p0 - d, p0 + d})
            if (p > 0.0 && p < kPi) phis.push_back(p);
      }
  }
  AdaptiveOptions outer;
  outer.abs_tol = 0.5 * kPi * opt.tol;
  outer.max_pieces = opt.max_pieces;
  const AdaptiveResult r = integrate_adaptive(along, refined(phis, opt.refine), outer);
  const double value = r.value / kPi;
  return {value, r.error / kPi + inner_error + rounding(value), converged && r.converged, evaluations};
}

Setup make_setup(const MicrofacetModel& m, double alpha, double mu, double eta, Lobe lobe) {
  // w_of and h_of have GGX's and Beckmann's closed forms only.
  assert((m.ndf == NdfKind::ggx || m.ndf == NdfKind::beckmann) && model_supported(m));
  assert(alpha > 0.0 && mu > 0.0 && mu <= 1.0 && eta > 0.0);
  Setup s{m, alpha, mu, std::sqrt((1.0 - mu) * (1.0 + mu)), eta, 0.0, lobe};
  if (m.masking != MaskingKind::vcavity) s.lambda_i = lambda_of(m.ndf, alpha, s.sin_i, 0.0, mu);
  return s;
}

}  // namespace

GlassAlbedo albedo_glass(const MicrofacetModel& m, double alpha, double mu, double eta, const AlbedoOptions& opt) {
  return {integrate_lobe(make_setup(m, alpha, mu, eta, Lobe::reflect), opt),
          integrate_lobe(make_setup(m, alpha, mu, eta, Lobe::transmit), opt)};
}

GlassAlbedo albedo_glass_average(const MicrofacetModel& m, double alpha, double eta, const AlbedoOptions& opt) {
  GlassAlbedo out;
  for (Lobe lobe : {Lobe::reflect, Lobe::transmit}) {
    double inner_error = 0.0;
    bool converged = true;
    long evaluations = 0;
    auto g = [&](double mu) {
      AlbedoOptions in = opt;
      in.tol = std::min(0.25 * opt.tol / mu, 1e-3);
      const BoundedValue e = integrate_lobe(make_setup(m, alpha, mu, eta, lobe), in);
      inner_error = std::max(inner_error, 2.0 * mu * e.error);
      converged = converged && e.converged;
      evaluations += e.evaluations;
      return e.value;
    };
    AdaptiveOptions o;
    o.abs_tol = 0.5 * opt.tol;
    o.max_pieces = opt.max_pieces;
    const AdaptiveResult r = integrate_adaptive([&](double mu) { return 2.0 * mu * g(mu); },
                                                refined({0.0, 0.25, 0.5, 0.75, 1.0}, opt.refine), o);
    (lobe == Lobe::reflect ? out.R : out.T) =
        BoundedValue{r.value, r.error + inner_error + rounding(r.value), converged && r.converged, evaluations};
  }
  return out;
}

}  // namespace vgroove::analytic
