// Test helper: run the built vgroove binary (VGROOVE_BIN) and capture its exit status, stdout and
// stderr. Shared by the CLI tests of every subcommand.
#pragma once

#include "tests/test_files.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
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

// Runs `env vgroove args` through sh (stdout and stderr to files in dir), sends sig after `after`
// seconds and waits for the exit (SIGKILL after 30 s).
inline Stopped signal_after(const std::string& args, int sig, double after, const TempDir& dir,
                            const std::string& env = "") {
  const std::string out = dir.file("sig.out"), err = dir.file("sig.err");
  const std::string cmd = env + " exec " + quoted(VGROOVE_BIN) + " " + args + " >" + quoted(out) + " 2>" + quoted(err);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
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

}  // namespace vgroove::testing_files
