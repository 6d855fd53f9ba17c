// The subcommands whose work is a script of the Python package (`vgroove plot`: plot.py, `vgroove
// report`: html_report.py): the script is found beside the binary or in the installed package, run
// by Debian's python3 (VGROOVE_PYTHON names another) in a process group of its own, and the stop
// signals (SIGINT, SIGTERM, SIGHUP) are passed on to it; a script that is stopped, or killed with
// vgroove, leaves no temporary file behind.
#pragma once

#include <atomic>
#include <string>
#include <vector>

namespace vgroove::app {

struct PythonScript {
  std::string command;            // the subcommand, first word of its messages: "plot"
  std::string file;               // the script in python/vgroove/: "plot.py"
  std::string needs;              // what the interpreter must have, for the message when it cannot run
  std::string nothing_written;    // said when stopped: "no plot written"
  std::vector<std::string> args;  // after the script's path
  // The directory where the script writes its outputs' temporaries (.NAME.tmp.PID): removed there
  // when a stopped script could not remove them itself.
  std::string output_dir;
  bool dry_run = false;                       // find the script, start nothing
  const std::atomic<bool>* cancel = nullptr;  // set (by SIGINT) before the script starts: it does not start
};

// Runs the script and returns vgroove's exit status: the script's own, or 128 + the signal that
// stopped it (130 when Ctrl-C stopped it before it started). Throws support::UserError when the
// script or the interpreter cannot be found or started.
int run_python_script(const PythonScript& s);

}  // namespace vgroove::app
