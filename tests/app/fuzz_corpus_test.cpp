// Replays the inputs the fuzzers found interesting (tests/fuzz/corpus/, grown by scripts/fuzz.sh)
// through the same entry points, without libFuzzer: each must end in a result or a UserError
// (loader), or in exit status 0, 1 or 2 (command line), never in a crash or another exception.
#include "vgroove/app/cli.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/suite.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove::validation {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> corpus(const std::string& target) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(VGROOVE_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / target;
  if (fs::is_directory(dir))
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file()) files.push_back(e.path());
  return files;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(FuzzCorpus, SuiteLoaderInputsEndInASuiteOrAUserError) {
  const auto files = corpus("suite_loader_fuzz");
  for (const auto& f : files) {
    const nlohmann::json j = nlohmann::json::parse(read_all(f), nullptr, false);
    if (j.is_discarded()) continue;
    try {
      (void)parse_suite_set(j, "/nonexistent-fuzz-dir/fuzz.json");
    } catch (const support::UserError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << f << ": " << e.what();
    }
  }
  SUCCEED() << files.size() << " inputs";
}

TEST(FuzzCorpus, CommandLinesEndInADocumentedStatus) {
  const auto files = corpus("cli_fuzz");
  // CLI11 prints help and errors; keep the test log readable.
  std::ostringstream sink;
  auto* out = std::cout.rdbuf(sink.rdbuf());
  auto* err = std::cerr.rdbuf(sink.rdbuf());
  for (const auto& f : files) {
    const std::string data = read_all(f);
    std::vector<std::string> args{"vgroove"};
    std::string cur;
    for (char c : data) {
      if (c == '\0' || c == '\n') {
        if (args.size() < 64) args.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    if (args.size() < 64) args.push_back(cur);
    std::vector<const char*> argv;
    for (const auto& a : args) argv.push_back(a.c_str());
    const int status = app::run_cli(static_cast<int>(argv.size()), argv.data(), {nullptr, true});
    EXPECT_TRUE(status >= 0 && status <= 2) << f << " gave exit status " << status;
  }
  std::cout.rdbuf(out);
  std::cerr.rdbuf(err);
}

}  // namespace
}  // namespace vgroove::validation
