// vgroove validation: distances between a traced histogram and the model's bin probabilities,
// and the L1 error a correct model is expected to show at a given sample count.
//
// A simulated bin fraction s_b scatters around the model's p_b for two reasons: the N rays
// (multinomial: variance p_b (1 - p_b) / N) and the G grooves drawn from the NDF (each ray picks
// one of G grooves, so the mixture's bin probability is itself an average of G draws: variance
// Var_g(p_gb) / G <= p_b (1 - p_b) / G, since a groove's share p_gb lies in [0, 1]). With
// v_b = p_b (1 - p_b) (1/N + 1/G) as the bound, a correct model shows an L1 error
// sum_b |s_b - p_b| of mean about sum_b sqrt(2 v_b / pi) (the mean of |normal|) and standard
// deviation about sqrt(sum_b (1 - 2/pi) v_b).
#pragma once

#include <cstddef>
#include <vector>

namespace vgroove::validation {

// Expected L1 error of a histogram of N rays over G grooves against its exact bin probabilities p
// (see the header comment): mean and standard deviation.
struct ExpectedL1 {
  double mean = 0.0, sd = 0.0;
};
ExpectedL1 expected_l1(const std::vector<double>& p, double rays, double grooves);

double sum(const std::vector<double>& v);
bool all_finite(const std::vector<double>& v);
// sum_n |a_n - b_n| over the common length.
double l1(const std::vector<double>& a, const std::vector<double>& b);
// v / sum(v) (unchanged when the sum is 0).
std::vector<double> normalized(std::vector<double> v);
// counts / total (0 when total is 0).
template <class Int>
std::vector<double> fractions(const std::vector<Int>& counts, double total) {
  std::vector<double> out(counts.size());
  for (std::size_t n = 0; n < counts.size(); ++n) out[n] = total > 0.0 ? static_cast<double>(counts[n]) / total : 0.0;
  return out;
}

}  // namespace vgroove::validation
