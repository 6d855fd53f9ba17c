// vgroove sim: one hit of a lifted 3D ray on an extruded dielectric interface, in the cross-section
// (sim/dielectric_lifted.h). Every part's normal m is perpendicular to the axis u, so n d.u is the
// same in both media (p = n1 q1 = n2 q2, q = d.u) and a direction is d = r e + q u with e the unit
// cross-section direction and r = sqrt(1 - q^2). At a hit in medium j: the 3D local cosine
// cos_i = r_j |e . m| (not |e . m|), F = fresnel_dielectric(cos_i, eta_rel) and total internal
// reflection decided there; the refracted e is optics::refract's 3D direction projected on the
// cross-section and divided by r_k (k the far medium): e_t = (r_j e / eta_rel + (cos_i / eta_rel -
// cos_t) m) / r_k, which is the 2D Snell law with eta_eff = sqrt(n2^2 - p^2) / sqrt(n1^2 - p^2).
// Reflection is the cross-section's own. Used through the tracers' trace_with (instantiated for
// FlatlandLaw and LiftedLaw). Tests: tests/sim/dielectric_lifted_test.cpp (DielectricLifted.*).
// Derivation: docs/derivations/dielectric_lifting.md.
#pragma once

#include "vgroove/optics/fresnel.h"
#include "vgroove/optics/snell.h"
#include "vgroove/sim/dielectric_groove.h"

#include <algorithm>
#include <cmath>

namespace vgroove::sim::detail {

struct LiftedLaw {
  double eta = 1.5;              // n2 / n1
  double inv_eta = 1.0 / 1.5;    // 1 / eta
  double r[2] = {1.0, 1.0};      // the cross-section length of a unit direction, by Medium; 0: unreachable
  bool conductor_limit = false;  // F = 1 at every hit

  // F, the reflected share at a hit of the cross-section direction e (unit) in medium `in` on a part
  // of unit normal n (towards medium 1); sets t to the refracted cross-section direction when F < 1.
  double operator()(const Vec2& e, const Vec2& n, Medium in, Vec2& t) const {
    if (conductor_limit) return 1.0;
    const int j = static_cast<int>(in);
    const double rj = r[j], rk = r[1 - j];
    const double eta_rel = in == Medium::above ? eta : inv_eta;
    const Vec2 m = in == Medium::above ? n : Vec2(-n);  // the normal on the incident side
    const double cos_i = std::clamp(-rj * e.dot(m), 0.0, 1.0);
    const double cos_t = optics::snell_cos_transmitted(cos_i, eta_rel);
    if (cos_t < 0.0 || !(rk > 0.0)) return 1.0;  // total internal reflection, in 3D terms
    if (eta_rel == 1.0) {
      t = e;  // index matched: no interface
    } else {
      const double inv = 1.0 / eta_rel;
      t = (inv * rj * e + (inv * cos_i - cos_t) * m) / rk;
    }
    return optics::fresnel_dielectric(cos_i, eta_rel);
  }
};

}  // namespace vgroove::sim::detail
