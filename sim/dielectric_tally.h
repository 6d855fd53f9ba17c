// vgroove sim: what the rays traced across a dielectric groove became, per side and interaction
// count k (sim/dielectric_groove.h).
//
// Energies, not ray counts: in split branching every path carries its exact weight, in random
// branching every exit weighs 1. Per side (the medium a path left into) and k: the energy, and a
// histogram of the exit angle (sim::exit_angle: from the normal of the exit side, counter-clockwise
// positive) over [-pi/2, pi/2] in equal bins; per side and path signature (k and the R/T bits):
// the energy. Besides the exits, the energy cut, at the bounce limit and on vertices, so that
// energy() of both sides + cut + bounce_limit + vertex = rays to rounding. Sums are in the order the
// rays were added (merging in another order changes them at rounding only).
#pragma once

#include "vgroove/sim/dielectric_groove.h"

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace vgroove::sim {

class DielectricTally {
 public:
  // Histograms of n_bins >= 1 equal bins over [-pi/2, pi/2].
  explicit DielectricTally(int n_bins);

  void add(const DielectricResult& r);
  void merge(const DielectricTally& o);

  int bins() const { return n_bins_; }
  // The bin of an exit angle (clamped into [0, bins() - 1]).
  int bin_of(double angle) const;

  std::int64_t rays() const { return rays_; }
  double energy(Medium side) const { return left_[static_cast<int>(side)]; }
  // The energy that left into side after exactly k interactions (0 when none did).
  double energy(Medium side, int k) const;
  // The histogram of side and k, bins() values (all 0 when no path left there with k).
  std::vector<double> histogram(Medium side, int k) const;
  // The largest k with a path that left into side; -1 when none did.
  int max_k(Medium side) const { return static_cast<int>(by_k_[static_cast<int>(side)].size()) - 1; }
  // Energy by path signature: key (k, bits), bit j set when interaction j refracted.
  const std::map<std::pair<int, std::uint64_t>, double>& by_path(Medium side) const {
    return by_path_[static_cast<int>(side)];
  }
  double cut() const { return cut_; }
  double bounce_limit() const { return bounce_limit_; }
  double vertex() const { return vertex_; }
  std::int64_t paths_cut() const { return paths_cut_; }
  // Everything accounted for: rays() when nothing is lost (to rounding).
  double total() const { return left_[0] + left_[1] + cut_ + bounce_limit_ + vertex_; }

 private:
  struct PerK {
    double energy = 0.0;
    std::vector<double> hist;  // empty until a path lands here
  };
  PerK& at(int side, int k);

  int n_bins_;
  std::int64_t rays_ = 0;
  double left_[2] = {0.0, 0.0};
  double cut_ = 0.0, bounce_limit_ = 0.0, vertex_ = 0.0;
  std::int64_t paths_cut_ = 0;
  std::vector<PerK> by_k_[2];
  std::map<std::pair<int, std::uint64_t>, double> by_path_[2];
};

}  // namespace vgroove::sim
