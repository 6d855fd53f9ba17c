// vgroove CLI: values from the command line, checked (a UserError naming the option) and
// turned into the libraries' types.
#pragma once

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/app/commands.h"
#include "vgroove/sim/beam.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/suite.h"

#include <string>

namespace vgroove::app {

using validation::check_rays;
using validation::check_seed;
using validation::check_threads;
using validation::parse_form;
using validation::parse_sampling;
// The groove the options name, checked; nonsymmetric grooves need both facet angles.
validation::GrooveParams groove_from(const GrooveArgs& g);

}  // namespace vgroove::app
