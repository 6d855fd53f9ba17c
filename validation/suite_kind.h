// vgroove validation: one interface for every kind of suite, and the registry that finds a suite
// file's kind.
//
// A SuiteKind reads a suite file of its kind (strictly, with the caller's overrides) into a
// PlannedSuite: the suite checked, its memory estimated before any work, and its job: the suite's
// fixed work items (validation/work_run.h) with what turns their results into the report, the
// printed table and the verdict. Every job runs the same way in one process, as shard I/N of a
// split run (a partial report) and as the merge of such parts (or of MPI ranks), and the merge
// gives the one-process report (timings aside); tests/cluster/shards_test.sh holds this for every
// kind. The kinds live in validation/kinds/, one file each, listed once in suite_kind.cpp.
#pragma once

#include "vgroove/support/parallel.h"
#include "vgroove/support/work_plan.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/run_options.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vgroove::validation {

// What a caller may override in a suite file (empty: the file's), and how messages name it.
struct SuiteOverrides {
  std::optional<long> rays;  // per lit facet (single grooves) or per case (rough surfaces)
  std::optional<long long> seed;
  std::optional<std::string> sampling;     // single grooves only: "stratified" or "random"
  std::optional<std::string> eq6_form;     // single grooves only: "corrected" or "printed"
  std::optional<std::string> model_table;  // "brdf" suites: a foreign model's lobes (validation/model_table.h)
  OptionNames names;
};

// What a run gives: the report JSON (when asked for), the table the command line prints, the verdict.
struct SuiteResult {
  nlohmann::json report;
  std::string table;
  bool pass = false;
};

// A suite's job: its work items and how their results become a SuiteResult.
class SuiteJob {
 public:
  virtual ~SuiteJob() = default;
  // What every part of the job carries (partial_report.h), with "units" and "items".
  virtual const nlohmann::json& descriptor() const = 0;
  // Every item in this process; nothing when *cancel was set.
  virtual std::optional<SuiteResult> run(int threads, const support::ProgressFn& progress,
                                         const std::atomic<bool>* cancel, bool report) const = 0;
  // The items of shard I/N as a partial report; nothing when *cancel was set.
  virtual std::optional<nlohmann::json> run_part(const support::Shard& shard, int threads,
                                                 const support::ProgressFn& progress,
                                                 const std::atomic<bool>* cancel) const = 0;
  // The result from parts checked together (check_parts) that cover the job; `threads` and
  // `wall_s` are the run's (the parts' sum and longest).
  virtual SuiteResult merge(const std::vector<Part>& parts, int threads, double wall_s, bool report) const = 0;
};

// A suite file read and checked, with the overrides applied.
class PlannedSuite {
 public:
  virtual ~PlannedSuite() = default;
  // The kind as the descriptor of its parts and messages name it ("brdf", "single-groove", ...).
  virtual std::string kind() const = 0;
  // The suite's name (progress lines).
  virtual std::string name() const = 0;
  // The files read beyond the suite file (a set's suites, a model table): never an output.
  virtual std::vector<std::string> extra_inputs() const { return {}; }
  // An upper bound of the memory a run on `threads` threads needs (support/memory.h), and what
  // makes it up, for the refusal message.
  virtual double memory_bytes(int threads, bool report) const = 0;
  virtual std::string memory_what(int threads) const = 0;
  // `descriptor` identifies the run in its parts (partial_report.h: job_descriptor); the work
  // polls `cancel` (may be null) inside its items, as the SuiteJob's runs are given it.
  virtual std::unique_ptr<SuiteJob> job(nlohmann::json descriptor, const std::atomic<bool>* cancel) const = 0;
};

class SuiteKind {
 public:
  virtual ~SuiteKind() = default;
  // The value of "kind" in the suite's file.
  virtual const char* name() const = 0;
  // Reads `j` (from `file`) strictly with the overrides: support::UserError naming the file, the
  // JSON path or the option and what was expected.
  virtual std::unique_ptr<PlannedSuite> plan(const nlohmann::json& j, const std::string& file,
                                             const SuiteOverrides& o) const = 0;
};

// The kind of a suite file: its "kind" among the registered ones; anything else is read as
// single-groove suites (Table 1, stress; a set of suites), whose reader names what is wrong.
const SuiteKind& find_kind(const nlohmann::json& suite);
// The registered kinds, in the registry's order.
const std::vector<const SuiteKind*>& suite_kinds();

// The refusals every kind of rough surface shares: the single-groove options, a model table
// outside "brdf", and the ranges of --rays and --seed.
void check_rough_surface_overrides(const SuiteOverrides& o, const std::string& file, const std::string& kind);

}  // namespace vgroove::validation
