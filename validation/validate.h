// vgroove validation: `validate` as one library call, shared by the command line and the Python
// module: read a suite file of any kind (single grooves: Table 1, stress; rough surfaces: "brdf"
// (Fig. 11), "furnace", "sampling", "table2", "profiles", "nonsymmetric_brdf"), apply the overrides, run it, and return
// the report JSON and the table the command line prints.
//
// Two steps, so that a caller can check everything (and its output target) before the work:
// plan_validation reads and checks (support::UserError naming the file, JSON path or option; the
// suite file is read once, so it may be a pipe; a run whose memory estimate exceeds what the
// process may use is refused, support/memory.h), run_validation does the work.
#pragma once

#include "vgroove/support/parallel.h"
#include "vgroove/validation/brdf_suite.h"
#include "vgroove/validation/furnace_suite.h"
#include "vgroove/validation/model_table.h"
#include "vgroove/validation/nonsymmetric_suite.h"
#include "vgroove/validation/profiles_suite.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/sampling_suite.h"
#include "vgroove/validation/suite.h"
#include "vgroove/validation/table2_suite.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace vgroove::validation {

struct ValidateOptions {
  std::string suite;                    // the suite file
  std::optional<long> rays;             // per lit facet (single grooves) or per case (rough surfaces)
  int threads = 0;                      // 0: all cores; the figures do not depend on it
  std::optional<std::string> sampling;  // single grooves only: "stratified" or "random"
  std::optional<std::string> eq6_form;  // single grooves only: "corrected" or "printed"
  std::optional<long long> seed;
  std::optional<std::string> model_table;  // "brdf" suites: a foreign model's lobes (validation/model_table.h)
  OptionNames names;                       // how messages name the options above
};

// A suite file read and checked, with the overrides applied.
struct ValidationPlan {
  enum class Kind {
    single_grooves,
    brdf,
    table2,
    model_table,
    profiles,
    nonsymmetric,
    furnace,
    sampling
  } kind = Kind::single_grooves;
  SuiteSet set;                   // single grooves
  std::vector<CaseOptions> opts;  // per suite of the set
  BrdfSuite brdf;
  FurnaceSuite furnace;
  SamplingSuite sampling;
  Table2Suite table2;
  ProfilesSuite profiles;
  NonsymmetricSuite nonsymmetric;
  std::shared_ptr<const ModelTable> table;  // Kind::model_table (with brdf)
  long rays = 0;                            // rough surfaces: the override, 0 for the suite's
  int threads = 0;
  std::vector<std::string> inputs;  // the files read (suite, the set's suites, model table): never an output
  bool report = true;               // build ValidationResult::report (the command line without --out does not)
};

ValidationPlan plan_validation(const ValidateOptions& opt);

struct ValidationResult {
  nlohmann::json report;  // what `vgroove validate --out` writes (empty when interrupted)
  std::string table;      // what `vgroove validate` prints
  bool pass = false;
  bool interrupted = false;  // `cancel` was set: no report
};

// A progress callback per suite (labelled "validate NAME"); may return an empty function.
using ProgressFactory = std::function<support::ProgressFn(const std::string& label)>;

ValidationResult run_validation(const ValidationPlan& plan, const ProgressFactory& progress = {},
                                const std::atomic<bool>* cancel = nullptr);

}  // namespace vgroove::validation
