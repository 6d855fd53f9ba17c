// Test helper: run the built vgroove binary (VGROOVE_BIN) and capture its exit status, stdout and
// stderr. Shared by the CLI tests of every subcommand.
#pragma once

#include "tests/test_files.h"

#include <sys/wait.h>
#include <cstdio>
#include <ostream>
#include <string>

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

}  // namespace vgroove::testing_files
