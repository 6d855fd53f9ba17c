#include "vgroove/validation/heightfield_lobe.h"

#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::validation {

const char* heightfield_surface_name(HeightfieldSurfaceKind k) {
  return k == HeightfieldSurfaceKind::grooves ? "grooves" : "gaussian";
}

sim::GrooveFieldOptions groove_field_options(const HeightfieldFieldSpec& spec, std::uint64_t seed) {
  sim::GrooveFieldOptions g;
  g.n = spec.field_size, g.ndf = spec.ndf, g.alpha = spec.alpha;
  g.groove_length = 3.0 * spec.correlation_length, g.groove_spacing = 3.0 * spec.correlation_length;
  g.seed_step = 0.5 * spec.correlation_length, g.seed = seed;
  return g;
}

sim::HeightfieldSurface make_field_surface(const HeightfieldFieldSpec& spec, std::uint64_t seed) {
  if (spec.surface == HeightfieldSurfaceKind::grooves)
    return sim::make_heightfield_surface(sim::make_random_groove_field(groove_field_options(spec, seed)));
  sim::GaussianHeightfieldOptions o;
  o.n = spec.field_size, o.alpha_x = spec.alpha, o.alpha_y = spec.alpha * spec.aspect;
  o.correlation_length = spec.correlation_length, o.seed = seed;
  return sim::make_heightfield_surface(spec.ndf == NdfKind::ggx ? sim::make_ggx_heightfield(o)
                                                                : sim::make_gaussian_heightfield(o));
}

void check_field_fits(int field_size, double workers, const std::string& what, int min_size) {
  const double w = std::max(1.0, workers);
  const double budget = support::memory_limit_bytes() / w;
  const double need = sim::heightfield_bytes(field_size);
  if (need <= budget) return;
  const int max_n = sim::heightfield_max_n(budget);
  const auto n_workers = static_cast<long long>(w);
  throw support::UserError(what + " = " + std::to_string(field_size) + " needs " + support::bytes_text(need) +
                           " with its hierarchy, more than the " + support::bytes_text(budget) + " " +
                           (n_workers == 1 ? std::string("this process may use")
                                           : "each of " + std::to_string(n_workers) + " workers may use") +
                           ": " +
                           (max_n < min_size ? std::string("no field fits")
                                             : "it must be a power of two in [" + std::to_string(min_size) + ", " +
                                                   std::to_string(max_n) + "]"));
}

double heightfield_patches(int field_size, double correlation_length, int fields) {
  const double n = field_size;
  return fields * n * n / (std::numbers::pi * correlation_length * correlation_length);
}

sim::HeightfieldTally trace_field(const sim::HeightfieldSurface& s, double theta_i, long rays, std::uint64_t seed,
                                  int theta_bins, int phi_bins, int max_k, const std::atomic<bool>* cancel) {
  sim::HeightfieldTraceOptions o;
  o.theta_i = theta_i, o.phi_i = std::numbers::pi, o.rays = rays, o.seed = seed;
  o.theta_bins = theta_bins, o.phi_bins = phi_bins, o.max_k = max_k;
  sim::HeightfieldTally t(theta_bins, phi_bins, max_k, o.phi_i);
  for (std::int64_t c = 0; c < sim::heightfield_chunk_count(o); ++c) {
    if (support::cancelled(cancel)) break;
    t.merge(sim::trace_heightfield_chunk(s, o, c));
  }
  return t;
}

namespace {

// `paths` walks from dir3(theta_i, pi) in chunks of sim::kHeightfieldRaysPerChunk, chunk c from
// Rng(seed, kHeightfieldRayStream, c), binned by the tracer's own rule; walk(wi, uniform) walks once.
template <class Walk>
sim::HeightfieldTally walk_lobe_with(Walk&& walk, double theta_i, long paths, std::uint64_t seed, int theta_bins,
                                     int phi_bins, int max_k, const std::atomic<bool>* cancel) {
  sim::HeightfieldTally t(theta_bins, phi_bins, max_k, std::numbers::pi);
  const analytic::Dir3 wi = analytic::dir3(theta_i, std::numbers::pi);
  const std::int64_t chunk_size = sim::kHeightfieldRaysPerChunk;
  for (std::int64_t c = 0; c * chunk_size < paths; ++c) {
    if (support::cancelled(cancel)) break;
    sim::Rng rng(seed, sim::kHeightfieldRayStream, static_cast<std::uint64_t>(c));
    auto uniform = [&rng] { return sim::uniform_open(rng); };
    const std::int64_t end = std::min<std::int64_t>(paths, (c + 1) * chunk_size);
    for (std::int64_t p = c * chunk_size; p < end; ++p) {
      const analytic::Walk3d w = walk(wi, uniform);
      sim::HeightfieldRayResult r;
      r.how = w.left ? sim::HeightfieldFate::escaped : sim::HeightfieldFate::bounce_limit;
      r.bounces = w.k;
      r.o = Eigen::Vector3d(w.o.x, w.o.y, w.o.z);
      t.add(r);
    }
  }
  return t;
}

}  // namespace

sim::HeightfieldTally walk_lobe(NdfKind ndf, double alpha, double theta_i, long paths, std::uint64_t seed,
                                int theta_bins, int phi_bins, int max_k, const std::atomic<bool>* cancel) {
  return walk_lobe_with(
      [&](const analytic::Dir3& wi, auto& uniform) { return analytic::smith_walk_3d(ndf, alpha, wi, uniform); },
      theta_i, paths, seed, theta_bins, phi_bins, max_k, cancel);
}

sim::HeightfieldTally walk_lobe(const analytic::Roughness& r, double theta_i, long paths, std::uint64_t seed,
                                int theta_bins, int phi_bins, int max_k, const std::atomic<bool>* cancel) {
  return walk_lobe(r, analytic::WalkHeights::log_c1, theta_i, paths, seed, theta_bins, phi_bins, max_k, cancel);
}

sim::HeightfieldTally walk_lobe(const analytic::Roughness& r, analytic::WalkHeights heights, double theta_i, long paths,
                                std::uint64_t seed, int theta_bins, int phi_bins, int max_k,
                                const std::atomic<bool>* cancel) {
  return walk_lobe_with(
      [&](const analytic::Dir3& wi, auto& uniform) { return analytic::smith_walk_3d(r, heights, wi, uniform); },
      theta_i, paths, seed, theta_bins, phi_bins, max_k, cancel);
}

std::vector<double> joint_fractions(const sim::HeightfieldTally& t, int first_row) {
  const std::size_t bins = static_cast<std::size_t>(t.theta_bins) * static_cast<std::size_t>(t.phi_bins);
  const std::size_t begin = static_cast<std::size_t>(first_row) * bins;
  std::vector<double> out;
  out.reserve(t.hist_by_k.size() - begin);
  const double n = static_cast<double>(t.rays);
  for (std::size_t q = begin; q < t.hist_by_k.size(); ++q)
    out.push_back(n > 0.0 ? static_cast<double>(t.hist_by_k[q]) / n : 0.0);
  return out;
}

}  // namespace vgroove::validation
