// vgroove validation: `validate` as one library call, shared by the command line and the Python
// module: read a suite file of any registered kind (suite_kind.h: single grooves, "brdf",
// "table2", "furnace", "sampling", "nonsymmetric_brdf", "profiles"), apply the overrides, run it in
// this process, and return the report JSON and the table the command line prints.
//
// Two steps, so that a caller can check everything (and its output target) before the work:
// plan_validation reads and checks (support::UserError naming the file, JSON path or option; the
// suite file is read once, so it may be a pipe; a run whose memory estimate exceeds what the
// process may use is refused, support/memory.h), run_validation does the work.
#pragma once

#include "vgroove/support/parallel.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/suite_kind.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vgroove::validation {

struct ValidateOptions {
  std::string suite;  // the suite file (with suite_json: the name messages give it)
  // The suite itself, already read (Python's validate(dict)); null: read the file `suite`. The
  // file names of a set's suites are then taken relative to the current directory.
  const nlohmann::json* suite_json = nullptr;
  std::optional<long> rays;             // per lit facet (single grooves) or per case (rough surfaces)
  int threads = 0;                      // 0: all cores; the figures do not depend on it
  std::optional<std::string> sampling;  // single grooves only: "stratified" or "random"
  std::optional<std::string> eq6_form;  // single grooves only: "corrected" or "printed"
  std::optional<long long> seed;
  std::optional<std::string> model_table;  // "brdf" suites: a foreign model's lobes (validation/model_table.h)
  OptionNames names;                       // how messages name the options above
};

// A suite file read and checked (by its kind, suite_kind.h), with the overrides applied.
struct ValidationPlan {
  std::shared_ptr<const PlannedSuite> suite;
  int threads = 0;
  std::vector<std::string> inputs;  // the files read (suite, the set's suites, model table): never an output
  bool report = true;               // build ValidationResult::report (the command line without --out does not)
};

// The options as a kind reads them.
SuiteOverrides overrides_of(const ValidateOptions& a);

ValidationPlan plan_validation(const ValidateOptions& opt);

struct ValidationResult {
  nlohmann::json report;  // what `vgroove validate --out` writes (empty when interrupted)
  std::string table;      // what `vgroove validate` prints
  bool pass = false;
  bool interrupted = false;  // `cancel` was set: no report
};

// A progress callback for the run (labelled "validate NAME"); may return an empty function.
using ProgressFactory = std::function<support::ProgressFn(const std::string& label)>;

ValidationResult run_validation(const ValidationPlan& plan, const ProgressFactory& progress = {},
                                const std::atomic<bool>* cancel = nullptr);

}  // namespace vgroove::validation
