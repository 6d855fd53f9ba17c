// Tests of the vgroove command line under signals, through the built binary (issue 36, items 4
// and 8): Ctrl-C inside the loops of `sample` (every mode), `brdf --directions` and the profiles
// and nonsymmetric suites stops the run within about a second with the status and line of every
// interrupted run (130, "interrupted; no report written") and no output; SIGINT, SIGTERM and SIGHUP
// to `vgroove plot` reach the plot script, which writes nothing after vgroove has exited.
#include "tests/cli_run.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace vgroove::app {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing_files::quoted;
using testing_files::read_text;
using testing_files::script_started;
using testing_files::signal_after;
using testing_files::Stopped;
using testing_files::TempDir;
using testing_files::write_text;

bool no_temporaries(const TempDir& dir) {
  for (const std::string& e : dir.entries())
    if (e.find(".tmp") != std::string::npos) return false;
  return true;
}

// Ctrl-C after 1 s: exit 130 with the line every interrupted run prints, within 3 s (the loops
// read the flag every few milliseconds of work; 3 s allows for a loaded machine and sanitizers),
// nothing on stdout and no file at `out` (when given).
void expect_prompt_stop(const std::string& args, const TempDir& dir, const std::string& out = "") {
  const Stopped r = signal_after(args, SIGINT, 1.0, dir);
  EXPECT_EQ(r.status, 130) << args << "\n" << r.err;
  EXPECT_LT(r.seconds, 3.0) << args;
  EXPECT_CONTAINS(r.err, "vgroove: interrupted; no report written");
  EXPECT_EQ(r.out, "") << args;
  if (!out.empty()) {
    EXPECT_FALSE(fs::exists(out)) << args;
  }
  EXPECT_TRUE(no_temporaries(dir)) << args;
}

std::string suite_file(const std::string& name) { return std::string(VGROOVE_SOURCE_DIR) + "/data/suites/" + name; }

// ---------------------------------------------------------------------------------------------
// Item 4: Ctrl-C inside `sample`, `brdf --directions`, profiles and nonsymmetric suites.

TEST(CliSignals, SampleStopsWhileDrawing) {
  TempDir dir;
  const std::string out = dir.file("s.json");
  for (const std::string mode :
       {"", "--dim flatland", "--model vgroove-nonsymmetric", "--model vgroove-nonsymmetric --dim flatland"})
    expect_prompt_stop("sample --n 1000000000 " + mode + " --out " + quoted(out), dir, out);
}

TEST(CliSignals, SampleStopsInsideTheCellIntegrals) {
  // Few samples, many cells (or the nonsymmetric pdf at ~1 ms an evaluation): minutes of quadrature.
  TempDir dir;
  const std::string out = dir.file("s.json");
  for (const std::string mode : {"--cos-bins 1000 --phi-bins 1000", "--model vgroove-nonsymmetric --cos-bins 2",
                                 "--model vgroove-nonsymmetric --dim flatland --theta-bins 10000"})
    expect_prompt_stop("sample --n 1000 " + mode + " --out " + quoted(out), dir, out);
}

TEST(CliSignals, BrdfDirectionsStopsBetweenPairs) {
  TempDir dir;
  // The nonsymmetric model in flatland: ~0.8 ms a pair (20000: ~16 s); 3D near the horizon: up to
  // ~20 ms a pair.
  json flat, three;
  for (int n = 0; n < 20000; ++n) flat["directions"].push_back({{"theta_i_deg", 30}, {"theta_o_deg", -20 + 1e-4 * n}});
  for (int n = 0; n < 100000; ++n)
    three["directions"].push_back(
        {{"theta_i_deg", 89.99}, {"theta_o_deg", 89.99}, {"phi_i_deg", 0}, {"phi_o_deg", 90 + 1e-3 * n}});
  const std::string f = dir.file("flat.json"), t = dir.file("three.json");
  write_text(f, flat.dump());
  write_text(t, three.dump());
  expect_prompt_stop("brdf --model vgroove-nonsymmetric --dim flatland --directions " + quoted(f), dir);
  expect_prompt_stop("brdf --model vgroove-nonsymmetric --dim flatland --directions " + quoted(f) + " --json", dir);
  expect_prompt_stop("brdf --directions " + quoted(t) + " --json", dir);
}

TEST(CliSignals, ProfilesSuiteStopsInsideACase) {
  // One case at a time, each stopped in its beams (10^9 rays) or its Smith walk (10^9 paths): a
  // case run to its end would take hours.
  TempDir dir;
  const std::string out = dir.file("r.json"), suite = suite_file("profiles.json");
  expect_prompt_stop("validate " + quoted(suite) + " --rays 1000000000 --threads 1 --out " + quoted(out), dir, out);
  json j = json::parse(read_text(suite));
  j["walk_paths"] = 1000000000;
  const std::string walk = dir.file("walk.json");
  write_text(walk, j.dump());
  expect_prompt_stop("validate " + quoted(walk) + " --threads 1 --out " + quoted(out), dir, out);
}

TEST(CliSignals, NonsymmetricSuiteStopsInsideACase) {
  // A case stopped in its tracing (10^9 rays) or in its 3D lobes' quadrature (90 x 72 bins: about a
  // minute for the pair of lobes, which the stop does not wait for).
  TempDir dir;
  const std::string out = dir.file("r.json");
  expect_prompt_stop("validate " + quoted(suite_file("nonsymmetric_brdf.json")) +
                         " --rays 1000000000 --threads 1 --out " + quoted(out),
                     dir, out);
  const std::string lobe = dir.file("lobe.json");
  write_text(lobe, R"({"name": "lobe", "kind": "nonsymmetric_brdf", "ndf": ["ggx"], "alpha": [0.5],
    "theta_i_deg": [40], "dimensions": ["3d"], "rays": 1000, "grooves": 1000, "theta_bins": 90, "phi_bins": 72,
    "reciprocity_pairs": 0, "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-3, "3d": 3e-3}}})");
  expect_prompt_stop("validate " + quoted(lobe) + " --out " + quoted(out), dir, out);
}

// ---------------------------------------------------------------------------------------------
// Item 8: the signals that stop `vgroove plot` reach its script.

// An interpreter standing in for python3 (VGROOVE_PYTHON): it writes its pid, starts a temporary
// file as plot.py does (.NAME.tmp.PID beside the target), takes `seconds` and then renames it into
// place.
std::string fake_python(const TempDir& dir, const std::string& seconds) {
  const std::string f = dir.file("fake-python");
  write_text(f,
             "#!/bin/sh\n"
             "echo $$ > " +
                 quoted(dir.file("pid")) +
                 "\n"
                 ": > " +
                 quoted(dir.file(".fig.png.tmp.")) +
                 "$$\n"
                 "sleep " +
                 seconds +
                 "\n"
                 "mv " +
                 quoted(dir.file(".fig.png.tmp.")) + "$$ " + quoted(dir.file("fig.png")) + "\n");
  ::chmod(f.c_str(), 0755);
  return f;
}

// A process that has exited (reaped or a zombie) or never was.
bool gone(pid_t pid) {
  if (::kill(pid, 0) != 0) return true;
  const std::string stat = read_text("/proc/" + std::to_string(pid) + "/stat");
  const std::size_t p = stat.rfind(')');
  return p != std::string::npos && p + 2 < stat.size() && stat[p + 2] == 'Z';
}

TEST(CliSignals, PlotPassesStopSignalsToItsScript) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    TempDir dir;
    const std::string report = dir.file("r.json");
    write_text(report, "{}");
    const std::string env = "VGROOVE_PYTHON=" + quoted(fake_python(dir, "1.5"));
    const Stopped r = signal_after("plot " + quoted(report) + " --out " + quoted(dir.file("fig.png")), sig, 0.2, dir,
                                   env, script_started(dir));
    // vgroove exits at once, as a process stopped by the signal would (128 + sig), after its script.
    EXPECT_EQ(r.status, 128 + sig) << "signal " << sig << "\n" << r.err;
    EXPECT_LT(r.seconds, 1.5) << "signal " << sig;
    EXPECT_CONTAINS(r.err, "vgroove: interrupted; no plot written");
    const pid_t script = static_cast<pid_t>(std::stol("0" + read_text(dir.file("pid"))));
    ASSERT_GT(script, 0) << "the script did not start";
    EXPECT_TRUE(gone(script)) << "signal " << sig << ": the script outlived vgroove";
    // Nothing written after vgroove's exit: no figure once the script would have finished.
    std::this_thread::sleep_for(std::chrono::milliseconds(1700));
    EXPECT_FALSE(fs::exists(dir.file("fig.png"))) << "signal " << sig;
    EXPECT_TRUE(no_temporaries(dir)) << "signal " << sig;
  }
}

TEST(CliSignals, PlotUnsignalledKeepsItsScriptsStatus) {
  TempDir dir;
  const std::string report = dir.file("r.json");
  write_text(report, "{}");
  const std::string env = "VGROOVE_PYTHON=" + quoted(fake_python(dir, "0"));
  const testing_files::CliRun r = testing_files::run_shell(env + " " + quoted(VGROOVE_BIN) + " plot " + quoted(report) +
                                                           " --out " + quoted(dir.file("fig.png")));
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_TRUE(fs::exists(dir.file("fig.png")));
  EXPECT_TRUE(no_temporaries(dir));
  const testing_files::CliRun missing = testing_files::run_shell("VGROOVE_PYTHON=" + quoted(dir.file("none")) + " " +
                                                                 quoted(VGROOVE_BIN) + " plot " + quoted(report));
  EXPECT_EQ(missing.status, 2) << missing;
  EXPECT_CONTAINS(missing.err, "plot: cannot run " + dir.file("none") + " (No such file or directory)");
}

}  // namespace
}  // namespace vgroove::app
