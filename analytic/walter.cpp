// Walter et al. 2007 in 3D and flatland; the derivation of each step is in docs/derivations/walter.md.
#include "vgroove/analytic/walter.h"

#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace vgroove::analytic {
namespace {

double dot(const Dir3& a, const Dir3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// The polar angle of a unit vector from the axis +-n (|z|), in [0, pi/2], without acos's loss near 0.
double polar_from_axis(const Dir3& v) { return std::atan2(std::hypot(v.x, v.y), std::abs(v.z)); }

// The normal distribution of h (h.z > 0): D in 3D, D2 in flatland (h.y = 0 there).
double ndf_of(const Dir3& h, NdfKind ndf, double alpha, int dim) {
  const double s = std::hypot(h.x, h.y);
  return dim == 3 ? D_cs(ndf, h.z, s, alpha) : D2_cs(ndf, h.z, s, alpha);
}

// log Gamma(x) without the global signgam of std::lgamma (x > 0 here, so the sign is +).
double log_gamma(double x) {
  int sign = 0;
  return ::lgamma_r(x, &sign);
}

// G2(i, o, h). i.h > 0 and o.h has the sign of o.z (checked by the callers).
double masking(MaskingKind g, const Dir3& i, const Dir3& o, const Dir3& h, NdfKind ndf, double alpha) {
  const bool transmit = o.z < 0.0;
  switch (g) {
    case MaskingKind::vcavity: {
      // Lee et al. 2018, Eq. (2)-(3) (Heitz 2014, Eq. 24): min of the two V-cavity G1.
      const double gi = G1_vcavity(dot(i, h), i.z, h.z);
      const double go = G1_vcavity(dot(o, h), o.z, h.z);
      return std::min(gi, go);
    }
    case MaskingKind::smith_separable:
    case MaskingKind::smith_height_correlated:
      break;
  }
  const double li = Lambda(ndf, polar_from_axis(i), alpha);
  const double lo = Lambda(ndf, polar_from_axis(o), alpha);
  if (g == MaskingKind::smith_separable) return 1.0 / ((1.0 + li) * (1.0 + lo));  // Heitz 2014, Eq. (20)
  if (!transmit) return 1.0 / (1.0 + li + lo);                                    // Heitz 2014, Eq. (21)
  // Transmission, height-correlated: int_0^1 u^Li (1 - u)^Lo du = B(1 + Li, 1 + Lo)
  // (docs/derivations/walter.md, "Height-correlated Smith for transmission").
  return std::exp(log_gamma(1.0 + li) + log_gamma(1.0 + lo) - log_gamma(2.0 + li + lo));
}

// Walter Eq. (16) (article Eq. 15b, A7) with n_i = 1, n_o = eta, oriented to the near side's normal
// (h.z >= 0, where D lives). False when |i + eta o| = 0 (eta = 1, o = -i: no facet is singled out).
bool half_vector_t(const Dir3& i, const Dir3& o, double eta, Dir3& h) {
  const Dir3 w{i.x + eta * o.x, i.y + eta * o.y, i.z + eta * o.z};
  const double len = std::sqrt(dot(w, w));
  if (!(len > 0.0)) return false;
  const double s = (w.z < 0.0 ? -1.0 : 1.0) / len;
  h = Dir3{s * w.x, s * w.y, s * w.z};
  return true;
}

Dir3 half_vector_r(const Dir3& i, const Dir3& o) {
  // Walter Eq. (13) (article Eq. 13b): h_r = (i + o) / |i + o| (i, o above: |i + o| > 0).
  const Dir3 w{i.x + o.x, i.y + o.y, i.z + o.z};
  const double inv = 1.0 / std::sqrt(dot(w, w));
  return Dir3{inv * w.x, inv * w.y, inv * w.z};
}

// Reflection in 3D (dim 3, Walter Eq. 20) or flatland (dim 2, the 1/2 Jacobian).
double brdf_dim(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, double eta, MaskingKind g, int dim) {
  assert(alpha > 0.0 && eta > 0.0);
  if (!(i.z > 0.0 && o.z > 0.0)) return 0.0;
  const Dir3 h = half_vector_r(i, o);
  const double ih = dot(i, h);
  if (!(ih > 0.0)) return 0.0;
  const double F = optics::fresnel_dielectric(ih, eta);
  const double G = masking(g, i, o, h, ndf, alpha);
  const double D = ndf_of(h, ndf, alpha, dim);
  // 3D: |d omega_h / d omega_o| = 1 / (4 o.h) (Walter Eq. 14, article Eq. 19b); flatland: d theta_h /
  // d theta_o = 1/2. Walter Eq. (20), article Eq. (21d) for f_r.
  return dim == 3 ? F * G * D / (4.0 * i.z * o.z) : F * G * D * ih / (2.0 * i.z * o.z);
}

// Transmission in 3D (Walter Eq. 21 with i the light; the article's Eq. 21d with its prefactor
// inverted, ERRATA W1) or flatland (n_o^1 and |.| for the square: docs/derivations/walter.md).
double btdf_dim(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, double eta, MaskingKind g, int dim) {
  assert(alpha > 0.0 && eta > 0.0);
  if (!(i.z > 0.0 && o.z < 0.0)) return 0.0;
  Dir3 h;
  if (!half_vector_t(i, o, eta, h)) return 0.0;
  const double ih = dot(i, h), oh = dot(o, h);
  // A refraction at h: lit from the near side, leaving on the far side (Walter Sec. 5, chi+ terms).
  if (!(ih > 0.0 && oh < 0.0 && h.z > 0.0)) return 0.0;
  const double F = optics::fresnel_dielectric(ih, eta);
  if (!(F < 1.0)) return 0.0;  // total internal reflection at this facet
  const double G = masking(g, i, o, h, ndf, alpha);
  const double D = ndf_of(h, ndf, alpha, dim);
  const double den = ih + eta * oh;  // n_i i.h + n_o o.h
  const double cos_io = i.z * -o.z;
  if (dim == 3) return ih * -oh * eta * eta * (1.0 - F) * G * D / (cos_io * den * den);
  return ih * -oh * eta * (1.0 - F) * G * D / (cos_io * std::abs(den));
}

Dir3 near2(double theta) { return Dir3{-std::sin(theta), 0.0, std::cos(theta)}; }
Dir3 far2(double phi) { return Dir3{std::sin(phi), 0.0, -std::cos(phi)}; }

}  // namespace

Dir3 walter_half_vector(const Dir3& i, const Dir3& o, double eta) {
  if (o.z >= 0.0) return half_vector_r(i, o);
  Dir3 h{0.0, 0.0, 1.0};
  half_vector_t(i, o, eta, h);
  return h;
}

double walter_jacobian_t(const Dir3& i, const Dir3& o, double eta) {
  Dir3 h;
  if (!half_vector_t(i, o, eta, h)) return 0.0;
  const double oh = dot(o, h), den = dot(i, h) + eta * oh;
  return eta * eta * std::abs(oh) / (den * den);  // Walter Eq. (17), article Eq. (20b)
}

double walter_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, double eta, MaskingKind g) {
  return brdf_dim(i, o, ndf, alpha, eta, g, 3);
}

double walter_btdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, double eta, MaskingKind g) {
  return btdf_dim(i, o, ndf, alpha, eta, g, 3);
}

double walter_bsdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, double eta, MaskingKind g) {
  return o.z >= 0.0 ? walter_brdf(i, o, ndf, alpha, eta, g) : walter_btdf(i, o, ndf, alpha, eta, g);
}

double walter_half_angle_t2(double theta_i, double theta_t, double eta) {
  Dir3 h{0.0, 0.0, 1.0};
  half_vector_t(near2(theta_i), far2(theta_t), eta, h);
  return std::atan2(-h.x, h.z);
}

double walter_jacobian_t2(double theta_i, double theta_t, double eta) {
  const Dir3 i = near2(theta_i), o = far2(theta_t);
  Dir3 h;
  if (!half_vector_t(i, o, eta, h)) return 0.0;
  const double oh = dot(o, h);
  return eta * std::abs(oh) / std::abs(dot(i, h) + eta * oh);
}

double walter_brdf2(double theta_i, double theta_o, NdfKind ndf, double alpha, double eta, MaskingKind g) {
  return brdf_dim(near2(theta_i), near2(theta_o), ndf, alpha, eta, g, 2);
}

double walter_btdf2(double theta_i, double theta_t, NdfKind ndf, double alpha, double eta, MaskingKind g) {
  return btdf_dim(near2(theta_i), far2(theta_t), ndf, alpha, eta, g, 2);
}

}  // namespace vgroove::analytic
