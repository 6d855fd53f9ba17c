#include "vgroove/sim/microsurface_nonsymmetric.h"

#include "vgroove/sim/partner_sampling.h"
#include "vgroove/sim/slope_sampling.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

namespace {

// The steepest tilt that still leaves an opening (as in make_microsurface).
double clamp_tilt(double t) { return std::min(std::nextafter(0.5 * std::numbers::pi, 0.0), t); }

double wrap_two_pi(double phi) {
  const double two_pi = 2.0 * std::numbers::pi;
  phi = std::fmod(phi, two_pi);
  return phi < 0.0 ? phi + two_pi : phi;
}

// A unit-roughness isotropic slope magnitude with the radial law of P22 (sim/microsurface3d.h: tan
// theta = alpha sqrt(u / (1 - u)) for GGX, alpha sqrt(-log(1 - u)) for Beckmann, at alpha = 1).
double unit_slope(NdfKind kind, double u) {
  assert(kind == NdfKind::ggx || kind == NdfKind::beckmann);
  return kind == NdfKind::ggx ? std::sqrt(u / (1.0 - u)) : std::sqrt(-std::log1p(-u));
}

}  // namespace

double alpha_along(double alpha_x, double alpha_y, double phi) {
  const double c = std::cos(phi) / alpha_x, s = std::sin(phi) / alpha_y;
  return 1.0 / std::sqrt(c * c + s * s);
}

NonsymmetricMicrosurface make_nonsymmetric_microsurface(const NonsymmetricSurfaceOptions& opt) {
  assert(opt.alpha_x > 0.0 && opt.isotropic() && opt.grooves > 0);
  assert(opt.partner == Partner::symmetric || theta_r_law_exists(opt.ndf, opt.alpha_x));
  NonsymmetricMicrosurface m;
  m.options = opt;
  const auto n = static_cast<std::size_t>(opt.grooves);
  m.theta_l.reserve(n);
  m.theta_r.reserve(n);
  m.grooves.reserve(n);
  for (int j = 0; j < opt.grooves; ++j) {
    Rng rng(opt.seed, kNonsymGrooveStream, static_cast<std::uint64_t>(j));
    // The facet from the NDF: |theta_m| folds the projected-length law D2 cos onto [0, pi/2).
    const double a = clamp_tilt(std::abs(sample_theta_m(opt.ndf, opt.alpha_x, uniform_open(rng))));
    const double b =
        opt.partner == Partner::symmetric ? a : clamp_tilt(sample_theta_r(opt.ndf, opt.alpha_x, uniform_open(rng)));
    // A fair coin puts the NDF's facet on the left (normal leaning right) or on the right.
    const bool ndf_left = uniform_open(rng) < 0.5;
    const double tl = -(ndf_left ? a : b), tr = ndf_left ? b : a;
    m.theta_l.push_back(tl);
    m.theta_r.push_back(tr);
    m.grooves.push_back(make_nonsymmetric_groove(tl, tr));
  }
  return m;
}

void add_nonsymmetric_groove3d(NonsymmetricMicrosurface3d& m, double theta_l, double theta_r, double phi_a) {
  m.theta_l.push_back(theta_l);
  m.theta_r.push_back(theta_r);
  m.phi_a.push_back(phi_a);
  m.frames.push_back(GrooveFrame3d{std::cos(phi_a), std::sin(phi_a)});
  m.grooves.push_back(make_nonsymmetric_groove(theta_l, theta_r));
}

NonsymmetricMicrosurface3d make_nonsymmetric_microsurface3d(const NonsymmetricSurfaceOptions& opt) {
  assert(opt.alpha_x > 0.0 && opt.alpha_y > 0.0 && opt.grooves > 0);
  assert(opt.ndf != NdfKind::phong || opt.isotropic());
  NonsymmetricMicrosurface3d m;
  m.options = opt;
  const auto n = static_cast<std::size_t>(opt.grooves);
  m.theta_l.reserve(n);
  m.theta_r.reserve(n);
  m.phi_a.reserve(n);
  m.frames.reserve(n);
  m.grooves.reserve(n);
  for (int j = 0; j < opt.grooves; ++j) {
    Rng rng(opt.seed, kNonsymGroove3dStream, static_cast<std::uint64_t>(j));
    double a = 0.0, phi_n = 0.0;  // the NDF's facet: tilt, and its normal's azimuth over the axes
    if (opt.ndf == NdfKind::phong) {
      a = sample_theta_m_3d(opt.ndf, opt.alpha_x, uniform_open(rng));
      phi_n = 2.0 * std::numbers::pi * uniform_open(rng);
    } else {
      // A slope of P22: the unit isotropic slope scaled by the axes; the normal is along -m.
      const double r = unit_slope(opt.ndf, uniform_open(rng));
      const double w = 2.0 * std::numbers::pi * uniform_open(rng);
      const double mx = opt.alpha_x * r * std::cos(w), my = opt.alpha_y * r * std::sin(w);
      a = std::atan(std::hypot(mx, my));
      phi_n = std::atan2(-my, -mx);
    }
    a = clamp_tilt(a);
    double b = a;
    if (opt.partner == Partner::independent) {
      const double alpha = opt.isotropic() ? opt.alpha_x : alpha_along(opt.alpha_x, opt.alpha_y, phi_n);
      assert(theta_r_law_exists(opt.ndf, alpha));
      b = clamp_tilt(sample_theta_r_3d(opt.ndf, alpha, rng));
    }
    // The NDF's facet leans towards a: it is the left facet of the cross-section (a, n).
    add_nonsymmetric_groove3d(m, -a, b, wrap_two_pi(phi_n + opt.axes_azimuth));
  }
  return m;
}

MicrosurfaceTally trace_nonsymmetric_microsurface_chunk(const NonsymmetricMicrosurface& surface,
                                                        const MicrosurfaceTraceOptions& opt, std::int64_t chunk) {
  assert(std::abs(opt.theta_i) < 0.5 * std::numbers::pi && opt.rays >= 0);
  MicrosurfaceTally tally(opt.theta_o_bins, opt.max_k);
  for_each_landing(surface.grooves, opt.theta_i, opt.sampling, opt.rays, opt.seed, chunk,
                   [&](const Groove& groove, const Ray2& ray) { tally.add(trace(groove, ray, opt.trace)); });
  return tally;
}

MicrosurfaceTally trace_nonsymmetric_microsurface(const NonsymmetricMicrosurface& surface,
                                                  const MicrosurfaceTraceOptions& opt) {
  MicrosurfaceTally total(opt.theta_o_bins, opt.max_k);
  const std::int64_t n = chunk_count(opt);
  for (std::int64_t c = 0; c < n; ++c) total.merge(trace_nonsymmetric_microsurface_chunk(surface, opt, c));
  return total;
}

Microsurface3dTally trace_nonsymmetric_microsurface3d_chunk(const NonsymmetricMicrosurface3d& surface,
                                                            const Microsurface3dTraceOptions& opt, std::int64_t chunk) {
  assert(opt.theta_i >= 0.0 && opt.theta_i < 0.5 * std::numbers::pi && opt.rays >= 0);
  Microsurface3dTally tally(opt.theta_bins, opt.phi_bins, opt.max_k);
  const std::int64_t begin = chunk * kRaysPerChunk;
  const std::int64_t end = std::min(opt.rays, begin + kRaysPerChunk);
  if (begin >= end || surface.grooves.empty()) return tally;
  Rng rng(opt.seed, kNonsymRay3dStream, static_cast<std::uint64_t>(chunk));
  // dir(theta_i, pi) with its y written as the exact 0.
  const Vec3 i(-std::sin(opt.theta_i), 0.0, std::cos(opt.theta_i));
  const double g_count = static_cast<double>(surface.grooves.size());
  const int last = static_cast<int>(surface.grooves.size()) - 1;
  for (std::int64_t j = begin; j < end; ++j) {
    // Equal macro areas: the groove uniformly; then the landing point uniformly across it.
    const int g = std::min(last, static_cast<int>(uniform_open(rng) * g_count));
    const double f = uniform_open(rng);
    const auto gi = static_cast<std::size_t>(g);
    tally.add(trace_groove3d(surface.grooves[gi], surface.frames[gi], i, f, opt.trace));
  }
  return tally;
}

Microsurface3dTally trace_nonsymmetric_microsurface3d(const NonsymmetricMicrosurface3d& surface,
                                                      const Microsurface3dTraceOptions& opt) {
  Microsurface3dTally total(opt.theta_bins, opt.phi_bins, opt.max_k);
  const std::int64_t n = chunk_count(opt);
  for (std::int64_t c = 0; c < n; ++c) total.merge(trace_nonsymmetric_microsurface3d_chunk(surface, opt, c));
  return total;
}

}  // namespace vgroove::sim
