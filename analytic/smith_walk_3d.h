// vgroove analytic: the Smith multiple-scattering random walk of Heitz, Hanika, d'Eon, Dachsbacher
// ("Multiple-Scattering Microfacet BSDFs with the Smith Model", ACM TOG 35(4), 2016) in 3D, for a
// conductor with any reflectance (F = 1 the white furnace), Beckmann and GGX, isotropic and (by
// stretching, alpha_x, alpha_y) anisotropic, heights log C1, uniform or gaussian; its BRDF by
// next-event estimation (Sec. 4.3). Shares the free path and visible slope along the view's
// azimuth with analytic/smith_walk_flatland.h; the cross slope exact. A pure function of the
// uniform numbers its caller supplies. E_1 is Smith's height-correlated E_ss (Heitz 2014, Eq. 21).
// Tests: tests/analytic/smith_walk_3d_test.cpp (SmithWalk3d.CrossSlopeInvertsItsDistribution,
// SmithWalk3d.SingleScatteringIsTheHeightCorrelatedAlbedo, SmithWalk3d.NextEventEstimatesIntegrateToTheSampledOrders,
// SmithWalk3dAnisotropic.ProjectedAreaIsTheProjectedRoughnessLambda,
// SmithWalk3dAnisotropic.EqualAxesAreTheIsotropicWalk, SmithWalk3dAnisotropic.SwappingTheAxesIsAQuarterTurn,
// SmithWalk3dAnisotropic.SingleScatteringIsTheHeightCorrelatedAlbedo,
// SmithWalk3dAnisotropic.EvaluationIsReciprocalPerOrder, SmithWalk3dAnisotropic.HeightDistributionsGiveTheSameOrders).
// Conventions: analytic/brdf_3d.h. Derivation: docs/derivations/smith_walk.md.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/ndf_anisotropic.h"
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

// ---- Anisotropic roughness (alpha_x, alpha_y) and the walk's heights -------------------------
// The slopes (p, q) of the isotropic law at alpha = 1 stretched to (alpha_x p, alpha_y q) (Heitz
// 2014, Sec. 3.3; the NDF of analytic/ndf_anisotropic.h). The isotropic functions above are not
// these at alpha_x = alpha_y: they stay as they were, and the tests hold the two together.

// alpha_o = sqrt(alpha_x^2 cos^2 phi + alpha_y^2 sin^2 phi), phi the azimuth of d: the roughness
// of the slopes along d's azimuth (Heitz 2014, Sec. 3.3, Eq. 11); alpha_x for a vertical d (no azimuth,
// Lambda 0).
double projected_roughness(const Roughness& r, const Dir3& d);
// Lambda(d) = Lambda_iso(theta_d; alpha_o(d)), d up or down (Lambda depends on |tan theta| only).
double Lambda_3d(const Roughness& r, const Dir3& d);
// A(v), D_v(m) and its sample as above, with the anisotropic D. The sample stretches v to (alpha_x
// v_x, alpha_y v_y, v_z), draws the isotropic visible normal at alpha = 1 and stretches it back
// (Heitz and d'Eon 2014; Heitz et al. 2016, their code).
double visible_projected_area(const Roughness& r, const Dir3& v);
double visible_normal_pdf_3d(const Roughness& r, const Dir3& v, const Dir3& m);
Dir3 sample_visible_normal_3d(const Roughness& r, const Dir3& v, double u0, double u1);
double next_event_estimate(const Roughness& r, const Dir3& v, double lc, const Dir3& o);

// The height distribution of the walk's microsurface (Heitz et al. 2016, Sec. 4 and their code):
// log_c1 keeps log C1(h) as the state (the walk above), uniform has h uniform on [-1, 1], gaussian
// h standard normal. The walk meets the heights only through C1(h), so its outcome does not depend
// on the law; the explicit laws round-trip h through C1 and C1^-1 at each step, as their code does.
enum class WalkHeights { log_c1, uniform, gaussian };
const char* walk_heights_name(WalkHeights law);
// log C1(h) (0 above the surface), and the height with log C1 = lc (lc = 0: the top, +inf for the
// gaussian). The gaussian's lower tail: C1 underflows below h = -37.5 (a walk never gets there).
double walk_log_C1(WalkHeights law, double h);
double walk_height(WalkHeights law, double lc);

// The walk with anisotropic roughness and heights from `law`: the same uniform() pattern and
// outcome as the isotropic smith_walk_3d.
template <class Uniform, class OnReflection>
Walk3d smith_walk_3d(const Roughness& r, WalkHeights law, const Dir3& i, Uniform&& uniform,
                     OnReflection&& on_reflection, int max_k = 100000) {
  Walk3d w;
  Dir3 d{-i.x, -i.y, -i.z};
  double h = walk_height(law, 0.0);  // above the whole surface
  for (;;) {
    const double next =
        walk_free_path(r.ndf, projected_roughness(r, d), walk_log_C1(law, h), polar_angle(d), uniform());
    if (std::isinf(next)) {
      w.o = d;
      w.left = true;
      return w;
    }
    if (w.k == max_k) return w;
    h = walk_height(law, next);
    ++w.k;
    const Dir3 v{-d.x, -d.y, -d.z};
    const double u0 = uniform(), u1 = uniform();
    const Dir3 m = sample_visible_normal_3d(r, v, u0, u1);
    const double c = std::max(0.0, v.x * m.x + v.y * m.y + v.z * m.z);  // rounding, as above
    on_reflection(c);
    d = {2.0 * c * m.x - v.x, 2.0 * c * m.y - v.y, 2.0 * c * m.z - v.z};
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    d = {d.x / len, d.y / len, d.z / len};
  }
}

template <class Uniform>
Walk3d smith_walk_3d(const Roughness& r, WalkHeights law, const Dir3& i, Uniform&& uniform, int max_k = 100000) {
  return smith_walk_3d(
      r, law, i, uniform, [](double) {}, max_k);
}

// The next-event estimates of the anisotropic walk, as smith_walk_3d_estimates above.
template <class Uniform>
void smith_walk_3d_estimates(const Roughness& r, WalkHeights law, const Dir3& i, const Dir3& o, Uniform&& uniform,
                             double* est, int n) {
  Dir3 d{-i.x, -i.y, -i.z};
  double h = walk_height(law, 0.0);
  for (int k = 1; k <= n; ++k) {
    const double next =
        walk_free_path(r.ndf, projected_roughness(r, d), walk_log_C1(law, h), polar_angle(d), uniform());
    if (std::isinf(next)) return;
    h = walk_height(law, next);
    const Dir3 v{-d.x, -d.y, -d.z};
    est[k - 1] += next_event_estimate(r, v, walk_log_C1(law, h), o);
    const double u0 = uniform(), u1 = uniform();
    const Dir3 m = sample_visible_normal_3d(r, v, u0, u1);
    const double c = std::max(0.0, v.x * m.x + v.y * m.y + v.z * m.z);
    d = {2.0 * c * m.x - v.x, 2.0 * c * m.y - v.y, 2.0 * c * m.z - v.z};
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    d = {d.x / len, d.y / len, d.z / len};
  }
}

}  // namespace vgroove::analytic
