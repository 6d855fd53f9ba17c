// vgroove bench: cost of one evaluation of the kaleidoscopic model (Lee et al. 2018, Eq. 4-6).
//
// The model is closed-form: G_kaleidoscopic and exit_angle take a fixed number of sines and a
// floor whatever the aperture, while the tracer's cost grows like the bounce count, ~pi/theta_v.
// Every call here is on the lit path (the full evaluation, no early return): theta_i runs over
// stratified midpoints of the range where the facet is lit, (-89 deg, min(89, theta_v/2) deg)
// for the left facet and its mirror image for the right one.
#include "vgroove/analytic/kaleidoscope.h"

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace {

using namespace vgroove;

constexpr int kAngles = 256;  // theta_i values per iteration

double deg(double d) { return d * std::numbers::pi / 180.0; }

// theta_i values lighting `first` for aperture theta_v.
std::vector<double> lit_theta_i(double theta_v, analytic::FacetSide first) {
  const double lo = deg(-89.0), hi = std::min(deg(89.0), 0.5 * theta_v);
  std::vector<double> v(kAngles);
  for (int j = 0; j < kAngles; ++j) {
    const double t = lo + (j + 0.5) / kAngles * (hi - lo);
    v[j] = first == analytic::FacetSide::left ? t : -t;
  }
  return v;
}

// Seconds per call (an inverted rate): printed with its SI prefix, e.g. "60ns".
void report_time_per_call(benchmark::State& state) {
  state.counters["time_per_call"] = benchmark::Counter(static_cast<double>(state.iterations()) * kAngles,
                                                       benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Args: theta_v_deg, facet hit first (0 left, 1 right: mirrored, two more exit_angle calls).
void BM_G_kaleidoscopic(benchmark::State& state) {
  const double theta_v = deg(static_cast<double>(state.range(0)));
  const auto first = state.range(1) == 0 ? analytic::FacetSide::left : analytic::FacetSide::right;
  const std::vector<double> theta_i = lit_theta_i(theta_v, first);
  for (auto _ : state) {
    for (double t : theta_i) {
      const analytic::FacetPrediction p = analytic::G_kaleidoscopic(t, theta_v, first);
      benchmark::DoNotOptimize(p);
    }
  }
  report_time_per_call(state);
}

// Eq. (5) at the bounce count the model predicts (n = k of Eq. 4, ~pi/theta_v): O(1) in n.
void BM_exit_angle(benchmark::State& state) {
  const double theta_v = deg(static_cast<double>(state.range(0)));
  const std::vector<double> theta_i = lit_theta_i(theta_v, analytic::FacetSide::left);
  std::vector<int> n(theta_i.size());
  for (std::size_t j = 0; j < n.size(); ++j) n[j] = analytic::bounce_count(theta_i[j], theta_v);
  for (auto _ : state) {
    for (std::size_t j = 0; j < theta_i.size(); ++j) {
      const double theta_o = analytic::exit_angle(theta_i[j], theta_v, n[j]);
      benchmark::DoNotOptimize(theta_o);
    }
  }
  report_time_per_call(state);
}

}  // namespace

BENCHMARK(BM_G_kaleidoscopic)->ArgNames({"theta_v_deg", "right"})->ArgsProduct({{1, 30, 90}, {0, 1}});
BENCHMARK(BM_exit_angle)->ArgName("theta_v_deg")->Arg(1)->Arg(30)->Arg(90);
