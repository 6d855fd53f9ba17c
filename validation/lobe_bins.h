// vgroove validation: the bins of a lobe histogram, read once for every suite kind that bins exit
// directions ("brdf", "nonsymmetric_brdf"): "flatland_bins", "theta_bins", "phi_bins" (even: the
// plane of incidence runs through two bins) and "max_k" (rows k = 0..max_k and one beyond), each
// optional, each in its range of validation/ranges.h, and their product per dimension at most
// kMaxHistogramCells (every work item holds its own tally of that size). Tested by
// tests/validation/lobe_bins_test.cpp.
#pragma once

#include "vgroove/support/json_reader.h"

namespace vgroove::validation {

struct LobeBins {
  int flatland_bins = 90;
  int theta_bins = 15;
  int phi_bins = 12;
  int max_k = 16;
};

// `defaults` for the keys that are absent; `flatland`, `three_d`: which dimensions the suite runs
// (the cell bound applies to those). Throws support::UserError naming the file, the key and range.
LobeBins read_lobe_bins(support::JsonObject& root, const LobeBins& defaults, bool flatland, bool three_d);

}  // namespace vgroove::validation
