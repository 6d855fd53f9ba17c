// vgroove bench: what a bounce observer costs the tracer (sim/effects.h).
//
// The same rays as tracer_bench.cpp (one symmetric groove, theta_i = 20 deg, 1000 stratified rays
// across the opening), traced with
//   none          sim::NoBounceObserver, the tracer's default: "all effects off";
//   unit          FresnelEnergyObserver<UnitReflectance>: F = 1, empty on_bounce by `if constexpr`;
//   unit_generic  FresnelEnergyObserver of a lambda returning 1.0: the generic path, where the
//                 optimizer must drop |d.n| and the multiply by 1 itself;
//   schlick       Schlick F0 = 0.04: a cosine, a fifth power and a product per bounce;
//   conductor     eta + i kappa = 0.2 + 3i: a complex square root and two |.|^2 ratios per bounce.
// BM_effects/<variant>/<theta_v> reports bounces/s; BM_effects_overhead/<variant>/<theta_v> times
// the variant and the bare tracer alternately on the same rays and reports their ratio
// (time with the observer / time without), so drift of the machine affects both alike.
#include "vgroove/sim/beam.h"
#include "vgroove/sim/effects.h"
#include "vgroove/sim/groove.h"
#include "vgroove/sim/tracer.h"

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <type_traits>

namespace {

using namespace vgroove;

constexpr double kThetaIDeg = 20.0;
constexpr long kRays = 1000;

double deg(double d) { return d * std::numbers::pi / 180.0; }

enum Variant : int { none, unit, unit_generic, schlick, conductor };

struct Setup {
  sim::Groove g;
  sim::Interval open;
  sim::Vec2 dir;
  sim::TraceOptions opt;
  explicit Setup(double theta_v_deg)
      : g(sim::make_symmetric_groove(deg(theta_v_deg))),
        open(sim::opening(g)),
        dir(sim::beam_direction(deg(kThetaIDeg))) {}
};

// Traces the kRays rays once, each with a fresh observer from make_obs(); returns the escaped
// rays' bounces and adds their throughputs to `energy` (so the observer's work cannot be dropped).
template <class Obs, class MakeObs>
std::int64_t trace_all(const Setup& s, MakeObs&& make_obs, double& energy) {
  sim::Rng unused(1, 0, 0);
  std::int64_t bounces = 0;
  for (long j = 0; j < kRays; ++j) {
    const double x = sim::sample_position(sim::Sampling::stratified, s.open, j, kRays, unused);
    Obs obs = make_obs();
    const sim::TraceResult r = sim::trace(s.g, sim::beam_ray(s.g, s.dir, x), s.opt, obs);
    benchmark::DoNotOptimize(r);
    if (r.how == sim::Termination::escaped) {
      bounces += r.bounces;
      if constexpr (!std::is_same_v<Obs, sim::NoBounceObserver>) energy += obs.throughput;
    }
  }
  return bounces;
}

// Calls f(make_obs) with the observer factory of variant v; the observer type is fixed at
// compile time inside each branch (the switch is per batch of rays, never per bounce).
template <class Fn>
void with_variant(int v, Fn&& f) {
  switch (v) {
    case none:
      f([] { return sim::NoBounceObserver{}; });
      break;
    case unit:
      f([] { return sim::FresnelEnergyObserver<sim::UnitReflectance>{}; });
      break;
    case unit_generic: {
      auto one = [](double) { return 1.0; };
      f([one] { return sim::FresnelEnergyObserver<decltype(one)>{one}; });
      break;
    }
    case schlick:
      f([] { return sim::FresnelEnergyObserver{sim::SchlickReflectance{0.04}}; });
      break;
    case conductor:
      f([] { return sim::FresnelEnergyObserver{sim::ConductorReflectance{0.2, 3.0}}; });
      break;
  }
}

void BM_effects(benchmark::State& state) {
  const Setup s(static_cast<double>(state.range(1)));
  std::int64_t bounces = 0, rays = 0;
  double energy = 0.0;
  with_variant(static_cast<int>(state.range(0)), [&](auto make_obs) {
    using Obs = decltype(make_obs());
    for (auto _ : state) {
      bounces += trace_all<Obs>(s, make_obs, energy);
      rays += kRays;
    }
  });
  benchmark::DoNotOptimize(energy);
  state.counters["bounces_per_s"] = benchmark::Counter(static_cast<double>(bounces), benchmark::Counter::kIsRate);
  state.counters["bounces_per_ray"] = benchmark::Counter(static_cast<double>(bounces) / static_cast<double>(rays));
  // Mean energy an escaped ray keeps (1 for none/unit): shows the work was done.
  state.counters["mean_energy"] = benchmark::Counter(energy / static_cast<double>(rays));
}

void BM_effects_overhead(benchmark::State& state) {
  const Setup s(static_cast<double>(state.range(1)));
  using clock = std::chrono::steady_clock;
  double t_bare = 0.0, t_obs = 0.0, energy = 0.0;
  std::int64_t bounces = 0;
  with_variant(static_cast<int>(state.range(0)), [&](auto make_obs) {
    using Obs = decltype(make_obs());
    auto bare = [] { return sim::NoBounceObserver{}; };
    for (auto _ : state) {
      const auto t0 = clock::now();
      bounces += trace_all<sim::NoBounceObserver>(s, bare, energy);
      const auto t1 = clock::now();
      trace_all<Obs>(s, make_obs, energy);
      const auto t2 = clock::now();
      t_bare += std::chrono::duration<double>(t1 - t0).count();
      t_obs += std::chrono::duration<double>(t2 - t1).count();
    }
  });
  benchmark::DoNotOptimize(energy);
  state.counters["ratio"] = benchmark::Counter(t_obs / t_bare);
  state.counters["bare_bounces_per_s"] = benchmark::Counter(static_cast<double>(bounces) / t_bare);
  state.counters["obs_bounces_per_s"] = benchmark::Counter(static_cast<double>(bounces) / t_obs);
}

void args(benchmark::internal::Benchmark* b) {
  b->ArgNames({"variant", "theta_v_deg"});
  for (int v : {none, unit, unit_generic, schlick, conductor})
    for (int theta_v_deg : {1, 30, 150}) b->Args({v, theta_v_deg});
}

}  // namespace

BENCHMARK(BM_effects)->Apply(args);
BENCHMARK(BM_effects_overhead)->Apply(args);
