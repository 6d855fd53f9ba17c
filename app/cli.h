// vgroove CLI: the command line parsed (CLI11) and dispatched to the subcommands.
#pragma once

#include <atomic>

namespace vgroove::app {

struct CliContext {
  const std::atomic<bool>* cancel = nullptr;  // set to stop a long run (Ctrl-C)
  bool dry_run = false;                       // parse and check every value, then stop before any work (for fuzzing)
};

// Exit status: 0 ok, 1 a threshold exceeded, 2 bad input (one line on stderr), 3 internal error,
// 130 interrupted.
int run_cli(int argc, const char* const* argv, const CliContext& ctx);

}  // namespace vgroove::app
