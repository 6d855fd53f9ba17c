// vgroove bench: the cost of importance sampling the 3D V-groove BRDF (analytic/sampling_3d.h) per
// call, beside Cook-Torrance's: sample() (facet, Eq. 4-6, Eq. 5, and the pdf and BRDF at the drawn
// direction in one pass over the paths, for the weight), pdf() alone, and Eq. (17) alone, against
// Cook-Torrance's VNDF sample (the Smith-GGX visible normals, the reflection and its pdf) and its
// evaluation (V-cavity G).
//
// Every benchmark runs over the same 1024 incident directions (cosine-weighted) and uniform
// numbers from a fixed seed; pdf() and eval() over the directions the V-cavity strategy draws for
// them (where a renderer evaluates them). GGX; arguments /strategy (0 printed, 1 vndf, 2 smith-vndf,
// 3 bounded-vndf)/alpha x 10.
//   build/vgroove_bench --benchmark_filter='BM_(vgroove_sample|vgroove_pdf|vgroove_eval|ct_)'
//     --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true
//
// Measured (Release, medians of 5, ns per call, max_k 256; the 2-core host shared with other jobs
// at load ~13, so +-30 % or worse):
//                       printed   vndf   smith-vndf   bounded-vndf   | Cook-Torrance
//   sample, alpha 0.3      877    1041       960          1272        |  125 (Smith-GGX VNDF)
//   sample, alpha 1.0      990    1143      1246          1327        |  123
//   pdf,    alpha 0.3      640     628       669          1066        |   67 (eval)
//   pdf,    alpha 1.0      755     849       893          1314        |   72 (eval)
//   eval (Eq. 17): 666 (alpha 0.3), 778 (alpha 1.0)
// sample() computes pdf and BRDF at the drawn direction in one pass (for the weight): it costs
// about one pdf() plus the draw (~250-350 ns: the facet, Eq. 4-6, Eq. 5), 8-10x Cook-Torrance's
// VNDF sample; pdf() costs about one evaluation of Eq. 17 (the same paths), 9-12x Cook-Torrance's
// evaluation. The bounded VNDF's pdf tests each path's facet against the cap (a stretched
// reflection): ~1.5x the others.
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/vndf.h"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace {

using namespace vgroove;

constexpr int kN = 1024;
constexpr int kMaxK = 256;

struct Inputs {
  std::vector<analytic::Dir3> i;
  std::vector<std::array<double, 4>> u;
  explicit Inputs(double alpha) {
    std::mt19937_64 g(2024);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int n = 0; n < kN; ++n) {
      i.push_back(analytic::dir3(std::acos(std::sqrt(U(g))), 2.0 * std::numbers::pi * U(g)));
      u.push_back({U(g), U(g), U(g), U(g)});
    }
    // Directions where pdf and eval are asked: those the sampler draws (zero-weight returns skipped).
    for (int n = 0; n < kN; ++n) {
      const analytic::VgrooveSample3d s =
          analytic::sample_vgroove_3d(i[n], u[n], analytic::NdfKind::ggx, alpha, analytic::SamplerOptions{});
      o.push_back(s.k > 0 ? s.o : analytic::Dir3{-i[n].x, -i[n].y, i[n].z});
    }
  }
  std::vector<analytic::Dir3> o;
};

const Inputs& inputs(double alpha) {
  static const Inputs a3(0.3), a10(1.0);
  return alpha < 0.5 ? a3 : a10;
}

analytic::FacetStrategy strategy_of(int64_t s) { return static_cast<analytic::FacetStrategy>(s); }

void per_call(benchmark::State& state) {
  state.counters["time_per_call"] = benchmark::Counter(static_cast<double>(state.iterations()) * kN,
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_vgroove_sample(benchmark::State& state) {
  const double alpha = state.range(1) / 10.0;
  const analytic::SamplerOptions opt{strategy_of(state.range(0)), kMaxK};
  const Inputs& in = inputs(alpha);
  for (auto _ : state)
    for (int n = 0; n < kN; ++n)
      benchmark::DoNotOptimize(analytic::sample_vgroove_3d(in.i[n], in.u[n], analytic::NdfKind::ggx, alpha, opt));
  per_call(state);
}

void BM_vgroove_pdf(benchmark::State& state) {
  const double alpha = state.range(1) / 10.0;
  const analytic::SamplerOptions opt{strategy_of(state.range(0)), kMaxK};
  const Inputs& in = inputs(alpha);
  for (auto _ : state)
    for (int n = 0; n < kN; ++n)
      benchmark::DoNotOptimize(analytic::vgroove_pdf_3d(in.i[n], in.o[n], analytic::NdfKind::ggx, alpha, opt));
  per_call(state);
}

void BM_vgroove_eval(benchmark::State& state) {
  const double alpha = state.range(0) / 10.0;
  const Inputs& in = inputs(alpha);
  for (auto _ : state)
    for (int n = 0; n < kN; ++n)
      benchmark::DoNotOptimize(analytic::vgroove_brdf(in.i[n], in.o[n], analytic::NdfKind::ggx, alpha, kMaxK));
  per_call(state);
}

// Cook-Torrance's VNDF sample: the Smith-GGX visible normal, the reflection about it, and the
// reflection's pdf D_i(m) / (4 <i.m>) (Tokuyoshi and Eto 2024, Sec. 4), as a renderer draws it.
void BM_ct_sample_vndf(benchmark::State& state) {
  const double alpha = state.range(0) / 10.0;
  const Inputs& in = inputs(alpha);
  for (auto _ : state)
    for (int n = 0; n < kN; ++n) {
      const analytic::Dir3& i = in.i[n];
      const analytic::Dir3 m = analytic::sample_ggx_vndf(alpha, i, in.u[n][0], in.u[n][1]);
      const double im = i.x * m.x + i.y * m.y + i.z * m.z;
      const analytic::Dir3 o{2.0 * im * m.x - i.x, 2.0 * im * m.y - i.y, 2.0 * im * m.z - i.z};
      benchmark::DoNotOptimize(o);
      benchmark::DoNotOptimize(analytic::ggx_vndf_pdf(alpha, i, m) / (4.0 * im));
    }
  per_call(state);
}

void BM_ct_eval(benchmark::State& state) {
  const double alpha = state.range(0) / 10.0;
  const Inputs& in = inputs(alpha);
  for (auto _ : state)
    for (int n = 0; n < kN; ++n)
      benchmark::DoNotOptimize(analytic::cook_torrance(in.i[n], in.o[n], analytic::NdfKind::ggx, alpha));
  per_call(state);
}

void strategies(benchmark::internal::Benchmark* b) {
  for (int s = 0; s < 4; ++s)
    for (int a : {3, 10}) b->Args({s, a});
}

BENCHMARK(BM_vgroove_sample)->Apply(strategies);
BENCHMARK(BM_vgroove_pdf)->Apply(strategies);
BENCHMARK(BM_vgroove_eval)->Arg(3)->Arg(10);
BENCHMARK(BM_ct_sample_vndf)->Arg(3)->Arg(10);
BENCHMARK(BM_ct_eval)->Arg(3)->Arg(10);

}  // namespace
