// vgroove bench: the whole Table 1 symmetric sweep (6444 cases) as `vgroove validate` runs it.
//
// Wall time, not CPU time: the sweep runs on `threads` workers (validation/parallel.h), so the
// speed-up from 1 to 2 threads is the ratio of the two rows' times.
#include "validation/suite.h"
#include "validation/suite_run.h"

#include <benchmark/benchmark.h>

#include <exception>

namespace {

using namespace vgroove;

void BM_table1_symmetric(benchmark::State& state) {
  validation::Suite suite;
  try {
    suite = validation::load_suite(VGROOVE_TABLE1_SUITE);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const int threads = static_cast<int>(state.range(0));
  double bounces_per_s = 0.0, wall_s = 0.0;
  bool pass = true;
  for (auto _ : state) {
    const validation::SuiteRun run = validation::run_suite(suite, suite.options, threads);
    benchmark::DoNotOptimize(run.summary);
    bounces_per_s += run.summary.bounces_per_s;
    wall_s += run.summary.wall_s;
    pass = pass && run.summary.pass();
  }
  // As the Summary measures them (run_suite's own clock), averaged over the iterations.
  state.counters["bounces_per_s"] = benchmark::Counter(bounces_per_s, benchmark::Counter::kAvgIterations);
  state.counters["wall_s"] = benchmark::Counter(wall_s, benchmark::Counter::kAvgIterations);
  // A sweep that stopped passing would make the timing meaningless.
  state.counters["pass"] = pass ? 1.0 : 0.0;
}

}  // namespace

BENCHMARK(BM_table1_symmetric)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
