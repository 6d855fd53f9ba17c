// vgroove support: standard output that is known to have been written.
//
// A report printed to a full disk (> /dev/full) or to a closed stdout (>&-) must not end in exit
// status 0. Two pieces: at start-up a closed descriptor 0, 1 or 2 is reopened on /dev/null in the
// direction that fails (stdout read-only), so that writing to it still fails, visibly, and no file
// the run opens can take its number (a report opened as descriptor 1 would receive the table);
// at the end, everything buffered is flushed and the stream's error state is read, with the reason
// of the first write that failed (std::cout's buffer keeps its errno: output larger than C's buffer
// fails before the flush).
#pragma once

#include <string>

namespace vgroove::support {

// Call once, first thing in main.
void guard_standard_descriptors();

// Flushes std::cout and C's stdout; "" when everything written so far reached its destination,
// else what went wrong ("standard output: write failed (No space left on device)").
std::string flush_standard_output();

}  // namespace vgroove::support
