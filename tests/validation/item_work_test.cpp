// ItemWork (validation/item_work.h) with outcome_fields.h: an item's outcome crosses processes bit
// for bit (NaN, infinities, subnormals, -0 and the largest integers included), and a part damaged
// in any field is refused with the part's file and the JSON path, never read into a report.
#include "vgroove/validation/item_work.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/furnace_suite.h"
#include "vgroove/validation/sampling_suite.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace vgroove::validation {
namespace {

using nlohmann::json;

FurnaceOutcome odd_outcome() {
  FurnaceOutcome o;
  o.albedo_quadrature = 0.1 + 0.2;  // 0.30000000000000004: the last bit matters
  o.quadrature_error = std::numeric_limits<double>::denorm_min();
  o.flux_beyond_max_k = -0.0;
  o.albedo_estimate = std::numeric_limits<double>::quiet_NaN();
  o.standard_error = std::numeric_limits<double>::infinity();
  o.cook_torrance_quadrature = -std::numeric_limits<double>::infinity();
  o.cook_torrance_estimate = std::numeric_limits<double>::max();
  o.cook_torrance_standard_error = std::numeric_limits<double>::min();
  o.albedo_sim = 1.0 / 3.0;
  o.rays = std::numeric_limits<long>::max();
  o.in_flight = std::numeric_limits<long>::min();
  o.quadrature_s = 1e-300, o.estimate_s = 2.5, o.sim_s = 0.0;
  o.energy_ok = true, o.estimate_ok = false, o.cook_torrance_ok = true, o.sim_ok = false, o.finite = true;
  o.pass = true;
  return o;
}

// The tally as a merge reads it back from a part: written, printed, parsed.
FurnaceOutcome read_back(const json& tally) {
  const json parsed = json::parse(tally.dump());
  FurnaceWork work;
  support::JsonObject o(parsed, "part.json", "/units/0/tally");
  FurnaceOutcome out = work.read_tally(o, 0, {{0, 1}});
  o.finish();
  return out;
}

// The message of the UserError reading `tally` throws (empty when it reads).
std::string refusal(const json& tally) {
  try {
    read_back(tally);
  } catch (const support::UserError& e) {
    return e.what();
  }
  return {};
}

// `tally` with its outcome changed by `edit` and the digest made to match again: what only a
// deliberate edit could write.
template <class Edit>
json forged(json tally, Edit edit) {
  edit(tally["outcome"]);
  tally["digest"] = text_digest(tally["outcome"].dump());
  return tally;
}

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

TEST(ItemWork, AnOutcomeCrossesProcessesBitForBit) {
  const FurnaceOutcome o = odd_outcome();
  const FurnaceOutcome r = read_back(FurnaceWork::tally_json(o));
  EXPECT_TRUE(same_bits(r.albedo_quadrature, o.albedo_quadrature));
  EXPECT_TRUE(same_bits(r.quadrature_error, o.quadrature_error));
  EXPECT_TRUE(same_bits(r.flux_beyond_max_k, o.flux_beyond_max_k));  // -0, not 0
  EXPECT_TRUE(std::isnan(r.albedo_estimate));
  EXPECT_TRUE(same_bits(r.standard_error, o.standard_error));
  EXPECT_TRUE(same_bits(r.cook_torrance_quadrature, o.cook_torrance_quadrature));
  EXPECT_TRUE(same_bits(r.cook_torrance_estimate, o.cook_torrance_estimate));
  EXPECT_TRUE(same_bits(r.cook_torrance_standard_error, o.cook_torrance_standard_error));
  EXPECT_TRUE(same_bits(r.albedo_sim, o.albedo_sim));
  EXPECT_EQ(r.rays, o.rays);
  EXPECT_EQ(r.in_flight, o.in_flight);
  EXPECT_TRUE(same_bits(r.quadrature_s, o.quadrature_s));
  EXPECT_EQ(r.energy_ok, o.energy_ok);
  EXPECT_EQ(r.estimate_ok, o.estimate_ok);
  EXPECT_EQ(r.sim_ok, o.sim_ok);
  EXPECT_EQ(r.pass, o.pass);
}

TEST(ItemWork, AnOutcomeChangedInAnyFieldIsRefusedByItsDigest) {
  const json good = FurnaceWork::tally_json(odd_outcome());
  ASSERT_EQ(refusal(good), "");
  for (const auto& [key, value] : good["outcome"].items()) {
    json bad = good;
    bad["outcome"][key] = value.is_boolean() ? json(!value.get<bool>()) : json(12345);
    const std::string e = refusal(bad);
    EXPECT_NE(e.find("part.json: /units/0/tally/digest"), std::string::npos) << key << ": " << e;
    EXPECT_NE(e.find("a damaged part"), std::string::npos) << key << ": " << e;
  }
  json no_digest = good;
  no_digest.erase("digest");
  EXPECT_NE(refusal(no_digest).find("/units/0/tally/digest is missing"), std::string::npos) << refusal(no_digest);
}

TEST(ItemWork, ADigestedOutcomeIsStillReadAsStrictlyAsASuiteFile) {
  const json good = FurnaceWork::tally_json(odd_outcome());
  const auto expect = [&](const json& bad, const std::string& part) {
    const std::string e = refusal(bad);
    EXPECT_NE(e.find(part), std::string::npos) << "expected \"" << part << "\" in \"" << e << "\"";
  };
  expect(forged(good, [](json& o) { o["albedo_sim"] = "0.5"; }),
         "/units/0/tally/outcome/albedo_sim = \"0.5\" must be a number");
  expect(forged(good, [](json& o) { o["pass"] = 1; }), "/units/0/tally/outcome/pass = 1 must be true or false");
  expect(forged(good, [](json& o) { o["rays"] = 1.5; }), "/units/0/tally/outcome/rays = 1.5 must be an integer");
  expect(forged(good, [](json& o) { o["rays"] = std::numeric_limits<std::uint64_t>::max(); }),
         "/units/0/tally/outcome/rays = 18446744073709551615 must be an integer in");
  expect(forged(good, [](json& o) { o.erase("sim_s"); }), "/units/0/tally/outcome/sim_s is missing");
  expect(forged(good, [](json& o) { o["sneaked_in"] = 1; }), "sneaked_in");
  expect(forged(good, [](json& o) { o = json::array(); }), "/units/0/tally/outcome = [] must be an object");
}

// A sampling suite of one chi-square test and one variance row (not run: only read against).
SamplingSuite two_item_suite() {
  SamplingSuite s;
  s.file = "sampling.json";
  s.chi_square.push_back(Chi2Spec{});
  s.variance.push_back(VarianceSpec{});
  return s;
}

std::string sampling_refusal(const SamplingItem& item, std::size_t unit) {
  const SamplingSuite s = two_item_suite();
  const Job<SamplingWork> job = sampling_job(s, json::object());
  const json parsed = json::parse(SamplingWork::tally_json(item).dump());
  try {
    support::JsonObject o(parsed, "part.json", "/units/" + std::to_string(unit) + "/tally");
    job.work.read_tally(o, unit, {{0, 1}});
    o.finish();
  } catch (const support::UserError& e) {
    return e.what();
  }
  return {};
}

Chi2Table table_of(const Chi2Spec& spec) {
  Chi2Table t;
  t.rows = spec.cos_bins, t.cols = spec.phi_bins;
  t.row_edges.assign(static_cast<std::size_t>(t.rows) + 1, 0.0);
  t.col_edges.assign(static_cast<std::size_t>(t.cols) + 1, 0.0);
  t.observed.assign(static_cast<std::size_t>(t.rows * t.cols), 1.0);
  t.expected = t.observed;
  return t;
}

TEST(ItemWork, AnItemHoldsItsOwnKindOfOutcomeInItsShape) {
  SamplingItem chi;
  chi.chi_square.emplace();
  chi.chi_square->table = table_of(Chi2Spec{});
  SamplingItem var;
  var.variance.emplace();
  EXPECT_EQ(sampling_refusal(chi, 0), "");
  EXPECT_EQ(sampling_refusal(var, 1), "");
  EXPECT_NE(sampling_refusal(var, 0).find("/units/0/tally/outcome must hold exactly the item's chi_square outcome"),
            std::string::npos)
      << sampling_refusal(var, 0);
  EXPECT_NE(sampling_refusal(chi, 1).find("must hold exactly the item's variance outcome"), std::string::npos);
  SamplingItem both = chi;
  both.variance.emplace();
  EXPECT_NE(sampling_refusal(both, 0).find("must hold exactly"), std::string::npos);
  // A table of another shape than the spec's: refused before a printer indexes it.
  SamplingItem short_table = chi;
  short_table.chi_square->table.observed.pop_back();
  EXPECT_NE(sampling_refusal(short_table, 0).find("/chi_square/table has 127 observed and 128 expected cells, not 128"),
            std::string::npos)
      << sampling_refusal(short_table, 0);
  SamplingItem other_grid = chi;
  other_grid.chi_square->table.rows = 4;
  EXPECT_NE(sampling_refusal(other_grid, 0).find("is a table of 4 x 16 cells, not the spec's 8 x 16"),
            std::string::npos)
      << sampling_refusal(other_grid, 0);
}

}  // namespace
}  // namespace vgroove::validation
