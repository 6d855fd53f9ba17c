// vgroove bench: the binned 3D lobes of a Fig. 11 case (what validation/brdf_suite.cpp times as
// model_wall_s): the vgroove lobe (Eq. 16 over 30 x 24 bins, max_k 16) and Cook-Torrance's.
//   BM_lobe_3d: the fast kernels (four nodes at a time, lobe_3d_nodes.h), Cook-Torrance as the
//   lobe's k = 1 row (as the suite runs);
//   BM_lobe_3d_reference: the reference kernels and Cook-Torrance integrated on its own.
// Arguments: /ndf (0 GGX, 1 Beckmann, 2 Phong)/alpha x 10/theta_i deg. One lobe per iteration.
// Phong 1.0 and 0.7 and GGX 0.3 at 20 deg are the slowest of the 60 3D cases of Fig. 11.
// Run: build/vgroove_bench --benchmark_filter=BM_lobe --benchmark_repetitions=3
#include "vgroove/analytic/lobe_3d.h"

#include <benchmark/benchmark.h>

#include <numbers>

namespace {

using namespace vgroove;

NdfKind ndf_of(int64_t a) { return a == 0 ? NdfKind::ggx : (a == 1 ? NdfKind::beckmann : NdfKind::phong); }

void BM_lobe_3d(benchmark::State& state) {
  const NdfKind ndf = ndf_of(state.range(0));
  const double alpha = state.range(1) / 10.0, theta_i = state.range(2) * std::numbers::pi / 180.0;
  for (auto _ : state) {
    const analytic::Lobe3d lobe = analytic::vgroove_lobe_3d(ndf, alpha, theta_i, 30, 24, 16);
    const analytic::Lobe3d single = analytic::cook_torrance_lobe_3d_from(lobe);
    benchmark::DoNotOptimize(single.albedo);
  }
}

void BM_lobe_3d_reference(benchmark::State& state) {
  const NdfKind ndf = ndf_of(state.range(0));
  const double alpha = state.range(1) / 10.0, theta_i = state.range(2) * std::numbers::pi / 180.0;
  analytic::Lobe3dOptions ref;
  ref.reference_kernels = true;
  for (auto _ : state) {
    const analytic::Lobe3d lobe = analytic::vgroove_lobe_3d(ndf, alpha, theta_i, 30, 24, 16, ref);
    const analytic::Lobe3d single = analytic::cook_torrance_lobe_3d(ndf, alpha, theta_i, 30, 24, ref);
    benchmark::DoNotOptimize(lobe.albedo + single.albedo);
  }
}

void lobe_args(benchmark::internal::Benchmark* b) {
  b->Args({0, 5, 40})
      ->Args({1, 5, 40})
      ->Args({2, 5, 40})
      ->Args({0, 3, 0})
      ->Args({0, 10, 80})
      ->Args({2, 7, 20})
      ->Args({2, 10, 20})
      ->Args({0, 3, 20});
  b->Unit(benchmark::kMillisecond)->Iterations(1);
}

}  // namespace

BENCHMARK(BM_lobe_3d)->Apply(lobe_args);
BENCHMARK(BM_lobe_3d_reference)->Apply(lobe_args);
