// vgroove analytic: sampling the kaleidoscopic dielectric model (sampling_dielectric.h). One cross-section
// is what kaleidoscope_dielectric_lobe.cpp integrates: its groove slope density, its facet share
// f_a / opening, its lobes' shares, Fresnel and (3D) lifting, here drawn instead of integrated.
#include "vgroove/analytic/sampling_dielectric.h"

#include "vgroove/analytic/dielectric_section.h"
#include "vgroove/analytic/kaleidoscope_dielectric.h"
#include "vgroove/analytic/vndf.h"
#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = 0.5 * std::numbers::pi;

// The drawn chain end in the cross-section: t the 2D exit angle (reflected: exit_angle's; transmitted:
// sim::exit_angle's angle below).
struct Drawn {
  bool ok = false;
  bool reflected = false;
  int k = 0;
  double t = 0.0;
  DielectricSampleFailure failure = DielectricSampleFailure::other;
};

Drawn draw_in_section(const DielectricSection& s, double theta_m, double u_facet, double u_lobe,
                      const DielectricSamplerOptions& opt) {
  Drawn d;
  const double theta_v = kPi - 2.0 * theta_m;
  auto F = [&](double cos2d) {
    if (s.all_tir) return 1.0;
    // Fresnel's angle is the 3D one (dielectric_lifting.md, "The 3D local angle").
    const double c = opt.broken == DielectricSamplerBreak::fresnel_cross_section_angle ? cos2d : s.c3d * cos2d;
    if (opt.reflectance) return opt.reflectance(c);
    const double e = opt.broken == DielectricSamplerBreak::fresnel_eta ? 1.1 * s.eta : s.eta;
    return optics::fresnel_dielectric(c, e);
  };
  const double e_dir = s.all_tir ? 1.0 : s.eta_dir;
  // The entering beam (opening_width) splits between the facets by f_a - f_b (Eq. 6): the widths
  // of it that each facet takes first; the two add to the opening.
  const FacetPrediction gl = G_kaleidoscopic(s.tau, theta_v, FacetSide::left);
  const FacetPrediction gr = G_kaleidoscopic(s.tau, theta_v, FacetSide::right);
  const double wl = gl.lit ? gl.f_a - gl.f_b : 0.0, wr = gr.lit ? gr.f_a - gr.f_b : 0.0;
  if (!(wl + wr > 0.0)) return d;
  FacetSide side = FacetSide::left;
  if (opt.broken == DielectricSamplerBreak::facet_uniform) {
    side = u_facet < 0.5 ? FacetSide::left : FacetSide::right;
    if ((side == FacetSide::left ? wl : wr) <= 0.0) return d;
  } else {
    const double x = u_facet * opening_width(s.tau, theta_v);
    if (x < wl)
      side = FacetSide::left;
    else if (x < wl + wr)
      side = FacetSide::right;
    else
      return d;  // rounding: the widths add to the opening
  }
  const DielectricFacetPrediction p = kaleidoscope_dielectric_with(s.tau, theta_v, e_dir, side, F);
  if (!p.lit) return d;
  if (p.k > opt.k_cap) {
    d.failure = DielectricSampleFailure::unresolved;
    return d;
  }
  // The shares are of f_a; the lit part is 1 - shadow of it.
  double y = u_lobe * (1.0 - p.shadow);
  for (const ReflectedLobe* r : {&p.fewer, &p.more}) {
    if (y < r->share) {
      if (!(std::cos(r->theta_o) > 0.0)) return d;  // below the horizon (not expected)
      d.ok = true, d.reflected = true, d.k = r->n, d.t = r->theta_o;
      d.failure = DielectricSampleFailure::none;
      return d;
    }
    y -= r->share;
  }
  for (const TransmittedLobe& t : p.transmitted) {
    if (y < t.share) {
      if (!(std::cos(t.theta_t) > 0.0)) {
        d.failure = DielectricSampleFailure::upward;  // KD-4: travels back up
        return d;
      }
      d.ok = true, d.reflected = false, d.k = t.j, d.t = t.theta_t;
      d.failure = DielectricSampleFailure::none;
      return d;
    }
    y -= t.share;
  }
  return d;  // rounding: R + T + shadow = 1
}

}  // namespace

DielectricSampleFlatland sample_vgroove_dielectric_flatland(double theta_i, const std::array<double, 4>& u, NdfKind ndf,
                                                            double alpha, double eta,
                                                            const DielectricSamplerOptions& opt) {
  DielectricSampleFlatland r;
  r.failure = DielectricSampleFailure::other;
  if (!(std::abs(theta_i) < kHalfPi && eta > 0.0 && alpha > 0.0)) return r;
  const bool below = opt.from == DielectricLightFrom::below;
  const DielectricSection s = flatland_section(theta_i, below ? 1.0 / eta : eta);
  // The groove slope: density 2 D2 cos over [0, pi/2] (the lobe's), |theta_s| of D2 cos.
  const double theta_m = std::abs(sample_projected_ndf2(ndf, alpha, u[0], u[1]));
  if (!(theta_m < kHalfPi)) return r;
  const Drawn d = draw_in_section(s, theta_m, u[2], u[3], opt);
  r.failure = d.failure;
  if (!d.ok) return r;
  // Light from below: the model at 1 / eta mirrored in the macrosurface, an exit angle t becomes -t.
  r.theta_o = below ? -d.t : d.t;
  r.reflected = d.reflected;
  r.k = d.k;
  r.weight = 1.0;
  return r;
}

DielectricSample3d sample_vgroove_dielectric_3d(double theta_i, const std::array<double, 5>& u, NdfKind ndf,
                                                double alpha, double eta, const DielectricSamplerOptions& opt) {
  DielectricSample3d r;
  r.failure = DielectricSampleFailure::other;
  if (!(theta_i >= 0.0 && theta_i < kHalfPi && eta > 0.0 && alpha > 0.0)) return r;
  const bool below = opt.from == DielectricLightFrom::below;
  const double e = below ? 1.0 / eta : eta;
  // The groove slope: density 2 pi D cos sin (the polar angle of a normal of D (m.n)).
  const Dir3 m = sample_projected_ndf(ndf, alpha, u[0], u[1]);
  const double theta_m = std::atan2(std::hypot(m.x, m.y), m.z);
  if (!(theta_m < kHalfPi)) return r;
  // The groove azimuth uniform over [0, pi); the lobe's lifting (kaleidoscope_dielectric_lobe.cpp).
  const double phi_a = kPi * u[2];
  const double st = std::sin(theta_i), ct = std::cos(theta_i);
  const double ca = std::cos(phi_a), sa = std::sin(phi_a);
  const double i_a = -st * ca, i_u = st * sa;
  const DielectricSection s = lifted_section(i_a, i_u, ct, e);
  const double c = s.c3d, q_1 = -i_u;
  const Drawn d = draw_in_section(s, theta_m, u[3], u[4], opt);
  r.failure = d.failure;
  if (!d.ok) return r;
  // Exits lifted: o = r (e_x a + e_y n) + q u, e = (-sin t, cos t) above, (sin t, -cos t) below.
  if (d.reflected) {
    const double ex = -c * std::sin(d.t);
    r.o = {ex * ca - q_1 * sa, ex * sa + q_1 * ca, c * std::cos(d.t)};
  } else {
    const double q_2 = q_1 / e, r_2 = std::sqrt((1.0 - q_2) * (1.0 + q_2));
    const double ex = r_2 * std::sin(d.t);
    r.o = {ex * ca - q_2 * sa, ex * sa + q_2 * ca, -r_2 * std::cos(d.t)};
  }
  if (below) r.o.z = -r.o.z;  // mirrored in the macrosurface
  r.reflected = d.reflected;
  r.k = d.k;
  r.weight = 1.0;
  return r;
}

}  // namespace vgroove::analytic
