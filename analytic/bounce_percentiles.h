// vgroove analytic: how many bounces a rough surface's grooves ask for — the rule behind Table 2 of
// Lee, Jarabo, Jeon, Gutierrez, Kim, "Practical Multiple Scattering for Rough Surfaces", ACM TOG
// 37(6), 2018 (Sec. 8, "Number of bounces").
//
// The paper's rule, as far as it is printed: "as theta_v decreases ... the number of bounces
// increase. Following this relationship, we analyze the number of bounces for different
// percentiles of D(s)". It does not say in which measure the percentile is taken, at which
// incident angle the bounce count is read, or how Phong's exponent follows alpha. These choices
// reproduce all 27 printed values (tests/analytic/bounce_percentiles_test.cpp):
//   - the percentile q of the facet angle theta_m in the projected-area measure D(s) cos(theta_s) ds
//     (the fraction of the macrosurface under facets steeper than theta_m is 1 - q; it is also the
//     paper's sampling pdf |s.n| D(s), Sec. 6), in closed form:
//       GGX:      tan^2 theta_m = alpha^2 q / (1 - q)          (CDF tan^2 / (alpha^2 + tan^2)),
//       Beckmann: tan^2 theta_m = -alpha^2 ln(1 - q)           (CDF 1 - exp(-tan^2 / alpha^2)),
//       Phong:    cos theta_m = (1 - q)^(1 / (alpha_p + 2))    (CDF 1 - cos^(alpha_p + 2)),
//     with alpha_p = 2 / alpha^2 - 2 (Walter et al. 2007, as analytic/ndf.h);
//   - the groove of that facet angle, aperture theta_v = pi - 2 theta_m, lit at normal incidence:
//     N = Eq. (4) at theta_i = 0, floor(pi / theta_v) + 1, the largest count its rays make.
// Other readings are computed too (solid-angle measure D(s) ds; the flatland measure D2 cos), so
// the report can show that they do not reproduce the table.
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
