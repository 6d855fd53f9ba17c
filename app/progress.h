// vgroove CLI: progress on stderr and the end of an interrupted run.
#pragma once

#include "vgroove/support/parallel.h"

#include <string>

namespace vgroove::app {

// Progress on stderr, only when it is a terminal and the run takes a while.
support::ProgressFn terminal_progress(const std::string& label);
// A run stopped by Ctrl-C: nothing is written, and the exit status says why.
int interrupted_no_report();

}  // namespace vgroove::app
