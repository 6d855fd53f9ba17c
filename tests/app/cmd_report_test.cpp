// `vgroove report` through the built binary: it runs html_report.py as `vgroove plot` runs plot.py
// (app/python_script.h): the stop signals reach the script, vgroove exits 128 + the signal after
// it, and the page's temporary beside its target is gone; the script's status is vgroove's; the
// interpreter that cannot run and a missing directory argument are one-line errors (exit 2). The
// page itself: tests/python/test_html_report*.py.
#include "tests/cli_run.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace vgroove::app {
namespace {

namespace fs = std::filesystem;
using testing_files::quoted;
using testing_files::read_text;
using testing_files::script_started;
using testing_files::signal_after;
using testing_files::Stopped;
using testing_files::TempDir;
using testing_files::write_text;

// An interpreter standing in for python3 (VGROOVE_PYTHON): it writes its pid and its arguments,
// starts the page's temporary as html_report.py does (.index.html.tmp.PID beside the target, here
// the directory's index.html), takes `seconds` and renames it into place.
std::string fake_python(const TempDir& dir, const std::string& seconds) {
  const std::string f = dir.file("fake-python");
  const std::string tmp = quoted(dir.file("run/.index.html.tmp.")) + "$$";
  write_text(f, "#!/bin/sh\necho $$ > " + quoted(dir.file("pid")) + "\necho \"$@\" > " + quoted(dir.file("args")) +
                    "\n: > " + tmp + "\nsleep " + seconds + "\nmv " + tmp + " " + quoted(dir.file("run/index.html")) +
                    "\n");
  ::chmod(f.c_str(), 0755);
  fs::create_directory(dir.file("run"));
  return f;
}

bool no_temporaries(const TempDir& dir) {
  for (const auto& e : fs::directory_iterator(dir.file("run")))
    if (e.path().filename().string().find(".tmp") != std::string::npos) return false;
  return true;
}

TEST(CmdReport, PassesStopSignalsToItsScript) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    TempDir dir;
    const std::string env = "VGROOVE_PYTHON=" + quoted(fake_python(dir, "1.5"));
    const Stopped r = signal_after("report " + quoted(dir.file("run")), sig, 0.2, dir, env, script_started(dir));
    EXPECT_EQ(r.status, 128 + sig) << "signal " << sig << "\n" << r.err;
    EXPECT_LT(r.seconds, 1.5) << "signal " << sig;
    EXPECT_CONTAINS(r.err, "vgroove: interrupted; no report written");
    // Nothing written after vgroove's exit, no temporary left.
    std::this_thread::sleep_for(std::chrono::milliseconds(1700));
    EXPECT_FALSE(fs::exists(dir.file("run/index.html"))) << "signal " << sig;
    EXPECT_TRUE(no_temporaries(dir)) << "signal " << sig;
  }
}

TEST(CmdReport, RunsHtmlReportWithItsOptions) {
  TempDir dir;
  const std::string env = "VGROOVE_PYTHON=" + quoted(fake_python(dir, "0"));
  const testing_files::CliRun r = testing_files::run_shell(env + " " + quoted(VGROOVE_BIN) + " report " +
                                                           quoted(dir.file("run")) + " --force --no-draw");
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_TRUE(fs::exists(dir.file("run/index.html")));
  // The script, then its options, then the directory after "--" (a directory named like an option
  // stays the directory).
  const std::string args = read_text(dir.file("args"));
  EXPECT_NE(args.find("/vgroove/html_report.py --force --no-draw -- " + dir.file("run")), std::string::npos) << args;
}

TEST(CmdReport, OneLineErrors) {
  TempDir dir;
  const testing_files::CliRun none = testing_files::vgroove("report");
  EXPECT_EQ(none.status, 2) << none;
  EXPECT_EQ(none.err, "vgroove: error: directory is required (see vgroove --help)\n");
  const testing_files::CliRun missing =
      testing_files::run_shell("VGROOVE_PYTHON=" + quoted(dir.file("none")) + " " + quoted(VGROOVE_BIN) + " report " +
                               quoted(dir.path().string()));
  EXPECT_EQ(missing.status, 2) << missing;
  EXPECT_EQ(missing.err, "vgroove: error: report: cannot run " + dir.file("none") +
                             " (No such file or directory): the report needs Debian's python3 "
                             "(scripts/install-deps.sh; python3-matplotlib to draw missing plots), or VGROOVE_PYTHON "
                             "naming another interpreter\n");
  const testing_files::CliRun empty = testing_files::vgroove("report " + quoted(dir.path().string()));
  EXPECT_EQ(empty.status, 2) << empty;
  EXPECT_EQ(empty.err, "vgroove: error: " + dir.path().string() +
                           ": holds no report (*.json); vgroove validate SUITE " + "--out " + dir.path().string() +
                           "/NAME.json writes one\n");
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace vgroove::app
