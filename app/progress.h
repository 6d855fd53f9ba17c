// vgroove CLI: progress on stderr and the end of an interrupted run.
#pragma once

#include "vgroove/support/parallel.h"

#include <cstddef>
#include <string>

namespace vgroove::app {

// Progress on stderr, only when it is a terminal and the run takes a while (a second): the work
// items done, the rate and the time left, at most four times a second; the closing line (100 %
// and the time taken) once, and only after a line was shown.
support::ProgressFn terminal_progress(const std::string& label);
// One progress line: "LABEL: D/T work items (P%), R per s, about S left", or at the end
// "LABEL: T/T work items (100%), S"; the label through support::printable.
std::string progress_text(const std::string& label, std::size_t done, std::size_t total, double elapsed_s);
// A run stopped by Ctrl-C: nothing is written, and the exit status says why.
int interrupted_no_report();

}  // namespace vgroove::app
