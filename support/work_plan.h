// vgroove support: one job cut into deterministic work items, and the items split over shards
// or processes.
//
// A job is a list of units (a suite's cases, an energy table's cells), in the job's order. A unit
// traces its rays in `chunks` chunks (sim::kRaysPerChunk rays each, each chunk with its own
// random stream, so a chunk's result never depends on who runs it) and may have a fixed part
// that is not traced (the analytic model of a case). A work item is one unit's fixed part or a
// run of at most `chunks_per_item` of its chunks. The items depend on the job alone, never on how
// many shards or processes run it; the results of a unit are merged from its items' integer
// tallies, so any split of the items gives the same figures bit for bit.
//
// Costs are integer estimates (nanoseconds of one core, roughly): every process computes the same
// split from the same job without talking to the others. They only balance the work; a wrong
// estimate makes a split uneven, never a result different.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vgroove::support {

struct WorkUnit {
  std::int64_t chunks = 1;      // >= 1
  std::int64_t chunk_cost = 1;  // estimated cost of one chunk
  bool has_fixed = false;       // a fixed (untraced) part, run once
  std::int64_t fixed_cost = 0;
};

struct WorkItem {
  std::size_t unit = 0;
  std::int64_t chunk_begin = 0, chunk_end = 0;  // chunks [begin, end); begin == end: the unit's fixed part
  std::int64_t cost = 0;
  bool fixed() const { return chunk_begin == chunk_end; }
};

// Every unit's items in unit order: its fixed part first, then its chunks in runs of at most
// `chunks_per_item` (>= 1), cut into equal runs (the last ones one chunk shorter at most).
std::vector<WorkItem> make_work_items(const std::vector<WorkUnit>& units, std::int64_t chunks_per_item);

// The I-th of N parts of a job, 1 <= I <= N.
struct Shard {
  int index = 1, count = 1;
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
inline constexpr int kMaxShards = 100000;
// "I/N" from the command line; a UserError naming `what` (e.g. "--shard") otherwise.
Shard parse_shard(const std::string& text, const std::string& what);

// The part (0-based) that runs each item when the job is cut into `parts` parts: the items in
// order, cut where the running cost crosses a multiple of total / parts (an item goes to the part
// that holds the middle of its cost). Consecutive items stay together, so a part touches few units
// (and builds few surfaces); each part's estimated cost is within one item of total / parts. A
// function of (items, parts) only.
std::vector<int> assign_items(const std::vector<WorkItem>& items, int parts);
// The items of part `part` (0-based), in item order.
std::vector<std::size_t> items_of_part(const std::vector<WorkItem>& items, int parts, int part);

}  // namespace vgroove::support
