// vgroove analytic: the kaleidoscopic V-groove model for symmetric grooves: the bounce count
// (Eq. 4), the exit angle (Eq. 5) and the shares of the beam per count (Eq. 6, printed and
// corrected, ERRATA E1). Lee, Jarabo, Jeon, Gutierrez, Kim, "Practical Multiple Scattering for
// Rough Surfaces", ACM TOG 37(6), 2018, Sec. 4.1, Eq. (4)-(6), App. B. Conventions (as
// sim/geometry.h): angles from n, counter-clockwise positive, a direction at theta is (-sin theta,
// cos theta); theta_i towards the light; the apex at the origin, unit facets; the right facet
// first is the mirror image of the left. Holds: the shares are fractions that sum to 1, the lit
// widths of both facets make the opening, hand values, the narrowest grooves do not overflow.
// Tests: tests/analytic/kaleidoscope_test.cpp (BounceCount.HandPoints, ExitAngle.HandPoints,
// GKaleidoscopic.RightAngleGrooveAt30DegreesByHand, GKaleidoscopic.PrintedFormGivesANegativeShareAtNormalIncidence,
// ModelGrid.SharesAreFractionsThatSumToOne, EqFourBoundary.FractionsPerBounceCountAreContinuous);
// against the tracer: tests/validation/groove_case_test.cpp.
// Derivation: docs/derivations/kaleidoscope.md.
#pragma once

#include "vgroove/common/side.h"

namespace vgroove::analytic {

// The facet hit first (common/side.h).
using FacetSide = vgroove::Side;

// Which form of Eq. (6) to evaluate.
enum class Eq6Form {
  corrected,  // f_k = max(0, f(k)), clamped into [f_b, f_a]
  printed,    // f_k = f(k) as printed; only f_b = max(f(b), 0)
};

// A count computed in double, as int; saturates instead of overflowing (apertures < 8e-8 deg).
int saturate_to_int(double k);

// Eq. (4): the larger of the two bounce counts (k - 1 or k) for light hitting the left facet
// first. theta_v = pi - 2|theta_s| is the aperture; below pi / INT_MAX the count saturates.
int bounce_count(double theta_i, double theta_v);

// Eq. (5): exit angle after n reflections for light hitting the left facet first,
// theta_o = (-1)^n (theta_i + pi - n theta_v), wrapped into (-pi, pi].
double exit_angle(double theta_i, double theta_v, int n);
// The same for light that hits `first` first (the right facet by mirroring).
double exit_angle(double theta_i, double theta_v, int n, FacetSide first);

// One of the model's outcomes: n reflections, a fraction G of the rays aimed at the facet.
struct BounceShare {
  int n;
  double G;
  double theta_o;
};

// The model's prediction for the rays aimed at one facet: over its projected width f_a (the
// paper's normalization of G), the fractions with k - 1 and k reflections and the shadowed one.
struct FacetPrediction {
  bool lit = false;  // f_a > 0: the light reaches the facet
  int k = 0;         // Eq. (4)
  double f_a = 0, f_b = 0, f_k = 0;
  BounceShare fewer{0, 0.0, 0.0};  // k - 1 reflections: rays between f_k and f_a
  BounceShare more{0, 0.0, 0.0};   // k reflections: rays between f_b and f_k
  double shadow = 0.0;             // f_b / f_a: rays that meet the other facet's rim first
};

// Eq. (6) for the rays aimed at `first`.
FacetPrediction G_kaleidoscopic(double theta_i, double theta_v, FacetSide first, Eq6Form form = Eq6Form::corrected);

// Width of the beam that enters the opening, in the same units as f: 2 sin(theta_v/2) cos(theta_i).
double opening_width(double theta_i, double theta_v);

}  // namespace vgroove::analytic
