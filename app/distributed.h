// vgroove CLI: a job (validation/work_run.h) run by every rank of an MPI run, merged on rank 0.
#pragma once

#include "vgroove/app/mpi_world.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/work_run.h"

#include <atomic>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace vgroove::app {

// Why a distributed run ended without results.
struct RankFailure : std::runtime_error {
  bool interrupted = false;
  explicit RankFailure(const std::string& what, bool interrupted_ = false)
      : std::runtime_error(what), interrupted(interrupted_) {}
};

// Every rank runs its part (run_part(shard), the items of shard rank+1 / size, returning the
// partial report or nothing when interrupted); rank 0 gets every rank's part, checked together
// (validation::check_parts), the other ranks nothing. A rank that throws or is interrupted makes
// every rank throw RankFailure, naming the first rank that failed; no rank returns partial
// results. The test hook VGROOVE_TEST_FAIL_RANK=R makes rank R fail after its work.
template <class RunPart>
std::optional<std::vector<validation::Part>> gather_parts(RunPart&& run_part) {
  const World& w = world();
  std::string text, error;
  bool ok = true;
  try {
    const std::optional<nlohmann::json> part = run_part(support::Shard{w.rank + 1, w.size});
    if (!part) {
      ok = false, error = "interrupted";
    } else {
      text = part->dump();
      if (const char* fail = std::getenv("VGROOVE_TEST_FAIL_RANK"); fail && std::atoi(fail) == w.rank)
        throw std::runtime_error("failure injected by VGROOVE_TEST_FAIL_RANK");
    }
  } catch (const std::exception& e) {
    ok = false, error = e.what();
  }
  std::string first;
  const bool every =
      all_ok(ok, "rank " + std::to_string(w.rank) + " of " + std::to_string(w.size) + ": " + error, &first);
  if (!every) throw RankFailure(first, first.ends_with(": interrupted"));
  const std::vector<std::string> texts = gather_text(text);
  if (!w.root()) return std::nullopt;
  std::vector<validation::Part> parts;
  for (std::size_t r = 0; r < texts.size(); ++r)
    parts.push_back(validation::part_from_json(nlohmann::json::parse(texts[r]), "rank " + std::to_string(r)));
  return validation::check_parts(std::move(parts));
}

// The threads of every part.
inline int threads_of(const std::vector<validation::Part>& parts) {
  int threads = 0;
  for (const auto& p : parts) threads += p.header.threads;
  return threads;
}

// A job run by every rank (gather_parts), merged on rank 0: every unit's results there, nothing
// on the other ranks.
template <class Work>
std::optional<std::vector<validation::UnitResult<Work>>> run_distributed(const validation::Job<Work>& job, int threads,
                                                                         const support::ProgressFn& progress,
                                                                         const std::atomic<bool>* cancel,
                                                                         int* threads_total = nullptr) {
  const auto parts = gather_parts([&](const support::Shard& shard) {
    return validation::run_job_part(job, shard, threads, world().root() ? progress : support::ProgressFn{}, cancel);
  });
  if (!parts) return std::nullopt;
  if (threads_total) *threads_total = threads_of(*parts);
  return validation::merge_job_parts(job, *parts);
}

}  // namespace vgroove::app
