#include "vgroove/validation/lobe_bins.h"

#include "vgroove/support/user_error.h"
#include "vgroove/validation/ranges.h"

#include <string>

namespace vgroove::validation {

LobeBins read_lobe_bins(support::JsonObject& root, const LobeBins& defaults, bool flatland, bool three_d) {
  LobeBins b;
  b.flatland_bins = static_cast<int>(root.integer_or("flatland_bins", defaults.flatland_bins, 1, kMaxFlatlandBins));
  b.theta_bins = static_cast<int>(root.integer_or("theta_bins", defaults.theta_bins, 1, kMaxThetaBins));
  b.phi_bins = static_cast<int>(root.integer_or("phi_bins", defaults.phi_bins, 2, kMaxPhiBins));
  if (b.phi_bins % 2 != 0)
    root.fail("phi_bins",
              "= " + std::to_string(b.phi_bins) + " must be even (the plane of incidence runs through two bins)");
  b.max_k = static_cast<int>(root.integer_or("max_k", defaults.max_k, kMinHistogramK, kMaxHistogramK));
  const auto bound = [&](bool runs, long long bins, const char* what) {
    const long long cells = bins * (b.max_k + 2);
    if (runs && cells > kMaxHistogramCells)
      throw support::UserError(root.file() + ": " + what + " x (max_k + 2) = " + std::to_string(cells) +
                               " histogram cells, out of range [1, " + std::to_string(kMaxHistogramCells) + "]");
  };
  bound(flatland, b.flatland_bins, "flatland_bins");
  bound(three_d, static_cast<long long>(b.theta_bins) * b.phi_bins, "theta_bins x phi_bins");
  return b;
}

}  // namespace vgroove::validation
