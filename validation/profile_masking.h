// vgroove validation: masking G1(o, m), masking-shadowing G2(i, o, m) and the lit length of one
// polyline profile from the traced counts (sim/profile_visibility.h), per facet-angle bin, beside
// Smith's and the V-cavity's predictions for the same segments. Heitz, "Understanding the
// Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2), 2014: Eq. (5) (projected-area
// identity, kept as a consistency check), Eq. (10) (Smith G1), Eq. (20)-(21) (G2), Eq. (24) (the
// V-cavity, exact on V-groove profiles: there the counts are a multinomial sample of it, tested by
// chi-square, validation/chi_square.h).
// Tests: tests/validation/profile_masking_test.cpp (ProfileMasking.VCavityIsExactOnVGrooveProfiles,
// ProfileMasking.ProjectedAreaIdentityHoldsOnEveryProfile,
// ProfileMasking.LitFractionIsPerMacroLengthAndPerArcLengthByHand,
// ProfileMasking.SmithIsRejectedOnVGrooveProfilesAtGrazingView, ProfileMasking.FlatProfileIsLitWhole).
// Derivation: docs/derivations/profiles.md.
#pragma once

#include "vgroove/analytic/ndf.h"
#include "vgroove/sim/polyline.h"
#include "vgroove/sim/profile_visibility.h"
#include "vgroove/validation/chi_square.h"

#include <vector>

namespace vgroove::validation {

struct MaskingCase {
  analytic::NdfKind ndf = analytic::NdfKind::beckmann;  // the Lambda of Smith's functions
  double alpha = 0.5;
  double theta_i = 0.0;  // light, radians in (-pi/2, pi/2)
  double theta_o = 0.0;  // view
  int bins = 18;
};

struct MaskingMeasure {
  int bins = 0;
  // G1 from o per bin: weight = the bin's front-facing projected length towards o per beam
  // width (sum over its segments of length (o.n)+ / (period cos theta_o)); traced and V-cavity
  // are NaN where the weight is 0. Smith's is one number.
  std::vector<double> g1_weight, g1_traced, g1_vcavity;
  double g1_smith = 0.0;
  // G2 from o, lit from i, per bin: weight over the segments facing both.
  std::vector<double> g2_weight, g2_traced, g2_vcavity;
  double g2_smith_separable = 0.0, g2_smith_correlated = 0.0;
  // Averages over all front-facing facets, projected-area weights (the identity, Eq. 5).
  double g1_average_traced = 0.0, g1_identity = 0.0, g1_average_vcavity = 0.0;
  // The lit fraction from i per unit macro (horizontal) length, Smith's classic illuminated
  // fraction (Smith 1967; Heitz 2014, Sec. 5): each segment weighted by its projected length
  // dx = ds (m.n), traced with the standard deviation of the ray counting.
  //   Smith:    chi+(i.m) / (1 + Lambda(i)) per point (Eq. 10), so the macro fraction is
  //             P_dx(i.m > 0) / (1 + Lambda(i)) over the profile's own dx (Smith 1967's
  //             S(theta) = (1 - erfc(cot theta / (sqrt 2 sigma)) / 2) / (1 + Lambda) for Gaussian
  //             slopes; for GGX slopes P(i.m > 0) = (1 + Lambda) / (1 + 2 Lambda), so 1 / (1 + 2 Lambda)).
  //   V-cavity: chi+(i.m) G1_vcavity(i, m) (Eq. 24) per segment, weighted by dx: exact on
  //             V-groove profiles (a groove of half-angle theta_m with theta_m + |theta_i| > pi/2
  //             has its width lit by cos theta_m cos theta_i / cos(theta_m - |theta_i|), else 1).
  double lit_traced = 0.0, lit_traced_sd = 0.0, lit_vcavity = 0.0, lit_smith = 0.0;
  // The same per unit arc length of the profile (weights ds): steep facets count 1 / cos theta_m
  // times more than in the macro fraction.
  double lit_arc_traced = 0.0, lit_arc_traced_sd = 0.0, lit_arc_vcavity = 0.0, lit_arc_smith = 0.0;
  // Traced counts against V-cavity's expected counts.
  OrderedChiSquare g1_chi2, g2_chi2;
  std::int64_t rays = 0, lost = 0;  // lost: first hits at a vertex or on a back face (view o)
};

// from_o: the beam from o with shadow rays towards i; from_i: the beam from i (its seen counts
// give the lit length). Both traced on p with the same ray count.
MaskingMeasure measure_masking(const sim::Polyline& p, const MaskingCase& c, const sim::VisibilityTally& from_o,
                               const sim::VisibilityTally& from_i);

}  // namespace vgroove::validation
