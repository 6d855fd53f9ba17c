#include "vgroove/validation/heightfield_albedo.h"

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/albedo_vgroove.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/seconds_since.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

// Streams of the suite's seed: fields, rays, walks (apart from the heightfield suite's).
constexpr std::uint64_t kFieldSeeds = 0x6861666965ULL, kRaySeeds = 0x6861726179ULL, kWalkSeeds = 0x686177616bULL;
// Tracer rows k = 0..2 and one beyond (k >= 3).
constexpr int kMaxK = 2;
// Per field and mu: E, E_1, E_2, E_3+.
constexpr int kStored = 4;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The polar angle of mu, exactly 0 at mu = 1.
double theta_of(double mu) { return std::acos(std::min(1.0, mu)); }

// A stored row (E, E_1, E_2, E_3+) as a reported one (E, E_1, E_ms, E_2, E_3+).
double reported(const double* s, int row) {
  switch (row) {
    case 0:
      return s[0];
    case 1:
      return s[1];
    case 2:
      return s[2] + s[3];  // E_ms: the orders k >= 2 counted, not E - E_1 (no cancellation)
    case 3:
      return s[2];
    default:
      return s[3];
  }
}

}  // namespace

HeightfieldAlbedoOutcome run_heightfield_albedo_item(const HeightfieldAlbedoSuite& suite, std::size_t item, long rays,
                                                     const std::atomic<bool>* cancel) {
  HeightfieldAlbedoOutcome out;
  const NdfKind ndf = suite.ndf_of(item);
  const double alpha = suite.alpha_of(item);
  const std::size_t nm = suite.mus.size();
  const HeightfieldFieldSpec spec{ndf, alpha, suite.field_size, suite.correlation_length, suite.surface, 1.0};
  for (int r = 0; r < suite.fields; ++r) {
    if (support::cancelled(cancel)) return out;
    auto t0 = Clock::now();
    const sim::HeightfieldSurface s = make_field_surface(
        spec, sim::derived_seed(suite.seed, kFieldSeeds, item * 65536 + static_cast<std::uint64_t>(r)));
    out.field_s += seconds_since(t0);
    t0 = Clock::now();
    for (std::size_t m = 0; m < nm; ++m) {
      const std::uint64_t key = (item * 65536 + static_cast<std::uint64_t>(r)) * 4096 + m;
      // One theta bin and two phi bins: counted per k only.
      const sim::HeightfieldTally t = trace_field(s, theta_of(suite.mus[m]), rays,
                                                  sim::derived_seed(suite.seed, kRaySeeds, key), 1, 2, kMaxK, cancel);
      if (support::cancelled(cancel)) return out;
      out.rays += t.rays, out.lost += t.lost, out.bounce_limit += t.bounce_limit;
      out.edge_hits += t.edge_hits, out.vertex_hits += t.vertex_hits;
      const double n = static_cast<double>(t.rays);
      // F = 1: each row's energy is its count (energy_by_k sums 1 per ray).
      out.traced.push_back(static_cast<double>(t.escaped) / n);
      for (int k = 1; k <= kMaxK + 1; ++k) out.traced.push_back(static_cast<double>(t.by_k[k]) / n);
    }
    out.trace_s += seconds_since(t0);
  }
  auto t0 = Clock::now();
  for (std::size_t m = 0; m < nm; ++m) {
    const sim::HeightfieldTally w =
        walk_lobe(ndf, alpha, theta_of(suite.mus[m]), suite.walk_paths,
                  sim::derived_seed(suite.seed, kWalkSeeds, item * 4096 + m), 1, 2, kMaxK, cancel);
    if (support::cancelled(cancel)) return out;
    out.walk_paths = w.rays;
    out.walk_counts.push_back(w.escaped);
    for (int k = 1; k <= kMaxK + 1; ++k) out.walk_counts.push_back(w.by_k[k]);
  }
  out.walk_s = seconds_since(t0);
  t0 = Clock::now();
  const analytic::MicrofacetModel smith{ndf, analytic::MaskingKind::smith_height_correlated};
  for (std::size_t m = 0; m < nm; ++m) {
    if (support::cancelled(cancel)) return out;
    const double mu = suite.mus[m];
    const analytic::BoundedValue e = analytic::albedo_single(smith, alpha, mu);
    out.ess.push_back(e.value);
    out.ess_error.push_back(e.converged ? e.error : kNaN);  // not converged: no bound (NaN fails the item)
    const analytic::VgrooveAlbedo v = analytic::vgroove_albedo(ndf, alpha, mu, 1, {}, kMaxK);
    out.vgroove.push_back(v.total[0]);
    for (int k = 1; k <= kMaxK + 1; ++k) out.vgroove.push_back(v.row(k, 0));
  }
  out.model_s = seconds_since(t0);
  return out;
}

double heightfield_albedo_memory_bytes(const HeightfieldAlbedoSuite& suite, int threads) {
  const double items = static_cast<double>(suite.items());
  const double workers = std::min<double>(support::resolve_threads(threads), items);
  check_field_fits(suite.field_size, workers, suite.file + ": /field_size", 16);
  const double per_item = static_cast<double>(suite.mus.size()) * kStored * 8.0 * (suite.fields + 4.0);
  return workers * sim::heightfield_bytes(suite.field_size) + items * per_item * 2.0;
}

Job<HeightfieldAlbedoWork> heightfield_albedo_job(const HeightfieldAlbedoSuite& suite, long rays,
                                                  nlohmann::json descriptor, const std::atomic<bool>* cancel) {
  const long n_rays = rays > 0 ? rays : suite.rays;
  return item_job<HeightfieldAlbedoOutcome>(
      suite.items(),
      [suite, n_rays, cancel](std::size_t c) { return run_heightfield_albedo_item(suite, c, n_rays, cancel); },
      [suite](support::JsonObject& o, std::size_t, HeightfieldAlbedoOutcome& out) {
        const std::size_t nm = suite.mus.size(), f = static_cast<std::size_t>(suite.fields);
        if (out.traced.size() != f * nm * kStored || out.walk_counts.size() != nm * kStored || out.ess.size() != nm ||
            out.ess_error.size() != nm || out.vgroove.size() != nm * kStored)
          o.fail("outcome", "/traced, /walk_counts, /ess, /ess_error or /vgroove is not of the suite's " +
                                std::to_string(suite.fields) + " fields x " + std::to_string(nm) + " mu x " +
                                std::to_string(kStored) + " rows");
      },
      std::move(descriptor),
      [&suite, n_rays](std::size_t) {
        return static_cast<std::int64_t>(suite.mus.size()) *
               (static_cast<std::int64_t>(n_rays) * suite.fields + suite.walk_paths);
      });
}

HeightfieldAlbedoRun heightfield_albedo_run_from(const HeightfieldAlbedoSuite& suite,
                                                 const std::vector<UnitResult<HeightfieldAlbedoWork>>& results) {
  HeightfieldAlbedoRun run;
  run.pass = true;
  const std::size_t nm = suite.mus.size();
  const double nf = suite.fields;
  for (std::size_t item = 0; item < results.size(); ++item) {
    const HeightfieldAlbedoOutcome& o = results[item].tally;
    run.items.push_back(o);
    bool ok = o.lost == 0 && o.bounce_limit == 0;
    const double rays_per_field = static_cast<double>(o.rays) / (nf * static_cast<double>(nm));
    for (std::size_t m = 0; m < nm; ++m) {
      AlbedoPoint p;
      p.ndf = suite.ndf_of(item), p.alpha = suite.alpha_of(item), p.mu = suite.mus[m];
      for (int row = 0; row < kAlbedoRows; ++row) {
        // Mean over the fields and its standard error: the fields' spread, at least the binomial
        // error of all rays (p the mean; p (1 - p) at least 1 / rays: a row all or none of the
        // rays took still has the error of their count).
        std::vector<double> x;
        for (int r = 0; r < suite.fields; ++r)
          x.push_back(reported(&o.traced[(static_cast<std::size_t>(r) * nm + m) * kStored], row));
        double mean = 0.0, var = 0.0;
        for (double v : x) mean += v;
        mean /= nf;
        for (double v : x) var += (v - mean) * (v - mean);
        const double q = std::clamp(mean, 0.0, 1.0);
        p.traced[row] = mean;
        p.traced_se[row] =
            std::max(suite.fields >= 2 ? std::sqrt(var / (nf - 1.0) / nf) : 0.0,
                     std::sqrt(std::max(q * (1.0 - q), 1.0 / (rays_per_field * nf)) / (rays_per_field * nf)));
        ok = ok && std::isfinite(mean);
      }
      const double paths = static_cast<double>(o.walk_paths);
      double walk[kStored], vg[kStored];
      for (int r = 0; r < kStored; ++r) {
        walk[r] = static_cast<double>(o.walk_counts[m * kStored + static_cast<std::size_t>(r)]) / paths;
        vg[r] = o.vgroove[m * kStored + static_cast<std::size_t>(r)];
      }
      for (int model = 0; model < kAlbedoModels; ++model)
        for (int row = 0; row < kAlbedoRows; ++row) {
          AlbedoComparison& c = p.models[model][row];
          double tol = suite.model_tolerance;
          if (model == 0) {
            c.value = reported(walk, row);
            c.var = std::max(0.0, c.value * (1.0 - c.value)) / paths;  // multinomial
          } else if (model == 1) {
            c.value = row == 1 ? o.ess[m] : kNaN;
            tol += o.ess_error[m];
          } else {
            c.value = reported(vg, row);
          }
          const double sd = std::sqrt(p.traced_se[row] * p.traced_se[row] + c.var);
          c.diff = p.traced[row] - c.value;
          c.threshold = suite.sigmas * sd + tol;
          c.z = sd > 0.0 ? c.diff / sd : (c.diff == 0.0 ? 0.0 : std::copysign(HUGE_VAL, c.diff));
          c.within_noise = std::abs(c.diff) <= c.threshold;  // NaN: never within
          if (!(model == 1 && row != 1)) ok = ok && std::isfinite(c.value) && std::isfinite(c.threshold);
        }
      run.points.push_back(p);
    }
    run.item_pass.push_back(ok);
    run.pass = run.pass && ok;
  }
  return run;
}

HeightfieldAlbedoRun run_heightfield_albedo(const HeightfieldAlbedoSuite& suite, long rays, int threads,
                                            const support::ProgressFn& progress, const std::atomic<bool>* cancel) {
  const auto t0 = Clock::now();
  const auto results = run_job(heightfield_albedo_job(suite, rays, {}, cancel), threads, progress, cancel);
  HeightfieldAlbedoRun run;
  if (results) run = heightfield_albedo_run_from(suite, *results);
  run.threads = support::resolve_threads(threads);
  run.wall_s = seconds_since(t0);
  run.pass = run.pass && results.has_value();
  return run;
}

}  // namespace vgroove::validation
