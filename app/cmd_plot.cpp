#include "vgroove/app/cli_options.h"
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

void add_plot_command(CLI::App& app, Commands& commands) {
  auto* plot = app.add_subcommand(
      "plot",
      "Draw a report with matplotlib (from the JSON alone, nothing recomputed): Table 1 heatmaps, the Fig. 11 "
      "grids, the furnace, Table 2, accuracy against time and cost, check_brdf. Runs python/vgroove/plot.py "
      "with Debian's python3 (VGROOVE_PYTHON names another); writes every figure or none.");
  PlotArgs& pa = commands.add(plot, cmd_plot);
  pa.cancel = commands.context().cancel;
  add_text(plot, "report", pa.report, "report JSON (vgroove validate --out, vgroove bench accuracy --out)")->required();
  add_text(plot, "--out", pa.out,
           "image to write, or its base name (default: the report's name without .json); figures after "
           "the first get a suffix (-ggx-3d, -cost)");
  add_text(plot, "--format", pa.format, "png (default), svg or pdf");
  plot->add_flag("--force", pa.force, "overwrite existing images");
}

}  // namespace vgroove::app
