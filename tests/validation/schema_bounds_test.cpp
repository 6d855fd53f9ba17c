// The JSON Schema's bounds are the readers' bounds. For every minimum and maximum that
// docs/schemas/suite.schema.json gives a field of a suite kind (and every "each in [a, b]" of a
// degrees list), a shipped suite of that kind (data/suites/) with the field set to the bound is
// read by plan_validation, and with the field one step past it (the next integer, or the next
// double) is refused with a message naming the field. A schema that copies a range the reader
// does not enforce, or a reader whose range drifted from the schema's, fails here.
#include "tests/test_files.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/validate.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace vgroove::validation {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing_files::TempDir;

const fs::path kSource = VGROOVE_SOURCE_DIR;

json read_json(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

// One bound of one field: where the field sits in a suite (object keys; "0" is an array's first
// element), the bound and whether the bound itself is allowed.
struct Bound {
  std::string kind;
  std::vector<std::string> path;
  double value = 0.0;   // a number's bound
  long long whole = 0;  // an integer's bound, exactly (a seed's reaches 2^63 - 1)
  bool upper = false, inclusive = true, integer = false;
  std::string text() const {
    std::string p;
    for (const auto& s : path) p += "/" + s;
    return kind + p +
           (upper ? (inclusive ? " maximum " : " exclusiveMaximum ")
                  : (inclusive ? " minimum " : " exclusiveMinimum ")) +
           (integer ? std::to_string(whole) : support::number_text(value));
  }
};

const json& resolve(const json& schema, const json& node) {
  if (!node.contains("$ref")) return node;
  const std::string ref = node["$ref"].get<std::string>();  // "#/$defs/NAME"
  return schema.at(json::json_pointer(ref.substr(1)));
}

void collect(const json& schema, const json& node, const std::string& kind, std::vector<std::string> path,
             std::vector<Bound>& out) {
  const json& n = resolve(schema, node);
  const bool integer = n.value("type", "") == "integer";
  auto add = [&](const char* key, bool upper, bool inclusive) {
    if (!n.contains(key)) return;
    Bound b{kind, path, n[key].get<double>(), 0, upper, inclusive, integer};
    if (integer) b.whole = n[key].get<long long>();
    out.push_back(b);
  };
  add("minimum", false, true), add("maximum", true, true);
  add("exclusiveMinimum", false, false), add("exclusiveMaximum", true, false);
  // A degrees list (a list, or from/to/step) states its items' range in its description.
  static const std::regex each_in(R"(each in \[(-?[0-9.]+), (-?[0-9.]+)\])");
  std::smatch m;
  const std::string description = node.value("description", "");
  if (node.contains("$ref") && std::regex_search(description, m, each_in)) {
    path.push_back("0");
    out.push_back({kind, path, std::stod(m[1]), 0, false, true, false});
    out.push_back({kind, path, std::stod(m[2]), 0, true, true, false});
    return;
  }
  if (n.contains("properties"))
    for (const auto& [key, sub] : n["properties"].items()) {
      auto p = path;
      p.push_back(key);
      collect(schema, sub, kind, p, out);
    }
  if (n.contains("items") && n["items"].is_object()) {
    path.push_back("0");
    collect(schema, n["items"], kind, path, out);
  }
}

// The field's slot in `doc` if every step of `path` exists (a degrees list given as from/to/step
// counts as present: it is replaced by a list).
json* slot(json& doc, const std::vector<std::string>& path) {
  json* at = &doc;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const std::string& step = path[i];
    if (step == "0") {
      if (at->is_object() && at->contains("from")) *at = json::array({0});
      if (!at->is_array() || at->empty()) return nullptr;
      at = &(*at)[0];
    } else {
      if (!at->is_object() || !at->contains(step)) return nullptr;
      at = &(*at)[step];
    }
  }
  return at;
}

// Values beside one another that the field's bound needs to be read alone, which the schema
// cannot express: a bin count at its maximum with max_k 0 stays within the histogram's cells
// (validation/ranges.h kMaxHistogramCells); alpha 2 has a nonsymmetric partner law for GGX and
// Beckmann, not for Phong (Eq. 20 needs alpha < sqrt(2)).
json at(const Bound& b);  // the value at the bound (below)

void make_room(json& doc, const Bound& b) {
  const std::string& field = b.path.back();
  if (b.kind == "nonsymmetric_brdf" && b.path[0] == "alpha" && b.upper) doc["ndf"] = json::array({"ggx"});
  if (b.kind == "sampling") return;  // its max_k bounds the sampler's orders, not a histogram
  if (b.kind == "heightfield") {
    // Its controls name cases of the suite: dropped, or (a control's own bound) given a case there.
    if (b.path[0] != "controls") doc.erase("controls");
    if (b.path[0] == "controls") doc["controls"] = json::array({doc["controls"][0]});
    if (b.path[0] == "controls" && (field == "alpha" || field == "theta_i_deg" || field == "aspect"))
      doc[field] = json::array({at(b)});
    // The masking controls name cases and measured angles: dropped, or (a masking control's own
    // bound) the first (a g2 control: it has every field) alone, its case and angles the suite's.
    if (b.path.size() > 2 && b.path[0] == "masking" && b.path[1] == "controls") {
      doc["masking"]["controls"] = json::array({doc["masking"]["controls"][0]});
      if (field == "alpha" || field == "theta_i_deg") doc[field] = json::array({at(b)});
      if (field == "theta_o_deg" || field == "phi_deg") doc["masking"][field] = json::array({at(b)});
    } else if (doc.contains("masking")) {
      doc["masking"].erase("controls");
    }
    // An aspect a makes l_y about l_x / a, which must stay in [2, field_size / 8] (its own refusal):
    // a field where both ends of the aspect's range fit (the number, a list's item, a control's).
    if (field == "aspect" || b.path[0] == "aspect") doc["field_size"] = 1024, doc["correlation_length"] = 16;
  }
  // The audit's heightfield: a correlation length in [2, field_size / 8] (its own refusal), so 2 at
  // the smallest field.
  if (b.kind == "energy_audit" && b.path[0] == "heightfield" && field == "field_size")
    doc["heightfield"]["correlation_length"] = 2;
  if (b.upper && (field == "flatland_bins" || field == "theta_bins" || field == "phi_bins" || field == "lobe_bins")) {
    if (b.kind != "heightfield") doc["max_k"] = b.kind == "profiles" || b.kind == "dielectric_brdf" ? 1 : 0;
    if (field != "flatland_bins" && doc.contains("theta_bins")) doc["theta_bins"] = 1, doc["phi_bins"] = 2;
    if (field == "lobe_bins") doc["lobe_bins"] = 1;
  }
  if (b.upper && field == "max_k") {
    for (const char* bins : {"flatland_bins", "theta_bins", "lobe_bins"})
      if (doc.contains(bins)) doc[bins] = 1;
    if (doc.contains("phi_bins")) doc["phi_bins"] = 2;
  }
}

// The value one step past the bound: outside the range (the next integer, or the next double).
json past(const Bound& b) {
  if (b.integer) {
    if (!b.inclusive) return b.whole;  // an exclusive bound is itself outside
    if (b.upper && b.whole == std::numeric_limits<long long>::max())
      return static_cast<unsigned long long>(b.whole) + 1;
    return b.upper ? b.whole + 1 : b.whole - 1;
  }
  if (!b.inclusive) return b.value;
  return std::nextafter(b.value,
                        b.upper ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity());
}

// The value inside the range next to the bound.
json at(const Bound& b) {
  if (b.integer) return b.inclusive ? b.whole : (b.upper ? b.whole - 1 : b.whole + 1);
  if (b.inclusive) return b.value;
  return std::nextafter(b.value,
                        b.upper ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity());
}

std::optional<std::string> refusal(const json& doc, const TempDir& dir) {
  const std::string file = dir.file("suite.json");
  testing_files::write_text(file, doc.dump());
  ValidateOptions o;
  o.suite = file;
  o.threads = 1;
  try {
    (void)plan_validation(o);
  } catch (const support::UserError& e) {
    // A brdf suite on heightfields runs only against a model table: read to the end, every field
    // accepted, the suite is refused for the missing table alone.
    const std::string what = e.what();
    if (what.find("surface heightfield is held against a model table") != std::string::npos) return std::nullopt;
    return what;
  }
  return std::nullopt;
}

// Every def of the suite schema that names a kind, with its bounds.
std::vector<Bound> suite_bounds() {
  const json schema = read_json(kSource / "docs/schemas/suite.schema.json");
  std::vector<Bound> out;
  for (const auto& [name, def] : schema["$defs"].items()) {
    if (!def.contains("properties") || !def["properties"].contains("kind")) continue;
    const json& kind = def["properties"]["kind"];
    if (!kind.contains("const")) continue;
    collect(schema, def, kind["const"].get<std::string>(), {}, out);
  }
  return out;
}

// The shipped suites by kind (a set of suites has no kind of its own and no bounds).
std::vector<std::pair<std::string, json>> shipped_suites() {
  std::vector<std::pair<std::string, json>> out;
  for (const auto& e : fs::directory_iterator(kSource / "data/suites"))
    if (e.path().extension() == ".json") {
      json j = read_json(e.path());
      if (j.contains("kind")) out.emplace_back(e.path().filename().string(), std::move(j));
    }
  // A brdf suite on heightfields last: the brdf fields' bounds are read on a V-groove suite
  // (fig11.json), and only the fields of its own (its "heightfield" options) on it.
  const auto late = [](const json& j) { return j.value("surface", "") == "heightfield"; };
  std::sort(out.begin(), out.end(), [&](const auto& a, const auto& b) {
    return std::pair(late(a.second), a.first) < std::pair(late(b.second), b.first);
  });
  // Fields no shipped suite sets, added to a copy of one that does not.
  for (const auto& [name, doc] : std::vector(out)) {
    if (name == "stress.json") {
      json j = doc;
      j["cases"].insert(j["cases"].begin(), json{{"theta_l_deg", -30}, {"theta_r_deg", 40}, {"theta_i_deg", 10}});
      j["max_bounces"] = 100000;
      out.emplace_back(name + " with a nonsymmetric case and max_bounces", std::move(j));
    }
    if (name == "sampling.json") {
      json j = doc;
      j["variance"]["cases"][0]["samples"] = 1000;
      out.emplace_back(name + " with a case's own samples", std::move(j));
    }
  }
  return out;
}

TEST(SchemaBounds, EverySuiteBoundIsTheReadersBound) {
  const std::vector<Bound> bounds = suite_bounds();
  const auto suites = shipped_suites();
  ASSERT_GT(bounds.size(), 100u);  // the schema was read
  TempDir dir;
  int checked = 0;
  for (const Bound& b : bounds) {
    SCOPED_TRACE(b.text());
    // The first shipped suite of the kind that holds the field.
    std::optional<json> base;
    std::string base_name;
    for (const auto& [name, doc] : suites) {
      json copy = doc;
      if (doc["kind"] == b.kind && slot(copy, b.path)) {
        base = copy;
        base_name = name;
        break;
      }
    }
    if (!base) {
      ADD_FAILURE() << "no suite in data/suites holds the field, so its bound is not checked";
      continue;
    }
    SCOPED_TRACE(base_name);
    json inside = *base;
    make_room(inside, b);
    *slot(inside, b.path) = at(b);
    const auto accepted = refusal(inside, dir);
    EXPECT_FALSE(accepted) << "the value at the bound is refused: " << *accepted;
    json outside = inside;
    *slot(outside, b.path) = past(b);
    const auto refused = refusal(outside, dir);
    ASSERT_TRUE(refused) << "the value past the bound (" << past(b).dump() << ") is read";
    EXPECT_NE(refused->find(b.path.back()), std::string::npos) << "the refusal does not name the field: " << *refused;
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(bounds.size()));
}

}  // namespace
}  // namespace vgroove::validation
