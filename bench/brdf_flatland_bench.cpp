// vgroove bench: cost of one flatland BRDF evaluation (analytic/brdf_flatland.h, Eq. 17 in flatland,
// GGX alpha 0.5) and of one near the horizon in 3D, each beside the evaluation it replaced, in
// the same run. Arguments: /max_k.
//   - BM_flatland_brdf: the single pass over the solutions Eq. (4) allows (flatland_brdf, what
//     `vgroove brdf --dim flatland` and Python's brdf run); BM_flatland_brdf_every_m: every k and m
//     with Eq. (6) through G_kaleidoscopic (flatland_brdf_reference, which flatland_brdf was:
//     O(max_k^2), ~0.4 s a pair at the command line's default max_k 4096). 64 pairs, theta in
//     (-89.9, 89.9) deg.
//   - BM_vgroove_brdf_grazing: 64 3D pairs within 10^-U(1, 13) deg of the horizon (the pairs the
//     batched pass hands to the per-solution pass; brdf_3d.cpp), at max_k 10^6 as the command line
//     sums by default.
#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_flatland.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace {

using namespace vgroove;

constexpr int kPairs = 64;

struct FlatPairs {
  std::vector<double> ti, to;
  FlatPairs() {
    std::mt19937_64 g(2018);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int n = 0; n < kPairs; ++n) {
      ti.push_back(U(g) * 89.9 * std::numbers::pi / 180.0);
      to.push_back(U(g) * 89.9 * std::numbers::pi / 180.0);
    }
  }
};

struct GrazingPairs {
  std::vector<analytic::Dir3> i, o;
  GrazingPairs() {
    std::mt19937_64 g(90);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto theta = [&]() { return (90.0 - std::pow(10.0, -1.0 - 12.0 * U(g))) * std::numbers::pi / 180.0; };
    for (int n = 0; n < kPairs; ++n) {
      i.push_back(analytic::dir3(theta(), 2.0 * std::numbers::pi * U(g)));
      o.push_back(analytic::dir3(theta(), 2.0 * std::numbers::pi * U(g)));
    }
  }
};

void per_call(benchmark::State& state) {
  state.counters["time_per_call"] = benchmark::Counter(static_cast<double>(state.iterations()) * kPairs,
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_flatland_brdf(benchmark::State& state) {
  static const FlatPairs p;
  const int max_k = static_cast<int>(state.range(0));
  for (auto _ : state)
    for (int n = 0; n < kPairs; ++n)
      benchmark::DoNotOptimize(analytic::flatland_brdf(analytic::NdfKind::ggx, 0.5, p.ti[n], p.to[n], max_k));
  per_call(state);
}

void BM_flatland_brdf_every_m(benchmark::State& state) {
  static const FlatPairs p;
  const int max_k = static_cast<int>(state.range(0));
  for (auto _ : state)
    for (int n = 0; n < kPairs; ++n)
      benchmark::DoNotOptimize(analytic::flatland_brdf_reference(analytic::NdfKind::ggx, 0.5, p.ti[n], p.to[n], max_k));
  per_call(state);
}

void BM_vgroove_brdf_grazing(benchmark::State& state) {
  static const GrazingPairs p;
  const int max_k = static_cast<int>(state.range(0));
  for (auto _ : state)
    for (int n = 0; n < kPairs; ++n)
      benchmark::DoNotOptimize(analytic::vgroove_brdf(p.i[n], p.o[n], analytic::NdfKind::ggx, 0.5, max_k));
  per_call(state);
}

}  // namespace

BENCHMARK(BM_flatland_brdf)->Arg(64)->Arg(4096)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_flatland_brdf_every_m)->Arg(64)->Arg(4096)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_vgroove_brdf_grazing)->Arg(16)->Arg(1000000)->Unit(benchmark::kMicrosecond);
