// vgroove validation: one traced lobe held against a model's, as every kind that bins exit
// directions does it ("brdf", "nonsymmetric_brdf", check_brdf and model tables).
//
// The lobes are fractions of the incident flux per (row, bin): rows of bounce counts k (or one
// row), bins of exit directions. Two L1 distances, each against the error a correct model shows
// at N rays over G grooves (histogram_metrics.h) plus `sigmas` standard deviations plus the
// model's tolerance: the shape (the rows summed, then normalized) and the joint fractions (shape
// and energy together). The albedo is a binomial fraction of the same N rays over G grooves,
// plus one ray's worth (the count is an integer) and the tolerance.
// Tested by tests/validation/lobe_comparison_test.cpp.
#pragma once

#include <vector>

namespace vgroove::validation {

// An L1 distance beside what a correct model is expected to show, and the threshold it must stay below.
struct L1Test {
  double l1 = 0.0, expected = 0.0, threshold = 0.0;
  bool holds() const { return l1 <= threshold; }
};
// `l1` against the expected L1 of bin probabilities p at N rays over G grooves.
L1Test l1_test(double l1, const std::vector<double>& p, double rays, double grooves, double sigmas, double tolerance);
// The largest |albedo_sim - albedo_model| a correct model shows (albedo_model clamped to [0, 1]).
double albedo_threshold(double albedo_model, double rays, double grooves, double sigmas, double tolerance);

struct LobeComparison {
  std::vector<double> sim_shape;  // the traced rows summed per bin, normalized
  L1Test shape;                   // sim_shape against the model's, likewise
  L1Test joint;                   // the joint fractions
};
// sim_joint and model_joint hold rows x bins fractions, row by row.
LobeComparison compare_lobes(const std::vector<double>& sim_joint, const std::vector<double>& model_joint, int bins,
                             double rays, double grooves, double sigmas, double tolerance);
// The rows of a joint lobe summed per bin (rows in order).
std::vector<double> bin_totals(const std::vector<double>& joint, int bins);

}  // namespace vgroove::validation
