#include "vgroove/analytic/brdf_nonsymmetric.h"

#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = 0.5 * std::numbers::pi;

CountWidth count_width(double t_i, double theta_l, double theta_r, int k) {
  // As G_nonsymmetric (analytic/kaleidoscope_nonsymmetric.cpp), the widths before the division
  // by f_a: Lee et al. 2018, Eq. (7) and (9) with the transition points of ERRATA E2.
  const double theta_v = aperture(theta_l, theta_r);
  const double h_l = std::sin(-theta_l), h_r = std::sin(theta_r), h_max = std::max(h_l, h_r);
  CountWidth out;
  const double len_l = h_max > 0.0 ? h_r / h_max : 1.0, len_r = h_max > 0.0 ? h_l / h_max : 1.0;
  out.len_left = len_l;
  const double phi_a = theta_l + kHalfPi;
  auto f_vertex = [&](int j) { return ((j % 2 == 0) ? len_l : len_r) * std::sin(phi_a + j * theta_v - t_i); };
  const double fa = f_vertex(0);
  if (!(fa > 0.0)) return out;
  const double fb = std::max(0.0, len_r * std::sin(phi_a - theta_v - t_i));
  out.f_a = fa;
  out.f_b = fb;
  const int kb = bounce_count_kb(t_i, theta_l, theta_r);
  const int counts[4] = {1, kb - 1, kb, kb + 1};
  if (k != 1 && k != kb - 1 && k != kb && k != kb + 1) return out;
  const double f2 = std::max(0.0, f_vertex(1));
  const double fkb = std::max(0.0, f_vertex(kb - 1));
  const double fka = std::max(0.0, f_vertex(kb));
  // Lee et al. 2018, Eq. (9), times f_a.
  const double w[4] = {std::max(0.0, fa - std::max(f2, fb)), std::max(0.0, std::min(fa, f2) - fkb),
                       std::max(0.0, std::min(fa, fkb) - std::max(fka, fb)), std::max(0.0, std::min(fkb, fka) - fb)};
  for (int z = 0; z < 4; ++z)
    if (counts[z] == k) out.width += w[z];
  return out;
}

namespace {

// prod_j F(c |d_j . s_j|) along the path in the groove (theta_l = -A, theta_r = B), left facet first.
double fresnel_product(const FresnelFn& F, double t_i, double A, double B, int k, double c) {
  if (!F) return 1.0;
  double dx = std::sin(t_i), dy = -std::cos(t_i);
  const double nl[2] = {std::sin(A), std::cos(A)}, nr[2] = {-std::sin(B), std::cos(B)};
  bool left = true;
  double prod = 1.0;
  for (int j = 0; j < k; ++j) {
    const double* n = left ? nl : nr;
    const double dn = dx * n[0] + dy * n[1];
    prod *= F(c * std::abs(dn));
    dx -= 2.0 * dn * n[0];
    dy -= 2.0 * dn * n[1];
    left = !left;
  }
  return prod;
}

// One family of grooves sending t_i to t_o after k reflections: theta_l = C + beta B, B in [lo, hi].
struct Family {
  double C = 0.0, beta = 0.0, lo = 0.0, hi = 0.0;
};

// Eq. (8) inverted at fixed theta_r = B (header), for the left facet hit first: the families.
std::vector<Family> families(double t_i, double t_o, int k) {
  std::vector<Family> out;
  const bool even = k % 2 == 0;
  const double beta = even ? 1.0 : static_cast<double>(k - 1) / (k + 1);
  const double base = even ? (t_i - t_o + (1 - k) * kPi) / k : (t_i + t_o + (1 - k) * kPi) / (k + 1);
  const double step = even ? 2.0 * kPi / k : 2.0 * kPi / (k + 1);
  // theta_l = C + beta B in (-pi/2, 0] for some B in [0, pi/2): C in (-pi/2 - beta pi/2, 0].
  const double c_lo = -kHalfPi * (1.0 + beta), c_hi = 0.0;
  const int j_lo = static_cast<int>(std::ceil((c_lo - base) / step)) - 1;
  const int j_hi = static_cast<int>(std::floor((c_hi - base) / step)) + 1;
  for (int j = j_lo; j <= j_hi; ++j) {
    Family f;
    f.C = base + j * step;
    f.beta = beta;
    double lo = 0.0, hi = kHalfPi;
    if (beta > 0.0) {
      lo = std::max(lo, (-kHalfPi - f.C) / beta);
      hi = std::min(hi, -f.C / beta);
    } else if (!(f.C > -kHalfPi && f.C <= 0.0)) {
      continue;
    }
    // Aperture pi + theta_l - B > 0: pi + C + (beta - 1) B > 0.
    if (beta < 1.0)
      hi = std::min(hi, (kPi + f.C) / (1.0 - beta));
    else if (!(kPi + f.C > 0.0))
      continue;
    if (!(hi > lo)) continue;
    f.lo = lo;
    f.hi = hi;
    out.push_back(f);
  }
  return out;
}

// Eq. (7)'s argument r = (pi + 2 t_i - theta_l - theta_r) / (2 theta_v) along a family, and the B
// where k_b = 2 floor(r + 1/2) changes from 2m - 2 to 2m (r = m - 1/2).
double kb_argument(double t_i, const Family& f, double B) {
  const double X = kPi + 2.0 * t_i - f.C - (f.beta + 1.0) * B, V = kPi + f.C + (f.beta - 1.0) * B;
  return X / (2.0 * V);
}
double kb_cut(double t_i, const Family& f, int m) {
  const double q = 2.0 * m - 1.0;
  return (kPi + 2.0 * t_i - f.C - q * (kPi + f.C)) / (q * (f.beta - 1.0) + f.beta + 1.0);
}

// The B-pieces of a family with constant k_b that can hold an outcome of k reflections.
std::vector<std::pair<double, double>> pieces(double t_i, const Family& f, int k) {
  std::vector<double> cuts{f.lo, f.hi};
  const double r0 = kb_argument(t_i, f, f.lo), r1 = kb_argument(t_i, f, f.hi);
  // k_b is monotone in B (a ratio of linear functions). Only the cuts between relevant k_b matter
  // for k >= 2 (k_b in {k - 1, k, k + 1}); count 1 is possible for every k_b.
  const double rmin = std::min(r0, r1), rmax = std::max(r0, r1);
  constexpr double kMaxM = 1e6;  // k_b beyond 2e6: apertures below ~1.6e-6 rad
  int m_lo = static_cast<int>(std::max(-kMaxM, std::floor(rmin + 0.5))) + 1;
  int m_hi = static_cast<int>(std::min(kMaxM, std::floor(rmax + 0.5)));
  if (k >= 2) {
    m_lo = std::max(m_lo, (k - 1) / 2);
    m_hi = std::min(m_hi, (k + 1) / 2 + 1);
  } else {
    // Count 1 is zone 1 of Eq. (9) for every k_b, and also zone 2 (k_b = 2) or 4 (k_b = 0): only
    // the changes between k_b = 0, 2 and 4 move a kink.
    m_lo = std::max(m_lo, 0);
    m_hi = std::min(m_hi, 2);
  }
  for (int m = m_lo; m <= m_hi; ++m) {
    const double b = kb_cut(t_i, f, m);
    if (b > f.lo && b < f.hi) cuts.push_back(b);
  }
  std::sort(cuts.begin(), cuts.end());
  std::vector<std::pair<double, double>> out;
  for (std::size_t n = 0; n + 1 < cuts.size(); ++n) {
    const double a = cuts[n], b = cuts[n + 1];
    if (!(b > a)) continue;
    if (k >= 2) {
      const int kb = 2 * static_cast<int>(std::floor(kb_argument(t_i, f, 0.5 * (a + b)) + 0.5));
      if (std::abs(kb - k) > 1) continue;
    }
    out.emplace_back(a, b);
  }
  return out;
}

// |d t_h / d theta_l| (Eq. 8): k/2 for k even, (k+1)/2 for k odd.
double half_slope(int k) { return std::abs(dtheta_h_dtheta_l(k)); }

// The partner law's density of B for a first facet at azimuth phi (3D) or in flatland.
double partner_density(const NonsymmetricModel& m, bool flatland, double B, double phi) {
  const double alpha = flatland ? m.roughness.alpha_x : alpha_along(m.roughness, phi);
  return flatland ? P2_theta_r(m.roughness.ndf, B, alpha) : P_theta_r(m.roughness.ndf, B, alpha);
}

// sum over families and their B of `term(A, B, width / l_L) * density(B)`: the integral of Eq. (23)
// for one orientation of the first facet, or its delta / near-delta forms.
template <class Term>
double integrate_families(double t_i, double t_o, int k, const NonsymmetricModel& m, bool flatland, double phi,
                          Term&& term) {
  double sum = 0.0;
  for (const Family& f : families(t_i, t_o, k)) {
    auto at = [&](double B) {
      const double theta_l = f.C + f.beta * B;
      if (!(theta_l <= 0.0 && theta_l > -kHalfPi && B >= 0.0 && B < kHalfPi)) return 0.0;
      const CountWidth w = count_width(t_i, theta_l, B, k);
      if (!(w.width > 0.0 && w.len_left > 0.0)) return 0.0;
      return term(-theta_l, B, w.width / w.len_left);
    };
    if (m.near_symmetric_halfwidth > 0.0) {
      // B uniform on [A - w, A + w]: B - A(B) = (1 + beta) B + C in [-w, w].
      const double w = m.near_symmetric_halfwidth, s = 1.0 + f.beta;
      const double lo = std::max(f.lo, (-f.C - w) / s), hi = std::min(f.hi, (-f.C + w) / s);
      for (const auto& [a, b] : pieces(t_i, f, k)) {
        const double pa = std::max(a, lo), pb = std::min(b, hi);
        if (pb > pa) sum += integrate_adaptive_parts(at, pa, pb, m.tolerance) / (2.0 * w);
      }
    } else if (m.partner == PartnerLaw::symmetric) {
      // delta(B - A): B* = -C / (1 + beta), weight 1 / |1 + beta| (Eq. 24).
      const double B = -f.C / (1.0 + f.beta);
      if (B >= f.lo && B <= f.hi) sum += at(B) / (1.0 + f.beta);
    } else {
      auto with_p = [&](double B) {
        const double v = at(B);
        return v > 0.0 ? v * partner_density(m, flatland, B, phi) : 0.0;
      };
      for (const auto& [a, b] : pieces(t_i, f, k)) sum += integrate_adaptive_parts(with_p, a, b, m.tolerance);
    }
  }
  return sum;
}

double brdf_k_3d(const Dir3& i, const Dir3& o, int k, const NonsymmetricModel& m, const FresnelFn& F) {
  const double cos_i = i.z, cos_o = o.z;
  if (!(cos_i > 0.0 && cos_o > 0.0) || k < 1) return 0.0;
  GrooveFrame s;
  const bool ok = groove_frame(i, o, s);
  if (!ok) {
    // h = n: k = 1 is the flat facet's single reflection, Cook-Torrance with G = 1 (the limit);
    // k >= 2 diverges like 1 / sin(theta_h) wherever grooves send light there.
    if (k == 1) {
      const double Fr = F ? F(s.cos_d) : 1.0;
      return Fr * D_anisotropic(m.roughness, 0.0, 0.0) / (4.0 * cos_i * cos_o);
    }
    s.sin_h = 1.0;
  }
  const double jac = 1.0 / (half_slope(k) * 4.0 * s.cos_d);
  const double phi_a = std::atan2(s.ay, s.ax);  // the azimuth of a
  double sum = 0.0;
  for (int side = 0; side < 2; ++side) {
    // side 0: the first facet leans towards a (left, azimuth phi_a); side 1: away (mirrored, phi_a + pi).
    const double sgn = side == 0 ? 1.0 : -1.0;
    const double ti = sgn * s.x.t_i, to = sgn * s.x.t_o;
    const double phi_s = side == 0 ? phi_a : phi_a + kPi;
    auto term = [&](double A, double B, double width_per_len) {
      // |i.s| G D(s) |ds/do| without P (Eq. 23).
      double v = s.c * width_per_len * D_anisotropic(m.roughness, A, phi_s) * jac;
      // k = 1: s = h, sin(A) / sin(theta_h) = 1 exactly (Eq. 25).
      v *= k == 1 ? 1.0 : std::sin(A) / s.sin_h;
      return v * fresnel_product(F, ti, A, B, k, s.c);
    };
    sum += integrate_families(ti, to, k, m, false, phi_s, term);
  }
  const double rho = sum / (cos_i * cos_o);
  if (!ok) return rho > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
  return rho;
}

double brdf_k_flatland(double theta_i, double theta_o, int k, const NonsymmetricModel& m) {
  const double cos_i = std::cos(theta_i), cos_o = std::cos(theta_o);
  if (!(cos_i > 0.0 && cos_o > 0.0) || k < 1) return 0.0;
  // |d theta_o / d theta_l| = 2 |d theta_h / d theta_l|.
  const double jac = 1.0 / (2.0 * half_slope(k));
  double sum = 0.0;
  for (int side = 0; side < 2; ++side) {
    const double sgn = side == 0 ? 1.0 : -1.0;
    auto term = [&](double A, double, double width_per_len) {
      return width_per_len * D2(m.roughness.ndf, A, m.roughness.alpha_x) * jac;
    };
    sum += integrate_families(sgn * theta_i, sgn * theta_o, k, m, true, 0.0, term);
  }
  return sum / (cos_i * cos_o);
}

NonsymmetricModel isotropic_model(NdfKind ndf, double alpha) {
  NonsymmetricModel m;
  m.roughness = isotropic_roughness(ndf, alpha);
  return m;
}

}  // namespace

std::vector<PartnerPiece> partner_pieces(double t_i, double t_o, int k) {
  std::vector<PartnerPiece> out;
  for (const Family& f : families(t_i, t_o, k))
    for (const auto& [a, b] : pieces(t_i, f, k)) out.push_back({f.C, f.beta, a, b});
  return out;
}

double nonsymmetric_brdf_k(const Dir3& i, const Dir3& o, int k, const NonsymmetricModel& m, const FresnelFn& F) {
  return brdf_k_3d(i, o, k, m, F);
}
double nonsymmetric_brdf(const Dir3& i, const Dir3& o, int max_k, const NonsymmetricModel& m, const FresnelFn& F) {
  double s = 0.0;
  for (int k = 1; k <= max_k; ++k) s += brdf_k_3d(i, o, k, m, F);
  return s;
}
double vgroove_nonsymmetric_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha) {
  return brdf_k_3d(i, o, k, isotropic_model(ndf, alpha), FresnelFn{});
}
double vgroove_nonsymmetric_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha, const FresnelFn& F) {
  return brdf_k_3d(i, o, k, isotropic_model(ndf, alpha), F);
}
double vgroove_nonsymmetric_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k) {
  return nonsymmetric_brdf(i, o, max_k, isotropic_model(ndf, alpha));
}
double vgroove_nonsymmetric_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k,
                                 const FresnelFn& F) {
  return nonsymmetric_brdf(i, o, max_k, isotropic_model(ndf, alpha), F);
}
double flatland_nonsymmetric_brdf_k(double theta_i, double theta_o, int k, const NonsymmetricModel& m) {
  return brdf_k_flatland(theta_i, theta_o, k, m);
}
double flatland_nonsymmetric_brdf(double theta_i, double theta_o, int max_k, const NonsymmetricModel& m) {
  double s = 0.0;
  for (int k = 1; k <= max_k; ++k) s += brdf_k_flatland(theta_i, theta_o, k, m);
  return s;
}

}  // namespace vgroove::analytic
