// libFuzzer target: `vgroove merge` reading a shard part (validation/partial_report.h, part_fields.h
// and each kind's tally reader), the input being one part's text merged alone and beside each real
// part of tests/fuzz/parts/ (fuzz/part_merge.h). Any input must end in exit status 0, 1 or 2: no
// crash, no hang, no uncaught exception, no sanitizer report.
#include "fuzz/part_merge.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace {
std::unique_ptr<vgroove::fuzz::PartMergeDir> dir;
}

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  dir = std::make_unique<vgroove::fuzz::PartMergeDir>(VGROOVE_SOURCE_DIR "/tests/fuzz/parts");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (const int status : dir->merge_statuses(std::string(reinterpret_cast<const char*>(data), size)))
    if (status < 0 || status > 2) __builtin_trap();
  return 0;
}
