#include "vgroove/app/cli.h"

#include "vgroove/app/cli_options.h"
#include "vgroove/app/distributed.h"
#include "vgroove/app/mpi_world.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/std_streams.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/report.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <iostream>
#include <iterator>
#include <new>
#include <string>
#include <vector>

namespace vgroove::app {

namespace {

// Every rank of an MPI run sees the same input errors: rank 0 alone prints them.
void print_error(const std::string& what) {
  if (world().root()) std::cerr << "vgroove: error: " << support::printable(what) << "\n";
}

int run_command(int argc, const char* const* argv, const CliContext& ctx) {
  CLI::App app{
      "vgroove: traces light exactly through 2D V-grooves and checks the kaleidoscopic model of\n"
      "Lee et al. 2018 (\"Practical Multiple Scattering for Rough Surfaces\") against it.\n"
      "Angles in degrees, measured from the surface normal, counter-clockwise positive\n"
      "(theta_i > 0: light from the upper left). Exit status: 0 ok, 1 a threshold exceeded, 2 bad input\n"
      "or output that could not be written, 3 internal error, 130 interrupted (Ctrl-C)."};
  app.set_version_flag("--version", std::string("vgroove ") + validation::version_string() + " (git " +
                                        validation::git_revision() + ")");
  app.require_subcommand(1);

  Commands commands(ctx);
  add_trace_command(app, commands);
  add_analytic_command(app, commands);
  add_validate_command(app, commands);
  auto* bench = app.add_subcommand("bench", "Benchmarks: what accuracy costs in time.");
  bench->require_subcommand(1);
  add_bench_accuracy_command(*bench, commands);
  add_plot_command(app, commands);
  add_simulate_command(app, commands);
  add_sample_command(app, commands);
  add_bins_command(app, commands);
  add_brdf_command(app, commands);
  add_energy_command(app, commands);
  add_merge_command(app, commands);
  add_report_command(app, commands);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, like every other input error.
    print_error(std::string(e.what()) + " (see vgroove --help)");
    return 2;
  } catch (const support::UserError& e) {
    print_error(e.what());
    return 2;
  }
  try {
    return commands.run_parsed();
  } catch (const support::UserError& e) {
    print_error(e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    print_error(
        "out of memory: the run needs more memory than this process may use (fewer rays, cases, grooves, "
        "bins or threads need less)");
    return 2;
  } catch (const RankFailure& e) {
    print_error(std::string(e.what()) + "; no report written");
    return e.interrupted ? kExitInterrupted : 3;
  } catch (const std::exception& e) {
    std::cerr << "vgroove: internal error: " << support::printable(e.what()) << "\n";
    return 3;
  }
}

}  // namespace

namespace {
// The comma-separated list options (energy's grid, bench accuracy's runs): CLI11 drops empty items
// and runs a repeated one twice, so both are refused here, naming the option: "" when fine.
std::string list_problem(int argc, const char* const* argv) {
  static const char* const kLists[] = {"--ndf", "--dim", "--mu", "--alpha", "--rays", "--sampling"};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    std::string name = arg, value;
    if (const auto eq = arg.find('='); arg.rfind("--", 0) == 0 && eq != std::string::npos)
      name = arg.substr(0, eq), value = arg.substr(eq + 1);
    else if (i + 1 < argc)
      value = argv[i + 1];
    if (std::find(std::begin(kLists), std::end(kLists), name) == std::end(kLists) ||
        value.find(',') == std::string::npos)
      continue;
    std::vector<std::string> items;
    for (std::size_t b = 0;;) {
      const std::size_t e = value.find(',', b);
      items.push_back(value.substr(b, e == std::string::npos ? std::string::npos : e - b));
      if (e == std::string::npos) break;
      b = e + 1;
    }
    for (std::size_t n = 0; n < items.size(); ++n) {
      if (items[n].empty())
        return name + " = \"" + value + "\" has an empty item (items are separated by single commas)";
      for (std::size_t m = 0; m < n; ++m)
        if (items[m] == items[n])
          return name + " = \"" + value + "\" gives " + items[n] + " twice (each item is run once: give it once)";
    }
  }
  return "";
}
}  // namespace

int run_cli(int argc, const char* const* argv, const CliContext& ctx) {
  // Paths and names reach the reports as JSON text, which holds UTF-8 only: refused before the work.
  for (int i = 1; i < argc; ++i)
    if (!support::valid_utf8(argv[i])) {
      print_error("argument " + std::to_string(i) + " = \"" + std::string(argv[i]) +
                  "\" is not valid UTF-8 (reports hold paths and names as JSON text): rename it or give another path");
      return 2;
    }
  if (const std::string problem = list_problem(argc, argv); !problem.empty()) {
    print_error(problem);
    return 2;
  }
  const int status = run_command(argc, argv, ctx);
  // Output that did not reach its destination (a full disk, a closed stdout) is a failure.
  if (const std::string failed = support::flush_standard_output(); !failed.empty()) {
    print_error(failed);
    return status == kExitInterrupted ? status : 2;
  }
  return status;
}

}  // namespace vgroove::app
