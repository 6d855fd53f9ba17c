#include "vgroove/sim/dielectric_lifted.h"

#include "vgroove/sim/beam.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace vgroove::sim {

namespace {

const char* polarization_name(Polarization p) {
  switch (p) {
    case Polarization::s:
      return "s";
    case Polarization::p:
      return "p";
    case Polarization::unpolarized:
      break;
  }
  return "unpolarized";
}

const DielectricOptions& checked(const DielectricOptions& opt) {
  if (opt.polarization != Polarization::unpolarized)
    throw std::invalid_argument(std::string("polarization = ") + polarization_name(opt.polarization) +
                                " is out of range {unpolarized} in 3D (the plane of incidence turns from hit to hit)");
  return opt;
}

void check_direction(const Vec3& d, Medium from) {
  const double dz = d.z();
  if (from == Medium::above ? !(dz < 0.0 && dz >= -1.0) : !(dz > 0.0 && dz <= 1.0)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", dz);
    throw std::invalid_argument(
        std::string("d.z = ") + buf + " is out of range " +
        (from == Medium::above ? "[-1, 0) for light from above" : "(0, 1] for light from below"));
  }
}

// The cross-section length of a unit direction whose axis component is q; 0 when |q| >= 1.
double length_of(double q) {
  const double r2 = (1.0 - q) * (1.0 + q);
  return r2 > 0.0 ? std::sqrt(r2) : 0.0;
}

void lift_exits(const LiftedRay& ray, const GrooveFrame3d& frame, LiftedResult& out) {
  out.dirs.clear();
  out.dirs.reserve(out.flat.exits.size());
  for (const DielectricExit& e : out.flat.exits) out.dirs.push_back(lift_exit(ray, frame, e.dir, e.side));
}

}  // namespace

LiftedRay lift_ray(const Vec3& d, const GrooveFrame3d& frame, Medium from, const DielectricOptions& opt) {
  // As trace_groove3d (there for i = -d): the components along a and u, and r from (d.a, d.n).
  const double da = d.x() * frame.cos_phi_a + d.y() * frame.sin_phi_a;
  const double du = -d.x() * frame.sin_phi_a + d.y() * frame.cos_phi_a;
  const double dn = d.z();
  const double r = std::sqrt(da * da + dn * dn);
  LiftedRay out;
  out.e = Vec2(da / r, dn / r);
  const int j = static_cast<int>(from), k = 1 - j;
  // n_j q_j = n_k q_k (n1 = 1, n2 = eta).
  const double qk = from == Medium::above ? du / opt.eta : du * opt.eta;
  out.q[j] = du;
  out.q[k] = qk;
  out.law.eta = opt.eta;
  out.law.inv_eta = 1.0 / opt.eta;
  out.law.r[j] = r;
  out.law.r[k] = length_of(qk);
  out.law.conductor_limit = opt.conductor_limit;
  return out;
}

Vec3 lift_exit(const LiftedRay& ray, const GrooveFrame3d& frame, const Vec2& e, Medium side) {
  // r (e_x a + e_y n) + q u, written as trace_groove3d writes o (with q = -i.u there).
  const int s = static_cast<int>(side);
  const double r = ray.law.r[s], q = ray.q[s];
  const double oa = r * e.x();
  return Vec3(oa * frame.cos_phi_a - q * frame.sin_phi_a, oa * frame.sin_phi_a + q * frame.cos_phi_a, r * e.y());
}

LiftedGrooveTracer::LiftedGrooveTracer(const Groove& g, const GrooveFrame3d& frame, const DielectricOptions& opt)
    : flat_(g, checked(opt)), frame_(frame) {}

LiftedResult& LiftedGrooveTracer::trace(const Vec3& d, double x, Medium from, Rng& rng, LiftedResult& out) const {
  check_direction(d, from);
  const LiftedRay ray = lift_ray(d, frame_, from, flat_.options());
  flat_.trace_with(beam_ray(flat_.groove(), ray.e, x), from, ray.law, rng, out.flat);
  lift_exits(ray, frame_, out);
  return out;
}

LiftedSurfaceTracer::LiftedSurfaceTracer(const Microsurface& surface, const GrooveFrame3d& frame,
                                         const DielectricOptions& opt)
    : surface_(surface), flat_(surface, checked(opt)), frame_(frame) {}

LiftedResult& LiftedSurfaceTracer::trace_from_above(int groove, double x, const Vec3& d, Rng& rng,
                                                    LiftedResult& out) const {
  check_direction(d, Medium::above);
  const LiftedRay ray = lift_ray(d, frame_, Medium::above, flat_.options());
  // The ray in groove `groove`'s own frame, crossing its rim line at x.
  const Groove& g = surface_.grooves.at(static_cast<std::size_t>(groove));
  flat_.trace_from_above_with(groove, beam_ray(g, ray.e, x), ray.law, rng, out.flat);
  lift_exits(ray, frame_, out);
  return out;
}

LiftedResult& LiftedSurfaceTracer::trace_from_below(double x, const Vec3& d, Rng& rng, LiftedResult& out) const {
  check_direction(d, Medium::below);
  const LiftedRay ray = lift_ray(d, frame_, Medium::below, flat_.options());
  flat_.trace_from_below_with(x, ray.e, ray.law, rng, out.flat);
  lift_exits(ray, frame_, out);
  return out;
}

}  // namespace vgroove::sim
