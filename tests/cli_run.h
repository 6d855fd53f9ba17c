// Test helper: run the built vgroove binary (VGROOVE_BIN) and capture its exit status, stdout and
// stderr. Shared by the CLI tests of every subcommand.
#pragma once

#include "tests/test_files.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <thread>

namespace vgroove::testing_files {

struct CliRun {
  int status = -1;  // exit status, -1 if the process did not exit normally
  std::string out, err;
};

inline std::ostream& operator<<(std::ostream& os, const CliRun& r) {
  return os << "exit " << r.status << "\n--- stdout:\n" << r.out << "\n--- stderr:\n" << r.err;
}

// Runs a shell command line, its standard error captured apart.
inline CliRun run_shell(const std::string& cmd) {
  TempDir dir;
  const std::string err = dir.file("stderr");
  CliRun r;
  FILE* p = ::popen(("{ " + cmd + "; } 2>" + quoted(err)).c_str(), "r");
  if (!p) return r;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.err = read_text(err);
  return r;
}

// Runs `vgroove <args>` (args already shell-quoted where needed).
inline CliRun vgroove(const std::string& args) { return run_shell(quoted(VGROOVE_BIN) + " " + args); }

// The number of lines of s (a last line without its newline counts).
inline int lines(const std::string& s) {
  int n = 0;
  for (char c : s) n += c == '\n';
  return n + (!s.empty() && s.back() != '\n');
}

struct Stopped {
  int status = -1;       // exit status, -1 if killed by a signal
  int signal = 0;        // the signal that killed it, if one did
  double seconds = 0.0;  // from the signal to the exit
  std::string out, err;
};

// Whether process pid runs the vgroove binary (sh has exec'd it) and takes sig: caught by a
// handler or blocked (read from /proc/PID/status, SigCgt and SigBlk, bit sig - 1). Before that, a
// signal would end it by its default action, which is not what the tests ask about.
inline bool takes_signal(pid_t pid, int sig) {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec);
  if (ec || exe != std::filesystem::canonical(VGROOVE_BIN, ec)) return false;
  const std::string status = read_text("/proc/" + std::to_string(pid) + "/status");
  unsigned long long mask = 0;
  for (const char* field : {"SigBlk:", "SigCgt:"}) {
    const std::size_t at = status.find(field);
    if (at != std::string::npos) mask |= std::stoull(status.substr(at + std::strlen(field)), nullptr, 16);
  }
  return (mask >> (sig - 1)) & 1ULL;
}

// Runs `env vgroove args` through sh (stdout and stderr to files in dir), waits until `ready` holds
// (by default: vgroove takes sig; at most 30 s, as on a loaded machine, under sanitizers, starting
// can take seconds), sends sig `after` seconds later and waits for the exit (SIGKILL after 30 s).
// A thread in sigtimedwait shows the signals it waits for as unblocked in /proc: a run that waits
// so (plot, report) gives its own `ready`.
inline Stopped signal_after(const std::string& args, int sig, double after, const TempDir& dir,
                            const std::string& env = "", const std::function<bool()>& ready = nullptr) {
  const std::string out = dir.file("sig.out"), err = dir.file("sig.err");
  const std::string cmd = env + " exec " + quoted(VGROOVE_BIN) + " " + args + " >" + quoted(out) + " 2>" + quoted(err);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  const auto started = std::chrono::steady_clock::now();
  const auto exited = [pid] {  // without reaping: the loop below reads the status
    siginfo_t info{};
    return ::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid;
  };
  while (!(ready ? ready() : takes_signal(pid, sig)) && !exited() &&
         std::chrono::steady_clock::now() - started < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::duration<double>(after));
  ::kill(pid, sig);
  const auto t0 = std::chrono::steady_clock::now();
  int st = 0;
  for (;;) {
    if (::waitpid(pid, &st, WNOHANG) == pid) break;
    if (std::chrono::steady_clock::now() - t0 > std::chrono::seconds(30)) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &st, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  Stopped r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.signal = WIFSIGNALED(st) ? WTERMSIG(st) : 0;
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

// For signal_after: the stand-in interpreter of the plot and report tests has written its pid
// (a whole line) to DIR/pid, so the script has started.
inline std::function<bool()> script_started(const TempDir& dir) {
  return [pid = dir.file("pid")] {
    const std::string s = read_text(pid);
    return !s.empty() && s.back() == '\n';
  };
}

}  // namespace vgroove::testing_files
