// vgroove bench: cost of one evaluation of the 3D V-groove BRDF (Lee et al. 2018, Eq. 17, summed
// over k = 1..max_k) against Cook-Torrance with the V-cavity G (Eq. 1-3), for GGX and Beckmann.
//
// Both run over the same fixed set of 1024 (i, o) pairs, uniform in the projected solid angle
// (cosine-weighted), from a fixed seed. The paper reports that its model adds 15-20% to the render
// time over Cook-Torrance; a render also pays for tracing and sampling, so the ratio of the BRDF
// evaluations alone is an upper bound on that overhead.
// Arguments: /ndf (0 = GGX, 1 = Beckmann)/alpha x 10/max_k (vgroove only).
//
// BM_vgroove_brdf runs the batched pass (analytic/brdf_3d_batch.cpp), BM_vgroove_brdf_per_solution
// the evaluation it replaced (each solution's term on its own), on the same pairs, in the same run.
// Measured (Release, idle 2-core host; medians of 5, ns per call): see the README's "The BRDF's
// cost against Cook-Torrance". GGX alpha 0.3: batched ~131 (max_k 4),
// ~158 (16); per solution ~311, ~369; cook_torrance ~72. Beckmann 0.3: ~160, ~194; ~339, ~417; ~84.
#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_nonsymmetric.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace {

using namespace vgroove;

constexpr int kPairs = 1024;

struct Pairs {
  std::vector<analytic::Dir3> i, o;
  Pairs() {
    std::mt19937_64 g(2018);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int n = 0; n < kPairs; ++n) {
      // cos theta = sqrt(u): cosine-weighted directions.
      i.push_back(analytic::dir3(std::acos(std::sqrt(U(g))), 2.0 * std::numbers::pi * U(g)));
      o.push_back(analytic::dir3(std::acos(std::sqrt(U(g))), 2.0 * std::numbers::pi * U(g)));
    }
  }
};
const Pairs& pairs() {
  static const Pairs p;
  return p;
}

analytic::NdfKind ndf_of(int64_t a) { return a == 0 ? analytic::NdfKind::ggx : analytic::NdfKind::beckmann; }

void report_time_per_call(benchmark::State& state) {
  state.counters["time_per_call"] = benchmark::Counter(static_cast<double>(state.iterations()) * kPairs,
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_vgroove_brdf(benchmark::State& state) {
  const analytic::NdfKind ndf = ndf_of(state.range(0));
  const double alpha = state.range(1) / 10.0;
  const int max_k = static_cast<int>(state.range(2));
  const Pairs& p = pairs();
  for (auto _ : state) {
    for (int n = 0; n < kPairs; ++n)
      benchmark::DoNotOptimize(analytic::vgroove_brdf(p.i[n], p.o[n], ndf, alpha, max_k));
  }
  report_time_per_call(state);
}

// The plain pass (each solution's term on its own), same pairs.
void BM_vgroove_brdf_per_solution(benchmark::State& state) {
  const analytic::NdfKind ndf = ndf_of(state.range(0));
  const double alpha = state.range(1) / 10.0;
  const int max_k = static_cast<int>(state.range(2));
  const Pairs& p = pairs();
  for (auto _ : state) {
    for (int n = 0; n < kPairs; ++n)
      benchmark::DoNotOptimize(analytic::vgroove_brdf_per_solution_reference(p.i[n], p.o[n], ndf, alpha, max_k));
  }
  report_time_per_call(state);
}

void BM_cook_torrance(benchmark::State& state) {
  const analytic::NdfKind ndf = ndf_of(state.range(0));
  const double alpha = state.range(1) / 10.0;
  const Pairs& p = pairs();
  for (auto _ : state) {
    for (int n = 0; n < kPairs; ++n) benchmark::DoNotOptimize(analytic::cook_torrance(p.i[n], p.o[n], ndf, alpha));
  }
  report_time_per_call(state);
}

// The nonsymmetric BRDF (Eq. 23 summed over k = 1..max_k, analytic/brdf_nonsymmetric.h): an
// integral over the partner's tilt per family of grooves, by adaptive Gauss-Kronrod to the relative
// tolerance 10^-range(3). The first 64 of the same pairs (one evaluation costs ~0.1-0.4 ms).
// Arguments: /ndf/alpha x 10/max_k/-log10(tolerance).
//
// Measured in one run beside the two above (CPU time per call, medians of 5, random interleaving,
// max_k 4; the host shared with ~7 other jobs, load average ~19, so +-30 %):
//                          GGX 0.3   GGX 1.0   Beckmann 0.3   Beckmann 1.0
//   nonsymmetric, tol 1e-4    89 us    107 us        131 us         113 us
//   nonsymmetric, tol 1e-9   323 us    303 us        315 us         360 us
//   symmetric (Eq. 17)       322 ns    288 ns        342 ns         336 ns
//   cook_torrance             68 ns     66 ns         77 ns          77 ns
// i.e. ~1300-1700 x Cook-Torrance at 1e-4 (a few families of grooves per k, each an integral of
// ~100-300 evaluations of Eq. 9 and D P). The paper's +15-20 % render time is for a renderer that
// samples the partner (Sec. 6) instead of integrating over it; this evaluation is the reference.
void BM_vgroove_nonsymmetric_brdf(benchmark::State& state) {
  analytic::NonsymmetricModel m;
  m.roughness = analytic::isotropic_roughness(ndf_of(state.range(0)), state.range(1) / 10.0);
  const int max_k = static_cast<int>(state.range(2));
  m.tolerance = std::pow(10.0, -static_cast<double>(state.range(3)));
  const Pairs& p = pairs();
  constexpr int kSome = 64;
  for (auto _ : state) {
    for (int n = 0; n < kSome; ++n) benchmark::DoNotOptimize(analytic::nonsymmetric_brdf(p.i[n], p.o[n], max_k, m));
  }
  state.counters["time_per_call"] = benchmark::Counter(static_cast<double>(state.iterations()) * kSome,
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
void nonsymmetric_args(benchmark::internal::Benchmark* b) {
  for (int ndf : {0, 1})
    for (int a : {3, 10})
      for (int tol : {4, 9}) b->Args({ndf, a, 4, tol});
}

void vgroove_args(benchmark::internal::Benchmark* b) {
  for (int ndf : {0, 1})
    for (int a : {3, 5, 7, 10})
      for (int k : {4, 16}) b->Args({ndf, a, k});
}
void ct_args(benchmark::internal::Benchmark* b) {
  for (int ndf : {0, 1})
    for (int a : {3, 5, 7, 10}) b->Args({ndf, a});
}

}  // namespace

BENCHMARK(BM_vgroove_brdf)->Apply(vgroove_args);
BENCHMARK(BM_vgroove_brdf_per_solution)->Apply(vgroove_args);
BENCHMARK(BM_cook_torrance)->Apply(ct_args);
BENCHMARK(BM_vgroove_nonsymmetric_brdf)->Apply(nonsymmetric_args)->Unit(benchmark::kMicrosecond);
