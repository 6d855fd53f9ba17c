#include "vgroove/app/progress.h"
#include "vgroove/support/printable.h"

#include "vgroove/app/commands.h"

#include <unistd.h>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <mutex>

namespace vgroove::app {

int interrupted_no_report() {
  std::cerr << "\nvgroove: interrupted; no report written\n";
  return kExitInterrupted;
}

support::ProgressFn terminal_progress(const std::string& label) {
  if (!::isatty(STDERR_FILENO)) return {};
  auto start = std::chrono::steady_clock::now();
  auto last = std::make_shared<std::chrono::steady_clock::time_point>(start);
  auto mu = std::make_shared<std::mutex>();
  return [=](std::size_t done, std::size_t total) {
    std::lock_guard<std::mutex> lock(*mu);
    const auto now = std::chrono::steady_clock::now();
    if (done < total && now - *last < std::chrono::milliseconds(250)) return;
    if (now - start < std::chrono::seconds(1) && done < total) return;
    *last = now;
    std::fprintf(stderr, "\r%s: %zu/%zu cases (%.0f%%)%s", support::printable(label).c_str(), done, total,
                 100.0 * static_cast<double>(done) / static_cast<double>(total), done == total ? "\n" : "");
  };
}

}  // namespace vgroove::app
