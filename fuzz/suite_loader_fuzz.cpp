// libFuzzer target: the suite/scene JSON loader. Any input must give a Suite or a UserError:
// no crash, no hang, no other exception.
#include "vgroove/support/user_error.h"
#include "vgroove/validation/suite.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return 0;  // not JSON: support::read_json_file reports that before the loader runs
  try {
    // A directory that does not exist: a set's member files fail to open, as they should.
    const auto set = vgroove::validation::parse_suite_set(j, "/nonexistent-fuzz-dir/fuzz.json");
    (void)set;
  } catch (const vgroove::support::UserError&) {
  }
  return 0;
}
