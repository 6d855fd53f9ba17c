// vgroove CLI: values from the command line, checked (a UserError naming the option) and
// turned into the libraries' types.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/app/commands.h"
#include "vgroove/sim/beam.h"
#include "vgroove/validation/suite.h"

#include <string>

namespace vgroove::app {

inline constexpr long kMaxRays = 1'000'000'000;

void check_seed(long long seed, const std::string& what);
void check_rays(long rays, const std::string& what);
void check_threads(int threads);
// "stratified", "random", and with `breakpoints` also "breakpoints" (suites only: validate and
// bench accuracy; `trace` places rays across the opening).
sim::Sampling parse_sampling(const std::string& s, const std::string& what, bool breakpoints = true);
analytic::Eq6Form parse_form(const std::string& s, const std::string& what);
// The groove the options name, checked; nonsymmetric grooves need both facet angles.
validation::GrooveParams groove_from(const GrooveArgs& g);
// A suite's case options with the command line's overrides (kUnset / empty: the suite's).
validation::CaseOptions options_with_overrides(const validation::Suite& suite, long rays, const std::string& sampling,
                                               const std::string& form, long long seed);

}  // namespace vgroove::app
