// vgroove validation: partial reports, what one shard of a run writes (`--shard I/N --out P`),
// and the checks that make `vgroove merge` refuse parts that do not make one whole run.
//
// A partial report carries the provenance (tool, version, git revision), the job (the command,
// the input as read, the options that change results, the numbers of units and work items), the
// shard I/N, the items it ran and, per unit, its chunk runs with their tallies and the fixed parts
// it ran (work_run.h). Its doubles are written with all their digits (nlohmann-json writes the
// shortest text that reads back as the same double; non-finite values as strings), so a merged
// run is the single-process run bit for bit.
#pragma once

#include "vgroove/sim/ray_fates.h"
#include "vgroove/support/work_plan.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace vgroove::validation {

struct PartialHeader {
  nlohmann::json job;  // {"command", "kind", "input_file", "input", "options", "units", "items"}
  support::Shard shard;
  std::vector<std::size_t> items;  // the work items this part ran, in item order
  int threads = 1;
  double wall_s = 0.0;
};

struct Part {
  std::string file;  // where it was read from (or "rank R" for an MPI rank)
  PartialHeader header;
  nlohmann::json version;  // {"version", "git"}
  nlohmann::json units;    // work_run.h: part_results_json
};

nlohmann::json partial_report_json(const PartialHeader& h, nlohmann::json units);

// A job's descriptor: the command, the kind of input, the input file as given on the command line
// with a digest of its bytes (and of the files it names: `files`, the first being `input_file`),
// and the options that change results. `vgroove merge` reads the input again and refuses parts
// whose digest no longer matches.
nlohmann::json job_descriptor(const std::string& command, const std::string& kind,
                              const std::vector<std::string>& files, nlohmann::json options);
// FNV-1a (64 bits) of the files' bytes, as 16 hex digits; a UserError when one cannot be read.
std::string file_digest(const std::vector<std::string>& files);
// The same digest of a text.
std::string text_digest(const std::string& text);
// The digest the descriptor holds against the files as they are now: a UserError when they changed.
void check_input_unchanged(const nlohmann::json& descriptor, const std::vector<std::string>& files,
                           const std::string& part);
// The input file a merge reads the job from: `input_file` as the shard was given it when it names
// the same file from here, else `input_path` (its absolute path when the part was written), so
// parts merge from any directory; a UserError naming the part when neither exists.
std::string input_file_of(const Part& part);
// The first JSON pointer where two jobs differ ("" when they are the same job). The input file's
// name as given is left out: parts of one suite given by other paths are one job (the digest
// holds its contents).
std::string job_difference(const nlohmann::json& a, const nlohmann::json& b);
// A partial report from its JSON; a UserError naming `where` when it is none.
Part part_from_json(const nlohmann::json& j, const std::string& where);
// Reads the file; a UserError when it is missing, truncated (not valid JSON) or not a partial report.
// A part may be larger than a spec file: it is read when the memory its JSON needs (about eight
// bytes per byte of text) is available (support/memory.h).
Part read_part(const std::string& file);

// The parts in shard order, after checking that they make one whole run: the same version and git
// revision, the same job, the shards 1..N of one N each exactly once, and items that cover the
// job's items exactly once. Every refusal is a one-line UserError naming the parts concerned.
std::vector<Part> check_parts(std::vector<Part> parts);

// Doubles written exactly: finite values as numbers, NaN and infinities as "nan", "inf", "-inf".
nlohmann::json exact_json(double v);
nlohmann::json exact_json(const std::vector<double>& v);
double exact_double(const nlohmann::json& j);
std::vector<double> exact_doubles(const nlohmann::json& j);
// The fates of a tally's rays (sim/ray_fates.h); part_fields.h reads them back.
nlohmann::json fates_json(const sim::RayFates& t);

}  // namespace vgroove::validation
