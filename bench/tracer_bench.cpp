// vgroove bench: exact single-groove tracer throughput, in bounces and rays per second.
//
// One symmetric groove, theta_i = 20 deg, N rays placed stratified across the whole opening
// (sim::opening). At theta_i = 20 deg only the right facet is lit for theta_v < 40 deg, and every
// ray entering the opening escapes after k - 1 or k reflections (Lee et al. 2018, Eq. 4), so
// the bounces per ray go from ~140 at theta_v = 1 deg (the long-aperture, many-bounce case)
// to 1-2 at theta_v = 150 deg (the short case). A long case measures the reflection loop; a
// short one mostly the per-ray set-up (first hit against both facets, result, tally).
//
// Three ways to trace the same rays, with the same results ray by ray: sim::trace per ray
// (BM_trace_groove), sim::BeamTracer per ray (BM_trace_beam), and BeamTracer's batch trace through
// sim::trace_beam (BM_trace_beam_batch: what the validation runs).
#include "vgroove/sim/beam.h"
#include "vgroove/sim/groove.h"
#include "vgroove/sim/tally.h"
#include "vgroove/sim/tracer.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <numbers>

namespace {

using namespace vgroove;

constexpr double kThetaIDeg = 20.0;
constexpr long kRays = 1000;  // per iteration: the suite's rays per lit facet

double deg(double d) { return d * std::numbers::pi / 180.0; }

struct TracerSetup {
  sim::Groove g;
  sim::Interval open;
  sim::Vec2 dir;
  sim::TraceOptions opt;
  explicit TracerSetup(double theta_v_deg)
      : g(sim::make_symmetric_groove(deg(theta_v_deg))),
        open(sim::opening(g)),
        dir(sim::beam_direction(deg(kThetaIDeg))) {}
};

void report(benchmark::State& state, std::int64_t bounces, std::int64_t rays) {
  state.counters["bounces_per_s"] = benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
  // Bounces per escaped ray, for reading the rates: iteration-invariant, so averaged.
  state.counters["bounces_per_ray"] =
      benchmark::Counter(rays ? static_cast<double>(bounces) / static_cast<double>(rays) : 0.0);
}

// The tracer alone: escaped rays' bounces are summed, nothing else is kept.
void BM_trace_groove(benchmark::State& state) {
  const TracerSetup s(static_cast<double>(state.range(0)));
  sim::Rng rng(1, 0, 0);  // unused by stratified placement
  std::int64_t bounces = 0, rays = 0;
  for (auto _ : state) {
    for (long j = 0; j < kRays; ++j) {
      const double x = sim::sample_position(sim::Sampling::stratified, s.open, j, kRays, rng);
      const sim::TraceResult r = sim::trace(s.g, sim::beam_ray(s.g, s.dir, x), s.opt);
      benchmark::DoNotOptimize(r);
      if (r.how == sim::Termination::escaped) bounces += r.bounces;
    }
    rays += kRays;
  }
  report(state, bounces, rays);
}

// The same rays through sim::BeamTracer, which computes the direction-only quantities of the
// beam once: every ray is still traced fully, with the same results bit for bit (bounce count,
// termination, exit direction), and escaped rays' bounces are summed as above.
void BM_trace_beam(benchmark::State& state) {
  const TracerSetup s(static_cast<double>(state.range(0)));
  const sim::BeamTracer beam(s.g, s.dir, s.opt);
  sim::Rng rng(1, 0, 0);  // unused by stratified placement
  std::int64_t bounces = 0, rays = 0;
  for (auto _ : state) {
    for (long j = 0; j < kRays; ++j) {
      const double x = sim::sample_position(sim::Sampling::stratified, s.open, j, kRays, rng);
      const sim::TraceResult r = beam.trace(x);
      benchmark::DoNotOptimize(r);
      if (r.how == sim::Termination::escaped) bounces += r.bounces;
    }
    rays += kRays;
  }
  report(state, bounces, rays);
}

// The same rays through the batch trace of sim::BeamTracer (results identical to trace, ray by
// ray), as the validation runs it: sim::trace_beam places a block of positions, traces them
// together and hands each result over.
void BM_trace_beam_batch(benchmark::State& state) {
  const TracerSetup s(static_cast<double>(state.range(0)));
  const sim::BeamTracer beam(s.g, s.dir, s.opt);
  sim::Rng rng(1, 0, 0);  // unused by stratified placement
  std::int64_t bounces = 0, rays = 0;
  for (auto _ : state) {
    sim::trace_beam(beam, sim::Sampling::stratified, s.open, kRays, rng, [&](long, const sim::TraceResult& r) {
      benchmark::DoNotOptimize(r);
      if (r.how == sim::Termination::escaped) bounces += r.bounces;
    });
    rays += kRays;
  }
  report(state, bounces, rays);
}

// The per-ray cost as the validator pays it (validation/groove_case.cpp): placement, trace and
// sim::Tally::add into a fresh tally per batch of rays.
void BM_trace_groove_tally(benchmark::State& state) {
  const TracerSetup s(static_cast<double>(state.range(0)));
  sim::Rng rng(1, 0, 0);
  std::int64_t bounces = 0, rays = 0;
  for (auto _ : state) {
    sim::Tally tally;
    for (long j = 0; j < kRays; ++j) {
      const double x = sim::sample_position(sim::Sampling::stratified, s.open, j, kRays, rng);
      tally.add(sim::trace(s.g, sim::beam_ray(s.g, s.dir, x), s.opt));
    }
    benchmark::DoNotOptimize(tally);
    bounces += tally.bounces;  // escaped rays only
    rays += tally.rays;
  }
  report(state, bounces, rays);
}

void theta_v_args(benchmark::internal::Benchmark* b) {
  b->ArgName("theta_v_deg");
  for (int theta_v_deg : {1, 5, 30, 90, 150}) b->Arg(theta_v_deg);
}

}  // namespace

BENCHMARK(BM_trace_groove)->Apply(theta_v_args);
BENCHMARK(BM_trace_beam)->Apply(theta_v_args);
BENCHMARK(BM_trace_beam_batch)->Apply(theta_v_args);
BENCHMARK(BM_trace_groove_tally)->Apply(theta_v_args);
