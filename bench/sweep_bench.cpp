// vgroove bench: the whole Table 1 sweeps (symmetric: 6444 cases; nonsymmetric: 57,996) as
// `vgroove validate` runs them.
//
// Wall time, not CPU time: the sweep runs on `threads` workers (validation/parallel.h), so the
// speed-up from 1 to 2 threads is the ratio of the two rows' times.
#include "vgroove/validation/groove_suite.h"
#include "vgroove/validation/groove_suite_run.h"

#include <benchmark/benchmark.h>

#include <exception>
#include <string>

namespace {

using namespace vgroove;

void run_sweep(benchmark::State& state, const char* file) {
  validation::GrooveSuite suite;
  try {
    suite = validation::load_groove_suite(std::string(VGROOVE_SUITES_DIR) + "/" + file);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const int threads = static_cast<int>(state.range(0));
  double bounces_per_s = 0.0, wall_s = 0.0;
  bool pass = true;
  for (auto _ : state) {
    const validation::GrooveSuiteRun run = validation::run_groove_suite(suite, suite.options, threads);
    benchmark::DoNotOptimize(run.summary);
    bounces_per_s += run.summary.bounces_per_s;
    wall_s += run.summary.wall_s;
    pass = pass && run.summary.pass();
  }
  // As the GrooveSuiteSummary measures them (run_groove_suite's own clock), averaged over the iterations.
  state.counters["bounces_per_s"] = benchmark::Counter(bounces_per_s, benchmark::Counter::kAvgIterations);
  state.counters["wall_s"] = benchmark::Counter(wall_s, benchmark::Counter::kAvgIterations);
  // A sweep that stopped passing would make the timing meaningless.
  state.counters["pass"] = pass ? 1.0 : 0.0;
}

void BM_table1_symmetric(benchmark::State& state) { run_sweep(state, "table1_symmetric.json"); }
void BM_table1_nonsymmetric(benchmark::State& state) { run_sweep(state, "table1_nonsymmetric.json"); }

}  // namespace

BENCHMARK(BM_table1_nonsymmetric)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
BENCHMARK(BM_table1_symmetric)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
