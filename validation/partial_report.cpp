#include "vgroove/validation/partial_report.h"
#include "vgroove/support/printable.h"

#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"

#include "vgroove/support/memory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>

namespace vgroove::validation {

namespace {

// The JSON pointer of the first place where a and b differ ("" when equal).
std::string first_difference(const nlohmann::json& a, const nlohmann::json& b, const std::string& at) {
  // Numbers by value: a count read back from a file is unsigned, the same count built here signed.
  if (a.is_number() && b.is_number()) return a == b ? "" : (at.empty() ? "/" : at);
  if (a.type() != b.type()) return at.empty() ? "/" : at;
  if (a.is_object()) {
    for (const auto& [k, v] : a.items()) {
      if (!b.contains(k)) return at + "/" + k;
      if (std::string d = first_difference(v, b[k], at + "/" + k); !d.empty()) return d;
    }
    for (const auto& [k, v] : b.items())
      if (!a.contains(k)) return at + "/" + k;
    return "";
  }
  if (a.is_array()) {
    if (a.size() != b.size())
      return at + " (lengths " + std::to_string(a.size()) + ", " + std::to_string(b.size()) + ")";
    for (std::size_t n = 0; n < a.size(); ++n)
      if (std::string d = first_difference(a[n], b[n], at + "/" + std::to_string(n)); !d.empty()) return d;
    return "";
  }
  return a == b ? "" : (at.empty() ? "/" : at);
}

std::string value_at(const nlohmann::json& j, const std::string& pointer) {
  try {
    const std::string p = pointer.substr(0, pointer.find(' '));
    const nlohmann::json& v = j.at(nlohmann::json::json_pointer(p == "/" ? "" : p));
    const std::string text = v.dump();
    return text.size() > 60 ? text.substr(0, 57) + "..." : text;
  } catch (const nlohmann::json::exception&) {
    return "(absent)";
  }
}

}  // namespace

nlohmann::json exact_json(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return v;
}

nlohmann::json exact_json(const std::vector<double>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (double x : v) a.push_back(exact_json(x));
  return a;
}

double exact_double(const nlohmann::json& j) {
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
  }
  return j.get<double>();
}

std::vector<double> exact_doubles(const nlohmann::json& j) {
  std::vector<double> v;
  v.reserve(j.size());
  for (const nlohmann::json& x : j) v.push_back(exact_double(x));
  return v;
}

nlohmann::json partial_report_json(const PartialHeader& h, nlohmann::json units) {
  nlohmann::json j = provenance();
  j["partial"] = {{"job", h.job},
                  {"shard", {{"index", h.shard.index}, {"count", h.shard.count}}},
                  {"items", h.items},
                  {"threads", h.threads},
                  {"wall_s", h.wall_s}};
  j["units"] = std::move(units);
  return j;
}

nlohmann::json job_descriptor(const std::string& command, const std::string& kind,
                              const std::vector<std::string>& files, nlohmann::json options) {
  return {{"command", command},
          {"kind", kind},
          {"input_file", files.empty() ? "" : files.front()},
          {"input_path", files.empty() ? "" : std::filesystem::absolute(files.front()).lexically_normal().string()},
          {"input_digest", file_digest(files)},
          {"options", std::move(options)}};
}

namespace {
constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ULL, kFnvPrime = 0x100000001b3ULL;
std::string hex16(std::uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}
}  // namespace

std::string file_digest(const std::vector<std::string>& files) {
  std::uint64_t h = kFnvOffset;
  for (const std::string& f : files) {
    support::check_file_name(f);
    std::ifstream in(f, std::ios::binary);
    if (!in) throw support::UserError(f + ": cannot open the file (missing or unreadable)");
    for (std::istreambuf_iterator<char> it(in), end; it != end; ++it) {
      h ^= static_cast<unsigned char>(*it);
      h *= kFnvPrime;
    }
    h ^= 0xff, h *= kFnvPrime;  // a file boundary
  }
  return hex16(h);
}

std::string text_digest(const std::string& text) {
  std::uint64_t h = kFnvOffset;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= kFnvPrime;
  }
  return hex16(h);
}

void check_input_unchanged(const nlohmann::json& descriptor, const std::vector<std::string>& files,
                           const std::string& part) {
  if (descriptor.value("input_digest", "") != file_digest(files))
    throw support::UserError("merge: " + files.front() + " has changed since " + part +
                             " was written (its digest differs): the parts were run on another input");
}

Part part_from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object() || !j.contains("partial") || !j.contains("units"))
    throw support::UserError(where + ": not a partial report (no /partial; one is written by --shard I/N --out FILE)");
  Part p;
  p.file = where;
  try {
    // Read as strictly as a suite: every key known, every value of its type and range.
    support::JsonObject top(j, where, "");
    top.one_of("tool", {"vgroove"});
    top.integer("schema_version", kReportSchemaVersion, kReportSchemaVersion);
    p.version = {{"version", top.string("version")}, {"git", top.string("git")}};
    p.units = top.raw("units");
    support::JsonObject h = top.object("partial");
    p.header.job = h.raw("job");
    if (!p.header.job.is_object()) h.fail("job", "must be an object (the run's descriptor)");
    support::JsonObject job(p.header.job, where, h.path("job"));
    const long long items = job.integer("items", 1, std::numeric_limits<long long>::max());
    job.string("input_file"), job.string("input_path"), job.string("command");
    support::JsonObject shard = h.object("shard");
    p.header.shard.count = static_cast<int>(shard.integer("count", 1, support::kMaxShards));
    p.header.shard.index = static_cast<int>(shard.integer("index", 1, p.header.shard.count));
    shard.finish();
    const nlohmann::json& list = h.raw("items");
    if (!list.is_array()) h.fail("items", "must be an array of work items");
    for (std::size_t n = 0; n < list.size(); ++n) {
      const nlohmann::json& v = list[n];
      const long long lo = p.header.items.empty() ? 0 : static_cast<long long>(p.header.items.back()) + 1;
      if (!v.is_number_integer() ||
          (v.is_number_unsigned() && v.get<unsigned long long>() >= static_cast<unsigned long long>(items)) ||
          v.get<long long>() < lo || v.get<long long>() >= items)
        h.fail_at("items", n,
                  "= " + support::value_text(v) + " is not a work item in [" + std::to_string(lo) + ", " +
                      std::to_string(items) + ") (items in increasing order, each once)");
      p.header.items.push_back(v.get<std::size_t>());
    }
    p.header.threads = static_cast<int>(h.integer("threads", 1, kMaxThreads));
    p.header.wall_s = h.number("wall_s", 0.0, true, std::numeric_limits<double>::max(), true);
    h.finish();
    top.finish();
  } catch (const nlohmann::json::exception& e) {
    throw support::UserError(where + ": not a partial report (" + e.what() + ")");
  }
  return p;
}

Part read_part(const std::string& file) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (!ec && size > support::kMaxJsonBytes)
    support::check_memory(8.0 * static_cast<double>(size), file + ": reading the part",
                          support::bytes_text(static_cast<double>(size)) + " of JSON");
  return part_from_json(support::read_json_file(file, std::numeric_limits<std::size_t>::max()), file);
}

std::string input_file_of(const Part& part) {
  const nlohmann::json& job = part.header.job;
  const std::string given = job.value("input_file", ""), path = job.value("input_path", "");
  std::error_code ec;
  if (!given.empty() && std::filesystem::is_regular_file(given, ec) &&
      std::filesystem::absolute(given).lexically_normal().string() == path)
    return given;
  if (!path.empty() && std::filesystem::is_regular_file(path, ec)) return path;
  if (!given.empty() && std::filesystem::is_regular_file(given, ec)) return given;
  throw support::UserError("merge: " + part.file + ": its input " + given + " (/partial/job/input_file; " + path +
                           ") is not found from here: merge where the shards' input can be read");
}

std::string job_difference(const nlohmann::json& a, const nlohmann::json& b) {
  nlohmann::json x = a, y = b;
  if (x.is_object()) x.erase("input_file");
  if (y.is_object()) y.erase("input_file");
  return first_difference(x, y, "");
}

std::vector<Part> check_parts(std::vector<Part> parts) {
  if (parts.empty()) throw support::UserError("merge: no parts given");
  const Part& first = parts.front();
  for (const Part& p : parts) {
    if (p.version != first.version)
      throw support::UserError("merge: " + p.file + " was written by vgroove " + p.version["version"].dump() +
                               " (git " + p.version["git"].dump() + "), " + first.file + " by " +
                               first.version["version"].dump() + " (git " + first.version["git"].dump() +
                               "): parts of different versions cannot be merged");
    if (const std::string d = job_difference(first.header.job, p.header.job); !d.empty())
      throw support::UserError("merge: " + p.file + " belongs to another run: /job" + d + " = " +
                               value_at(p.header.job, d) + ", " + first.file + " has " + value_at(first.header.job, d) +
                               " (different suites, options or seeds)");
    if (p.header.shard.count != first.header.shard.count)
      throw support::UserError("merge: " + p.file + " is shard " + p.header.shard.text() + " (/partial/shard), " +
                               first.file + " shard " + first.header.shard.text() + ": parts of different splits");
  }
  const int n = first.header.shard.count;
  std::map<int, const Part*> by_index;
  for (const Part& p : parts) {
    const auto [it, fresh] = by_index.emplace(p.header.shard.index, &p);
    if (!fresh)
      throw support::UserError("merge: shard " + p.header.shard.text() + " (/partial/shard) is given twice (" +
                               it->second->file + ", " + p.file + ")");
  }
  std::string missing;
  int missing_count = 0;
  for (int i = 1; i <= n; ++i)
    if (!by_index.count(i)) {
      if (++missing_count <= 8) missing += (missing.empty() ? "" : ", ") + std::to_string(i) + "/" + std::to_string(n);
    }
  if (missing_count)
    throw support::UserError("merge: " + std::to_string(missing_count) + " of " + std::to_string(n) +
                             " shards missing (" + missing + (missing_count > 8 ? ", ..." : "") +
                             "): an incomplete set is never merged");
  const auto items = first.header.job.at("items").get<std::size_t>();
  std::vector<const Part*> owner(items, nullptr);
  for (const Part& p : parts)
    for (std::size_t i : p.header.items) {
      if (owner[i])
        throw support::UserError("merge: " + owner[i]->file + " and " + p.file + " both ran work item " +
                                 std::to_string(i) + " (/partial/items): overlapping parts");
      owner[i] = &p;
    }
  for (std::size_t i = 0; i < items; ++i)
    if (!owner[i]) {
      std::string files;
      for (const Part& p : parts) files += (files.empty() ? "" : ", ") + p.file;
      throw support::UserError("merge: no part ran work item " + std::to_string(i) + " of " + std::to_string(items) +
                               " (/partial/items of " + files + "): an incomplete set is never merged");
    }
  std::sort(parts.begin(), parts.end(),
            [](const Part& a, const Part& b) { return a.header.shard.index < b.header.shard.index; });
  return parts;
}

nlohmann::json fates_json(const sim::RayFates& t) {
  return {{"rays", t.rays},
          {"escaped", t.escaped},
          {"blocked", t.blocked},
          {"vertex_hits", t.vertex_hits},
          {"bounce_limit", t.bounce_limit},
          {"not_upward", t.not_upward},
          {"bounces", t.bounces},
          {"max_k_seen", t.max_k_seen}};
}

}  // namespace vgroove::validation
