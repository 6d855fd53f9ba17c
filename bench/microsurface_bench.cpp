// vgroove bench: procedural microsurface throughput, in rays per second on one core.
//
// The flatland surface (sim::trace_microsurface: one groove per ray, 2D exit angle binned) and the
// 3D one (sim::trace_microsurface3d: groove and landing point drawn, the cross-section traced with
// the same 2D tracer, the exit lifted to 3D and binned in (theta_o, phi_o)), GGX alpha 0.3 and
// 1.0, theta_i 0 and 60 deg, 10^4 grooves (the surface is built once, outside the timing). One
// iteration traces one chunk of kRaysPerChunk rays with default bins (90; 90 x 72 in 3D). Rougher
// surfaces have deeper grooves: bounces_per_ray says how much of the time is the reflection loop.
// BM_microsurface_*: the batch trace (sim/symmetric_block.h, bins from vectorized arctangent guesses,
// sim/exit_bins.h); *_reference:
// the plain path (sim::trace per ray, atan2/acos bins). Both give the same tallies.
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <numbers>

namespace {

using namespace vgroove;

constexpr int kGrooves = 10000;

double deg(double d) { return d * std::numbers::pi / 180.0; }

void report(benchmark::State& state, std::int64_t rays, std::int64_t bounces) {
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["bounces_per_ray"] =
      benchmark::Counter(rays ? static_cast<double>(bounces) / static_cast<double>(rays) : 0.0);
}

// One chunk of rays per iteration on a surface built once. Arguments: alpha in hundredths,
// theta_i in degrees.
template <class Options, class Make, class Trace>
void run(benchmark::State& state, Make make, Trace trace) {
  const double alpha = static_cast<double>(state.range(0)) / 100.0;
  const auto m = make({sim::NdfKind::ggx, alpha, kGrooves, 1});
  Options opt;
  opt.theta_i = deg(static_cast<double>(state.range(1)));
  opt.rays = sim::kRaysPerChunk;
  std::int64_t rays = 0, bounces = 0;
  for (auto _ : state) {
    const auto t = trace(m, opt);
    benchmark::DoNotOptimize(t.escaped);
    rays += t.rays;
    bounces += t.bounces;
  }
  report(state, rays, bounces);
}

void BM_microsurface_flatland(benchmark::State& state) {
  run<sim::MicrosurfaceTraceOptions>(state, sim::make_microsurface,
                                     [](const auto& m, const auto& o) { return sim::trace_microsurface(m, o); });
}
BENCHMARK(BM_microsurface_flatland)->ArgsProduct({{30, 100}, {0, 60}})->Unit(benchmark::kMillisecond);

// One ray at a time with sim::trace, bins by atan2 (same tallies).
void BM_microsurface_flatland_reference(benchmark::State& state) {
  run<sim::MicrosurfaceTraceOptions>(state, sim::make_microsurface, [](const auto& m, const auto& o) {
    return sim::trace_microsurface_chunk_reference(m, o, 0);
  });
}
BENCHMARK(BM_microsurface_flatland_reference)->ArgsProduct({{30, 100}, {0, 60}})->Unit(benchmark::kMillisecond);

void BM_microsurface_3d(benchmark::State& state) {
  run<sim::Microsurface3dTraceOptions>(state, sim::make_microsurface3d,
                                       [](const auto& m, const auto& o) { return sim::trace_microsurface3d(m, o); });
}
BENCHMARK(BM_microsurface_3d)->ArgsProduct({{30, 100}, {0, 60}})->Unit(benchmark::kMillisecond);

void BM_microsurface_3d_reference(benchmark::State& state) {
  run<sim::Microsurface3dTraceOptions>(state, sim::make_microsurface3d, [](const auto& m, const auto& o) {
    return sim::trace_microsurface3d_chunk_reference(m, o, 0);
  });
}
BENCHMARK(BM_microsurface_3d_reference)->ArgsProduct({{30, 100}, {0, 60}})->Unit(benchmark::kMillisecond);

}  // namespace
