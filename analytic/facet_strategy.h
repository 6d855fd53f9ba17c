// vgroove analytic: how a V-groove sampler draws the facet the light meets first (vndf.h has the
// distributions; sampling_3d.h and sampling_flatland.h use them).
#pragma once

#include "vgroove/common/ndf_kind.h"

#include <optional>
#include <string_view>

namespace vgroove::analytic {

enum class FacetStrategy : unsigned char {
  printed,       // Lee et al. 2018, Sec. 6: s from |s.n| D(s), k by Russian roulette on Eq. (6)'s G
  vndf,          // the V-cavity's visible normals (Heitz and d'Eon 2014): the facet met first, exactly
  smith_vndf,    // the Smith visible normals (GGX: Heitz 2018, Dupuy and Benyoub 2023; Student-T): a proposal
  bounded_vndf,  // the bounded Smith-GGX visible normals (Tokuyoshi and Eto 2024): a proposal
};

constexpr const char* strategy_name(FacetStrategy s) {
  switch (s) {
    case FacetStrategy::printed:
      return "printed";
    case FacetStrategy::vndf:
      return "vndf";
    case FacetStrategy::smith_vndf:
      return "smith-vndf";
    case FacetStrategy::bounded_vndf:
      return "bounded-vndf";
  }
  return "?";
}

constexpr std::optional<FacetStrategy> strategy_from_name(std::string_view name) {
  for (FacetStrategy s :
       {FacetStrategy::printed, FacetStrategy::vndf, FacetStrategy::smith_vndf, FacetStrategy::bounded_vndf})
    if (name == strategy_name(s)) return s;
  return std::nullopt;
}

// The Smith VNDF exists for GGX (closed form) and Student-T (detail/vndf_student_t.h): Smith's Lambda
// has no closed form for Phong (not shape invariant), and Beckmann's visible normals need a
// numerical inversion (Heitz and d'Eon 2014) that is not implemented. The bounded VNDF is a 3D
// spherical-cap construction for GGX: no flatland form.
constexpr bool strategy_supports(FacetStrategy s, NdfKind ndf, bool flatland) {
  if (s == FacetStrategy::smith_vndf) return ndf == NdfKind::ggx || ndf == NdfKind::student_t;
  if (s == FacetStrategy::bounded_vndf) return ndf == NdfKind::ggx && !flatland;
  return true;
}

}  // namespace vgroove::analytic
