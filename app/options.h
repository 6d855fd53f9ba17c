// vgroove CLI: values from the command line, checked (a UserError naming the option) and
// turned into the libraries' types.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/app/commands.h"
#include "vgroove/sim/beam.h"
#include "vgroove/validation/groove_suite.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/run_options.h"

#include <string>

namespace vgroove::app {

using validation::kMaxRays;

// Strict numbers, read from the option's text before CLI11 converts it (so every option reads
// numbers the same way, and a message quotes the text as typed):
//   integers: decimal, optional sign, leading zeros read as decimal ("010" is 10), an exponent
//   allowed when the value is a whole number ("1e6", "2.5e3"); the plain decimal text of the value
//   is returned, or a UserError thrown naming the option: not an integer, or outside [lo, hi];
//   reals: decimal (an optional exponent), finite text; no "", "0x10", "inf", "nan", spaces.
std::string integer_text(const std::string& text, const std::string& option, long long lo, long long hi,
                         const std::string& note = "");
std::string real_text(const std::string& text, const std::string& option);

using validation::check_rays;
using validation::check_seed;
using validation::check_threads;
using validation::parse_form;
using validation::parse_sampling;
// The groove the options name, checked; nonsymmetric grooves need both facet angles.
validation::GrooveParams groove_from(const GrooveArgs& g);

}  // namespace vgroove::app
