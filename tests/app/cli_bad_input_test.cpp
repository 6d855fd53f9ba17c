// Tests of the vgroove command line under hostile use, through the built binary: odd output
// targets, Ctrl-C inside long loops, deep or duplicated JSON, full disks and closed streams,
// thread and memory limits, pipes, strict numbers, control characters. Each class of defect is
// tried with the example that found it and at least one other member.
#include "tests/cli_run.h"
#include "tests/sanitized.h"
#include "tests/test_files.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <thread>

namespace vgroove::validation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing_files::CliRun;
using testing_files::read_text;
using testing_files::TempDir;
using testing_files::vgroove;
using testing_files::write_text;

using testing_files::lines;
using testing_files::quoted;
using testing_files::run_shell;
using testing_files::type_of;
const std::string kBin = std::string("'") + VGROOVE_BIN + "'";

// AddressSanitizer reserves terabytes of address space at start-up: under `ulimit -v` a sanitized
// binary does not start at all, so the tests of address-space limits need a plain build.
using testing_files::kSanitized;

// Bad input: exit 2, one line on stderr holding `part`.
void expect_refused(const CliRun& r, const std::string& part) {
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_EQ(lines(r.err), 1) << r;
  EXPECT_CONTAINS(r.err, part);
}

bool no_temporaries(const TempDir& dir) {
  for (const std::string& e : dir.entries())
    if (e.find("vgroove-tmp") != std::string::npos) return false;
  return true;
}

// A table1 suite of 2 x 3 quick cases.
std::string small_suite(const TempDir& dir, const std::string& name = "small.json") {
  const std::string f = dir.file(name);
  write_text(f, R"({"name": "small", "kind": "table1",
    "groove": {"type": "symmetric", "theta_v_deg": [30, 90]}, "theta_i_deg": [-40, 0, 25], "rays": 200,
    "thresholds": {"max_l1": 0.05, "mean_l1": 0.05, "max_theta_o_error_rad": 1e-9}})");
  return f;
}

std::string small_scene(const TempDir& dir, const std::string& extra_light = "") {
  const std::string f = dir.file("scene.json");
  write_text(f, R"({"scene": "s", "geometry": {"kind": "groove", "theta_v_deg": 60},
    "light": {"theta_i_deg": [0, 30], "rays": 1000)" +
                    extra_light + R"(}, "effects": {"fresnel": {"kind": "none"}}})");
  return f;
}

// ---------------------------------------------------------------------------------------------
// 1. --out onto what is not a regular file: write through or refuse, never replace.

TEST(CliOutput, CharacterDevicesAreWrittenThroughNeverReplaced) {
  TempDir dir;
  const std::string suite = small_suite(dir);
  // /dev/null itself: written through (as root a replaced /dev/null would break the system).
  const CliRun r = vgroove("validate " + quoted(suite) + " --out /dev/null --force");
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_EQ(type_of("/dev/null"), static_cast<mode_t>(S_IFCHR));
  if (::geteuid() != 0) GTEST_SKIP() << "copies of /dev/null and /dev/full need mknod (root)";
  const std::string null_copy = dir.file("null"), full_copy = dir.file("full");
  ASSERT_EQ(::mknod(null_copy.c_str(), S_IFCHR | 0666, makedev(1, 3)), 0);
  ASSERT_EQ(::mknod(full_copy.c_str(), S_IFCHR | 0666, makedev(1, 7)), 0);
  EXPECT_EQ(vgroove("validate " + quoted(suite) + " --out " + quoted(null_copy) + " --force").status, 0);
  EXPECT_EQ(type_of(null_copy), static_cast<mode_t>(S_IFCHR));
  // A write error on the device is reported, and the node stays.
  const CliRun f = vgroove("validate " + quoted(suite) + " --out " + quoted(full_copy) + " --force");
  expect_refused(f, "No space left on device");
  EXPECT_EQ(type_of(full_copy), static_cast<mode_t>(S_IFCHR));
  // The same for `simulate`.
  const CliRun s = vgroove("simulate " + quoted(small_scene(dir)) + " --out " + quoted(full_copy));
  expect_refused(s, "No space left on device");
  EXPECT_EQ(type_of(full_copy), static_cast<mode_t>(S_IFCHR));
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(CliOutput, FifosAreWrittenThrough) {
  TempDir dir;
  const std::string fifo = dir.file("pipe"), got = dir.file("got.json");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const CliRun r = run_shell(kBin + " validate " + quoted(small_suite(dir)) + " --out " + quoted(fifo) + " & cat " +
                             quoted(fifo) + " > " + quoted(got) + "; wait $!");
  EXPECT_EQ(type_of(fifo), static_cast<mode_t>(S_IFIFO));
  EXPECT_EQ(json::parse(read_text(got)).at("suite"), "small") << r;
}

TEST(CliOutput, BlockDevicesAndDirectoriesAreRefused) {
  TempDir dir;
  const std::string suite = small_suite(dir);
  const std::string sub = dir.file("sub");
  fs::create_directory(sub);
  expect_refused(vgroove("validate " + quoted(suite) + " --out " + quoted(sub) + " --force"), "is a directory");
  if (::geteuid() != 0) GTEST_SKIP() << "a block device node needs mknod (root)";
  // Device 0:0 is never a real disk: even a wrong write would fail to open.
  const std::string blk = dir.file("blk");
  ASSERT_EQ(::mknod(blk.c_str(), S_IFBLK | 0600, makedev(0, 0)), 0);
  expect_refused(vgroove("validate " + quoted(suite) + " --out " + quoted(blk) + " --force"), "is a block device");
  EXPECT_EQ(type_of(blk), static_cast<mode_t>(S_IFBLK));
}

TEST(CliOutput, SymbolicLinksAreFollowedAndDanglingOnesRefused) {
  TempDir dir;
  const std::string suite = small_suite(dir);
  // A link to a regular file: --force replaces the file it points to; the link stays a link.
  const std::string target = dir.file("target.json"), link = dir.file("link.json");
  write_text(target, "old");
  fs::create_symlink(target, link);
  expect_refused(vgroove("validate " + quoted(suite) + " --out " + quoted(link)), "--force");
  EXPECT_EQ(read_text(target), "old");
  EXPECT_EQ(vgroove("validate " + quoted(suite) + " --out " + quoted(link) + " --force").status, 0);
  EXPECT_EQ(type_of(link), static_cast<mode_t>(S_IFLNK));
  EXPECT_EQ(json::parse(read_text(target)).at("suite"), "small");
  // A link to a directory, even with --force: refused, the link and the directory untouched.
  const std::string sub = dir.file("sub"), to_dir = dir.file("to_dir");
  fs::create_directory(sub);
  fs::create_directory_symlink(sub, to_dir);
  expect_refused(vgroove("validate " + quoted(suite) + " --out " + quoted(to_dir) + " --force"), "is a directory");
  EXPECT_EQ(type_of(to_dir), static_cast<mode_t>(S_IFLNK));
  // A dangling link: refused with or without --force, and nothing created where it points.
  const std::string dangling = dir.file("dangling.json"), nowhere = dir.file("nowhere.json");
  fs::create_symlink(nowhere, dangling);
  for (const char* force : {"", " --force"})
    expect_refused(vgroove("simulate " + quoted(small_scene(dir)) + " --out " + quoted(dangling) + force), "dangling");
  EXPECT_FALSE(fs::exists(nowhere));
  EXPECT_EQ(type_of(dangling), static_cast<mode_t>(S_IFLNK));
  EXPECT_TRUE(no_temporaries(dir));
}

// ---------------------------------------------------------------------------------------------
// 2. Ctrl-C inside any long loop: exit 130 within about a second, no report.

struct Interrupted {
  int status = -1;       // exit status, -1 if killed by a signal
  double seconds = 0.0;  // from SIGINT to exit
  std::string err;
};

// Starts `vgroove args` (output files in dir), sends SIGINT after `after` s, waits for the exit.
Interrupted interrupt_after(const std::string& args, double after, const TempDir& dir) {
  const testing_files::Stopped s = testing_files::signal_after(args, SIGINT, after, dir);
  return {s.signal ? -1 : s.status, s.seconds, s.err};
}

// The first Ctrl-C ends the run promptly, with 130 and no report. The loops read the flag every
// few milliseconds of work (0.05-0.2 s measured from SIGINT to exit); 3 s allows for a machine
// loaded ten times over and for the sanitizers (it took 7-8 minutes before).
void expect_prompt_stop(const std::string& args, const TempDir& dir, const std::string& report) {
  const Interrupted r = interrupt_after(args, 1.0, dir);
  EXPECT_EQ(r.status, 130) << args << "\n" << r.err;
  EXPECT_LT(r.seconds, 3.0) << args;
  EXPECT_CONTAINS(r.err, "interrupted");
  if (!report.empty()) {
    EXPECT_FALSE(fs::exists(report)) << args;
  }
  EXPECT_TRUE(no_temporaries(dir));
}

TEST(CliInterrupt, InsideOneCaseOfABillionRays) {
  TempDir dir;
  const std::string suite = dir.file("big.json"), report = dir.file("r.json");
  write_text(suite, R"({"name": "big", "kind": "table1", "cases": [{"theta_v_deg": 1, "theta_i_deg": 30}],
    "rays": 1000000000, "thresholds": {"max_l1": 1, "mean_l1": 1, "max_theta_o_error_rad": 1}})");
  expect_prompt_stop("validate " + quoted(suite) + " --out " + quoted(report), dir, report);
}

TEST(CliInterrupt, InsideTheTraceOfOneHugeBeam) {
  TempDir dir;
  expect_prompt_stop("trace --theta-v-deg 0.001 --rays 1e9", dir, "");
  expect_prompt_stop("trace --theta-v-deg 30 --rays 1e9 --json", dir, "");
}

TEST(CliInterrupt, InsideASimulateChunkOfANarrowGroove) {
  TempDir dir;
  const std::string scene = dir.file("narrow.json"), report = dir.file("r.json");
  // 32768 rays of 180,000 reflections each per chunk: tens of seconds without the per-ray check.
  write_text(scene, R"({"scene": "narrow", "geometry": {"kind": "groove", "theta_v_deg": 0.001},
    "light": {"theta_i_deg": [10], "rays": 1000000000}, "effects": {"fresnel": {"kind": "none"}}})");
  expect_prompt_stop("simulate " + quoted(scene) + " --out " + quoted(report), dir, report);
}

TEST(CliInterrupt, InsideRoughSurfaceCases) {
  TempDir dir;
  const std::string report = dir.file("r.json");
  const std::string fig11 = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/fig11.json";
  expect_prompt_stop("validate " + quoted(fig11) + " --rays 1000000000 --out " + quoted(report), dir, report);
  const std::string table2 = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table2.json";
  expect_prompt_stop("validate " + quoted(table2) + " --rays 1000000000 --threads 1 --out " + quoted(report), dir,
                     report);
}

TEST(CliInterrupt, InsideTheLobeIntegration) {
  // 200 x 200 bins: the 3D lobe's quadrature takes minutes (a few rays, so it starts at once).
  TempDir dir;
  const std::string suite = dir.file("lobe.json"), report = dir.file("r.json");
  write_text(suite, R"({"name": "g", "kind": "brdf", "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [30],
    "dimensions": ["3d"], "rays": 1000, "grooves": 1000, "theta_bins": 200, "phi_bins": 200, "max_k": 23,
    "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}}})");
  expect_prompt_stop("validate " + quoted(suite) + " --out " + quoted(report), dir, report);
}

TEST(CliInterrupt, InsideABenchmarkRun) {
  TempDir dir;
  const std::string report = dir.file("r.json");
  expect_prompt_stop("bench accuracy " + quoted(small_suite(dir)) + " --rays 1000000000 --out " + quoted(report), dir,
                     report);
}

// ---------------------------------------------------------------------------------------------
// 3. Deeply nested JSON: exit 2 with one line, never a crash.

std::string nested(int depth, char open, char close, const std::string& inner) {
  return std::string(static_cast<std::size_t>(depth), open) + inner +
         std::string(static_cast<std::size_t>(depth), close);
}

TEST(CliJson, DeepNestingIsRefusedInOneLine) {
  TempDir dir;
  const std::string f = dir.file("deep.json");
  // The example: "rays" an array nested 10^5 deep (refused by its depth, not printed recursively).
  write_text(f, R"({"name": "x", "kind": "table1", "rays": )" + nested(100000, '[', ']', "1") + "}");
  expect_refused(vgroove("validate " + quoted(f)), "nested more than 64 levels");
  // Another member: "name" an object nested 10^5 deep, in a scene.
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "{\"a\": ";
  deep += "1" + std::string(100000, '}');
  write_text(f, R"({"scene": )" + deep + "}");
  expect_refused(vgroove("simulate " + quoted(f)), "nested more than 64 levels");
  // A wrong value at a known key is printed briefly, whatever its size; so is a parser's message.
  write_text(f, R"({"name": "x", "kind": "table1", "cases": [{"theta_v_deg": 60, "theta_i_deg": 0}], "rays": [")" +
                    std::string(200000, '7') + "\"]}");
  const CliRun r = vgroove("validate " + quoted(f));
  expect_refused(r, "/rays = [\"7777");
  EXPECT_LT(r.err.size(), 400u) << r;
  write_text(f, R"({"name": "x", "kind": "table1", "rays": [)" + std::string(200000, '7') + "]}");
  const CliRun p = vgroove("validate " + quoted(f));
  expect_refused(p, "not valid JSON");
  EXPECT_LT(p.err.size(), 400u) << p;
}

// ---------------------------------------------------------------------------------------------
// 5. Output that does not arrive is a failure.

TEST(CliOutput, FullDiskAndClosedStdoutAreFailures) {
  TempDir dir;
  for (const std::string& args :
       {std::string("trace --json"), std::string("analytic"), std::string("analytic --json"),
        "validate " + quoted(small_suite(dir)), "simulate " + quoted(small_scene(dir)), std::string("--help")}) {
    const CliRun full = vgroove(args + " > /dev/full");
    expect_refused(full, "standard output: write failed (No space left on device)");
    const CliRun closed = vgroove(args + " >&-");
    expect_refused(closed, "standard output: write failed");
  }
  // A report written while stdout is closed does not take descriptor 1: it holds only the report.
  const std::string report = dir.file("r.json");
  const CliRun r = vgroove("validate " + quoted(small_suite(dir)) + " --out " + quoted(report) + " >&-");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_EQ(json::parse(read_text(report)).at("suite"), "small");
}

// A report on a full file system: the write error is reported, and nothing is left there.
TEST(CliOutput, FullFileSystemIsAFailure) {
  if (::geteuid() != 0) GTEST_SKIP() << "mounting a small tmpfs needs root";
  TempDir dir;
  const std::string mnt = dir.file("small");
  fs::create_directory(mnt);
  if (run_shell("mount -t tmpfs -o size=16k tmpfs " + quoted(mnt)).status != 0)
    GTEST_SKIP() << "mount not permitted here";
  const std::string sym = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table1_symmetric.json";
  const CliRun r = vgroove("validate " + quoted(sym) + " --out " + quoted(mnt + "/r.json"));  // a 3 MB report
  const bool empty = fs::is_empty(mnt);
  run_shell("umount " + quoted(mnt));
  expect_refused(r, "r.json: writing failed (No space left on device)");
  EXPECT_TRUE(empty) << "a partial report or temporary was left";
}

// ---------------------------------------------------------------------------------------------
// 6. Thread creation failing (an address-space limit): fewer threads, never a crash.

TEST(CliLimits, ThreadsThatCannotStartAreNotACrash) {
  if (kSanitized) GTEST_SKIP() << "ulimit -v stops a sanitized binary from starting";
  const std::string nonsym = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table1_nonsymmetric.json";
  // 1024 threads of 8 MB stacks do not fit in 4 GB of address space.
  const CliRun r = run_shell("ulimit -v 4000000; exec " + kBin + " validate " + quoted(nonsym) +
                             " --threads 1024 --rays 10 > /dev/null");
  EXPECT_TRUE(r.status == 0 || r.status == 1) << r;
  TempDir dir;
  const CliRun s = run_shell("ulimit -v 3000000; exec " + kBin + " simulate " + quoted(small_scene(dir)) +
                             " --threads 1024 > /dev/null");
  EXPECT_EQ(s.status, 0) << s;
}

// ---------------------------------------------------------------------------------------------
// 7. Specs that cannot fit in memory are refused before any work, with the estimate.

TEST(CliLimits, SpecsThatCannotFitAreRefusedWithTheEstimate) {
  TempDir dir;
  const std::string f = dir.file("huge.json");
  // The example: a brdf suite of 10^7 grooves (the maximum) under 4 GB, 2 threads.
  write_text(f, R"({"name": "g", "kind": "brdf", "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [0, 30],
    "dimensions": ["3d"], "rays": 1000, "grooves": 10000000,
    "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}}})");
  if (!kSanitized) {  // ulimit -v stops a sanitized binary from starting
    const CliRun g = run_shell("ulimit -v 4000000; exec " + kBin + " validate " + quoted(f) + " --threads 2");
    expect_refused(g, "of memory (");
    EXPECT_CONTAINS(g.err, "this process may use");
    // The same surfaces in a nonsymmetric suite (two 3D surfaces of 10^7 grooves at once, about 3 GB)
    // under 2 GB: refused with its estimate, not started to die of the allocation.
    const std::string n = dir.file("huge_nonsymmetric.json");
    write_text(n, R"({"name": "n", "kind": "nonsymmetric_brdf", "ndf": ["ggx"], "alpha": [0.5],
      "theta_i_deg": [0, 30], "dimensions": ["3d"], "rays": 1000, "grooves": 10000000, "reciprocity_pairs": 0,
      "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-3, "3d": 3e-3}}})");
    const CliRun ns = run_shell("ulimit -v 2000000; exec " + kBin + " validate " + quoted(n) + " --threads 2");
    expect_refused(ns, "of memory (2 cases, 10000000 grooves per surface on each thread)");
    EXPECT_CONTAINS(ns.err, "this process may use");
  }
  // A grid of 10^6 x 10^6 cases (each list within its own limit).
  write_text(f, R"({"name": "grid", "kind": "table1",
    "groove": {"type": "symmetric", "theta_v_deg": {"from": 1, "to": 180, "step": 0.0002}},
    "theta_i_deg": {"from": -89, "to": 89, "step": 0.0002}, "rays": 10,
    "thresholds": {"max_l1": 1, "mean_l1": 1, "max_theta_o_error_rad": 1}})");
  expect_refused(vgroove("validate " + quoted(f)), "cases), more than");
  // A scene of 10^5 angles x 64 channels x 10^6 histogram cells.
  std::string angles = "0";
  for (int n = 1; n < 100000; ++n) angles += ", " + std::to_string((n % 1700) * 0.05);
  std::string channels;
  for (int c = 0; c < 64; ++c)
    channels += std::string(c ? ", " : "") + "{\"name\": \"c" + std::to_string(c) + "\", \"F0\": 0.5}";
  write_text(f, R"({"scene": "big", "geometry": {"kind": "groove", "theta_v_deg": 60},
    "light": {"theta_i_deg": [)" +
                    angles + R"(], "rays": 10}, "effects": {"fresnel": {"kind": "schlick", "channels": [)" + channels +
                    R"(]}, "record": {"theta_o_histograms": {"bins": 10000, "max_k": 98}, "energy_per_k": true}}})");
  const CliRun sc = vgroove("simulate " + quoted(f));
  expect_refused(sc, "100000 incident angles x 64 channels, 1000000 histogram cells");
}

// ---------------------------------------------------------------------------------------------
// 8. The per-k tally grows with the bounce counts seen: 4 rays of 180,000 reflections in 150 MB.

TEST(CliLimits, TallyMemoryDoesNotGrowWithTheBounceLimit) {
  if (kSanitized) GTEST_SKIP() << "ulimit -v stops a sanitized binary from starting";
  const CliRun r = run_shell("ulimit -v 150000; exec " + kBin +
                             " trace --theta-v-deg 0.001 --theta-i-deg 10 --rays 4 --max-bounces 100000000 --json");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_EQ(json::parse(r.out).at("buckets").at("escaped"), 4);
}

// ---------------------------------------------------------------------------------------------
// 10. Numerics at the documented extremes: refused beyond them, sums of 1 within them.

TEST(CliNumerics, InputsBeyondTheAccurateRangeAreRefused) {
  // The examples: 1e-6 deg (the tracer's rounding moves the bounce counts' boundaries by 30 %) and
  // theta_i = 89.99999999999999 deg (the opening is lost to rounding).
  expect_refused(vgroove("trace --theta-v-deg 1e-6"), "[0.001, 180]");
  expect_refused(vgroove("analytic --theta-v-deg 60 --theta-i-deg 89.99999999999999"),
                 "--theta-i-deg = 89.99999999999999 is out of range [-89.999, 89.999]");
  expect_refused(vgroove("analytic --theta-v-deg 30 --theta-i-deg -89.9999"), "[-89.999, 89.999]");
  expect_refused(vgroove("analytic --theta-l-deg -89.9999 --theta-r-deg 89.9999"), "out of range [0.001, 180]");
  TempDir dir;
  const std::string f = dir.file("s.json");
  write_text(f, R"({"name": "x", "kind": "table1", "cases": [{"theta_v_deg": 0.0005, "theta_i_deg": 0}], "rays": 10,
    "thresholds": {"max_l1": 1, "mean_l1": 1, "max_theta_o_error_rad": 1}})");
  expect_refused(vgroove("validate " + quoted(f)), "/cases/0/theta_v_deg = 0.0005 is out of range [0.001, 180]");
  write_text(f, R"({"scene": "s", "geometry": {"kind": "groove", "theta_v_deg": 60},
    "light": {"theta_i_deg": [89.9995], "rays": 10}, "effects": {"fresnel": {"kind": "none"}}})");
  expect_refused(vgroove("simulate " + quoted(f)), "/light/theta_i_deg/0 = 89.9995 is out of range [-89.999, 89.999]");
}

// The model's fractions of the entering beam sum to 1 at every corner of the accepted range
// (they summed to 1.035 at 30 deg and 1.1547 at 60 deg next to 90 deg; and to 1 - 3e-8 at
// 0.001 deg and 89.999 deg when the width came from 1 - shadow).
TEST(CliNumerics, ModelFractionsSumToOneAtTheExtremes) {
  for (const std::string g : {"--theta-v-deg 0.001", "--theta-v-deg 0.0017", "--theta-v-deg 30", "--theta-v-deg 60",
                              "--theta-v-deg 180", "--theta-l-deg -89.9995 --theta-r-deg 89.9995",
                              "--theta-l-deg -0.0 --theta-r-deg 89.999", "--theta-l-deg -10 --theta-r-deg 30"})
    for (const char* ti : {"89.999", "-89.999", "89.9989", "89.99", "0", "45"}) {
      const CliRun r = vgroove("analytic --json " + g + " --theta-i-deg " + ti);
      ASSERT_EQ(r.status, 0) << r;
      double sum = 0.0;
      const json j = json::parse(r.out);  // kept: a range-for over a temporary's member dangles
      for (const json& row : j.at("bounces")) sum += row.at("fraction").get<double>();
      EXPECT_NEAR(sum, 1.0, 1e-14) << g << " theta_i " << ti;
    }
}

// At the narrowest accepted aperture the trace agrees with the model within the stratified bound:
// each boundary between bounce counts moves a traced fraction by at most 1/(2N), so the L1
// distance over the rows is at most (rows)/N. (At 1e-6 deg: L1 0.05-0.10 with 40 rays.)
TEST(CliNumerics, TraceAgreesWithTheModelAtTheNarrowestAperture) {
  const int n = 200;
  for (const char* ti : {"70.1234567", "89.7654321", "89.999", "-30", "0"}) {
    const std::string common = " --json --theta-v-deg 0.001 --theta-i-deg " + std::string(ti);
    const CliRun t = vgroove("trace --rays " + std::to_string(n) + common);
    const CliRun a = vgroove("analytic" + common);
    ASSERT_EQ(t.status, 0) << t;
    ASSERT_EQ(a.status, 0) << a;
    std::map<std::pair<std::string, int>, double> traced, model;
    const json tj = json::parse(t.out), aj = json::parse(a.out);
    for (const json& r : tj.at("bounces")) traced[{r.at("first_facet"), r.at("k")}] = r.at("fraction");
    for (const json& r : aj.at("bounces")) model[{r.at("first_facet"), r.at("k")}] = r.at("fraction");
    double l1 = 0.0;
    std::size_t rows = model.size();
    for (const auto& [key, f] : traced)
      l1 += std::abs(f - (model.count(key) ? model[key] : 0.0)), rows += !model.count(key);
    for (const auto& [key, f] : model)
      if (!traced.count(key)) l1 += f;
    EXPECT_LE(l1, static_cast<double>(rows) / n) << "theta_i " << ti;
    EXPECT_EQ(json::parse(t.out).at("buckets").at("bounce_limit"), 0) << "theta_i " << ti;
  }
}

// ---------------------------------------------------------------------------------------------
// 11. An --out that cannot be created is found before the run.

TEST(CliOutput, UnwritableOutIsFoundBeforeTheRun) {
  const std::string furnace = std::string(VGROOVE_SOURCE_DIR) + "/data/suites/furnace.json";
  const auto t0 = std::chrono::steady_clock::now();
  const CliRun r = vgroove("validate " + quoted(furnace) + " --out /proc/vgroove-report.json");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.0);
  expect_refused(r, "/proc/vgroove-report.json: cannot create a file in the directory /proc");
  TempDir dir;
  const CliRun s = vgroove("simulate " + quoted(small_scene(dir)) + " --out /sys/vgroove.json");
  expect_refused(s, "cannot create a file in the directory /sys");
  if (::geteuid() != 0) {
    const std::string ro = dir.file("ro");
    fs::create_directory(ro);
    fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
    expect_refused(vgroove("simulate " + quoted(small_scene(dir)) + " --out " + quoted(ro + "/r.json")),
                   "Permission denied");
  }
}

// ---------------------------------------------------------------------------------------------
// 12. Suites and scenes from pipes: read once.

TEST(CliInput, SuitesAndScenesFromPipes) {
  TempDir dir;
  const std::string suite = small_suite(dir);
  const CliRun a = run_shell("cat " + quoted(suite) + " | " + kBin + " validate /dev/stdin");
  EXPECT_EQ(a.status, 0) << a;
  const CliRun b = run_shell("bash -c \"" + kBin + " validate <(cat " + quoted(suite) + ")\"");
  EXPECT_EQ(b.status, 0) << b;
  const CliRun c = run_shell("cat " + quoted(small_scene(dir)) + " | " + kBin + " simulate /dev/stdin");
  EXPECT_EQ(c.status, 0) << c;
  // A rough-surface suite: dispatched by its kind after the one read.
  const std::string furnace = dir.file("furnace.json");
  write_text(furnace, R"({"name": "f", "kind": "furnace", "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [30],
    "dimensions": ["flatland"], "max_k": 16, "samples": 2000, "strategy": "vndf", "rays": 1000, "grooves": 1000,
    "thresholds": {"sigmas": 5, "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-6}}})");
  const CliRun d = run_shell("cat " + quoted(furnace) + " | " + kBin + " validate /dev/stdin");
  EXPECT_EQ(d.status, 0) << d;
}

// ---------------------------------------------------------------------------------------------
// 13. --out naming an input file is refused.

TEST(CliOutput, OutputOntoAnInputIsRefused) {
  TempDir dir;
  const std::string suite = small_suite(dir);
  const std::string before = read_text(suite);
  expect_refused(vgroove("validate " + quoted(suite) + " --out " + quoted(suite) + " --force"), "is the input file");
  // Through a link, a member of a set, and a scene.
  const std::string link = dir.file("link.json");
  fs::create_symlink(suite, link);
  expect_refused(vgroove("validate " + quoted(suite) + " --out " + quoted(link) + " --force"), "is the input file");
  const std::string set = dir.file("set.json");
  small_suite(dir, "b.json");
  write_text(set, R"({"name": "set", "suites": ["small.json", "b.json"]})");
  expect_refused(vgroove("validate " + quoted(set) + " --out " + quoted(dir.file("b.json")) + " --force"),
                 "is the input file");
  const std::string scene = small_scene(dir);
  expect_refused(vgroove("simulate " + quoted(scene) + " --out " + quoted(scene) + " --force"), "is the input file");
  EXPECT_EQ(read_text(suite), before);
  // The file standard output goes to is not replaced either.
  const std::string out = dir.file("out.txt");
  const CliRun r = vgroove("validate " + quoted(suite) + " --out " + quoted(out) + " --force > " + quoted(out));
  expect_refused(r, "standard output goes to");
}

// ---------------------------------------------------------------------------------------------
// 14. Duplicate keys are refused.

TEST(CliJson, DuplicateKeysAreRefused) {
  TempDir dir;
  const std::string f = dir.file("dup.json");
  write_text(f, R"({"name": "x", "kind": "table1", "rays": 1000, "cases": [{"theta_v_deg": 60, "theta_i_deg": 0}],
    "thresholds": {"max_l1": 1, "mean_l1": 1, "max_theta_o_error_rad": 1}, "rays": 5})");
  expect_refused(vgroove("validate " + quoted(f)), "/rays is given twice");
  write_text(f, R"({"scene": "s", "geometry": {"kind": "groove", "theta_v_deg": 60, "theta_v_deg": 90},
    "light": {"theta_i_deg": [0], "rays": 10}, "effects": {"fresnel": {"kind": "none"}}})");
  expect_refused(vgroove("simulate " + quoted(f)), "/geometry/theta_v_deg is given twice");
  write_text(f, R"({"a": [{"b": 1}, {"c": 1, "c": 2}]})");
  expect_refused(vgroove("validate " + quoted(f)), "/a/1/c is given twice");
}

// ---------------------------------------------------------------------------------------------
// 15. One range per quantity, enforced by every reader.

TEST(CliInput, OneRangePerQuantity) {
  TempDir dir;
  const std::string f = dir.file("a.json");
  // alpha: [0.01, 2] in brdf suites, table2 suites and scenes alike (1e-12 must not pass a suite).
  write_text(f, R"({"name": "g", "kind": "brdf", "ndf": ["ggx"], "alpha": [1e-12], "theta_i_deg": [0],
    "dimensions": ["3d"], "rays": 1000, "grooves": 1000,
    "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}}})");
  expect_refused(vgroove("validate " + quoted(f)), "/alpha/0 = 1e-12 is out of range [0.01, 2]");
  write_text(f, R"({"name": "t", "kind": "table2", "ndf": ["ggx"], "alpha": [0.005], "percentiles": [90],
    "rays": 10, "grooves": 10, "paper": {"source": "x", "max_bounces": [[1]]}})");
  expect_refused(vgroove("validate " + quoted(f)), "/alpha/0 = 0.005 is out of range [0.01, 2]");
  write_text(f, R"({"scene": "s", "geometry": {"kind": "microsurface", "ndf": "ggx", "alpha": 0.001, "grooves": 10},
    "light": {"theta_i_deg": [0], "rays": 10}, "effects": {"fresnel": {"kind": "none"}}})");
  expect_refused(vgroove("simulate " + quoted(f)), "/geometry/alpha = 0.001 is out of range [0.01, 2]");
  // The bounce limit: [1, 100000000] in suites, scenes and on the command line.
  expect_refused(vgroove("trace --max-bounces 200000000"), "--max-bounces = 200000000 is out of range [1, 100000000]");
  write_text(f, R"({"scene": "s", "geometry": {"kind": "groove", "theta_v_deg": 60}, "light": {"theta_i_deg": [0],
    "rays": 10}, "effects": {"fresnel": {"kind": "none"}, "max_bounces": 200000000}})");
  expect_refused(vgroove("simulate " + quoted(f)), "/effects/max_bounces = 200000000 is out of range [1, 100000000]");
  // Histogram cells: bounded in brdf suites as in scenes.
  write_text(f, R"({"name": "g", "kind": "brdf", "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [0],
    "dimensions": ["3d"], "rays": 1000, "grooves": 1000, "theta_bins": 1000, "phi_bins": 1000, "max_k": 16,
    "thresholds": {"sigmas": 5, "model_tolerance": {"flatland": 1e-5, "3d": 1e-4}}})");
  expect_refused(vgroove("validate " + quoted(f)), "histogram cells, out of range [1, 1000000]");
}

// ---------------------------------------------------------------------------------------------
// 16. Conductor extremes inside the accepted range give numbers, never nan or null.

TEST(CliNumerics, ConductorExtremesAreFinite) {
  TempDir dir;
  const std::string f = dir.file("c.json");
  for (const char* ch :
       {R"({"name": "a", "eta": 1e-300, "kappa": 0})", R"({"name": "b", "eta": 1e-300, "kappa": 1e-300})",
        R"({"name": "c", "eta": 1000, "kappa": 1000})", R"({"name": "d", "eta": 1e-300, "kappa": 1000})"}) {
    write_text(f, std::string(R"({"scene": "s", "geometry": {"kind": "groove", "theta_v_deg": 60},
      "light": {"theta_i_deg": [0, 60, 89.999], "rays": 100}, "effects": {"fresnel": {"kind": "conductor",
      "channels": [)") +
                      ch + R"(]}, "record": {"energy_per_k": true}}})");
    const std::string out = dir.file("r.json");
    const CliRun r = vgroove("simulate " + quoted(f) + " --out " + quoted(out) + " --force");
    ASSERT_EQ(r.status, 0) << r;
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << r;
    const std::string text = read_text(out);
    EXPECT_EQ(text.find("null"), std::string::npos) << ch;
    const json result = json::parse(text);
    for (const json& row : result.at("results"))
      for (const auto& [name, e] : row.at("energy").items()) {
        EXPECT_GE(e.get<double>(), 0.0) << ch;
        EXPECT_LE(e.get<double>(), 1.0) << ch;
      }
  }
}

// ---------------------------------------------------------------------------------------------
// 17. Strict numbers on the command line.

TEST(CliInput, NumbersAreReadStrictly) {
  // Empty strings are not 0.
  expect_refused(vgroove("trace --theta-i-deg ''"), "--theta-i-deg = \"\" is not a number");
  expect_refused(vgroove("trace --seed ''"), "--seed = \"\" is not an integer");
  expect_refused(vgroove("validate x.json --threads ''"), "--threads = \"\" is not an integer");
  expect_refused(vgroove("validate x.json --out ''"), "--out = \"\" is empty");
  // Leading zeros are decimal, not octal.
  const CliRun r = vgroove("trace --rays 010 --json");
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_EQ(json::parse(r.out).at("rays"), 10);
  EXPECT_EQ(json::parse(vgroove("trace --rays 1e3 --json").out).at("rays"), 1000);
  expect_refused(vgroove("trace --rays 0x10"), "--rays = \"0x10\" is not an integer");
  expect_refused(vgroove("trace --rays 2.5"), "--rays = \"2.5\" is not an integer");
  // Values past the type are out of range, reported as typed (no clamping, no wrapping).
  expect_refused(vgroove("trace --seed 9223372036854775808"),
                 "--seed = 9223372036854775808 is out of range [0, 9223372036854775807]");
  expect_refused(vgroove("trace --seed 18446744073709551617"), "--seed = 18446744073709551617 is out of range");
  expect_refused(vgroove("trace --rays 9223372036854775808"),
                 "--rays = 9223372036854775808 is out of range [1, 1000000000]");
  expect_refused(vgroove("trace --theta-i-deg nan"), "--theta-i-deg = \"nan\" is not a number");
  // A value above a range is not described as below it.
  const CliRun above = vgroove("trace --theta-v-deg 195");
  expect_refused(above, "--theta-v-deg = 195 is out of range [0.001, 180]");
  EXPECT_EQ(above.err.find("below"), std::string::npos) << above;
  EXPECT_CONTAINS(vgroove("trace --theta-v-deg 0.0001").err, "below 0.001 deg");
  const CliRun left = vgroove("trace --theta-l-deg -95 --theta-r-deg 10");
  expect_refused(left, "[-90, 0]");
  EXPECT_EQ(left.err.find("leans right"), std::string::npos) << left;
}

// ---------------------------------------------------------------------------------------------
// 18. A directory or an overflowing number: bad input (2), not an internal error (3).

TEST(CliInput, DirectoriesAndOverflowingNumbersAreBadInput) {
  TempDir dir;
  expect_refused(vgroove("validate " + quoted(dir.path().string())), "is a directory");
  expect_refused(vgroove("simulate " + quoted(dir.path().string())), "is a directory");
  const std::string f = dir.file("o.json");
  write_text(f, R"({"name": "x", "kind": "table1", "rays": 1e400})");
  expect_refused(vgroove("validate " + quoted(f)), "not valid JSON");
  write_text(f, R"({"scene": "s", "light": {"rays": -1e400}})");
  expect_refused(vgroove("simulate " + quoted(f)), "not valid JSON");
}

// ---------------------------------------------------------------------------------------------
// 19. Control and bidirectional characters in names are escaped in tables and error lines.

TEST(CliOutput, ControlCharactersAreEscaped) {
  TempDir dir;
  const std::string f = dir.file("n.json");
  // A name with a newline, ESC, a right-to-left override and a C1 control (JSON escapes).
  write_text(f, R"({"name": "a\nb\u001b[31m\u202ec\u0085", "kind": "table1", "cases": [{"theta_v_deg": 60,
    "theta_i_deg": 0}], "rays": 10, "thresholds": {"max_l1": 1, "mean_l1": 1, "max_theta_o_error_rad": 1}})");
  const CliRun r = vgroove("validate " + quoted(f));
  ASSERT_EQ(r.status, 0) << r;
  EXPECT_CONTAINS(r.out, "a\\nb\\x1b[31m\\u{202E}c\\u{0085}");
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos);
  EXPECT_EQ(r.out.find("\xe2\x80\xae"), std::string::npos);
  // Error lines: an unknown key and an option value with the same characters stay on one line.
  write_text(f, R"({"name": "x", "kind": "table1", "cases": [{"theta_v_deg": 60, "theta_i_deg": 0}], "rays": 10,
    "thresholds": {"max_l1": 1, "mean_l1": 1, "max_theta_o_error_rad": 1}, "bad\nkey\u202e": 1})");
  expect_refused(vgroove("validate " + quoted(f)), "/bad\\nkey\\u{202E} is not a known key");
  const CliRun o = vgroove("trace --sampling \"$(printf 'a\\nb\\033c')\"");
  expect_refused(o, "--sampling = \"a\\nb\\x1bc\" is not one of");
  const CliRun s = vgroove("validate " + quoted(dir.file("new\nline\x1b.json")));
  expect_refused(s, "new\\nline\\x1b.json: cannot open the file");
}

// ---------------------------------------------------------------------------------------------
// 20. A temporary file left by a killed run is removed by the next run writing the same target.

TEST(CliOutput, LeftoverTemporariesOfDeadRunsAreRemoved) {
  TempDir dir;
  const std::string report = dir.file("r.json");
  // The pid of a process that has ended.
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const std::string leftover = report + ".vgroove-tmp." + std::to_string(dead);
  const std::string other = dir.file("other.json.vgroove-tmp." + std::to_string(dead));
  write_text(leftover, "partial");
  write_text(other, "partial");
  EXPECT_EQ(vgroove("validate " + quoted(small_suite(dir)) + " --out " + quoted(report)).status, 0);
  EXPECT_FALSE(fs::exists(leftover));
  EXPECT_TRUE(fs::exists(other));  // another target's: left to its own next run
  // Also with --force, and a live process's temporary (our own test process) is kept.
  const std::string live = report + ".vgroove-tmp." + std::to_string(::getpid());
  write_text(leftover, "partial");
  write_text(live, "in progress");
  EXPECT_EQ(vgroove("simulate " + quoted(small_scene(dir)) + " --out " + quoted(report) + " --force").status, 0);
  EXPECT_FALSE(fs::exists(leftover));
  EXPECT_TRUE(fs::exists(live));
}

// ---------------------------------------------------------------------------------------------
// 22. Help text and enforcement agree; the default bounce limit fits the groove.

TEST(CliInput, HelpStatesTheEnforcedRanges) {
  const CliRun h = vgroove("trace --help");
  EXPECT_CONTAINS(h.out, "[0.001, 180]");
  EXPECT_CONTAINS(h.out, "[-89.999, 89.999]");
  EXPECT_CONTAINS(h.out, "[1, 1000000000]");
  EXPECT_EQ(vgroove("trace --theta-v-deg 0.001 --rays 2").status, 0);
  expect_refused(vgroove("trace --theta-v-deg 0.00099"), "[0.001, 180]");
  EXPECT_EQ(vgroove("analytic --theta-i-deg 89.999").status, 0);
  expect_refused(vgroove("analytic --theta-i-deg 89.9991"), "[-89.999, 89.999]");
}

TEST(CliInput, DefaultBounceLimitFitsTheNarrowestGroove) {
  // 0.001 deg needs up to 180,000 reflections: more than the plain default of 100,000.
  const CliRun r = vgroove("trace --json --theta-v-deg 0.001 --theta-i-deg 30 --rays 20");
  ASSERT_EQ(r.status, 0) << r;
  const json j = json::parse(r.out);
  EXPECT_EQ(j.at("buckets").at("bounce_limit"), 0) << r;
  EXPECT_FALSE(j.at("bounces").empty()) << r;
  EXPECT_GE(j.at("inputs").at("max_bounces").get<int>(), 180001);
  // An explicit smaller limit is kept, and the table says what it cost.
  const CliRun s = vgroove("trace --theta-v-deg 0.001 --theta-i-deg 30 --rays 20 --max-bounces 1000");
  ASSERT_EQ(s.status, 0) << s;
  EXPECT_CONTAINS(s.out, "20 of 20 rays were still inside after --max-bounces = 1000 reflections");
}

// ---------------------------------------------------------------------------------------------
// The commands and suite kinds added after the issue (sample, energy, merge, --shard, plot
// --format; furnace, sampling, profiles, nonsymmetric_brdf) read their inputs by the same rules:
// a message naming the flag or field, its value and range, exit 2, nothing written.

TEST(CliInput, NewCommandsReadOptionsStrictly) {
  TempDir dir;
  const std::string out = dir.file("r.json");
  const std::pair<std::string, std::string> cases[] = {
      {"sample --alpha ''", "--alpha = \"\" is not a number"},
      {"sample --alpha 1e-12", "--alpha = 1e-12 is out of range [0.01, 2]"},
      {"sample --theta-i-deg 89.95", "--theta-i-deg = 89.95 is out of range [0, 89.9]"},
      {"sample --n 2^63", "--n = \"2^63\" is not an integer"},
      {"sample --n 1e10", "--n = 1e10 is out of range [1, 1000000000]"},
      {"sample --n 1",
       "--n = 1 is too few samples for a chi-square test (the 129 cells pool into 0 with >= 5 expected"},
      {"sample --seed 18446744073709551616", "--seed = 18446744073709551616 is out of range [0, 9223372036854775807]"},
      {"sample --phi-bins 3", "--phi-bins = 3 is out of range [2, 1000], even"},
      {"sample --cos-bins 0x10", "--cos-bins = \"0x10\" is not an integer"},
      {"sample --ndf ''", "--ndf = \"\" is empty"},
      {"energy --alpha 0.001", "--alpha = 0.001 is out of range [0.01, 2]"},
      {"energy --alpha 0.5,nan", "--alpha = \"nan\" is not a number"},
      {"energy --alpha-points 51", "--alpha-points = 51 is out of range [1, 50]"},
      {"energy --mu 0", "--mu = 0 is out of range [0.0017453283658983088, 1]"},
      {"energy --mu 1e-16", "--mu = 1e-16 is out of range [0.0017453283658983088, 1]"},
      {"energy --mu 0.0017453283658983", "--mu = 0.0017453283658983 is out of range [0.0017453283658983088, 1]"},
      {"energy --mu-points 0", "--mu-points = 0 is out of range [1, 286]"},
      {"energy --mu-points 287", "--mu-points = 287 is out of range [1, 286]"},
      {"energy --rays ''", "--rays = \"\" is not an integer"},
      {"energy --ndf ggx,,phong", "--ndf = \"ggx,,phong\" has an empty item (items are separated by single commas)"},
      {"energy --dim=3d,", "--dim = \"3d,\" has an empty item"},
      {"energy --ndf ggx,ggx", "--ndf = \"ggx,ggx\" gives ggx twice (each item is run once: give it once)"},
      {"energy --mu 1,0.5,1", "--mu = \"1,0.5,1\" gives 1 twice"},
      {"bench accuracy x.json --rays 100,100", "--rays = \"100,100\" gives 100 twice"},
      {"energy --max-k 1001", "--max-k = 1001 is out of range [1, 1000]"},
      {"energy --threads 2000", "--threads = 2000 is out of range [0, 1024]"},
      {"energy --shard ''", "--shard = \"\" is empty"},
      {"validate x.json --shard ''", "--shard = \"\" is empty"},
      {"energy --shard 3/2 --out " + quoted(out), "--shard = 3/2 is out of range"},
      {"energy --shard +1/2 --out " + quoted(out), "--shard = \"+1/2\" is not of the form"},
      {"merge ''", "parts = \"\" is empty"},
      {"energy --rays 10 --mu 1 --alpha 1 --out -", "--out = \"-\": results go to files"},
      {"sample --n 100 --out -", "--out = \"-\": results go to files"},
      {"plot --format jpg r.json", "--format = \"jpg\" is not one of \"png\", \"svg\", \"pdf\""},
      {"plot r.json --out ''", "--out = \"\" is empty"},
  };
  for (const auto& [args, message] : cases) {
    SCOPED_TRACE(args);
    expect_refused(vgroove(args), message);
  }
  EXPECT_FALSE(fs::exists(out));
  // The help states the ranges enforced.
  EXPECT_CONTAINS(vgroove("sample --help").out, "[0.01, 2]");
  EXPECT_CONTAINS(vgroove("energy --help").out, "[0.01, 2]");
}

TEST(CliInput, NewSuiteKindsUseTheSameRanges) {
  TempDir dir;
  const std::string f = dir.file("a.json");
  write_text(f, R"({"name": "f", "kind": "furnace", "ndf": ["ggx"], "alpha": [1e-6], "theta_i_deg": [30],
    "dimensions": ["flatland"], "max_k": 16, "samples": 2000, "strategy": "vndf", "rays": 1000, "grooves": 1000,
    "thresholds": {"sigmas": 5, "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-6}}})");
  expect_refused(vgroove("validate " + quoted(f)), "/alpha/0 = 1e-06 is out of range [0.01, 2]");
  write_text(f, R"({"name": "f", "kind": "furnace", "ndf": ["ggx"], "alpha": [0.5], "theta_i_deg": [89.95],
    "dimensions": ["flatland"], "max_k": 16, "samples": 2000, "strategy": "vndf", "rays": 1000, "grooves": 1000,
    "thresholds": {"sigmas": 5, "quadrature_tolerance": {"flatland": 1e-9, "3d": 1e-6}}})");
  expect_refused(vgroove("validate " + quoted(f)), "/theta_i_deg/0 = 89.95 is out of range [0, 89.9]");
}

// A suite path that is not UTF-8 ran the whole suite and then failed writing its report ("internal
// error", exit 3, nothing written): every argument is checked before the work.
TEST(CliInput, ArgumentsThatAreNotUtf8AreRefusedBeforeTheWork) {
  TempDir dir;
  const std::string suite = dir.file("bad\xff.json"), out = dir.file("r.json");
  write_text(suite, read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/table1_symmetric.json"));
  for (const std::string& args :
       {"validate " + quoted(suite) + " --rays 10 --out " + quoted(out), "validate " + quoted(suite) + " --rays 10",
        "simulate x.json --out " + quoted(dir.file("r\xc3\x28.json"))}) {
    SCOPED_TRACE(args);
    const CliRun r = vgroove(args);
    EXPECT_EQ(r.status, 2) << r;
    EXPECT_EQ(r.out, "");
    EXPECT_CONTAINS(r.err, "is not valid UTF-8 (reports hold paths and names as JSON text)");
    EXPECT_EQ(lines(r.err), 1) << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_CONTAINS(vgroove("validate " + quoted(suite) + " --rays 10").err, "bad\\xff.json");  // printed escaped
}

// A profiles suite ran 155 s up to 10.7 GB with no estimate: it is now refused before the work
// when its profiles (about 150 bytes per segment on each worker) do not fit.
TEST(CliInput, ProfilesSuitesThatCannotFitAreRefusedBeforeTheWork) {
  TempDir dir;
  const std::string f = dir.file("p.json"), out = dir.file("r.json");
  json s = json::parse(read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/suites/profiles.json"));
  s["segments"] = 1 << 24;
  s["alpha"] = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0};
  write_text(f, s.dump());
  const CliRun r = vgroove("validate " + quoted(f) + " --threads 64 --out " + quoted(out));
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_CONTAINS(r.err, ": the run needs about ");
  EXPECT_CONTAINS(r.err, "(16777216 segments per profile on each of 64 workers), more than the ");
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CliOutput, MergeNeverOverwritesItsParts) {
  TempDir dir;
  const std::string scene = small_scene(dir), part = dir.file("part.json");
  ASSERT_EQ(vgroove("simulate " + quoted(scene) + " --shard 1/1 --out " + quoted(part)).status, 0);
  const std::string before = read_text(part);
  expect_refused(vgroove("merge " + quoted(part) + " --out " + quoted(part) + " --force"),
                 "; the output would replace it");
  expect_refused(vgroove("merge " + quoted(part) + " --out " + quoted(scene) + " --force"),
                 "; the output would replace it");
  EXPECT_EQ(read_text(part), before);
  EXPECT_EQ(vgroove("merge " + quoted(part) + " --out " + quoted(dir.file("merged.json"))).status, 0);
}

}  // namespace
}  // namespace vgroove::validation
