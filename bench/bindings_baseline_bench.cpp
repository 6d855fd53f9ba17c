// The C++ side of the Python module's throughput check: the library calls that vgroove.trace,
// vgroove.brdf, vgroove.kaleidoscope, vgroove.sample and vgroove.pdf make (and vgroove.BRDF's
// eval, sample and pdf, with the model's default max_k), on 10^6 rays or directions, one thread,
// written into arrays as the bindings write them.
// scripts/bench_python.py times the Python calls on the same inputs; the two are compared in the
// README (Python within 10 % of these). Like the Python calls, each iteration allocates its output
// arrays (uninitialized, as numpy.empty).
#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_model.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/rng.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/single_groove.h"

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

namespace {

using namespace vgroove;
constexpr long kN = 1'000'000;

// An output array, uninitialized.
template <class T>
std::unique_ptr<T[]> out(std::size_t n) {
  return std::make_unique_for_overwrite<T[]>(n);
}

// vgroove.trace(30, 10**6, 60): every ray's fate into arrays, the tally and the summary JSON.
void BM_baseline_trace_1e6(benchmark::State& state) {
  const validation::GrooveParams g = validation::GrooveParams::make_symmetric(60.0 * kRadPerDeg);
  for (auto _ : state) {
    auto x = out<double>(kN), theta_o = out<double>(kN), exit_dir = out<double>(2 * kN);
    auto first = out<std::int8_t>(kN), fate = out<std::int8_t>(kN);
    auto k = out<std::int32_t>(kN);
    sim::Tally t;
    validation::trace_beam_rays(g, 30.0 * kRadPerDeg, kN, sim::Sampling::stratified, 1, 100000,
                                [&](long j0, int m, const double* xs, const sim::TraceResult* res) {
                                  for (int j = 0; j < m; ++j) {
                                    const sim::TraceResult& r = res[j];
                                    const std::size_t a = static_cast<std::size_t>(j0 + j);
                                    t.add(r);
                                    const bool esc = r.how == sim::Termination::escaped;
                                    x[a] = xs[j];
                                    first[a] = r.bounces > 0 ? static_cast<std::int8_t>(r.first) : std::int8_t{-1};
                                    k[a] = r.bounces;
                                    fate[a] = static_cast<std::int8_t>(r.how);
                                    exit_dir[2 * a] = esc ? r.exit_dir.x() : 0.0;
                                    exit_dir[2 * a + 1] = esc ? r.exit_dir.y() : 0.0;
                                    theta_o[a] = esc ? sim::angle_from_normal(r.exit_dir) * kDegPerRad : 0.0;
                                  }
                                });
    benchmark::DoNotOptimize(validation::trace_json(g, 30.0, kN, sim::Sampling::stratified, 1, 100000, t));
    benchmark::DoNotOptimize(theta_o.get());
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_baseline_trace_1e6)->Unit(benchmark::kMillisecond);

// Directions uniform on the upper hemisphere (scripts/bench_python.py draws the same law).
std::vector<analytic::Dir3> hemisphere(std::uint64_t seed) {
  sim::Rng rng(seed, 0, 0);
  std::vector<analytic::Dir3> d(kN);
  for (auto& w : d) {
    const double z = rng.uniform(), phi = 2.0 * std::numbers::pi * rng.uniform(), s = std::sqrt(1.0 - z * z);
    w = {s * std::cos(phi), s * std::sin(phi), z};
  }
  return d;
}

// vgroove.brdf("vgroove", "ggx", 0.5, wi, wo, threads=1) on 10^6 pairs (max_k 16).
void BM_baseline_brdf_1e6(benchmark::State& state) {
  const auto wi = hemisphere(1), wo = hemisphere(2);
  for (auto _ : state) {
    auto f = out<double>(kN);
    for (long j = 0; j < kN; ++j) f[j] = analytic::vgroove_brdf(wi[j], wo[j], NdfKind::ggx, 0.5, 16);
    benchmark::DoNotOptimize(f.get());
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_baseline_brdf_1e6)->Unit(benchmark::kMillisecond);

// vgroove.BRDF("vgroove", "ggx", 0.5).eval(wi, wo, threads=1): the same pairs at the model's
// default max_k (every order in 3D, analytic::default_max_k).
void BM_baseline_brdf_default_1e6(benchmark::State& state) {
  const auto wi = hemisphere(1), wo = hemisphere(2);
  const int max_k = analytic::default_max_k(analytic::BrdfModel::vgroove, false);
  for (auto _ : state) {
    auto f = out<double>(kN);
    for (long j = 0; j < kN; ++j) f[j] = analytic::vgroove_brdf(wi[j], wo[j], NdfKind::ggx, 0.5, max_k);
    benchmark::DoNotOptimize(f.get());
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_baseline_brdf_default_1e6)->Unit(benchmark::kMillisecond);

// vgroove.kaleidoscope(theta_i, 60) on 10^6 incident angles: each element's groove and angle
// checked, both facets' lit, k, f_a, shadow and per zone n, G, fraction and theta_o.
void BM_baseline_kaleidoscope_1e6(benchmark::State& state) {
  sim::Rng rng(3, 0, 0);
  std::vector<double> ti(kN), v(kN, 60.0);
  for (double& t : ti) t = -89.0 + 178.0 * rng.uniform();
  const validation::OptionNames names = validation::OptionNames::keywords();
  for (auto _ : state) {
    auto f_a = out<double>(2 * kN), shadow = out<double>(2 * kN), G = out<double>(8 * kN), frac = out<double>(8 * kN),
         theta_o = out<double>(8 * kN);
    auto k = out<int>(2 * kN), n = out<int>(8 * kN);
    auto lit = out<bool>(2 * kN);
    std::vector<validation::GrooveParams> grooves(kN);
    for (long j = 0; j < kN; ++j) {
      grooves[j] = validation::groove_from_degrees(v[j], std::nullopt, std::nullopt, names);
      validation::check_theta_i(ti[j], names.theta_i);
    }
    for (long j = 0; j < kN; ++j) {
      validation::ModelShares m[2];
      double width = 0.0;
      for (int f = 0; f < 2; ++f) {
        m[f] = validation::model_shares(grooves[j], ti[j] * kRadPerDeg, static_cast<sim::Side>(f),
                                        analytic::Eq6Form::corrected);
        if (m[f].lit) width += m[f].f_a * (1.0 - m[f].shadow);
      }
      for (int f = 0; f < 2; ++f) {
        const std::size_t a = 2 * static_cast<std::size_t>(j) + f;
        lit[a] = m[f].lit, k[a] = m[f].lit ? m[f].k : 0;
        f_a[a] = m[f].lit ? m[f].f_a : 0.0, shadow[a] = m[f].lit ? m[f].shadow : 0.0;
        for (int z = 0; z < 4; ++z) {
          const std::size_t b = 4 * a + z;
          const bool used = m[f].lit && z < m[f].shares;
          n[b] = used ? m[f].share[z].n : 0;
          G[b] = used ? m[f].share[z].G : 0.0;
          frac[b] = used ? m[f].share[z].G * m[f].f_a / width : 0.0;
          theta_o[b] = used ? m[f].share[z].theta_o * kDegPerRad : 0.0;
        }
      }
    }
    benchmark::DoNotOptimize(frac.get());
    benchmark::DoNotOptimize(theta_o.get());
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_baseline_kaleidoscope_1e6)->Unit(benchmark::kMillisecond);

// vgroove.sample("ggx", 0.5, u, theta_i_deg=30, threads=1) (and vgroove.BRDF().sample(wi, u) with
// wi = direction(30, 180)) on 10^6 rows of four uniform numbers (the defaults: V-cavity VNDF,
// max_k kSamplerMaxK): o, k, pdf, weight and beyond_max_k into arrays.
void BM_baseline_sample_1e6(benchmark::State& state) {
  sim::Rng rng(4, 0, 0);
  std::vector<std::array<double, 4>> u(kN);
  for (auto& r : u)
    for (double& x : r) x = rng.uniform();
  const analytic::Dir3 i = analytic::dir3(30.0 * kRadPerDeg, std::numbers::pi);
  const analytic::SamplerOptions opt;
  for (auto _ : state) {
    auto o = out<double>(3 * kN), pdf = out<double>(kN), weight = out<double>(kN);
    auto k = out<std::int32_t>(kN);
    auto beyond = out<bool>(kN);
    for (long j = 0; j < kN; ++j) {
      const analytic::VgrooveSample3d x = analytic::sample_vgroove_3d(i, u[j], NdfKind::ggx, 0.5, opt);
      o[3 * j] = x.o.x, o[3 * j + 1] = x.o.y, o[3 * j + 2] = x.o.z;
      k[j] = x.k, pdf[j] = x.pdf, weight[j] = x.weight, beyond[j] = x.beyond_max_k;
    }
    benchmark::DoNotOptimize(beyond.get());
    benchmark::DoNotOptimize(weight.get());
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_baseline_sample_1e6)->Unit(benchmark::kMillisecond);

// vgroove.pdf("ggx", 0.5, wo, theta_i_deg=30, threads=1) (and vgroove.BRDF().pdf(wi, wo)) on 10^6
// directions of the hemisphere.
void BM_baseline_pdf_1e6(benchmark::State& state) {
  const auto wo = hemisphere(2);
  const analytic::Dir3 i = analytic::dir3(30.0 * kRadPerDeg, std::numbers::pi);
  const analytic::SamplerOptions opt;
  for (auto _ : state) {
    auto p = out<double>(kN);
    for (long j = 0; j < kN; ++j) p[j] = analytic::vgroove_pdf_3d(i, wo[j], NdfKind::ggx, 0.5, opt);
    benchmark::DoNotOptimize(p.get());
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_baseline_pdf_1e6)->Unit(benchmark::kMillisecond);

}  // namespace
