// vgroove common: the normal distribution functions vgroove knows, named once for every module.
#pragma once

#include <optional>
#include <string_view>

namespace vgroove {

enum class NdfKind : unsigned char { beckmann, ggx, phong };

constexpr const char* ndf_name(NdfKind kind) {
  switch (kind) {
    case NdfKind::beckmann:
      return "beckmann";
    case NdfKind::ggx:
      return "ggx";
    case NdfKind::phong:
      return "phong";
  }
  return "?";
}

// The kind named `name` ("beckmann", "ggx", "phong"), or nothing.
constexpr std::optional<NdfKind> ndf_from_name(std::string_view name) {
  for (NdfKind k : {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong})
    if (name == ndf_name(k)) return k;
  return std::nullopt;
}

}  // namespace vgroove
