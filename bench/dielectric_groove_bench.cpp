// vgroove bench: the dielectric groove tracer (sim/dielectric_groove.h) beside the conductor
// tracer (sim::trace) on the same groove and the same rays, in one run.
//
// One symmetric groove, light from above at theta_i = 20 deg, kRays rays stratified across the
// opening (as bench/tracer_bench.cpp). Per case: the conductor tracer; the dielectric tracer in its
// conductor limit (F = 1: the same paths, so the difference is the dielectric machinery's own
// cost); and the dielectric tracer at eta = 1.5, splitting every path down to weights of 1e-12
// (interactions per ray grow with the paths: a narrow groove splits at every hit) and with random
// branching (one path per ray). Counters: rays/s, and interactions (reflections for the conductor
// tracer) per second. The same four on a procedural surface (GGX, alpha 0.5, 10,000 grooves, light
// from above at 20 deg, for_each_landing's rays): sim::trace in each ray's groove beside
// sim::DielectricSurfaceTracer. The lifted 3D tracer (sim/dielectric_lifted.h) on the same groove
// and rays, split and random: light at 20 deg from the normal, its azimuth from the axis a across
// the groove 0 deg (d.u = 0: the flatland paths, the lift's own cost) or 60 deg (d.u = 0.30).
#include "vgroove/sim/beam.h"
#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/sim/dielectric_lifted.h"
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/sim/groove.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/tracer.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <numbers>

namespace {

using namespace vgroove;

constexpr double kThetaIDeg = 20.0;
constexpr long kRays = 1000;

double deg(double d) { return d * std::numbers::pi / 180.0; }

void report(benchmark::State& state, std::int64_t interactions, std::int64_t rays) {
  state.counters["interactions_per_s"] =
      benchmark::Counter(static_cast<double>(interactions), benchmark::Counter::kIsRate);
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  state.counters["interactions_per_ray"] =
      benchmark::Counter(rays ? static_cast<double>(interactions) / static_cast<double>(rays) : 0.0);
}

void BM_conductor_groove(benchmark::State& state) {
  const sim::Groove g = sim::make_symmetric_groove(deg(static_cast<double>(state.range(0))));
  const sim::Interval open = sim::opening(g);
  const sim::Vec2 dir = sim::beam_direction(deg(kThetaIDeg));
  sim::Rng rng(1, 0, 0);  // unused by stratified placement
  std::int64_t bounces = 0, rays = 0;
  for (auto _ : state) {
    for (long j = 0; j < kRays; ++j) {
      const double x = sim::sample_position(sim::Sampling::stratified, open, j, kRays, rng);
      const sim::TraceResult r = sim::trace(g, sim::beam_ray(g, dir, x));
      benchmark::DoNotOptimize(r);
      bounces += r.bounces;
    }
    rays += kRays;
  }
  report(state, bounces, rays);
}

// mode 0: the conductor limit; 1: eta 1.5, split; 2: eta 1.5, random branching.
void dielectric(benchmark::State& state, int mode) {
  const sim::Groove g = sim::make_symmetric_groove(deg(static_cast<double>(state.range(0))));
  const sim::Interval open = sim::opening(g);
  const sim::Vec2 dir = sim::beam_direction(deg(kThetaIDeg));
  sim::DielectricOptions opt;
  opt.eta = 1.5;
  opt.conductor_limit = mode == 0;
  opt.branching = mode == 2 ? sim::Branching::random : sim::Branching::split;
  const sim::DielectricGrooveTracer tracer(g, opt);
  sim::Rng place(1, 0, 0);
  sim::DielectricResult r;
  std::int64_t interactions = 0, rays = 0;
  for (auto _ : state) {
    for (long j = 0; j < kRays; ++j) {
      const double x = sim::sample_position(sim::Sampling::stratified, open, j, kRays, place);
      sim::Rng rng(1, 0, static_cast<std::uint64_t>(j));
      tracer.trace(sim::beam_ray(g, dir, x), sim::Medium::above, rng, r);
      benchmark::DoNotOptimize(r.left);
      interactions += r.interactions;
    }
    rays += kRays;
  }
  report(state, interactions, rays);
}

// The lifted tracer, light at kThetaIDeg from the normal and azimuth_deg from a, the rays crossing
// the rim plane at the flatland cases' x; split (mode 1) or random branching (mode 2).
void lifted(benchmark::State& state, int mode) {
  const sim::Groove g = sim::make_symmetric_groove(deg(static_cast<double>(state.range(0))));
  const sim::Interval open = sim::opening(g);
  const double az = deg(static_cast<double>(state.range(1)));
  const double th = deg(kThetaIDeg);
  // Travelling down, in the frame a = x, u = y (the flatland light travels along +x: azimuth 0).
  const sim::Vec3 d(std::sin(th) * std::cos(az), std::sin(th) * std::sin(az), -std::cos(th));
  sim::DielectricOptions opt;
  opt.eta = 1.5;
  opt.branching = mode == 2 ? sim::Branching::random : sim::Branching::split;
  const sim::LiftedGrooveTracer tracer(g, sim::GrooveFrame3d{1.0, 0.0}, opt);
  sim::Rng place(1, 0, 0);
  sim::LiftedResult r;
  std::int64_t interactions = 0, rays = 0;
  for (auto _ : state) {
    for (long j = 0; j < kRays; ++j) {
      const double x = sim::sample_position(sim::Sampling::stratified, open, j, kRays, place);
      sim::Rng rng(1, 0, static_cast<std::uint64_t>(j));
      tracer.trace(d, x, sim::Medium::above, rng, r);
      benchmark::DoNotOptimize(r.dirs.data());
      interactions += r.flat.interactions;
    }
    rays += kRays;
  }
  report(state, interactions, rays);
}

void BM_lifted_split(benchmark::State& state) { lifted(state, 1); }
void BM_lifted_random(benchmark::State& state) { lifted(state, 2); }

void BM_dielectric_conductor_limit(benchmark::State& state) { dielectric(state, 0); }
void BM_dielectric_split(benchmark::State& state) { dielectric(state, 1); }
void BM_dielectric_random(benchmark::State& state) { dielectric(state, 2); }

// The surface cases: mode -1 sim::trace per ray (today's reference path), 0 the conductor limit,
// 1 eta 1.5 split, 2 eta 1.5 random branching.
void surface(benchmark::State& state, int mode) {
  sim::MicrosurfaceOptions mo;
  mo.alpha = 0.5;
  mo.grooves = 10000;
  const sim::Microsurface m = sim::make_microsurface(mo);
  sim::DielectricOptions opt;
  opt.eta = 1.5;
  opt.conductor_limit = mode == 0;
  opt.branching = mode == 2 ? sim::Branching::random : sim::Branching::split;
  const sim::DielectricSurfaceTracer tracer(m, opt);
  sim::DielectricResult r;
  std::int64_t interactions = 0, rays = 0;
  std::uint64_t seed = 0;  // a fresh beam every iteration (chunk 0 of kRays rays)
  for (auto _ : state) {
    long j = 0;
    sim::for_each_landing(m.grooves, deg(kThetaIDeg), sim::Sampling::random, kRays, seed++, 0,
                          [&](const sim::Groove& g, const sim::Ray2& ray) {
                            if (mode < 0) {
                              const sim::TraceResult t = sim::trace(g, ray);
                              benchmark::DoNotOptimize(t);
                              interactions += t.bounces;
                              return;
                            }
                            sim::Rng rng(1, 1, static_cast<std::uint64_t>(j++));
                            tracer.trace_from_above(static_cast<int>(&g - m.grooves.data()), ray, rng, r);
                            benchmark::DoNotOptimize(r.left);
                            interactions += r.interactions;
                          });
    rays += kRays;
  }
  report(state, interactions, rays);
}

void BM_conductor_surface(benchmark::State& state) { surface(state, -1); }
void BM_dielectric_surface_conductor_limit(benchmark::State& state) { surface(state, 0); }
void BM_dielectric_surface_split(benchmark::State& state) { surface(state, 1); }
void BM_dielectric_surface_random(benchmark::State& state) { surface(state, 2); }
BENCHMARK(BM_conductor_surface);
BENCHMARK(BM_dielectric_surface_conductor_limit);
BENCHMARK(BM_dielectric_surface_split);
BENCHMARK(BM_dielectric_surface_random);

// Apertures (degrees) from the many-bounce case to the short one.
BENCHMARK(BM_conductor_groove)->Arg(10)->Arg(60)->Arg(150);
BENCHMARK(BM_dielectric_conductor_limit)->Arg(10)->Arg(60)->Arg(150);
BENCHMARK(BM_dielectric_split)->Arg(10)->Arg(60)->Arg(150);
BENCHMARK(BM_dielectric_random)->Arg(10)->Arg(60)->Arg(150);
// (aperture, azimuth from a) in degrees.
BENCHMARK(BM_lifted_split)->ArgsProduct({{10, 60, 150}, {0, 60}});
BENCHMARK(BM_lifted_random)->ArgsProduct({{10, 60, 150}, {0, 60}});

}  // namespace
