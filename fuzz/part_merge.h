// `vgroove merge` fed one shard part's text beside real parts: shared by the libFuzzer target
// (part_merge_fuzz.cpp) and the corpus replay (tests/app/fuzz_corpus_test.cpp).
//
// tests/fuzz/parts/ holds small jobs of every kind that shards (a brdf suite in flatland and 3D,
// table2, a single-groove suite, energy, simulate) and both parts of each job split in two
// (NAME.1.part.json, NAME.2.part.json, written by `vgroove ... --shard I/2` from that directory,
// so that a part names its input file as it is there). PartMergeDir copies them into a temporary
// directory and works there; each text is written as fuzz.part.json and merged alone and with each
// real part in turn (`vgroove merge fuzz.part.json P --out merged.json --force`), so that a text
// close to a real part reaches the tally readers and the merge itself (validation/detail/part_fields.h,
// work_run.h). Every merge must end in exit status 0, 1 or 2 (3 is an exception that escaped).
#pragma once

#include "vgroove/app/cli.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove::fuzz {

class PartMergeDir {
 public:
  explicit PartMergeDir(const std::string& parts_dir) {
    namespace fs = std::filesystem;
    std::string tmpl = (fs::temp_directory_path() / "vgroove-part-merge-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) std::abort();
    dir_ = tmpl;
    for (const auto& e : fs::directory_iterator(parts_dir)) {
      if (!e.is_regular_file()) continue;
      fs::copy_file(e.path(), fs::path(dir_) / e.path().filename());
      const std::string name = e.path().filename().string();
      if (name.size() > 10 && name.substr(name.size() - 10) == ".part.json") parts_.push_back(name);
    }
    std::sort(parts_.begin(), parts_.end());
    back_ = fs::current_path().string();
    fs::current_path(dir_);
  }
  ~PartMergeDir() {
    std::error_code ec;
    std::filesystem::current_path(back_, ec);
    std::filesystem::remove_all(dir_, ec);
  }
  PartMergeDir(const PartMergeDir&) = delete;
  PartMergeDir& operator=(const PartMergeDir&) = delete;

  const std::vector<std::string>& parts() const { return parts_; }

  // The exit statuses of the merges of `text` (alone, then beside each real part).
  std::vector<int> merge_statuses(const std::string& text) const {
    {
      std::ofstream f("fuzz.part.json", std::ios::binary | std::ios::trunc);
      f << text;
    }
    std::vector<int> out;
    out.push_back(merge({"fuzz.part.json"}));
    for (const std::string& p : parts_) out.push_back(merge({"fuzz.part.json", p}));
    return out;
  }

 private:
  static int merge(const std::vector<std::string>& files) {
    std::vector<std::string> args{"vgroove", "merge"};
    args.insert(args.end(), files.begin(), files.end());
    for (const char* a : {"--out", "merged.json", "--force"}) args.emplace_back(a);
    std::vector<const char*> argv;
    for (const std::string& a : args) argv.push_back(a.c_str());
    return app::run_cli(static_cast<int>(argv.size()), argv.data(), {nullptr, false});
  }

  std::string dir_, back_;
  std::vector<std::string> parts_;
};

}  // namespace vgroove::fuzz
