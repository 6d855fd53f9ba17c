#include "vgroove/validation/traced_lobe.h"

#include "vgroove/support/parallel.h"
#include "vgroove/validation/case_surface.h"
#include "vgroove/validation/histogram_metrics.h"

namespace vgroove::validation {

std::vector<TracedLobe> trace_lobes(const LobeSetup& s, const std::vector<double>& theta_i, int threads,
                                    const std::atomic<bool>* cancel) {
  const CaseSurface surface = make_case_surface(s.dim, s.ndf, s.alpha, s.grooves, s.seed);
  const std::int64_t chunks = (static_cast<std::int64_t>(s.rays) + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
  const std::size_t items = theta_i.size() * static_cast<std::size_t>(chunks);
  std::vector<std::vector<std::int64_t>> hist(items), hist_k1(items);
  std::vector<std::int64_t> rays(items, 0);
  std::vector<double> secs(items, 0.0);
  const bool complete = support::parallel_for(
      items, support::resolve_threads(threads),
      [&](std::size_t item) {
        const std::size_t c = item / static_cast<std::size_t>(chunks);
        const std::int64_t chunk = static_cast<std::int64_t>(item % static_cast<std::size_t>(chunks));
        CaseRays r;
        r.theta_i = theta_i[c], r.rays = s.rays, r.seed = s.seed;
        r.flatland_bins = s.flatland_bins, r.theta_bins = s.theta_bins, r.phi_bins = s.phi_bins;
        r.max_k = s.k1 ? 1 : 0;  // rows k = 0, 1 and more, or the histogram alone
        BinnedTally t = trace_case_chunks(surface, r, chunk, chunk + 1);
        if (s.k1) {
          const auto row = t.hist_by_k.begin() + s.bins();  // row k = 1
          hist_k1[item].assign(row, row + s.bins());
        }
        hist[item] = std::move(t.hist), rays[item] = t.rays, secs[item] = t.thread_s;
      },
      {}, cancel, 1);
  if (!complete) return {};
  std::vector<TracedLobe> out(theta_i.size());
  for (std::size_t c = 0; c < theta_i.size(); ++c) {
    std::vector<std::int64_t> sum(static_cast<std::size_t>(s.bins()), 0), sum_k1(s.k1 ? sum.size() : 0, 0);
    for (std::int64_t k = 0; k < chunks; ++k) {
      const std::size_t item = c * static_cast<std::size_t>(chunks) + static_cast<std::size_t>(k);
      for (std::size_t n = 0; n < sum.size(); ++n) sum[n] += hist[item][n];
      for (std::size_t n = 0; n < sum_k1.size(); ++n) sum_k1[n] += hist_k1[item][n];
      out[c].rays += rays[item];
      out[c].thread_s += secs[item];
    }
    out[c].flux = fractions(sum, static_cast<double>(out[c].rays));
    if (s.k1) out[c].flux_k1 = fractions(sum_k1, static_cast<double>(out[c].rays));
  }
  return out;
}

}  // namespace vgroove::validation
