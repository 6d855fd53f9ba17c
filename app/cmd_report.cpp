#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"
#include "vgroove/app/python_script.h"

#include <filesystem>
#include <string>

namespace vgroove::app {

int cmd_report(const ReportArgs& a) {
  // The page is html_report.py's (standard library only; plot.py draws a figure that is missing),
  // run as `vgroove plot` runs plot.py: it reads the directory, names what it skips and writes the
  // page whole or not at all.
  PythonScript s;
  s.command = "report";
  s.file = "html_report.py";
  s.needs =
      "the report needs Debian's python3 (scripts/install-deps.sh; python3-matplotlib to draw missing plots), or "
      "VGROOVE_PYTHON naming another interpreter";
  s.nothing_written = "no report written";
  if (!a.out.empty()) s.args.insert(s.args.end(), {"--out", a.out});
  if (a.force) s.args.push_back("--force");
  if (a.no_draw) s.args.push_back("--no-draw");
  s.args.insert(s.args.end(), {"--", a.directory});  // a directory named like an option stays the directory
  // The page's temporary lies beside it (default: DIRECTORY/index.html).
  const std::filesystem::path target =
      a.out.empty() ? std::filesystem::path(a.directory) / "index.html" : std::filesystem::path(a.out);
  s.output_dir = target.has_parent_path() ? target.parent_path().string() : ".";
  s.dry_run = a.dry_run;
  s.cancel = a.cancel;
  return run_python_script(s);
}

void add_report_command(CLI::App& app, Commands& commands) {
  auto* report = app.add_subcommand(
      "report",
      "Write one self-contained HTML page (plots embedded, no script, nothing loaded) of every report in a "
      "directory: verdicts, the paper's figures beside ours, thresholds, worst cases, wall times, versions, "
      "seeds and the plots of `vgroove plot` (a missing one drawn for the page). Runs python/vgroove/html_report.py.");
  ReportArgs& ra = commands.add(report, cmd_report);
  ra.cancel = commands.context().cancel;
  add_text(report, "directory", ra.directory, "the directory of the reports, e.g. results/")->required();
  add_text(report, "--out", ra.out,
           "page to write (default: DIRECTORY/index.html; refuses to overwrite without --force)");
  report->add_flag("--force", ra.force, "overwrite an existing page");
  report->add_flag("--no-draw", ra.no_draw, "name the plots missing beside their reports instead of drawing them");
}

}  // namespace vgroove::app
