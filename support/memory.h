// vgroove support: what a run will need in memory, checked before it starts.
//
// A spec can ask for more than the machine holds (10^7 grooves per surface on every thread, a
// grid of 10^12 cases, 10^5 angles x 64 channels x 10^6 histogram cells). Each runner estimates
// its need from the spec (its largest data structures, counted by their sizes), and the command
// refuses a run whose estimate exceeds what this process may use, before any work, with both
// numbers in the message. The estimate is an upper bound of the large allocations, not of every
// byte; a bad_alloc that still happens is caught and reported as a one-line error.
#pragma once

#include <string>

namespace vgroove::support {

// The bytes this process may use: the least of the physical memory, the address-space and
// data-segment limits (ulimit -v, -d) and the control group's memory.max.
double memory_limit_bytes();

// Throws UserError "<what> needs about 12.3 GB of memory (<detail>), more than the 4.0 GB this
// process may use" when bytes plus the program's own (code, libraries) exceeds the limit. Thread
// stacks are not counted: threads that cannot start are left out (support/parallel.h).
void check_memory(double bytes, const std::string& what, const std::string& detail);

// "12.3 GB", "512 MB", "4.0 kB".
std::string bytes_text(double bytes);

}  // namespace vgroove::support
