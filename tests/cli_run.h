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

// Runs `vgroove <args>` (args already shell-quoted where needed).
inline CliRun vgroove(const std::string& args) {
  TempDir dir;
  const std::string err = dir.file("stderr");
  const std::string cmd = std::string("'") + VGROOVE_BIN + "' " + args + " 2>'" + err + "'";
  CliRun r;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) r.out.append(buf, n);
  const int st = ::pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  r.err = read_text(err);
  return r;
}

}  // namespace vgroove::testing_files
