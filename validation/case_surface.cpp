#include "vgroove/validation/case_surface.h"

#include "vgroove/support/seconds_since.h"

#include <utility>

namespace vgroove::validation {

const char* surface_dim_name(SurfaceDim d) { return d == SurfaceDim::flatland ? "flatland" : "3d"; }

const char* check_surface_name(CheckSurface s) { return s == CheckSurface::heightfield ? "heightfield" : "vgroove"; }

CaseSurface make_case_surface(SurfaceDim dim, NdfKind ndf, double alpha, int grooves, std::uint64_t seed) {
  CaseSurface s;
  s.dim = dim;
  // Flatland and 3D options have the same fields.
  auto options = [&](auto o) {
    o.ndf = ndf, o.alpha = alpha, o.grooves = grooves, o.seed = seed;
    return o;
  };
  if (dim == SurfaceDim::flatland)
    s.flat = sim::make_microsurface(options(sim::MicrosurfaceOptions{}));
  else
    s.three_d = sim::make_microsurface3d(options(sim::Microsurface3dOptions{}));
  return s;
}

BinnedTally trace_case_chunks(const CaseSurface& surface, const CaseRays& r, std::int64_t begin, std::int64_t end,
                              support::CancelFlag cancel) {
  const auto t0 = support::Clock::now();
  BinnedTally out;
  if (surface.dim == SurfaceDim::flatland) {
    sim::MicrosurfaceTraceOptions to;
    to.theta_i = r.theta_i, to.rays = r.rays, to.sampling = sim::Sampling::random, to.seed = r.seed;
    to.theta_o_bins = r.flatland_bins, to.max_k = r.max_k;
    sim::MicrosurfaceTally t(to.theta_o_bins, to.max_k);
    for (std::int64_t c = begin; c < end && !support::cancelled(cancel); ++c)
      sim::trace_microsurface_chunk(surface.flat, to, c, t);
    static_cast<sim::RayFates&>(out) = t;
    out.by_k = std::move(t.by_k), out.hist = std::move(t.theta_o), out.hist_by_k = std::move(t.theta_o_by_k);
  } else {
    sim::Microsurface3dTraceOptions to;
    to.theta_i = r.theta_i, to.rays = r.rays, to.seed = r.seed;
    to.theta_bins = r.theta_bins, to.phi_bins = r.phi_bins, to.max_k = r.max_k;
    sim::Microsurface3dTally t(to.theta_bins, to.phi_bins, to.max_k);
    for (std::int64_t c = begin; c < end && !support::cancelled(cancel); ++c)
      sim::trace_microsurface3d_chunk(surface.three_d, to, c, t);
    static_cast<sim::RayFates&>(out) = t;
    out.by_k = std::move(t.by_k), out.hist = std::move(t.hist), out.hist_by_k = std::move(t.hist_by_k);
  }
  out.thread_s = support::seconds_since(t0);
  return out;
}

}  // namespace vgroove::validation
