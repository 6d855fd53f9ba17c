#include "vgroove/validation/traced_lobe.h"

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/histogram_metrics.h"

#include <chrono>

namespace vgroove::validation {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

std::vector<TracedLobe> trace_lobes(const LobeSetup& s, const std::vector<double>& theta_i, int threads,
                                    const std::atomic<bool>* cancel) {
  const bool flat = s.dim == SurfaceDim::flatland;
  sim::Microsurface flat_surface;
  sim::Microsurface3d surface3d;
  if (flat) {
    sim::MicrosurfaceOptions so;
    so.ndf = s.ndf, so.alpha = s.alpha, so.grooves = s.grooves, so.seed = s.seed;
    flat_surface = sim::make_microsurface(so);
  } else {
    sim::Microsurface3dOptions so;
    so.ndf = s.ndf, so.alpha = s.alpha, so.grooves = s.grooves, so.seed = s.seed;
    surface3d = sim::make_microsurface3d(so);
  }
  const std::int64_t chunks = (static_cast<std::int64_t>(s.rays) + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
  const std::size_t items = theta_i.size() * static_cast<std::size_t>(chunks);
  std::vector<std::vector<std::int64_t>> hist(items);
  std::vector<std::int64_t> rays(items, 0);
  std::vector<double> secs(items, 0.0);
  const bool complete = support::parallel_for(
      items, support::resolve_threads(threads),
      [&](std::size_t item) {
        const auto t0 = Clock::now();
        const std::size_t c = item / static_cast<std::size_t>(chunks);
        const std::int64_t chunk = static_cast<std::int64_t>(item % static_cast<std::size_t>(chunks));
        if (flat) {
          sim::MicrosurfaceTraceOptions to;
          to.theta_i = theta_i[c], to.rays = s.rays, to.seed = s.seed, to.theta_o_bins = s.flatland_bins;
          to.max_k = 0;
          sim::MicrosurfaceTally t = sim::trace_microsurface_chunk(flat_surface, to, chunk);
          hist[item] = std::move(t.theta_o), rays[item] = t.rays;
        } else {
          sim::Microsurface3dTraceOptions to;
          to.theta_i = theta_i[c], to.rays = s.rays, to.seed = s.seed;
          to.theta_bins = s.theta_bins, to.phi_bins = s.phi_bins, to.max_k = 0;
          sim::Microsurface3dTally t = sim::trace_microsurface3d_chunk(surface3d, to, chunk);
          hist[item] = std::move(t.hist), rays[item] = t.rays;
        }
        secs[item] = seconds_since(t0);
      },
      {}, cancel, 1);
  if (!complete) return {};
  std::vector<TracedLobe> out(theta_i.size());
  for (std::size_t c = 0; c < theta_i.size(); ++c) {
    std::vector<std::int64_t> sum(static_cast<std::size_t>(s.bins()), 0);
    for (std::int64_t k = 0; k < chunks; ++k) {
      const std::size_t item = c * static_cast<std::size_t>(chunks) + static_cast<std::size_t>(k);
      for (std::size_t n = 0; n < sum.size(); ++n) sum[n] += hist[item][n];
      out[c].rays += rays[item];
      out[c].thread_s += secs[item];
    }
    out[c].flux = fractions(sum, static_cast<double>(out[c].rays));
  }
  return out;
}

}  // namespace vgroove::validation
