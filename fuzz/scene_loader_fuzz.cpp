// libFuzzer target: the scene JSON loader (vgroove simulate). Any input must give a Scene or a
// UserError: no crash, no hang, no other exception.
#include "vgroove/scene/scene.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const nlohmann::json j = vgroove::support::parse_json_text(text, "fuzz.json");
    const vgroove::scene::Scene scene = vgroove::scene::parse_scene(j, "fuzz.json");
    (void)scene;
  } catch (const vgroove::support::UserError&) {
  }
  return 0;
}
