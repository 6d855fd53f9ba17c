// vgroove analytic: the G2 a single-scattering microfacet model takes (the energy formulas'
// albedos, analytic/albedo_single.h, and Walter's dielectric BSDF, analytic/walter.h), and its names.
#pragma once

#include "vgroove/common/ndf_kind.h"

#include <optional>
#include <string_view>

namespace vgroove::analytic {

enum class MaskingKind : unsigned char {
  smith_height_correlated,  // reflection 1 / (1 + Lambda(i) + Lambda(o)), Heitz 2014 Eq. (21)
  smith_separable,          // G1(i) G1(o), Heitz 2014 Eq. (20) (Walter et al. 2007 Eq. 23)
  vcavity,                  // min(G1_vcavity(i, h), G1_vcavity(o, h)): Cook-Torrance, Lee et al. 2018 Eq. (3)
};
// "smith_height_correlated", "smith_separable", "vcavity" (reports).
const char* masking_name(MaskingKind kind);
// The command line's and Python's names: "smith" (height-correlated), "smith_separable", "vcavity".
const char* masking_flag_name(MaskingKind kind);
std::optional<MaskingKind> masking_from_flag(std::string_view name);
// Smith's G2 needs Lambda in closed form: the V-cavity takes any NDF, Smith not Phong (ndf.h).
inline bool masking_supported(MaskingKind kind, NdfKind ndf) {
  return kind == MaskingKind::vcavity || ndf != NdfKind::phong;
}

}  // namespace vgroove::analytic
