// vgroove validation: the report JSON and the table on stdout.
//
// The report carries what is needed to rerun and diff a run: tool, version, git revision, suite
// file, seed, sampling, rays, threads, wall time, every case's figures, the summary, the
// thresholds and pass/fail.
#pragma once

#include "vgroove/validation/groove_suite_run.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace vgroove::validation {

// The version of the report layout (docs/schemas/); raised when a field changes meaning or goes.
inline constexpr int kReportSchemaVersion = 1;
// {"tool", "schema_version", "version", "git"} for every JSON the tool writes.
nlohmann::json provenance();
const char* version_string();
const char* git_revision();
// What names a suite in its report and table: every kind's report opens with these.
struct SuiteHeader {
  std::string name, file, kind, description;
  std::uint64_t seed = 0;
};
// provenance() with "suite", "suite_file", "kind", "description", "seed", "threads" and "wall_s".
nlohmann::json report_header(const SuiteHeader& suite, int threads, double wall_s);
// Radians to degrees for output, rounded to 1e-9 deg so that 5 prints as 5, never -0.
double output_deg(double rad);

nlohmann::json report_json(const GrooveSuite& suite, const GrooveSuiteRun& run);
// One case of a single-groove report (its entry in "cases").
nlohmann::json case_json(const CaseOutcome& c);
void print_table(std::ostream& os, const GrooveSuite& suite, const GrooveSuiteRun& run);

// A set of suites: one report with every suite's, and the paper's table beside ours.
nlohmann::json report_json(const GrooveSuiteSet& set, const std::vector<GrooveSuiteRun>& runs);
void print_set_table(std::ostream& os, const GrooveSuiteSet& set, const std::vector<GrooveSuiteRun>& runs);

// The groove's angles for output (degrees).
nlohmann::json groove_json(const GrooveParams& g);
std::string groove_text(const GrooveParams& g);

}  // namespace vgroove::validation
