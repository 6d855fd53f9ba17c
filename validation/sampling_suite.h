// vgroove validation: the suite of kind "sampling" (data/suites/sampling.json): the importance
// sampling of the symmetric V-groove BRDF (Lee et al. 2018, Sec. 6; analytic/sampling_3d.h) held
// to account in one run:
//   - "chi_square": listed cases (dimension, NDF, alpha, theta_i, strategy), each a chi-square
//     goodness-of-fit test of the sampled directions against the sampler's pdf with the
//     normalization check (validation/sampling_check.h); the family's level is Sidak-corrected
//     over the listed cases;
//   - "variance": listed cases, each sampled with every strategy and with cosine-weighted
//     hemisphere sampling, F = 1 and Schlick F0 values: the weight's variance, the cost per sample
//     and the efficiency 1 / (variance x time) (reported, not thresholded);
//   - "furnace": listed cases of the white furnace (validation/furnace_suite.h).
// The run passes when every chi-square accepts with its normalization and every furnace case passes.
#pragma once

#include "vgroove/support/parallel.h"
#include "vgroove/validation/furnace_suite.h"
#include "vgroove/validation/sampling_check.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

struct SamplingSuite {
  std::string file, name, description;
  std::uint64_t seed = 1;
  std::vector<Chi2Spec> chi_square;
  std::vector<VarianceSpec> variance;
  FurnaceSuite furnace;  // its grid fields unused: the cases are listed
  std::vector<BrdfCase> furnace_cases;
};

struct SamplingRun {
  std::vector<Chi2Outcome> chi_square;
  std::vector<VarianceOutcome> variance;
  std::vector<FurnaceOutcome> furnace;
  int threads = 1;
  double wall_s = 0.0;
  bool interrupted = false;
  bool pass = false;
};

// One item of the run (item_work.h), in the order chi_square, variance, furnace: the one it is set.
struct SamplingItem {
  std::optional<Chi2Outcome> chi_square;
  std::optional<VarianceOutcome> variance;
  std::optional<FurnaceOutcome> furnace;
};
template <class F>
void fields(SamplingItem& o, F&& f) {
  f("chi_square", o.chi_square), f("variance", o.variance), f("furnace", o.furnace);
}
using SamplingWork = ItemWork<SamplingItem>;
Job<SamplingWork> sampling_job(const SamplingSuite& suite, nlohmann::json descriptor,
                               const std::atomic<bool>* cancel = nullptr);
SamplingRun sampling_run_from(const SamplingSuite& suite, const std::vector<UnitResult<SamplingWork>>& results);

SamplingSuite parse_sampling_suite(const nlohmann::json& j, const std::string& file);
nlohmann::json sampling_report_json(const SamplingSuite& suite, const SamplingRun& run);
void print_sampling_table(std::ostream& os, const SamplingSuite& suite, const SamplingRun& run);

}  // namespace vgroove::validation
