// vgroove validation: a job's work items (support/work_plan.h) run, and the results of the
// processes that ran them merged into each unit's. One process, a shard (partial_report.h) or an
// MPI rank all take this path; a process keeps per unit the chunk runs it traced (tallies merged)
// and the unit's fixed part (the model) if it ran it. Tallies are integer counts, so any grouping
// merges to the same totals; merge_unit_parts checks that the parts cover every chunk and fixed
// part of every unit exactly once, so a merged result is never silently partial. A Work type
// provides Context, Tally, Fixed, prepare, run_chunks, run_fixed (called from several threads),
// merge, tally_json, fixed_json, read_tally and read_fixed (as strictly as a suite file: counts,
// lengths and sums; model values in their physical range, rows adding up to totals).
// Tests: tests/validation/item_work_test.cpp (ItemWork.AnOutcomeCrossesProcessesBitForBit),
// tests/cluster/shards_test.sh, tests/cluster/mpi_test.sh, tests/cluster/merge_parts_test.py.
// Derivation: docs/derivations/validation.md.
#pragma once

#include "vgroove/support/json_reader.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/seconds_since.h"
#include "vgroove/support/user_error.h"
#include "vgroove/support/work_plan.h"
#include "vgroove/validation/partial_report.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace vgroove::validation {

using ChunkRun = std::pair<std::int64_t, std::int64_t>;  // chunks [first, second)

// The rays of the chunks `runs` of a unit of `rays` rays cut in chunks of `per_chunk` (the last
// chunk holds the rest).
inline std::int64_t rays_in_chunks(const std::vector<ChunkRun>& runs, std::int64_t rays, std::int64_t per_chunk) {
  std::int64_t n = 0;
  for (const ChunkRun& c : runs)
    n += std::max<std::int64_t>(0, std::min(c.second * per_chunk, rays) - c.first * per_chunk);
  return n;
}

template <class Tally, class Fixed>
struct UnitPart {
  std::vector<ChunkRun> runs;  // in chunk order
  std::optional<Tally> tally;  // the runs' tallies merged
  std::optional<Fixed> fixed;
};
template <class Work>
using PartResults = std::map<std::size_t, UnitPart<typename Work::Tally, typename Work::Fixed>>;

// A unit's results with every chunk and its fixed part present.
template <class Work>
struct UnitResult {
  typename Work::Tally tally;
  std::optional<typename Work::Fixed> fixed;
};

// Runs the items `mine` (indices into `items`) on `threads` threads: fixed parts first (the
// costliest first), then the chunk runs in item order, so that the items of one unit follow each
// other and its context (prepare) is built once per process while they run. Returns nothing when
// *cancel was set during the run.
template <class Work>
std::optional<PartResults<Work>> run_work_items(const Work& work, const std::vector<support::WorkItem>& items,
                                                std::vector<std::size_t> mine, int threads,
                                                const support::ProgressFn& progress = {},
                                                const std::atomic<bool>* cancel = nullptr) {
  using Context = typename Work::Context;
  std::stable_sort(mine.begin(), mine.end(), [&](std::size_t a, std::size_t b) {
    const support::WorkItem &x = items[a], &y = items[b];
    if (x.fixed() != y.fixed()) return x.fixed();
    return x.fixed() ? x.cost > y.cost : a < b;
  });
  std::map<std::size_t, int> pending;  // chunk items per unit still to run here
  for (std::size_t i : mine)
    if (!items[i].fixed()) ++pending[items[i].unit];
  std::mutex mutex;
  std::map<std::size_t, std::shared_future<std::shared_ptr<const Context>>> contexts;
  PartResults<Work> out;
  const bool complete = support::parallel_for(
      mine.size(), support::resolve_threads(threads),
      [&](std::size_t n) {
        const support::WorkItem& it = items[mine[n]];
        if (it.fixed()) {
          auto fixed = work.run_fixed(it.unit);
          std::lock_guard<std::mutex> lock(mutex);
          out[it.unit].fixed = std::move(fixed);
          return;
        }
        std::shared_future<std::shared_ptr<const Context>> ctx;
        std::optional<std::promise<std::shared_ptr<const Context>>> builder;
        {
          std::lock_guard<std::mutex> lock(mutex);
          auto found = contexts.find(it.unit);
          if (found == contexts.end()) {
            builder.emplace();
            found = contexts.emplace(it.unit, builder->get_future().share()).first;
          }
          ctx = found->second;
        }
        if (builder) {
          try {
            builder->set_value(work.prepare(it.unit));
          } catch (...) {
            builder->set_exception(std::current_exception());
          }
        }
        auto tally = work.run_chunks(*ctx.get(), it.unit, it.chunk_begin, it.chunk_end);
        std::lock_guard<std::mutex> lock(mutex);
        auto& part = out[it.unit];
        part.runs.emplace_back(it.chunk_begin, it.chunk_end);
        if (part.tally)
          Work::merge(*part.tally, tally);
        else
          part.tally = std::move(tally);
        if (--pending[it.unit] == 0) contexts.erase(it.unit);  // its last item here: free the context
      },
      progress, cancel, 1);
  // A work item that polls the flag inside its chunks returns early with a partial tally: a run
  // cancelled at any point is incomplete.
  if (!complete || support::cancelled(cancel)) return std::nullopt;
  for (auto& [unit, part] : out) std::sort(part.runs.begin(), part.runs.end());
  return out;
}

// {"unit", "chunks": [[begin, end], ...], "tally", "fixed"} per unit, in unit order.
template <class Work>
nlohmann::json part_results_json(const PartResults<Work>& r) {
  nlohmann::json units = nlohmann::json::array();
  for (const auto& [unit, part] : r) {
    nlohmann::json u = {{"unit", unit}};
    nlohmann::json runs = nlohmann::json::array();
    for (const ChunkRun& c : part.runs) runs.push_back({c.first, c.second});
    u["chunks"] = std::move(runs);
    if (part.tally) u["tally"] = Work::tally_json(*part.tally);
    if (part.fixed) u["fixed"] = Work::fixed_json(*part.fixed);
    units.push_back(std::move(u));
  }
  return units;
}

// The inverse of part_results_json, as strictly as a suite file: `file` and the JSON path of the
// first damaged value in every message; every chunk within its unit, every tally and fixed part
// read by the work itself (Work::read_tally, read_fixed) against the job.
template <class Work>
PartResults<Work> part_results_from_json(const Work& work, const nlohmann::json& units,
                                         const std::vector<support::WorkUnit>& job_units, const std::string& file) {
  PartResults<Work> r;
  if (!units.is_array()) throw support::UserError(file + ": /units must be an array, found " + units.type_name());
  try {
    for (std::size_t n = 0; n < units.size(); ++n) {
      support::JsonObject u(units[n], file, "/units/" + std::to_string(n));
      const auto unit = static_cast<std::size_t>(u.integer("unit", 0, static_cast<long long>(job_units.size()) - 1));
      if (r.count(unit)) u.fail("unit", "= " + std::to_string(unit) + " is listed twice");
      auto& part = r[unit];
      const nlohmann::json& chunks = u.raw("chunks");
      if (!chunks.is_array()) u.fail("chunks", "must be an array of [begin, end] pairs");
      for (std::size_t c = 0; c < chunks.size(); ++c) {
        const nlohmann::json& run = chunks[c];
        const std::int64_t count = job_units[unit].chunks;
        if (!run.is_array() || run.size() != 2 || !run[0].is_number_integer() || !run[1].is_number_integer() ||
            run[0].get<std::int64_t>() < 0 || run[1].get<std::int64_t>() > count ||
            run[0].get<std::int64_t>() >= run[1].get<std::int64_t>() ||
            (run[1].is_number_unsigned() && run[1].get<std::uint64_t>() > static_cast<std::uint64_t>(count)))
          u.fail_at("chunks", c,
                    "= " + support::value_text(run) + " is not a run [begin, end) of the unit's " +
                        std::to_string(count) + " chunks");
        part.runs.emplace_back(run[0].get<std::int64_t>(), run[1].get<std::int64_t>());
      }
      std::sort(part.runs.begin(), part.runs.end());
      for (std::size_t c = 1; c < part.runs.size(); ++c)
        if (part.runs[c].first < part.runs[c - 1].second) u.fail("chunks", "has overlapping runs");
      if (u.has("tally")) {
        support::JsonObject t = u.object("tally");
        part.tally = work.read_tally(t, unit, part.runs);
        t.finish();
      }
      if (u.has("fixed")) {
        support::JsonObject f = u.object("fixed");
        part.fixed = work.read_fixed(f, unit);
        f.finish();
      }
      u.finish();
      if (part.runs.empty() != !part.tally)
        u.fail(part.tally ? "tally" : "chunks", part.tally ? "is given for no chunks" : "are given without a tally");
      if (!part.tally && !part.fixed) u.fail("chunks", "are empty and there is no fixed part: the unit ran nothing");
    }
  } catch (const nlohmann::json::exception& e) {
    throw support::UserError(file + ": not a vgroove partial report (" + e.what() + ")");
  }
  return r;
}

// Every unit's results from the parts (in any order): each chunk of each unit and each fixed part
// present exactly once, or a UserError naming the unit and what is missing or doubled.
template <class Work>
std::vector<UnitResult<Work>> merge_unit_parts(const std::vector<support::WorkUnit>& units,
                                               const std::vector<PartResults<Work>>& parts) {
  std::vector<UnitResult<Work>> out(units.size());
  for (std::size_t u = 0; u < units.size(); ++u) {
    std::vector<ChunkRun> runs;
    std::optional<typename Work::Tally> tally;
    int fixed_parts = 0;
    for (const auto& p : parts) {
      const auto found = p.find(u);
      if (found == p.end()) continue;
      const auto& part = found->second;
      runs.insert(runs.end(), part.runs.begin(), part.runs.end());
      if (part.tally) {
        if (tally)
          Work::merge(*tally, *part.tally);
        else
          tally = *part.tally;
      }
      if (part.fixed) ++fixed_parts, out[u].fixed = *part.fixed;
    }
    std::sort(runs.begin(), runs.end());
    std::int64_t next = 0;
    for (const ChunkRun& c : runs) {
      if (c.first != next || c.second <= c.first)
        throw support::UserError("unit " + std::to_string(u) + ": chunks [" + std::to_string(c.first) + ", " +
                                 std::to_string(c.second) + ") " + (c.first < next ? "overlap" : "leave a gap") +
                                 " (parts of different splits?)");
      next = c.second;
    }
    if (next != units[u].chunks || !tally)
      throw support::UserError("unit " + std::to_string(u) + ": chunks " + std::to_string(next) + ".." +
                               std::to_string(units[u].chunks) + " are missing");
    if (fixed_parts != (units[u].has_fixed ? 1 : 0))
      throw support::UserError("unit " + std::to_string(u) + ": its model part is given " +
                               std::to_string(fixed_parts) + " times");
    out[u].tally = std::move(*tally);
  }
  return out;
}

}  // namespace vgroove::validation

namespace vgroove::validation {

// A job ready to run: its work, units, items and the descriptor every part of it carries
// (partial_report.h: {"command", "kind", "input_file", "input", "options"}; "units" and "items"
// are added here).
template <class Work>
struct Job {
  Work work;
  std::vector<support::WorkUnit> units;
  std::vector<support::WorkItem> items;
  nlohmann::json descriptor;
};

// Runs per job of about this many chunks: items of one chunk each up to 4096 chunks, longer runs
// above (at most 64 chunks, 2 x 10^6 rays), so that a job of any size is cut into a few thousand
// items at least: enough to balance over many processes, few enough to list.
inline std::int64_t chunks_per_item(const std::vector<support::WorkUnit>& units) {
  std::int64_t total = 0;
  for (const auto& u : units) total += u.chunks;
  return std::clamp<std::int64_t>(total / 4096, 1, 64);
}

template <class Work>
Job<Work> make_job(Work work, std::vector<support::WorkUnit> units, nlohmann::json descriptor) {
  Job<Work> job{std::move(work), std::move(units), {}, std::move(descriptor)};
  job.items = support::make_work_items(job.units, chunks_per_item(job.units));
  job.descriptor["units"] = job.units.size();
  job.descriptor["items"] = job.items.size();
  return job;
}

// Every item in this process: every unit's results, or nothing when cancelled.
template <class Work>
std::optional<std::vector<UnitResult<Work>>> run_job(const Job<Work>& job, int threads,
                                                     const support::ProgressFn& progress = {},
                                                     const std::atomic<bool>* cancel = nullptr) {
  std::vector<std::size_t> all(job.items.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  auto part = run_work_items(job.work, job.items, std::move(all), threads, progress, cancel);
  if (!part) return std::nullopt;
  return merge_unit_parts<Work>(job.units, {std::move(*part)});
}

// The items of shard I/N (support::assign_items), as a partial report; nothing when cancelled.
template <class Work>
std::optional<nlohmann::json> run_job_part(const Job<Work>& job, const support::Shard& shard, int threads,
                                           const support::ProgressFn& progress = {},
                                           const std::atomic<bool>* cancel = nullptr) {
  const auto t0 = std::chrono::steady_clock::now();
  PartialHeader h;
  h.job = job.descriptor;
  h.shard = shard;
  h.items = support::items_of_part(job.items, shard.count, shard.index - 1);
  h.threads = support::resolve_threads(threads);
  auto part = run_work_items(job.work, job.items, h.items, threads, progress, cancel);
  if (!part) return std::nullopt;
  h.wall_s = support::seconds_since(t0);
  return partial_report_json(h, part_results_json<Work>(*part));
}

// Every unit's results from parts already checked together (check_parts) against this job.
template <class Work>
std::vector<UnitResult<Work>> merge_job_parts(const Job<Work>& job, const std::vector<Part>& parts) {
  for (const Part& p : parts)
    if (const std::string d = job_difference(p.header.job, job.descriptor); !d.empty())
      throw support::UserError("merge: " + p.file + ": its job differs at /partial/job" + d +
                               " from the one rebuilt from it (another version?)");
  std::vector<PartResults<Work>> results;
  for (const Part& p : parts) {
    results.push_back(part_results_from_json<Work>(job.work, p.units, job.units, p.file));
    // The part ran exactly the chunks and fixed parts of its items.
    std::map<std::size_t, std::vector<ChunkRun>> expected;
    std::map<std::size_t, bool> fixed;
    for (std::size_t i : p.header.items) {
      const support::WorkItem& it = job.items[i];
      if (it.fixed())
        fixed[it.unit] = true;
      else
        expected[it.unit].emplace_back(it.chunk_begin, it.chunk_end);
    }
    for (auto& [unit, runs] : expected) std::sort(runs.begin(), runs.end());
    for (const auto& [unit, part] : results.back()) {
      const auto e = expected.find(unit);
      if ((e == expected.end() ? std::vector<ChunkRun>{} : e->second) != part.runs ||
          fixed.count(unit) != (part.fixed ? 1u : 0u))
        throw support::UserError("merge: " + p.file + ": /units: unit " + std::to_string(unit) +
                                 " holds other chunks than the part's items (/partial/items): a damaged part");
    }
    std::set<std::size_t> units;
    for (const auto& [unit, runs] : expected) units.insert(unit);
    for (const auto& [unit, f] : fixed) units.insert(unit);
    if (results.back().size() != units.size())
      throw support::UserError("merge: " + p.file +
                               ": /units lacks units of the part's items (/partial/items): a damaged part");
  }
  return merge_unit_parts<Work>(job.units, results);
}

}  // namespace vgroove::validation
