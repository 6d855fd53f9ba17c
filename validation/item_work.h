// vgroove validation: a suite whose run is a list of independent items (a case, a chi-square
// test, a reciprocity row), each computed on one thread from its own seeded stream, as a job of
// work items (work_run.h): one unit per item, of one chunk, whose tally is the item's outcome.
// A suite of N items splits over up to N processes (`--shard`, mpirun) and gives the same
// numbers as in one process, since no item depends on another or on where it ran.
//
// The outcome travels between processes as it is: written field by field (outcome_fields.h,
// exactly) with the digest of what was written (partial_report.h text_digest), read back as
// strictly as a suite file and refused when the digest does not match (a damaged part).
// `after_read(o, item, outcome)` sets what the suite fixes (the case) and checks what the suite
// knows of the outcome's shape (array lengths), failing through `o` (support::JsonObject::fail).
#pragma once

#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/support/work_plan.h"
#include "vgroove/validation/outcome_fields.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/work_run.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <utility>
#include <vector>

namespace vgroove::validation {

template <class Outcome>
struct ItemWork {
  struct Context {};
  struct Fixed {};
  using Tally = Outcome;

  std::function<Outcome(std::size_t)> run_item;  // called from several threads at once
  std::function<void(support::JsonObject&, std::size_t, Outcome&)> after_read;

  std::shared_ptr<const Context> prepare(std::size_t) const { return std::make_shared<const Context>(); }
  Tally run_chunks(const Context&, std::size_t item, std::int64_t, std::int64_t) const { return run_item(item); }
  Fixed run_fixed(std::size_t) const { throw std::logic_error("ItemWork: an item has no fixed part"); }
  static void merge(Tally&, const Tally&) { throw std::logic_error("ItemWork: an item is one chunk, run once"); }

  static nlohmann::json tally_json(const Tally& t) {
    nlohmann::json outcome = outcome_fields::to_json(t);
    const std::string digest = text_digest(outcome.dump());
    return {{"outcome", std::move(outcome)}, {"digest", digest}};
  }
  static nlohmann::json fixed_json(const Fixed&) { return nlohmann::json::object(); }

  Tally read_tally(support::JsonObject& j, std::size_t item, const std::vector<ChunkRun>&) const {
    const nlohmann::json& outcome = j.raw("outcome");
    const std::string digest = j.string("digest");
    if (digest != text_digest(outcome.dump()))
      j.fail("digest", "= \"" + digest + "\" is not the digest of /outcome (" + text_digest(outcome.dump()) +
                           "): a damaged part");
    Tally t{};
    outcome_fields::read(outcome, j.file(), j.path("outcome"), t);
    if (after_read) after_read(j, item, t);
    return t;
  }
  Fixed read_fixed(support::JsonObject& j, std::size_t) const {
    throw support::UserError(j.file() + ": " + j.pointer() + " is given: an item has no fixed part");
  }
};

// `items` items, item n's outcome run_item(n); `cost(n)` (may be empty) its estimated cost, so
// that shards get even shares.
template <class Outcome>
Job<ItemWork<Outcome>> item_job(std::size_t items, std::function<Outcome(std::size_t)> run_item,
                                std::function<void(support::JsonObject&, std::size_t, Outcome&)> after_read,
                                nlohmann::json descriptor, const std::function<std::int64_t(std::size_t)>& cost = {}) {
  std::vector<support::WorkUnit> units(items);
  for (std::size_t n = 0; n < items; ++n) units[n].chunk_cost = cost ? std::max<std::int64_t>(1, cost(n)) : 1;
  return make_job(ItemWork<Outcome>{std::move(run_item), std::move(after_read)}, std::move(units),
                  std::move(descriptor));
}

}  // namespace vgroove::validation
