// vgroove analytic: deterministic integrals of a function of the exit direction over the upper
// hemisphere (3D) or the half circle (flatland), for BRDF lobes that peak at the mirror direction:
// the white furnace of the pointwise BRDF and the normalization of the samplers' densities. The
// integrand is any callable of the direction: nothing here knows the V-groove.
//
// 3D: polar coordinates (theta', phi') about a pole p (the mirror direction of i), so that dw =
// sin(theta') d theta' d phi' cancels the 1/sin(theta_h) ~ 2/theta' of Eq. (14)'s k >= 2 terms at
// the pole; theta' runs from 0 to the horizon, theta'_max(phi') = atan2(p_z, p_xy cos phi'), and
// is cut where the direction crosses the cone theta_o = theta_p (where narrow grooves send their
// light, kaleidoscope_solutions.h) and at theta' = scale 2^j (the lobe's width). Nested adaptive
// Gauss-Kronrod (quadrature.h), inner tolerance tol / (8 pi).
// Flatland: theta_o over (-pi/2, pi/2), cut at +-theta_i and graded about both.
#pragma once

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/quadrature.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

struct HemisphereOptions {
  double tol = 1e-8;             // absolute, on the whole integral
  double scale = 0.1;            // the lobe's angular width (e.g. alpha): where the grading is centred
  bool mirror_symmetric = true;  // f(o) = f(o mirrored about the plane of p and n): half the work
  int max_pieces = 400;          // per one-dimensional integral
};

// The pole's frame: p, e1 in the plane (p, n) pointing away from n, e2 = horizontal.
struct PolarFrame {
  Dir3 p, e1, e2;
};
inline PolarFrame polar_frame(const Dir3& p) {
  const double st = std::hypot(p.x, p.y);
  const double cp = st > 0.0 ? p.x / st : 1.0, sp = st > 0.0 ? p.y / st : 0.0;
  return {p, {p.z * cp, p.z * sp, -st}, {-sp, cp, 0.0}};
}
inline Dir3 polar_dir(const PolarFrame& f, double tp, double pp) {
  const double st = std::sin(tp), ct = std::cos(tp), sp = std::sin(pp), cp = std::cos(pp);
  return {ct * f.p.x + st * (cp * f.e1.x + sp * f.e2.x), ct * f.p.y + st * (cp * f.e1.y + sp * f.e2.y),
          ct * f.p.z + st * (cp * f.e1.z)};
}

template <class F>
AdaptiveResult integrate_hemisphere(const Dir3& pole, F&& f, const HemisphereOptions& opt = {}) {
  const PolarFrame frame = polar_frame(pole);
  const double sin_p = std::hypot(pole.x, pole.y), cos_p = pole.z;
  const double phi_max = opt.mirror_symmetric ? std::numbers::pi : 2.0 * std::numbers::pi;
  AdaptiveOptions inner;
  inner.abs_tol = opt.tol / (8.0 * std::numbers::pi);
  inner.max_pieces = opt.max_pieces;
  long evaluations = 0;
  bool converged = true;
  auto along = [&](double pp) {
    const double t_max = std::atan2(cos_p, sin_p * std::cos(pp));
    std::vector<double> cuts{0.0, t_max};
    const double cone = 2.0 * std::atan2(-sin_p * std::cos(pp), cos_p);  // theta_o = theta_p
    if (cone > 0.0 && cone < t_max) cuts.push_back(cone);
    for (int j = -10; j <= 6; ++j) {
      const double t = opt.scale * std::ldexp(1.0, j);
      if (t < t_max) cuts.push_back(t);
    }
    std::sort(cuts.begin(), cuts.end());
    const AdaptiveResult r =
        integrate_adaptive([&](double tp) { return f(polar_dir(frame, tp, pp)) * std::sin(tp); }, cuts, inner);
    evaluations += r.evaluations;
    converged = converged && r.converged;
    return r.value;
  };
  std::vector<double> outer_cuts;
  for (int j = 0; j <= 8; ++j) outer_cuts.push_back(phi_max * j / 8.0);
  AdaptiveOptions outer;
  outer.abs_tol = opt.mirror_symmetric ? 0.5 * opt.tol : opt.tol;
  outer.max_pieces = opt.max_pieces;
  AdaptiveResult r = integrate_adaptive(along, outer_cuts, outer);
  if (opt.mirror_symmetric) r.value *= 2.0, r.error *= 2.0;
  r.evaluations = evaluations;
  r.converged = r.converged && converged;
  return r;
}

// int f(theta_o) d theta_o over (-pi/2, pi/2), cut at -theta_i (mirror) and +theta_i (back) and
// graded about both by scale 2^j.
template <class F>
AdaptiveResult integrate_half_circle(double theta_i, F&& f, double scale, double tol, int max_pieces = 2000) {
  const double h = 0.5 * std::numbers::pi;
  std::vector<double> cuts{-h, h};
  for (double c : {-theta_i, theta_i}) {
    cuts.push_back(c);
    for (int j = -10; j <= 6; ++j)
      for (double s : {-1.0, 1.0}) {
        const double t = c + s * scale * std::ldexp(1.0, j);
        if (t > -h && t < h) cuts.push_back(t);
      }
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  AdaptiveOptions o;
  o.abs_tol = tol;
  o.max_pieces = max_pieces;
  return integrate_adaptive(f, cuts, o);
}

}  // namespace vgroove::analytic
