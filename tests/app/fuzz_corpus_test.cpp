// Replays the inputs the fuzzers found interesting (tests/fuzz/corpus/, grown by scripts/fuzz.sh)
// through the same entry points, without libFuzzer: each must end in a result or a UserError
// (loader), or in exit status 0, 1 or 2 (command line, merge of shard parts), never in a crash or
// another exception.
#include "fuzz/part_merge.h"
#include "vgroove/app/cli.h"
#include "vgroove/scene/scene.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/groove_suite.h"
#include "vgroove/validation/table2_suite.h"

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

// Each input through the strict reader and the loader; only UserError may come out.
template <class Load>
void replay(const std::string& target, Load&& load) {
  const auto files = corpus(target);
  for (const auto& f : files) {
    try {
      load(support::parse_json_text(read_all(f), "fuzz.json"));
    } catch (const support::UserError&) {
    } catch (const std::exception& e) {
      ADD_FAILURE() << f << ": " << e.what();
    }
  }
  SUCCEED() << files.size() << " inputs";
}

TEST(FuzzCorpus, SuiteLoaderInputsEndInASuiteOrAUserError) {
  replay("suite_loader_fuzz", [](const nlohmann::json& j) {
    const std::string kind =
        j.is_object() && j.contains("kind") && j["kind"].is_string() ? j["kind"].get<std::string>() : std::string();
    const std::string file = "/nonexistent-fuzz-dir/fuzz.json";
    if (kind == "brdf" || kind == "furnace")
      (void)parse_brdf_suite(j, file);
    else if (kind == "table2")
      (void)parse_table2_suite(j, file);
    else
      (void)parse_groove_suite_set(j, file);
  });
}

TEST(FuzzCorpus, SceneLoaderInputsEndInASceneOrAUserError) {
  replay("scene_loader_fuzz", [](const nlohmann::json& j) { (void)scene::parse_scene(j, "fuzz.json"); });
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

// Shard parts (part_merge_fuzz): each corpus text merged alone and beside each real part of
// tests/fuzz/parts/. The real parts are among the corpus, so some merges get through and write a
// report (the replay reaches the tally readers, not only the first checks).
TEST(FuzzCorpus, ShardPartsEndInADocumentedStatus) {
  const auto files = corpus("part_merge_fuzz");
  ASSERT_FALSE(files.empty());
  std::vector<std::string> texts;
  for (const auto& f : files) texts.push_back(read_all(f));
  std::ostringstream sink;
  auto* out = std::cout.rdbuf(sink.rdbuf());
  auto* err = std::cerr.rdbuf(sink.rdbuf());
  int merged = 0;
  {
    fuzz::PartMergeDir dir(std::string(VGROOVE_SOURCE_DIR) + "/tests/fuzz/parts");
    EXPECT_GE(dir.parts().size(), 10u);
    for (std::size_t n = 0; n < texts.size(); ++n)
      for (const int status : dir.merge_statuses(texts[n])) {
        EXPECT_TRUE(status >= 0 && status <= 2) << files[n] << " gave exit status " << status;
        merged += status == 0 || status == 1;
      }
  }
  std::cout.rdbuf(out);
  std::cerr.rdbuf(err);
  EXPECT_GE(merged, 5) << texts.size() << " inputs";
}

}  // namespace
}  // namespace vgroove::validation
