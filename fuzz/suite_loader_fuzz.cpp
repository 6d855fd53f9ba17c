// libFuzzer target: the suite JSON loaders (every kind: single grooves and sets of them, brdf and
// furnace, table2), dispatched as `vgroove validate` does. Any input must give a suite or a
// UserError: no crash, no hang, no other exception.
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/groove_suite.h"
#include "vgroove/validation/table2_suite.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // The reader every command uses: not JSON, duplicate keys, deep nesting are UserErrors too.
    const nlohmann::json j = vgroove::support::parse_json_text(text, "fuzz.json");
    const std::string kind =
        j.is_object() && j.contains("kind") && j["kind"].is_string() ? j["kind"].get<std::string>() : std::string();
    // A directory that does not exist: a set's member files fail to open, as they should.
    const std::string file = "/nonexistent-fuzz-dir/fuzz.json";
    if (kind == "brdf" || kind == "furnace")
      (void)vgroove::validation::parse_brdf_suite(j, file);
    else if (kind == "table2")
      (void)vgroove::validation::parse_table2_suite(j, file);
    else
      (void)vgroove::validation::parse_groove_suite_set(j, file);
  } catch (const vgroove::support::UserError&) {
  }
  return 0;
}
