// vgroove analytic: how many bounces a rough surface's grooves ask for, the rule behind Table 2 of
// Lee, Jarabo, Jeon, Gutierrez, Kim, "Practical Multiple Scattering for Rough Surfaces", ACM TOG
// 37(6), 2018 (Sec. 8). The reading that reproduces all 27 printed values: the percentile q of
// the facet angle in the projected-area measure D(s) cos(theta_s) ds (closed-form quantiles per
// NDF), the groove of that facet angle lit at normal incidence, N = Eq. (4) at theta_i = 0,
// floor(pi / theta_v) + 1. Other readings (solid-angle measure, flatland D2 cos) are computed too,
// so the report can show that they do not reproduce the table.
// Tests: tests/analytic/bounce_percentiles_test.cpp (Table2.ProjectedAreaPercentileAtNormalIncidenceReproducesAll27,
// Table2.ClosedFormQuantilesInvertTheNdf, Table2.OtherMeasuresDisagreeSomewhere, Table2.GgxAlphaOneHandValue).
// Derivation: docs/derivations/kaleidoscope.md.
#pragma once

#include "vgroove/analytic/ndf.h"

namespace vgroove::analytic {

enum class PercentileMeasure : unsigned char {
  projected_area,  // D(s) cos(theta_s) ds over the hemisphere: the reading that reproduces Table 2
  solid_angle,     // D(s) ds over the hemisphere, normalized to 1
  flatland,        // |theta_m| under 2 D2(theta) cos(theta) dtheta (analytic/ndf.h's flatland D2)
};
const char* percentile_measure_name(PercentileMeasure m);

// The facet angle theta_m in [0, pi/2) below which the fraction q in (0, 1) of the measure lies.
double theta_m_quantile(NdfKind ndf, double alpha, double q, PercentileMeasure m);

// Table 2's entry: Eq. (4) at theta_i = 0 for the groove whose facets sit at the q-th percentile.
int max_bounces_at_percentile(NdfKind ndf, double alpha, double q, PercentileMeasure m);

}  // namespace vgroove::analytic
