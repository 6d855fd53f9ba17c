// vgroove analytic: the NDF of a kind as its formulas (ndf_ggx.h, ndf_beckmann.h, ndf_phong.h,
// ndf_student_t.h):
// visit_ndf(kind, alpha, f) calls f with the NDF object, so that code written once as a generic
// lambda or template runs every NDF's own formulas. A new NDF is its file and one line here.
#pragma once

#include "vgroove/analytic/ndf_beckmann.h"
#include "vgroove/analytic/ndf_ggx.h"
#include "vgroove/analytic/ndf_phong.h"
#include "vgroove/analytic/ndf_student_t.h"
#include "vgroove/common/ndf_kind.h"

namespace vgroove::analytic {

template <typename F>
[[gnu::always_inline]] inline decltype(auto) visit_ndf(NdfKind kind, double alpha, F&& f) {
  switch (kind) {
    case NdfKind::beckmann:
      return f(Beckmann{alpha});
    case NdfKind::phong:
      return f(Phong{alpha});
    case NdfKind::student_t:
      return f(StudentT{alpha, kind.gamma});
    case NdfKind::ggx:
      break;
  }
  return f(Ggx{alpha});
}

}  // namespace vgroove::analytic
