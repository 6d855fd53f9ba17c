#include "vgroove/app/progress.h"
#include "vgroove/support/format.h"
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

namespace {
std::string duration_text(double s) {
  if (s < 99.5) return support::format("%.0f s", s);
  if (s < 99.5 * 60) return support::format("%.0f min", s / 60);
  return support::format("%.1f h", s / 3600);
}
}  // namespace

std::string progress_text(const std::string& label, std::size_t done, std::size_t total, double elapsed_s) {
  const double share = total ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
  std::string line =
      support::format("%s: %zu/%zu work items (%.0f%%)", support::printable(label).c_str(), done, total, 100.0 * share);
  if (done >= total) return line + ", " + duration_text(elapsed_s);
  if (done == 0 || elapsed_s <= 0) return line;
  const double rate = static_cast<double>(done) / elapsed_s;
  return line + support::format(", %.3g per s, about ", rate) +
         duration_text(static_cast<double>(total - done) / rate) + " left";
}

support::ProgressFn terminal_progress(const std::string& label) {
  if (!::isatty(STDERR_FILENO)) return {};
  struct State {
    std::mutex mu;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now(), last = start;
    bool shown = false, finished = false;
    std::size_t width = 0;  // of the last line, to clear what a shorter one leaves
  };
  auto st = std::make_shared<State>();
  return [st, label](std::size_t done, std::size_t total) {
    std::lock_guard<std::mutex> lock(st->mu);
    if (st->finished) return;
    const auto now = std::chrono::steady_clock::now();
    const bool end = done >= total;
    // Nothing for runs under a second; then at most four lines a second, and the last once.
    if (!end && (now - st->start < std::chrono::seconds(1) || now - st->last < std::chrono::milliseconds(250))) return;
    if (end && !st->shown) return;
    st->last = now, st->shown = true, st->finished = end;
    const std::string line = progress_text(label, done, total, std::chrono::duration<double>(now - st->start).count());
    const std::size_t pad = st->width > line.size() ? st->width - line.size() : 0;
    st->width = line.size();
    std::fprintf(stderr, "\r%s%*s%s", line.c_str(), static_cast<int>(pad), "", end ? "\n" : "");
  };
}

}  // namespace vgroove::app
