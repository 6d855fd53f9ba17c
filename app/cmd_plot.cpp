#include "vgroove/app/commands.h"
#include "vgroove/support/printable.h"

#include <cstdio>
#include "vgroove/support/atomic_file.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/plot.h"

namespace vgroove::app {

using namespace validation;

int cmd_plot(const PlotArgs& a) {
  const nlohmann::json report = support::read_json_file(a.report);
  std::string out = a.out;
  if (out.empty()) {
    out = a.report;
    const auto dot = out.rfind(".json");
    out = (dot != std::string::npos && dot + 5 == out.size() ? out.substr(0, dot) : out) + ".svg";
  }
  if (is_brdf_report(report)) {
    // The Fig. 11 grid: one SVG per (NDF, dimension), named after --out (or the report).
    const std::string base =
        out.size() > 4 && out.compare(out.size() - 4, 4, ".svg") == 0 ? out.substr(0, out.size() - 4) : out;
    const auto svgs = brdf_grid_svgs(report, a.report);
    for (const auto& [suffix, svg] : svgs)
      support::check_writable_target(base + "-" + suffix + ".svg", a.force, {a.report});
    if (a.dry_run) return 0;
    for (const auto& [suffix, svg] : svgs) {
      support::write_file_atomically(base + "-" + suffix + ".svg", svg, a.force);
      std::printf("plot: %s\n", support::printable(base + "-" + suffix + ".svg").c_str());
    }
    return 0;
  }
  const std::string svg = accuracy_svg(report, a.report);
  const std::string cost = cost_svg(report);
  const std::string cost_out =
      (out.size() > 4 && out.compare(out.size() - 4, 4, ".svg") == 0 ? out.substr(0, out.size() - 4) : out) +
      "-cost.svg";
  support::check_writable_target(out, a.force, {a.report});
  if (!cost.empty()) support::check_writable_target(cost_out, a.force, {a.report});
  if (a.dry_run) return 0;
  support::write_file_atomically(out, svg, a.force);
  std::printf("plot: %s\n", support::printable(out).c_str());
  if (!cost.empty()) {
    support::write_file_atomically(cost_out, cost, a.force);
    std::printf("plot: %s\n", support::printable(cost_out).c_str());
  }
  return 0;
}

}  // namespace vgroove::app
