#include "vgroove/analytic/masking_kind.h"

namespace vgroove::analytic {

const char* masking_name(MaskingKind kind) {
  switch (kind) {
    case MaskingKind::smith_height_correlated:
      return "smith_height_correlated";
    case MaskingKind::smith_separable:
      return "smith_separable";
    case MaskingKind::vcavity:
      return "vcavity";
  }
  return "?";
}

const char* masking_flag_name(MaskingKind kind) {
  return kind == MaskingKind::smith_height_correlated ? "smith" : masking_name(kind);
}

std::optional<MaskingKind> masking_from_flag(std::string_view name) {
  for (MaskingKind k : {MaskingKind::smith_height_correlated, MaskingKind::smith_separable, MaskingKind::vcavity})
    if (name == masking_flag_name(k)) return k;
  return std::nullopt;
}

}  // namespace vgroove::analytic
