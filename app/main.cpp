// vgroove: check the kaleidoscopic V-groove model (Lee et al. 2018) against exact 2D tracing.
// Parse, run, report: the command line is in cli.cpp, the work in the cmd_*.cpp files.
#include "vgroove/app/cli.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/support/std_streams.h"

#include <atomic>
#include <csignal>

namespace {
// Set by the first Ctrl-C; every long loop polls it (support::cancelled) and the run stops
// without writing a report. A second Ctrl-C ends the process at once (the handler restores the
// default action).
std::atomic<bool> interrupted{false};
extern "C" void on_sigint(int) {
  interrupted.store(true);
  std::signal(SIGINT, SIG_DFL);
}
}  // namespace

int main(int argc, char** argv) {
  vgroove::support::guard_standard_descriptors();
  vgroove::app::world_init(&argc, &argv);
  std::signal(SIGINT, on_sigint);
  const int status = vgroove::app::run_cli(argc, argv, {&interrupted, false});
  vgroove::app::world_finalize();
  return status;
}
