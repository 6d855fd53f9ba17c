#include "vgroove/sim/dielectric_vgroove_surface.h"

#include "vgroove/sim/microsurface3d.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

Microsurface make_dielectric_vgroove_surface(const MicrosurfaceOptions& o, bool three_d) {
  if (!three_d) return make_microsurface(o);
  Microsurface m;
  m.options = o;
  const double steepest = std::nextafter(0.5 * std::numbers::pi, 0.0);
  for (int j = 0; j < o.grooves; ++j) {
    Rng rng(o.seed, kGrooveStream, static_cast<std::uint64_t>(j));
    const double t = std::min(steepest, sample_theta_m_3d(o.ndf, o.alpha, uniform_open(rng)));
    m.theta_m.push_back(t);
    m.grooves.push_back(make_symmetric_groove(std::numbers::pi - 2.0 * t));
    m.data.push_back(symmetric_groove_data(m.grooves.back()));
  }
  return m;
}

DielectricVgrooveRay trace_dielectric_vgroove_ray(const DielectricSurfaceTracer& tracer, const Microsurface& surface,
                                                  bool three_d, Medium from, const Vec2& flat_dir, const Vec3& dir3,
                                                  const DielectricOptions& opt, Rng& rng, DielectricResult& r) {
  const int last = static_cast<int>(surface.grooves.size()) - 1;
  const double x = uniform_open(rng) * static_cast<double>(surface.grooves.size());
  const int gi = std::min(last, static_cast<int>(x));
  const Groove& groove = surface.grooves[static_cast<std::size_t>(gi)];
  const double xl = groove.rim_x(Side::left), xr = groove.rim_x(Side::right);
  const double x_open = xl + (x - gi) * (xr - xl);
  const bool above = from == Medium::above;
  if (!three_d) {
    if (above)
      tracer.trace_from_above(gi, beam_ray(groove, flat_dir, x_open), rng, r);
    else
      tracer.trace_from_below(x, flat_dir, rng, r);
    return {};
  }
  const double phi_a = std::numbers::pi * rng.uniform();
  DielectricVgrooveRay out;
  out.frame = GrooveFrame3d{std::cos(phi_a), std::sin(phi_a)};
  out.ray = lift_ray(dir3, out.frame, from, opt);
  if (above)
    tracer.trace_from_above_with(gi, beam_ray(groove, out.ray.e, x_open), out.ray.law, rng, r);
  else
    tracer.trace_from_below_with(x, out.ray.e, out.ray.law, rng, r);
  return out;
}

}  // namespace vgroove::sim
