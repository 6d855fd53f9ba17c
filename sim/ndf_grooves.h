// vgroove sim: the rough surface's infinite limit: every ray falls into a V-groove of its own,
// drawn from the NDF (flatland |theta_m| from 2 D2 cos; 3D theta_m from 2 pi D cos sin, phi_a
// uniform on [0, pi)), landing uniformly across its opening, and is traced exactly (3D in the
// groove's cross-section, lifted back): the process of sim/microsurface.h and
// sim/microsurface3d.h with one groove per ray. Its fractions are multinomial shares of N
// independent rays, standard error sqrt(p (1 - p) / N) and nothing else. Deterministic: chunk c
// from Rng(splitmix64(seed ^ kNdfGrooveStream), stream, c), integer counts.
// Tests: through validation/energy_table.h (tests/cluster/shards_test.sh, tests/cluster/mpi_test.sh).
// Derivation: docs/derivations/microsurface.md.
#pragma once

#include "vgroove/common/ndf_kind.h"
#include "vgroove/sim/ray_fates.h"
#include "vgroove/sim/tracer.h"

#include <cstdint>
#include <vector>

namespace vgroove::sim {

inline constexpr std::uint64_t kNdfGrooveStream = 0x6e64666772ULL;  // "ndfgr"

// Escaped rays by bounce count: rows k = 0..max_k, and row max_k + 1 for every k > max_k.
struct BounceCounts : RayFates {
  int max_k = 0;
  std::vector<std::int64_t> by_k;

  BounceCounts() = default;
  explicit BounceCounts(int max_k_) : max_k(max_k_), by_k(static_cast<std::size_t>(max_k_) + 2, 0) {}
  int row_of(int k) const { return k > max_k ? max_k + 1 : k; }
  void merge(const BounceCounts& o);  // same max_k
};

struct NdfGrooveOptions {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;    // > 0
  double theta_i = 0.0;  // flatland: in (-pi/2, pi/2); 3D: the polar angle of the light, in [0, pi/2)
  bool three_d = false;
  std::int64_t rays = 100000;
  std::uint64_t seed = 1;
  std::uint64_t stream = 0;  // which stream of the seed (e.g. a table cell's index)
  int max_k = 16;
  TraceOptions trace;
};

std::int64_t chunk_count(const NdfGrooveOptions& opt);
// The rays of chunk c (kRaysPerChunk of them; the last chunk holds the rest).
BounceCounts trace_ndf_grooves_chunk(const NdfGrooveOptions& opt, std::int64_t chunk);

}  // namespace vgroove::sim
