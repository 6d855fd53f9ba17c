#include "vgroove/sim/dielectric_tally.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vgroove::sim {

DielectricTally::DielectricTally(int n_bins) : n_bins_(n_bins) {
  if (n_bins < 1) throw std::invalid_argument("bins = " + std::to_string(n_bins) + " is out of range [1, 2147483647]");
}

int DielectricTally::bin_of(double angle) const {
  const double u = (angle + 0.5 * std::numbers::pi) / std::numbers::pi * n_bins_;
  if (!(u >= 0.0)) return 0;  // below the range, or NaN
  return std::min(n_bins_ - 1, static_cast<int>(u));
}

DielectricTally::PerK& DielectricTally::at(int side, int k) {
  std::vector<PerK>& v = by_k_[side];
  if (static_cast<int>(v.size()) <= k) v.resize(static_cast<std::size_t>(k) + 1);
  PerK& e = v[static_cast<std::size_t>(k)];
  if (e.hist.empty()) e.hist.assign(static_cast<std::size_t>(n_bins_), 0.0);
  return e;
}

void DielectricTally::add(const DielectricResult& r) {
  ++rays_;
  for (const DielectricExit& e : r.exits) {
    const int side = static_cast<int>(e.side);
    PerK& pk = at(side, e.k);
    pk.energy += e.weight;
    pk.hist[static_cast<std::size_t>(bin_of(exit_angle(e)))] += e.weight;
    by_path_[side][{e.k, e.path}] += e.weight;
    left_[side] += e.weight;
  }
  cut_ += r.cut;
  bounce_limit_ += r.bounce_limit;
  vertex_ += r.vertex;
  paths_cut_ += r.paths_cut;
}

void DielectricTally::merge(const DielectricTally& o) {
  if (o.n_bins_ != n_bins_)
    throw std::invalid_argument("bins = " + std::to_string(o.n_bins_) + " is out of range [" + std::to_string(n_bins_) +
                                ", " + std::to_string(n_bins_) + "] (merging tallies)");
  rays_ += o.rays_;
  for (int side = 0; side < 2; ++side) {
    left_[side] += o.left_[side];
    for (std::size_t k = 0; k < o.by_k_[side].size(); ++k) {
      const PerK& src = o.by_k_[side][k];
      if (src.hist.empty()) continue;
      PerK& dst = at(side, static_cast<int>(k));
      dst.energy += src.energy;
      for (std::size_t b = 0; b < src.hist.size(); ++b) dst.hist[b] += src.hist[b];
    }
    for (const auto& [key, w] : o.by_path_[side]) by_path_[side][key] += w;
  }
  cut_ += o.cut_;
  bounce_limit_ += o.bounce_limit_;
  vertex_ += o.vertex_;
  paths_cut_ += o.paths_cut_;
}

double DielectricTally::energy(Medium side, int k) const {
  const std::vector<PerK>& v = by_k_[static_cast<int>(side)];
  return k >= 0 && k < static_cast<int>(v.size()) ? v[static_cast<std::size_t>(k)].energy : 0.0;
}

std::vector<double> DielectricTally::histogram(Medium side, int k) const {
  const std::vector<PerK>& v = by_k_[static_cast<int>(side)];
  if (k >= 0 && k < static_cast<int>(v.size()) && !v[static_cast<std::size_t>(k)].hist.empty())
    return v[static_cast<std::size_t>(k)].hist;
  return std::vector<double>(static_cast<std::size_t>(n_bins_), 0.0);
}

}  // namespace vgroove::sim
