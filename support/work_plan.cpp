#include "vgroove/support/work_plan.h"

#include "vgroove/support/user_error.h"

#include <algorithm>
#include <cassert>
#include <charconv>
#include <numeric>

namespace vgroove::support {

std::vector<WorkItem> make_work_items(const std::vector<WorkUnit>& units, std::int64_t chunks_per_item) {
  assert(chunks_per_item >= 1);
  std::vector<WorkItem> items;
  for (std::size_t u = 0; u < units.size(); ++u) {
    const WorkUnit& w = units[u];
    assert(w.chunks >= 1);
    if (w.has_fixed) items.push_back({u, 0, 0, w.fixed_cost});
    const std::int64_t runs = (w.chunks + chunks_per_item - 1) / chunks_per_item;
    for (std::int64_t r = 0; r < runs; ++r) {
      const std::int64_t b = w.chunks * r / runs, e = w.chunks * (r + 1) / runs;
      items.push_back({u, b, e, (e - b) * w.chunk_cost});
    }
  }
  return items;
}

Shard parse_shard(const std::string& text, const std::string& what) {
  const std::string range = "I/N with 1 <= I <= N <= " + std::to_string(kMaxShards);
  Shard s;
  const auto slash = text.find('/');
  auto number = [&](const std::string& t, int& v) {
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    return !t.empty() && r.ec == std::errc() && r.ptr == t.data() + t.size();
  };
  if (slash == std::string::npos || !number(text.substr(0, slash), s.index) || !number(text.substr(slash + 1), s.count))
    throw UserError(what + " = \"" + text + "\" is not of the form " + range + " (e.g. 2/8)");
  if (s.count < 1 || s.count > kMaxShards || s.index < 1 || s.index > s.count)
    throw UserError(what + " = " + text + " is out of range: " + range);
  return s;
}

std::vector<int> assign_items(const std::vector<WorkItem>& items, int parts) {
  assert(parts >= 1);
  double total = 0.0;
  for (const WorkItem& it : items) total += static_cast<double>(std::max<std::int64_t>(it.cost, 1));
  std::vector<int> owner(items.size(), 0);
  double before = 0.0;
  for (std::size_t i = 0; i < items.size(); ++i) {
    const double c = static_cast<double>(std::max<std::int64_t>(items[i].cost, 1));
    // The part whose share of the total holds the item's middle.
    owner[i] = std::min(parts - 1, static_cast<int>((before + 0.5 * c) / total * parts));
    before += c;
  }
  return owner;
}

std::vector<std::size_t> items_of_part(const std::vector<WorkItem>& items, int parts, int part) {
  const std::vector<int> owner = assign_items(items, parts);
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < owner.size(); ++i)
    if (owner[i] == part) mine.push_back(i);
  return mine;
}

}  // namespace vgroove::support
