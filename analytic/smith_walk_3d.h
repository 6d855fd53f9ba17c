// vgroove analytic: the Smith multiple-scattering random walk of Heitz, Hanika, d'Eon and
// Dachsbacher ("Multiple-Scattering Microfacet BSDFs with the Smith Model", ACM TOG 35(4), 2016)
// in 3D, for a conductor with any reflectance (F = 1 the white furnace), isotropic Beckmann and
// GGX. A model, not a simulation: a pure function of the uniform numbers its caller supplies.
//
// What it shares with the flatland walk (analytic/smith_walk_flatland.h, whose header derives
// both): the state (the travel direction and lc = log C1(h) <= 0 at the last intersection), the
// free path (walk_free_path: Smith's Lambda depends only on |tan theta| of the travel direction,
// so the flatland formula serves 3D with theta the polar angle of the direction), and the
// sampling of the slope along the view's azimuth (below).
//
// Phase function (Heitz et al. 2016, Sec. 5): at an intersection the facet normal m is drawn from
// the normals visible from v = -d (the direction the ray came from), up or down,
//   D_v(m) = <v, m>+ D(m) / A(v),
// and the ray leaves mirrored, o = 2 <v, m> m - v, keeping F(<v, m>) of its energy. In the frame
// turned about n so that v = (s, 0, v_z), s = |v_xy| >= 0, a normal with slopes (p, q) is m =
// (-p, -q, 1) / sqrt(1 + p^2 + q^2) and <v, m> D(m) d omega_m = (v_z - s p) P22(p, q) dp dq, since
// D d omega_m cos(theta_m) = P22 dp dq and cos(theta_m) = 1 / sqrt(1 + p^2 + q^2). So
//   - p has the density (a + b p)+ P(p) / A with a = v_z, b = -s and P the marginal of P22 along
//     x: the flatland visible slopes at the flatland view theta_v = atan2(-s, v_z) (the flatland
//     direction theta is the 3D (-sin theta, 0, cos theta), analytic/ndf.h), sampled by
//     sample_visible_normal, and A(v) = visible_projected_length(theta_v), which is
//     v_z (1 + Lambda(v)) for an upward v and |v_z| Lambda(-v) for a downward one;
//   - q given p has the density P22(p, q) / P(p), which does not depend on v:
//       Beckmann: P22 = e^{-(p^2 + q^2) / alpha^2} / (pi alpha^2): q ~ N(0, alpha^2 / 2),
//         q = alpha erfinv(2 u - 1);
//       GGX: P22 = (1 + (p^2 + q^2) / alpha^2)^-2 / (pi alpha^2): q = alpha c t, c^2 = 1 + p^2 /
//         alpha^2, t with the density (2 / pi) (1 + t^2)^-2, whose distribution function is
//         1/2 + (atan t + t / (1 + t^2)) / pi = 1/2 + (gamma + sin gamma) / (2 pi), gamma = 2
//         atan t. With delta = pi - |gamma|: delta - sin delta = 2 pi min(u, 1 - u), t = +-cot(
//         delta / 2) (+ for u > 1/2), solved by Newton's method (delta - sin delta is convex and
//         increasing on (0, pi]; its series near 0 avoids the cancellation).
// Both are exact (Heitz et al.'s published code draws GGX's q from a rational fit instead).
//
// The walk: the ray enters travelling along -i from above the surface (lc = 0) and alternates a
// free path and a reflection until a free path leaves. The bounce count k and the exit direction o
// are the walk's outcome; with F = 1 every walk leaves with probability 1 (the white furnace), so
// the fraction of walks leaving after k reflections is the albedo of order k, E_k(i), and E_1 is
// the single-scattering albedo with the height-correlated G2 (Heitz 2014, Eq. 21; the first hit's
// C1 is xi^{1 / (1 + Lambda(i))}, and it leaves with E[C1^Lambda(o)] = (1 + Lambda(i)) / (1 +
// Lambda(i) + Lambda(o))). With a reflectance F each walk carries prod_j F(<v_j, m_j>), the
// conductor's energy (Heitz et al. 2016, Sec. 6).
//
// Its BRDF by next-event estimation (Heitz et al. 2016, Sec. 4.3, the estimator of their Fig. 5):
// after each reflection j at lc_j from v_j, the contribution of leaving at once towards o is
//   phase(v_j, o) G1(o, h_j) = D_v(h) / (4 <v_j, h>) * C1(h_j)^Lambda(o),   h = (v_j + o) / |.|,
// an unbiased estimate of sum_k f_k(i, o) cos(theta_o) with the k-th term f_k's; the tests
// integrate it over o and compare with the sampled E_k.
//
// Conventions: analytic/brdf_3d.h (n = (0, 0, 1), Dir3 unit vectors, i and o pointing away from
// the surface). Beckmann and GGX only (Phong has no closed-form Lambda).
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/smith_walk_flatland.h"

#include <algorithm>
#include <cmath>

namespace vgroove::analytic {

// A(v) = int <v, m>+ D(m) d omega_m, the projected area of the facets facing v (any direction
// with v_z > -1), per unit macrosurface area.
double visible_projected_area(NdfKind ndf, double alpha, const Dir3& v);

// D_v(m) = <v, m>+ D(m) / A(v) over the upper hemisphere of m (per unit solid angle), and a
// sample of it from u0 (the slope along v's azimuth) and u1 (the slope across it), both in
// (0, 1). v must see some facet (A(v) > 0).
double visible_normal_pdf_3d(NdfKind ndf, double alpha, const Dir3& v, const Dir3& m);
Dir3 sample_visible_normal_3d(NdfKind ndf, double alpha, const Dir3& v, double u0, double u1);

// The slope across the view given the slope p along it (the header's q), from u in (0, 1),
// increasing in u.
double sample_cross_slope(NdfKind ndf, double alpha, double p, double u);

// The polar angle of a direction in [0, pi], from atan2 (accurate near the poles, where acos is not).
inline double polar_angle(const Dir3& d) { return std::atan2(std::hypot(d.x, d.y), d.z); }

struct Walk3d {
  int k = 0;          // reflections
  Dir3 o{};           // exit direction (o.z > 0) when left
  bool left = false;  // false: still inside after max_k reflections
};

// The walk from i (i.z > 0). uniform() returns numbers in (0, 1): one per free path and two per
// reflection, in that order. on_reflection(cos_vm) is called at each reflection with <v, m>, the
// cosine of the local angle of incidence (a conductor's F takes it).
template <class Uniform, class OnReflection>
Walk3d smith_walk_3d(NdfKind ndf, double alpha, const Dir3& i, Uniform&& uniform, OnReflection&& on_reflection,
                     int max_k = 100000) {
  Walk3d w;
  Dir3 d{-i.x, -i.y, -i.z};  // travelling along -i
  double lc = 0.0;
  for (;;) {
    const double next = walk_free_path(ndf, alpha, lc, polar_angle(d), uniform());
    if (std::isinf(next)) {
      w.o = d;
      w.left = true;
      return w;
    }
    if (w.k == max_k) return w;
    lc = next;
    ++w.k;
    const Dir3 v{-d.x, -d.y, -d.z};
    const double u0 = uniform(), u1 = uniform();
    const Dir3 m = sample_visible_normal_3d(ndf, alpha, v, u0, u1);
    // <v, m> > 0 for every visible normal; the clamp only absorbs rounding.
    const double c = std::max(0.0, v.x * m.x + v.y * m.y + v.z * m.z);
    on_reflection(c);
    d = {2.0 * c * m.x - v.x, 2.0 * c * m.y - v.y, 2.0 * c * m.z - v.z};
    // A unit vector to rounding; renormalized so that no drift accumulates over long walks.
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    d = {d.x / len, d.y / len, d.z / len};
  }
}

// The walk with F = 1.
template <class Uniform>
Walk3d smith_walk_3d(NdfKind ndf, double alpha, const Dir3& i, Uniform&& uniform, int max_k = 100000) {
  return smith_walk_3d(
      ndf, alpha, i, uniform, [](double) {}, max_k);
}

// The next-event estimate after a reflection from the view v at lc = log C1(h): the phase
// function towards o times the chance to leave from there unmasked, D_v(h) / (4 <v, h>) C1(h)^Lambda(o)
// (the header's NEE term; 0 when o.z <= 0 or h is not a visible normal).
double next_event_estimate(NdfKind ndf, double alpha, const Dir3& v, double lc, const Dir3& o);

// One walk's next-event estimates towards o (o.z > 0): est[k - 1] += next_event_estimate after
// reflection k, for k = 1..n (the estimate of f_k(i, o) cos(theta_o)); the walk stops when it
// leaves or after n reflections (orders beyond n are not estimated). The same uniform() pattern
// as smith_walk_3d, so that the same numbers give the same path.
template <class Uniform>
void smith_walk_3d_estimates(NdfKind ndf, double alpha, const Dir3& i, const Dir3& o, Uniform&& uniform, double* est,
                             int n) {
  Dir3 d{-i.x, -i.y, -i.z};
  double lc = 0.0;
  for (int k = 1; k <= n; ++k) {
    const double next = walk_free_path(ndf, alpha, lc, polar_angle(d), uniform());
    if (std::isinf(next)) return;
    lc = next;
    const Dir3 v{-d.x, -d.y, -d.z};
    est[k - 1] += next_event_estimate(ndf, alpha, v, lc, o);
    const double u0 = uniform(), u1 = uniform();
    const Dir3 m = sample_visible_normal_3d(ndf, alpha, v, u0, u1);
    const double c = std::max(0.0, v.x * m.x + v.y * m.y + v.z * m.z);
    d = {2.0 * c * m.x - v.x, 2.0 * c * m.y - v.y, 2.0 * c * m.z - v.z};
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    d = {d.x / len, d.y / len, d.z / len};
  }
}

}  // namespace vgroove::analytic
