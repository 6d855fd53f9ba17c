#include "vgroove/app/commands.h"
#include "vgroove/app/python_script.h"
#include "vgroove/support/user_error.h"

#include <filesystem>
#include <string>

namespace vgroove::app {

int cmd_plot(const PlotArgs& a) {
  if (!a.format.empty() && a.format != "png" && a.format != "svg" && a.format != "pdf")
    throw support::UserError("--format = \"" + a.format + "\" is not one of \"png\", \"svg\", \"pdf\"");
  // Drawing is matplotlib's: the work is plot.py's, run by Debian's interpreter (VGROOVE_PYTHON
  // names another). It validates the report, renders every figure and writes all or nothing.
  PythonScript s;
  s.command = "plot";
  s.file = "plot.py";
  s.needs =
      "plots need Debian's python3 with python3-matplotlib (scripts/install-deps.sh), or VGROOVE_PYTHON naming an "
      "interpreter that has matplotlib";
  s.nothing_written = "no plot written";
  // A report named like an option must stay the report: after "--" argparse reads no options.
  if (!a.report.empty() && a.report[0] == '-') s.args.push_back("--");
  s.args.push_back(a.report);
  if (!a.out.empty()) s.args.insert(s.args.end(), {"--out", a.out});
  if (!a.format.empty()) s.args.insert(s.args.end(), {"--format", a.format});
  if (a.force) s.args.push_back("--force");
  // The figures' temporaries lie beside their targets.
  const std::filesystem::path target(a.out.empty() ? a.report : a.out);
  s.output_dir = target.has_parent_path() ? target.parent_path().string() : ".";
  s.dry_run = a.dry_run;
  s.cancel = a.cancel;
  return run_python_script(s);
}

}  // namespace vgroove::app
