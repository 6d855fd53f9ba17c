// vgroove common: the normal distribution functions vgroove knows, named once for every module.
// An NdfKind is an NDF's family and, for Student-T, its tail parameter gamma: it converts to its
// family (NdfFamily), so that a switch over an NdfKind, or a comparison with NdfKind::ggx, sees the
// family, while two NdfKinds are equal only with the same gamma.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace vgroove {

enum class NdfFamily : unsigned char { beckmann, ggx, phong, student_t };

struct NdfKind {
  // The families as NdfKind::ggx and so on (as the enumerators of a plain enum were named).
  static constexpr NdfFamily beckmann = NdfFamily::beckmann;
  static constexpr NdfFamily ggx = NdfFamily::ggx;
  static constexpr NdfFamily phong = NdfFamily::phong;
  static constexpr NdfFamily student_t = NdfFamily::student_t;

  NdfFamily family = NdfFamily::ggx;
  // Student-T's tail (analytic/ndf_student_t.h), gamma > 1.5: 2 is GGX, infinity Beckmann. 0 for
  // the other families.
  double gamma = 0.0;

  constexpr NdfKind() = default;
  constexpr NdfKind(NdfFamily f) : family(f) {}  // NOLINT: a family is a kind
  constexpr NdfKind(NdfFamily f, double g) : family(f), gamma(g) {}
  constexpr operator NdfFamily() const { return family; }  // NOLINT: switch and compare by family
  friend constexpr bool operator==(NdfKind a, NdfKind b) { return a.family == b.family && a.gamma == b.gamma; }
  friend constexpr bool operator==(NdfKind a, NdfFamily f) { return a.family == f; }
};

// Student-T with the tail gamma.
constexpr NdfKind student_t_ndf(double gamma) { return {NdfFamily::student_t, gamma}; }

constexpr const char* ndf_name(NdfKind kind) {
  switch (kind) {
    case NdfKind::beckmann:
      return "beckmann";
    case NdfKind::ggx:
      return "ggx";
    case NdfKind::phong:
      return "phong";
    case NdfKind::student_t:
      return "student_t";
  }
  return "?";
}

// The kind named `name` ("beckmann", "ggx", "phong"), or nothing. Student-T needs its gamma:
// ndf_from_name(name, gamma) also knows "student_t".
constexpr std::optional<NdfKind> ndf_from_name(std::string_view name) {
  for (NdfKind k : {NdfKind::beckmann, NdfKind::ggx, NdfKind::phong})
    if (name == ndf_name(k)) return k;
  return std::nullopt;
}
constexpr std::optional<NdfKind> ndf_from_name(std::string_view name, double gamma) {
  if (name == ndf_name(NdfKind::student_t)) return student_t_ndf(gamma);
  return ndf_from_name(name);
}

}  // namespace vgroove
