#include "vgroove/app/commands.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>
#include "vgroove/support/user_error.h"

extern char** environ;

namespace vgroove::app {

namespace {

namespace fs = std::filesystem;

// The plot script (python/vgroove/plot.py): beside the binary in the build tree
// (build/python/vgroove/plot.py), or in the installed Python package (PREFIX/bin/vgroove ->
// PREFIX/VGROOVE_PYTHON_INSTALL_DIR/vgroove/plot.py).
std::string plot_script() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const fs::path& p : {exe.parent_path() / "python" / "vgroove" / "plot.py",
                              exe.parent_path().parent_path() / VGROOVE_PYTHON_INSTALL_DIR / "vgroove" / "plot.py"})
      if (fs::is_regular_file(p, ec)) return p.string();
  }
  throw support::UserError(
      "plot: the plot script (python/vgroove/plot.py) is neither beside this binary nor in its installed Python "
      "package (" VGROOVE_PYTHON_INSTALL_DIR ")");
}

}  // namespace

int cmd_plot(const PlotArgs& a) {
  if (!a.format.empty() && a.format != "png" && a.format != "svg" && a.format != "pdf")
    throw support::UserError("--format = \"" + a.format + "\" is not one of \"png\", \"svg\", \"pdf\"");
  // Drawing is matplotlib's: the work is plot.py's, run by Debian's interpreter (VGROOVE_PYTHON
  // names another). It validates the report, renders every figure and writes all or nothing.
  const char* env = std::getenv("VGROOVE_PYTHON");
  const std::string python = env && *env ? env : VGROOVE_PYTHON_EXECUTABLE;
  const std::string script = plot_script();
  std::vector<std::string> args = {python, script, a.report};
  if (!a.out.empty()) args.insert(args.end(), {"--out", a.out});
  if (!a.format.empty()) args.insert(args.end(), {"--format", a.format});
  if (a.force) args.push_back("--force");
  if (a.dry_run) return 0;  // the report is the script's to check; a dry run starts nothing
  // A report named like an option must stay the report: after "--" argparse reads no options.
  if (!a.report.empty() && a.report[0] == '-') args.insert(args.begin() + 2, "--");
  std::vector<char*> argv;
  for (std::string& s : args) argv.push_back(s.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (const int err = posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ); err != 0)
    throw support::UserError("plot: cannot run " + python + " (" + std::strerror(err) +
                             "): plots need Debian's python3 with python3-matplotlib (scripts/install-deps.sh), "
                             "or VGROOVE_PYTHON naming an interpreter that has matplotlib");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR)
      throw support::UserError(std::string("plot: waiting for the plot script: ") + std::strerror(errno));
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 3;
}

}  // namespace vgroove::app
