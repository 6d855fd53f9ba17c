// vgroove support: wall time, in seconds, from a point of the monotonic clock (the timings that
// reports carry beside their figures, never compared between runs).
#pragma once

#include <chrono>

namespace vgroove::support {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

}  // namespace vgroove::support
