// vgroove analytic: the kaleidoscopic dielectric model over an NDF at a point (kaleidoscope_dielectric_point.h).
// One cross-section (flatland: the problem; 3D: the one groove azimuth whose lifted exits keep o's axis
// component, KD-11) and facet: per band of Eq. (4)'s k and per chain end, the groove slopes whose exit
// angle is the target are found (reflected: Eq. 5 is linear in theta_v, closed form; transmitted:
// KD-3 is monotone between the points KD-10 names, bracketed and bisected), and each adds the lobe's
// density there. Derivation: docs/derivations/kaleidoscope_dielectric.md, "The BSDF at a point".
#include "vgroove/analytic/kaleidoscope_dielectric_point.h"

#include "vgroove/analytic/dielectric_section.h"
#include "vgroove/analytic/kaleidoscope_dielectric.h"
#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vgroove::analytic {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = 0.5 * std::numbers::pi;

// One cross-section problem (dielectric_section.h) and what the density needs.
struct Section : DielectricSection {
  bool three_d = false;  // the slope density: flatland 2 D2 cos, 3D 2 pi D cos sin
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.3;
  const DielectricPointOptions* opt = nullptr;
};

double slope_pdf(const Section& s, double tm) {
  return s.three_d ? 2.0 * kPi * D(s.ndf, tm, s.alpha) * std::cos(tm) * std::sin(tm)
                   : 2.0 * D2(s.ndf, tm, s.alpha) * std::cos(tm);
}

DielectricFacetPrediction predict(const Section& s, double theta_v, FacetSide side) {
  const DielectricPointOptions& o = *s.opt;
  auto F = [&](double cos2d) {
    if (s.all_tir) return 1.0;
    const double c = s.c3d * cos2d;  // Fresnel's angle is the 3D one (dielectric_lifting.md)
    return o.reflectance ? o.reflectance(c) : optics::fresnel_dielectric(c, s.eta);
  };
  return kaleidoscope_dielectric_with(s.tau, theta_v, s.all_tir ? 1.0 : s.eta_dir, side, F);
}

// KD-10: the transmitted exit angle at hit j (refracted_angle) and its derivative in theta_v, left
// facet first in the frame where the light is at tf (right: the caller mirrors).
struct TransmittedExit {
  double beta = 0.0;
  bool ok = false;
  double t = 0.0, dt = 0.0;
};
TransmittedExit transmitted_exit(double tf, double theta_v, double e, int j, bool broken_index) {
  TransmittedExit x;
  x.beta = (j - 0.5) * theta_v - tf;
  const double cb = std::cos(x.beta);
  const double rad = (e - cb) * (e + cb);  // e^2 cos^2 alpha_t
  if (!(rad > 0.0)) return x;
  const double sj = (j % 2 == 1) ? 1.0 : -1.0;
  x.ok = true;
  x.t = sj * (std::asin(std::clamp(cb / e, -1.0, 1.0)) - 0.5 * (kPi - theta_v));                // KD-3
  x.dt = broken_index ? sj * 0.5 : sj * (0.5 - (j - 0.5) * std::sin(x.beta) / std::sqrt(rad));  // KD-10
  return x;
}

// The accumulated density of (theta_m, facet, chain end) mass per unit exit angle t, by k.
struct Acc {
  int max_k = 0;
  std::vector<double>* by_k = nullptr;
  void add(int k, double v) const { (*by_k)[static_cast<std::size_t>(std::min(k, max_k + 1))] += v; }
};

// Adds the lobe's mass at theta_v per unit t: dP f_a / opening x share / |dt/dtheta_m|.
void add_root(const Section& s, FacetSide side, double theta_v, bool reflected, int index, double dt_dv, double weight,
              const Acc& acc) {
  const DielectricFacetPrediction p = predict(s, theta_v, side);
  if (!p.lit || p.k > s.opt->k_cap) return;
  double share = 0.0;
  if (reflected) {
    if (p.fewer.n == index) share = p.fewer.share;
    if (p.more.n == index) share = p.more.share;
  } else if (index >= 1 && index <= static_cast<int>(p.transmitted.size())) {
    share = p.transmitted[static_cast<std::size_t>(index - 1)].share;
  }
  if (!(share > 0.0)) return;
  const double tm = 0.5 * (kPi - theta_v);
  const double jac = 2.0 * std::abs(dt_dv);  // |dt/dtheta_m|, theta_v = pi - 2 theta_m
  if (!(jac > 0.0) || !std::isfinite(jac)) return;
  acc.add(index, weight * slope_pdf(s, tm) * p.f_a / opening_width(s.tau, theta_v) * share / jac);
}

// Bisection of g (continuous, monotone on [a, b], g(a) and g(b) of opposite signs) to rounding.
template <class G>
double bisect(G&& g, double a, double b, double ga) {
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b);
    if (!(m > a && m < b)) break;
    const double gm = g(m);
    if ((gm < 0.0) == (ga < 0.0)) {
      a = m;
      ga = gm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

// One facet of one cross-section: every chain end's roots with exit angle t (the exit side's angle).
void facet_density(const Section& s, FacetSide side, double t, bool reflected, double weight, const Acc& acc) {
  const DielectricPointOptions& o = *s.opt;
  const double tf = side == FacetSide::left ? s.tau : -s.tau;
  const double target = side == FacetSide::left ? t : -t;  // in the left-first frame
  const double lit_lo = std::max(0.0, 2.0 * tf);           // f_a = sin(theta_v/2 - tf) > 0
  const double cpk = kPi + 2.0 * tf;                       // Eq. (4): k changes at theta_v = cpk / m
  const double e = s.all_tir ? 1.0 : s.eta_dir;
  const bool broken_index = o.broken == DielectricPointBreak::no_index_jacobian;
  for (int m = 1; m <= o.k_cap; ++m) {
    const double hi = std::min(kPi, m == 1 ? kPi : cpk / (m - 1));
    const double lo = std::max(lit_lo, cpk / m);
    if (hi <= lit_lo) break;
    if (!(hi > lo)) continue;
    if (reflected) {
      // KD-9: Eq. (5) unwrapped, s_n (tf + pi - n theta_v) = target + 2 pi l, for n = m - 1 and m.
      for (int n = std::max(1, m - 1); n <= m; ++n) {
        const double sn = (n % 2 == 0) ? 1.0 : -1.0;
        const double u_lo = sn * (tf + kPi - n * hi), u_hi = sn * (tf + kPi - n * lo);
        const double u0 = std::min(u_lo, u_hi), u1 = std::max(u_lo, u_hi);
        for (double l = std::ceil((u0 - target) / (2.0 * kPi)); target + 2.0 * kPi * l <= u1; l += 1.0) {
          const double v = (tf + kPi - sn * (target + 2.0 * kPi * l)) / n;
          if (v > lo && v < hi) add_root(s, side, v, true, n, static_cast<double>(n), weight, acc);
        }
      }
      continue;
    }
    if (s.all_tir) continue;
    // KD-10: transmitted at hit j = 1..m. Pieces in theta_v between the points where cos beta = 0
    // (the derivative's monotonicity changes) or |cos beta| = e (total internal reflection starts).
    for (int j = 1; j <= m; ++j) {
      const double h = j - 0.5;
      std::vector<double> cuts{lo, hi};
      const double b_lo = h * lo - tf, b_hi = h * hi - tf;
      auto add_beta = [&](double b0) {
        for (double l = std::ceil((b_lo - b0) / kPi); b0 + kPi * l < b_hi; l += 1.0) {
          const double v = (b0 + kPi * l + tf) / h;
          if (v > lo && v < hi) cuts.push_back(v);
        }
      };
      add_beta(kHalfPi);
      if (e < 1.0) add_beta(std::acos(e)), add_beta(kPi - std::acos(e));
      std::sort(cuts.begin(), cuts.end());
      auto ex = [&](double v) { return transmitted_exit(tf, v, e, j, broken_index); };
      for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
        const double a = cuts[c], b = cuts[c + 1];
        if (!(b > a) || !ex(0.5 * (a + b)).ok) continue;  // total internal reflection on the whole piece
        // The derivative is monotone on the piece: at most one turning point.
        const double ia = a + 1e-12 * (b - a), ib = b - 1e-12 * (b - a);
        const TransmittedExit xa = ex(ia), xb = ex(ib);
        std::vector<double> mono{a, b};
        if (xa.ok && xb.ok && (xa.dt < 0.0) != (xb.dt < 0.0))
          mono.insert(mono.begin() + 1, bisect([&](double v) { return ex(v).dt; }, ia, ib, xa.dt));
        for (std::size_t q = 0; q + 1 < mono.size(); ++q) {
          const double p0 = mono[q], p1 = mono[q + 1];
          const TransmittedExit y0 = ex(p0), y1 = ex(p1);
          // At a total-internal-reflection end the angle is the clamp's (continuous).
          auto angle = [&](double v) {
            const double bt = h * v - tf, sj = (j % 2 == 1) ? 1.0 : -1.0;
            return sj * (std::asin(std::clamp(std::cos(bt) / e, -1.0, 1.0)) - 0.5 * (kPi - v));
          };
          const double g0 = (y0.ok ? y0.t : angle(p0)) - target, g1 = (y1.ok ? y1.t : angle(p1)) - target;
          if ((g0 < 0.0) == (g1 < 0.0) || g0 == 0.0) continue;
          const double v = bisect([&](double x) { return angle(x) - target; }, p0, p1, g0);
          const TransmittedExit r = ex(v);
          if (r.ok) add_root(s, side, v, false, j, r.dt, weight, acc);
        }
      }
    }
  }
}

void section_density(const Section& s, double t, bool reflected, double weight, const Acc& acc) {
  for (FacetSide side : {FacetSide::left, FacetSide::right}) facet_density(s, side, t, reflected, weight, acc);
}

void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

void check_common(double alpha, double eta, int max_k, const DielectricPointOptions& o) {
  check(alpha > 0.0 && std::isfinite(alpha), "alpha must be > 0");
  check(eta > 0.0 && std::isfinite(eta), "eta must be in (0, inf)");
  check(max_k >= 0, "max_k must be >= 0");
  check(o.k_cap >= 1, "k_cap must be >= 1");
}

void finish(DielectricPointValue& r, double scale) {
  r.f = 0.0;
  for (double& v : r.by_k) {
    v *= scale;
    r.f += v;
  }
}

// KD-11: the area element |do/dphi_a x do/dt| of o = -c sin t a + q u + c cos t n, q = q(phi_a),
// c = sqrt(1 - q^2), a = (cos phi_a, sin phi_a, 0), u = n x a.
double lifted_area(double c, double q, double dq, double sin_t) {
  const double dc = -q * dq / c;
  return c * std::hypot(dq - c * sin_t, dc + q * sin_t);
}

// The 3D density in the frame where the light is at phi = pi from above (the model at e), o.z != 0.
void density_3d(NdfKind ndf, double alpha, double e, double theta_i, const Dir3& o, const DielectricPointOptions& opt,
                DielectricPointValue& r, int max_k) {
  const bool reflected = o.z > 0.0;
  const double st = std::sin(theta_i), ct = std::cos(theta_i);
  // KD-11: the groove axis u keeps n_o o.u = -(i.u): a along the horizontal part of n_o o + i.
  const double no = reflected ? 1.0 : e;
  const double wx = no * o.x - st, wy = no * o.y;
  double phi_a = std::atan2(wy, wx);
  if (phi_a < 0.0) phi_a += kPi;
  if (phi_a >= kPi) phi_a -= kPi;
  const double ca = std::cos(phi_a), sa = std::sin(phi_a);
  const double i_a = -st * ca, i_u = st * sa;
  Section s;
  static_cast<DielectricSection&>(s) = lifted_section(i_a, i_u, ct, e);
  const double c = s.c3d;
  const double q_1 = -i_u, dq_1 = -st * ca;
  s.three_d = true;
  s.ndf = ndf;
  s.alpha = alpha;
  s.opt = &opt;
  const double o_a = o.x * ca + o.y * sa;
  double t = 0.0, area = 0.0;
  if (reflected) {
    t = std::atan2(-o_a, o.z);
    area = lifted_area(c, q_1, dq_1, std::sin(t));
  } else {
    if (s.all_tir) return;
    t = std::atan2(o_a, -o.z);
    const double q_2 = q_1 / e, dq_2 = dq_1 / e;
    const double r_2 = std::sqrt((1.0 - q_2) * (1.0 + q_2));
    area = lifted_area(r_2, q_2, dq_2, -std::sin(t));  // o = -r_2 sin(t + pi) a + q_2 u + r_2 cos(t + pi) n
  }
  if (opt.broken == DielectricPointBreak::section_jacobian) area = 1.0;
  if (!(area > 0.0)) return;
  std::vector<double> by_k(static_cast<std::size_t>(max_k + 2), 0.0);
  section_density(s, t, reflected, 1.0 / (kPi * area), Acc{max_k, &by_k});  // phi_a uniform over [0, pi)
  for (std::size_t k = 0; k < by_k.size(); ++k) r.by_k[k] += by_k[k];
}

}  // namespace

DielectricPointValue kaleidoscope_dielectric_bsdf_flatland(NdfKind ndf, double alpha, double eta, double theta_i,
                                                           double theta_o, bool reflected, int max_k,
                                                           const DielectricPointOptions& opt) {
  check_common(alpha, eta, max_k, opt);
  check(std::abs(theta_i) < kHalfPi, "theta_i must be in (-pi/2, pi/2)");
  check(std::abs(theta_o) < kHalfPi, "theta_o must be in (-pi/2, pi/2)");
  DielectricPointValue r;
  r.by_k.assign(static_cast<std::size_t>(max_k + 2), 0.0);
  // Light from below: the model at 1 / eta mirrored in the macrosurface, exit angles negated.
  const bool below = opt.from == DielectricLightFrom::below;
  Section s;
  static_cast<DielectricSection&>(s) = flatland_section(theta_i, below ? 1.0 / eta : eta);
  s.ndf = ndf;
  s.alpha = alpha;
  s.opt = &opt;
  section_density(s, below ? -theta_o : theta_o, reflected, 1.0, Acc{max_k, &r.by_k});
  finish(r, opt.broken == DielectricPointBreak::no_cosine ? 1.0 : 1.0 / std::cos(theta_o));
  return r;
}

DielectricPointValue kaleidoscope_dielectric_bsdf_3d(NdfKind ndf, double alpha, double eta, const Dir3& i,
                                                     const Dir3& o, int max_k, const DielectricPointOptions& opt) {
  check_common(alpha, eta, max_k, opt);
  const double ni = std::sqrt(i.x * i.x + i.y * i.y + i.z * i.z), no = std::sqrt(o.x * o.x + o.y * o.y + o.z * o.z);
  check(std::isfinite(ni) && std::abs(ni - 1.0) < 1e-6 && i.z != 0.0, "i must be a unit vector off the horizon");
  check(std::isfinite(no) && std::abs(no - 1.0) < 1e-6, "o must be a unit vector");
  DielectricPointValue r;
  r.by_k.assign(static_cast<std::size_t>(max_k + 2), 0.0);
  if (o.z == 0.0) return r;
  // The light's side: below, the model at 1 / eta mirrored in z.
  const bool below = i.z < 0.0;
  const double e = below ? 1.0 / eta : eta;
  const double sz = below ? -1.0 : 1.0;
  // Turned about n so that the light is at phi = pi (the model is isotropic).
  const double st = std::hypot(i.x, i.y);
  const double theta_i = std::atan2(st, sz * i.z);
  double cr = 1.0, sr = 0.0;  // the rotation taking i's azimuth to pi
  if (st > 0.0) cr = -i.x / st, sr = i.y / st;
  Dir3 m{cr * o.x - sr * o.y, sr * o.x + cr * o.y, sz * o.z};
  // KD-11's azimuth is undefined where n_o o_h + i_h = 0 (the mirror and straight-through directions,
  // and o = n at normal incidence): there the mean of the values 1e-7 rad away on either side.
  const double nm = m.z > 0.0 ? 1.0 : e;
  if (std::hypot(nm * m.x - std::sin(theta_i), nm * m.y) < 1e-9) {
    constexpr double d = 1e-7;
    for (double sgn : {-1.0, 1.0}) {
      const Dir3 p{m.x * std::cos(d), m.y * std::cos(d) + sgn * std::sin(d), m.z * std::cos(d)};
      const double len = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
      const Dir3 q{p.x / len, p.y / len, p.z / len};
      DielectricPointValue half;
      half.by_k.assign(r.by_k.size(), 0.0);
      density_3d(ndf, alpha, e, theta_i, q, opt, half, max_k);
      for (std::size_t k = 0; k < r.by_k.size(); ++k) r.by_k[k] += 0.5 * half.by_k[k];
    }
  } else {
    density_3d(ndf, alpha, e, theta_i, m, opt, r, max_k);
  }
  finish(r, opt.broken == DielectricPointBreak::no_cosine ? 1.0 : 1.0 / std::abs(o.z));
  return r;
}

double kaleidoscope_dielectric_pdf_flatland(NdfKind ndf, double alpha, double eta, double theta_i, double theta_o,
                                            bool reflected, const DielectricPointOptions& opt) {
  return kaleidoscope_dielectric_bsdf_flatland(ndf, alpha, eta, theta_i, theta_o, reflected, 0, opt).f *
         std::cos(theta_o);
}

double kaleidoscope_dielectric_pdf_3d(NdfKind ndf, double alpha, double eta, const Dir3& i, const Dir3& o,
                                      const DielectricPointOptions& opt) {
  return kaleidoscope_dielectric_bsdf_3d(ndf, alpha, eta, i, o, 0, opt).f * std::abs(o.z);
}

}  // namespace vgroove::analytic
