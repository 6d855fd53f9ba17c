// vgroove CLI: what the subcommands' registrations share. Each app/cmd_*.cpp registers its own
// subcommand and flags (add_*_command, commands.h) with these option adders, whose validators read
// numbers strictly and in range (options.h) before CLI11 converts them and throw a UserError naming
// the option; and `Commands`, the registry from which run_cli runs the subcommand parsed.
#pragma once

#include "vgroove/app/cli.h"
#include "vgroove/app/commands.h"

#include <CLI/CLI.hpp>

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace vgroove::app {

CLI::Validator strict_integer(const std::string& name, long long lo, long long hi, const std::string& note = "");
CLI::Validator strict_real(const std::string& name);
CLI::Validator non_empty(const std::string& name);
std::string range_text(long long lo, long long hi);  // "[lo, hi]"

// An integer option in [lo, hi]; its help ends with the range (and `note`, also in its messages).
template <class T>
CLI::Option* add_integer(CLI::App* app, const std::string& name, T& v, const std::string& help, long long lo,
                         long long hi, const std::string& note = "") {
  return app->add_option(name, v, help + ", " + range_text(lo, hi))->transform(strict_integer(name, lo, hi, note));
}
template <class T>
CLI::Option* add_real(CLI::App* app, const std::string& name, T& v, const std::string& help) {
  return app->add_option(name, v, help)->transform(strict_real(name));
}
template <class T>
CLI::Option* add_text(CLI::App* app, const std::string& name, T& v, const std::string& help) {
  return app->add_option(name, v, help)->check(non_empty(name));
}
// Comma-separated values in one option (--ndf ggx,phong), each non-empty.
template <class T>
CLI::Option* add_list(CLI::App* app, const std::string& name, std::vector<T>& v, const std::string& help) {
  return add_text(app, name, v, help)->delimiter(',')->capture_default_str();
}
CLI::Option* add_threads(CLI::App* app, int& v);
CLI::Option* add_seed(CLI::App* app, long long& v, const std::string& help);
// --shard I/N (its range: support::kMaxShards); `joined` says what `vgroove merge` makes of the
// parts.
CLI::Option* add_shard(CLI::App* app, std::string& v, const std::string& joined);
// --theta-v-deg for a symmetric groove, or --theta-l-deg with --theta-r-deg for a nonsymmetric one.
void add_groove_options(CLI::App* app, GrooveArgs& g);

// The registered subcommands, each with the arguments its options fill and the function that runs
// on them.
class Commands {
 public:
  explicit Commands(const CliContext& ctx) : ctx_(ctx) {}
  const CliContext& context() const { return ctx_; }
  // Registers `cmd` to run on the arguments `sub` parsed into; returns those arguments (they live as
  // long as the registry), with dry_run set from the context.
  template <class Args>
  Args& add(CLI::App* sub, int (*cmd)(const Args&)) {
    auto args = std::make_shared<Args>();
    args->dry_run = ctx_.dry_run;
    entries_.push_back({sub, [args, cmd] { return cmd(*args); }});
    return *args;
  }
  // The run of the subcommand parsed: its exit status (0 when none was parsed).
  int run_parsed() const {
    for (const auto& [sub, run] : entries_)
      if (*sub) return run();
    return 0;
  }

 private:
  CliContext ctx_;
  std::vector<std::pair<CLI::App*, std::function<int()>>> entries_;
};

}  // namespace vgroove::app
