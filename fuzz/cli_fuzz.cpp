// libFuzzer target: command-line parsing and checking. The input is split at NUL and newline
// bytes into arguments; the CLI runs in dry-run mode (every value checked, no work done). Any input
// must end in an exit status: no crash, no hang, no uncaught exception.
#include "vgroove/app/cli.h"

#include <cstddef>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args{"vgroove"};
  std::string cur;
  for (std::size_t n = 0; n < size && args.size() < 64; ++n) {
    const char c = static_cast<char>(data[n]);
    if (c == '\0' || c == '\n') {
      args.push_back(cur);
      cur.clear();
    } else {
      cur += c;
    }
  }
  args.push_back(cur);
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  const int status = vgroove::app::run_cli(static_cast<int>(argv.size()), argv.data(), {nullptr, true});
  // 0, 1, 2 are the documented outcomes; 3 is an exception that escaped as an internal error.
  if (status < 0 || status > 2) __builtin_trap();
  return 0;
}
