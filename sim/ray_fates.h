// vgroove sim: what happened to a set of traced rays, one bucket per fate.
//
// Shared by the tallies of single grooves (sim/tally.h), procedural surfaces (sim/microsurface.h,
// sim/microsurface3d.h) and scenes (validation/simulate.h): every ray counted is in exactly one of
// escaped, blocked, vertex_hits, bounce_limit, not_upward; the caller bins the escaped ones.
// Integer counts, so any merge order gives the same totals.
#pragma once

#include "vgroove/sim/tracer.h"

#include <algorithm>
#include <cstdint>

namespace vgroove::sim {

struct RayFates {
  std::int64_t rays = 0;
  std::int64_t escaped = 0;       // left going up: the caller bins these
  std::int64_t blocked = 0;       // never entered its groove (not expected: peaks on one line)
  std::int64_t vertex_hits = 0;   // hit a ridge or a groove's bottom exactly: reflection undefined
  std::int64_t bounce_limit = 0;  // still inside after TraceOptions::max_bounces reflections
  std::int64_t not_upward = 0;    // "escaped" along or below the horizon (not expected), kept apart
  std::int64_t bounces = 0;       // reflections summed over escaped rays
  int max_k_seen = 0;             // largest bounce count of an escaped ray

  // Counts one ray; true when it escaped going up (`upward`: its exit direction's component along
  // the macrosurface normal is > 0), i.e. when the caller should bin it.
  bool count(Termination how, int k, bool upward) {
    ++rays;
    switch (how) {
      case Termination::blocked:
        ++blocked;
        return false;
      case Termination::vertex_hit:
        ++vertex_hits;
        return false;
      case Termination::bounce_limit:
        ++bounce_limit;
        return false;
      case Termination::escaped:
        break;
    }
    if (!upward) {
      ++not_upward;
      return false;
    }
    ++escaped;
    bounces += k;
    max_k_seen = std::max(max_k_seen, k);
    return true;
  }

  // count() for n rays that escaped going up, with sum_k reflections in all and k_max the most
  // of any (the block tallies keep these in registers over a block).
  void add_escaped(std::int64_t n, std::int64_t sum_k, int k_max) {
    rays += n;
    escaped += n;
    bounces += sum_k;
    max_k_seen = std::max(max_k_seen, k_max);
  }

  void merge_fates(const RayFates& o) {
    rays += o.rays;
    escaped += o.escaped;
    blocked += o.blocked;
    vertex_hits += o.vertex_hits;
    bounce_limit += o.bounce_limit;
    not_upward += o.not_upward;
    bounces += o.bounces;
    max_k_seen = std::max(max_k_seen, o.max_k_seen);
  }

  // Fraction of the rays that left (with F = 1 the albedo); 1 - albedo() = lost() / rays.
  double albedo() const { return rays > 0 ? static_cast<double>(escaped) / static_cast<double>(rays) : 0.0; }
  std::int64_t lost() const { return blocked + vertex_hits + bounce_limit + not_upward; }
};

}  // namespace vgroove::sim
