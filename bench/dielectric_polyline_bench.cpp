// vgroove bench: the dielectric polyline tracer (sim/dielectric_polyline.h) beside the conductor
// polyline tracer (sim/polyline_tracer.h) on the same random profile, in rays and interactions per
// second on one core.
//
// The profile: sim/random_profile.h, 2^16 segments, 16 per correlation length, Beckmann (Arg 2 = 0)
// or GGX (Arg 2 = 1) of roughness alpha (Arg 0: alpha x 100). The rays: 2^14 landing points per
// iteration from theta_i (Arg 1, deg), the same for every tracer.
//   BM_dpoly_conductor:       sim::trace_polyline (the conductor).
//   BM_dpoly_conductor_limit: the dielectric tracer with F = 1 (the same paths, bit for bit).
//   BM_dpoly_above:           the dielectric tracer, eta 1.5, random branching, light from above.
//   BM_dpoly_below:           the same, light from below (the march under the profile first).
#include "vgroove/sim/dielectric_polyline.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/polyline_tracer.h"
#include "vgroove/sim/profile_tally.h"
#include "vgroove/sim/random_profile.h"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <numbers>
#include <vector>

namespace {

using namespace vgroove;

constexpr int kRays = 1 << 14;

double deg(double d) { return d * std::numbers::pi / 180.0; }

struct Setup {
  sim::Polyline p;
  std::vector<double> x;
  double theta;
  explicit Setup(const benchmark::State& state) {
    sim::RandomProfileOptions po;
    po.ndf = state.range(2) == 0 ? NdfKind::beckmann : NdfKind::ggx;
    po.alpha = static_cast<double>(state.range(0)) / 100.0, po.segments = 1 << 16, po.seed = 1;
    p = sim::make_random_profile(po);
    sim::Rng rng(2, sim::kRayStream, 0);
    for (int j = 0; j < kRays; ++j) x.push_back(sim::landing_x(p, sim::uniform_open(rng)));
    theta = deg(static_cast<double>(state.range(1)));
  }
};

void report(benchmark::State& state, std::int64_t interactions, std::int64_t rays) {
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["hits_per_s"] = benchmark::Counter(static_cast<double>(interactions), benchmark::Counter::kIsRate);
  state.counters["hits_per_ray"] = benchmark::Counter(static_cast<double>(interactions) / static_cast<double>(rays));
}

void BM_dpoly_conductor(benchmark::State& state) {
  const Setup s(state);
  const sim::Vec2 dir = sim::beam_direction(s.theta);
  std::int64_t hits = 0, rays = 0;
  for (auto _ : state) {
    for (double x : s.x) {
      const sim::PolylineTraceResult r = sim::trace_polyline(s.p, x, dir);
      benchmark::DoNotOptimize(r);
      hits += r.bounces;
    }
    rays += kRays;
  }
  report(state, hits, rays);
}

void run_dielectric(benchmark::State& state, bool conductor_limit, sim::Medium from) {
  const Setup s(state);
  sim::DielectricOptions opt;
  opt.eta = 1.5, opt.branching = sim::Branching::random, opt.conductor_limit = conductor_limit;
  const sim::DielectricPolylineTracer tr(s.p, opt);
  const sim::Vec2 dir = from == sim::Medium::above ? sim::beam_direction(s.theta) : sim::direction_at(s.theta);
  sim::DielectricResult out;
  std::int64_t hits = 0, rays = 0, it = 0;
  for (auto _ : state) {
    sim::Rng rng(3, 0, static_cast<std::uint64_t>(it++));
    for (double x : s.x) {
      tr.trace(x, dir, from, rng, out);
      benchmark::DoNotOptimize(out.left[0]);
      hits += out.interactions;
    }
    rays += kRays;
  }
  report(state, hits, rays);
}

void BM_dpoly_conductor_limit(benchmark::State& state) { run_dielectric(state, true, sim::Medium::above); }
void BM_dpoly_above(benchmark::State& state) { run_dielectric(state, false, sim::Medium::above); }
void BM_dpoly_below(benchmark::State& state) { run_dielectric(state, false, sim::Medium::below); }

void args(benchmark::internal::Benchmark* b) {
  for (int ndf : {0, 1})
    for (int alpha : {30, 80})
      for (int theta : {0, 45, 75}) b->Args({alpha, theta, ndf});
}

BENCHMARK(BM_dpoly_conductor)->Apply(args);
BENCHMARK(BM_dpoly_conductor_limit)->Apply(args);
BENCHMARK(BM_dpoly_above)->Apply(args);
BENCHMARK(BM_dpoly_below)->Apply(args);

}  // namespace
