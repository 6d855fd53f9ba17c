// vgroove bench: the polyline tracer (sim/polyline_tracer.h) against the groove tracer
// (sim/tracer.h) on the same V-groove surface, in rays and bounces per second on one core.
//
// The surface: the procedural flatland microsurface of sim/microsurface.h, 20,000 grooves drawn
// from GGX of roughness alpha (Arg 0: alpha x 100), and the same grooves as one periodic polyline
// (sim::vgroove_polyline). The rays: 2^15 landing points per iteration from theta_i (Arg 1, deg),
// the same for both tracers (sim/profile_tally.h's landing points are the microsurface's, scaled
// by 2); each tracer gives every ray the same bounce count (tests/sim/profile_tally_test.cpp).
//   BM_groove_tracer:   per ray, find the groove under the landing point and sim::trace in it.
//   BM_polyline_tracer: per ray, sim::trace_polyline from the top line over the whole polyline.
//   BM_polyline_random: the polyline tracer on a Gaussian random profile (sim/random_profile.h,
//                       2^16 segments, Beckmann of the same alpha), for scale.
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

constexpr int kGrooves = 20000;
constexpr int kRays = 1 << 15;

double deg(double d) { return d * std::numbers::pi / 180.0; }

struct Setup {
  sim::Microsurface m;
  sim::Polyline p;
  std::vector<double> u;  // landing fractions in (0, 1)
  sim::Vec2 dir;
  explicit Setup(const benchmark::State& state) {
    sim::MicrosurfaceOptions mo;
    mo.ndf = NdfKind::ggx, mo.alpha = static_cast<double>(state.range(0)) / 100.0, mo.grooves = kGrooves, mo.seed = 1;
    m = sim::make_microsurface(mo);
    p = sim::vgroove_polyline(m.theta_m);
    sim::Rng rng(2, sim::kRayStream, 0);
    for (int j = 0; j < kRays; ++j) u.push_back(sim::uniform_open(rng));
    dir = sim::beam_direction(deg(static_cast<double>(state.range(1))));
  }
};

void report(benchmark::State& state, std::int64_t bounces, std::int64_t rays) {
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["bounces_per_s"] = benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
  state.counters["bounces_per_ray"] = benchmark::Counter(static_cast<double>(bounces) / static_cast<double>(rays));
}

void BM_groove_tracer(benchmark::State& state) {
  const Setup s(state);
  std::int64_t bounces = 0, rays = 0;
  for (auto _ : state) {
    for (double u : s.u) {
      const double x = u * kGrooves;
      const int g = std::min(kGrooves - 1, static_cast<int>(x));
      const sim::Groove& groove = s.m.grooves[static_cast<std::size_t>(g)];
      const double xl = groove.rim_x(sim::Side::left), xr = groove.rim_x(sim::Side::right);
      const sim::TraceResult r = sim::trace(groove, sim::beam_ray(groove, s.dir, xl + (x - g) * (xr - xl)));
      benchmark::DoNotOptimize(r);
      bounces += r.bounces;
    }
    rays += kRays;
  }
  report(state, bounces, rays);
}

void BM_polyline_tracer(benchmark::State& state) {
  const Setup s(state);
  std::int64_t bounces = 0, rays = 0;
  for (auto _ : state) {
    for (double u : s.u) {
      const sim::PolylineTraceResult r = sim::trace_polyline(s.p, sim::landing_x(s.p, u), s.dir);
      benchmark::DoNotOptimize(r);
      bounces += r.bounces;
    }
    rays += kRays;
  }
  report(state, bounces, rays);
}

void BM_polyline_random(benchmark::State& state) {
  sim::RandomProfileOptions o;
  o.ndf = NdfKind::beckmann, o.alpha = static_cast<double>(state.range(0)) / 100.0, o.segments = 1 << 16, o.seed = 1;
  const sim::Polyline p = sim::make_random_profile(o);
  const Setup s(state);
  std::int64_t bounces = 0, rays = 0;
  for (auto _ : state) {
    for (double u : s.u) {
      const sim::PolylineTraceResult r = sim::trace_polyline(p, sim::landing_x(p, u), s.dir);
      benchmark::DoNotOptimize(r);
      bounces += r.bounces;
    }
    rays += kRays;
  }
  report(state, bounces, rays);
}

}  // namespace

BENCHMARK(BM_groove_tracer)->ArgsProduct({{30, 100}, {0, 60, 85}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_polyline_tracer)->ArgsProduct({{30, 100}, {0, 60, 85}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_polyline_random)->ArgsProduct({{30, 100}, {0, 60, 85}})->Unit(benchmark::kMillisecond);
