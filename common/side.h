// vgroove common: the two facets of a V-groove, named once for the tracer and the model.
//
// Seen in the groove's cross-section with the macrosurface normal n up, "left" is the facet on
// the -x side, whose normal leans to +x (Lee et al. 2018, Fig. 5); "right" is its mirror image.
#pragma once

namespace vgroove {

enum class Side : unsigned char { left = 0, right = 1 };

constexpr Side other(Side s) { return s == Side::left ? Side::right : Side::left; }
constexpr const char* side_name(Side s) { return s == Side::left ? "left" : "right"; }

}  // namespace vgroove
