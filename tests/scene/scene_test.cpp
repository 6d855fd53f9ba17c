// Scene specs (validation/scene.h) and `vgroove simulate` (validation/simulate.h): every class of
// bad input with its exact message; the traced energy of conductor grooves against the
// kaleidoscopic model with the same Fresnel (Lee et al. 2018, Eq. (11)); the flat mirror at
// normal incidence against the closed form; bit-identical results for any thread count; the
// counts against sim::trace_microsurface; and a CLI that leaves no file behind on bad input.
#include "tests/cli_run.h"
#include "tests/test_files.h"

#include "vgroove/scene/scene.h"
#include "vgroove/scene/simulate.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>

namespace vgroove::scene {
namespace {

using nlohmann::json;
using testing_files::read_text;
using testing_files::TempDir;
using testing_files::write_text;

// A valid scene; each error test changes one thing in it.
json base_scene() {
  return json::parse(R"({
    "scene": "t",
    "geometry": {"kind": "groove", "theta_v_deg": 90},
    "light": {"theta_i_deg": [0, 30], "rays": 100},
    "effects": {"fresnel": {"kind": "conductor", "channels": [{"name": "r", "eta": 0.2, "kappa": 3.0}]}}
  })");
}

// The message parse_scene throws for `j` ("" if it parses).
std::string error_of(const json& j) {
  try {
    parse_scene(j, "s.json");
  } catch (const support::UserError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneSpec, BaseSceneParses) {
  const Scene s = parse_scene(base_scene(), "s.json");
  EXPECT_EQ(s.name, "t");
  EXPECT_EQ(s.geometry.kind, GeometryKind::groove);
  EXPECT_DOUBLE_EQ(s.geometry.groove.theta_v, std::numbers::pi / 2);
  ASSERT_EQ(s.light.theta_i.size(), 2u);
  EXPECT_DOUBLE_EQ(s.light.theta_i[1], std::numbers::pi / 6);
  EXPECT_EQ(s.light.rays, 100);
  EXPECT_EQ(s.light.sampling, sim::Sampling::stratified);  // the defaults
  EXPECT_EQ(s.light.seed, 1u);
  EXPECT_EQ(s.max_bounces, 100000);
  EXPECT_EQ(s.record.theta_o_bins, 0);
  EXPECT_FALSE(s.record.energy_per_k);
  ASSERT_EQ(s.channels.size(), 1u);
  EXPECT_EQ(s.fresnel, FresnelKind::conductor);
}

TEST(SceneSpec, WavelengthChannelsAreNamedByTheirWavelength) {
  json j = base_scene();
  j["effects"]["fresnel"] = json::parse(
      R"({"kind": "conductor", "wavelengths": [{"lambda_nm": 450, "eta": 1.3, "kappa": 1.8},
                                               {"lambda_nm": 632.8, "eta": 0.2, "kappa": 3}]})");
  const Scene s = parse_scene(j, "s.json");
  ASSERT_EQ(s.channels.size(), 2u);
  EXPECT_EQ(s.channels[0].name, "450nm");
  EXPECT_EQ(s.channels[1].name, "632.8nm");
  EXPECT_EQ(s.channels[1].lambda_nm, 632.8);
}

TEST(SceneSpec, CheckedInScenesParse) {
  for (const char* name : {"gold_groove", "schlick_microsurface", "bounce_counts_only"}) {
    const Scene s = load_scene(std::string(VGROOVE_SOURCE_DIR) + "/data/scenes/" + name + ".json");
    EXPECT_EQ(s.name, name);
  }
}

// Every error class, with the exact message the user sees (after "vgroove: error: ").
TEST(SceneSpec, UnknownKey) {
  json j = base_scene();
  j["colour"] = "gold";
  EXPECT_EQ(error_of(j), "s.json: /colour is not a known key (known here: effects, geometry, light, note, scene)");
  j = base_scene();
  j["effects"]["fresnel"]["channels"][0]["etaa"] = 1;
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel/channels/0/etaa is not a known key (known here: eta, kappa, name)");
  j = base_scene();
  j["effects"]["record"] = {{"bounce_counts", true}};
  EXPECT_EQ(error_of(j),
            "s.json: /effects/record/bounce_counts is not a known key (known here: energy_per_k, theta_o_histograms)");
  // Schlick takes "channels" only: "wavelengths" is not its key.
  j = base_scene();
  j["effects"]["fresnel"] = json::parse(R"({"kind": "schlick", "wavelengths": [{"lambda_nm": 500, "F0": 0.5}]})");
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel/channels is missing (required)");
}

TEST(SceneSpec, WrongType) {
  json j = base_scene();
  j["light"]["rays"] = "many";
  EXPECT_EQ(error_of(j), "s.json: /light/rays = \"many\" must be an integer");
  j["light"]["rays"] = 1.5;
  EXPECT_EQ(error_of(j), "s.json: /light/rays = 1.5 must be an integer");
  j = base_scene();
  j["light"]["theta_i_deg"] = 30;
  EXPECT_EQ(error_of(j),
            "s.json: /light/theta_i_deg = 30 must be a list of incident angles in degrees, each in [-89.999, 89.999]");
  j["light"]["theta_i_deg"] = json::parse(R"([0, "45"])");
  EXPECT_EQ(error_of(j), "s.json: /light/theta_i_deg/1 = \"45\" must be a number");
  j = base_scene();
  j["geometry"] = 5;
  EXPECT_EQ(error_of(j), "s.json: /geometry must be a JSON object, found number");
  j = base_scene();
  j["effects"]["record"] = {{"energy_per_k", 1}};
  EXPECT_EQ(error_of(j), "s.json: /effects/record/energy_per_k = 1 must be true or false");
  j = base_scene();
  j["effects"]["fresnel"]["channels"][0]["name"] = 7;
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel/channels/0/name = 7 must be a string");
}

TEST(SceneSpec, OutOfRange) {
  json j = base_scene();
  j["geometry"]["theta_v_deg"] = 195;
  EXPECT_EQ(error_of(j), "s.json: /geometry/theta_v_deg = 195 is out of range [0.001, 180]");
  j = base_scene();
  j["light"]["theta_i_deg"] = {0, 90};
  EXPECT_EQ(error_of(j), "s.json: /light/theta_i_deg/1 = 90 is out of range [-89.999, 89.999]");
  j = base_scene();
  j["light"]["rays"] = 0;
  EXPECT_EQ(error_of(j), "s.json: /light/rays = 0 is out of range [1, 1000000000]");
  j = base_scene();
  j["light"]["seed"] = -1;
  EXPECT_EQ(error_of(j), "s.json: /light/seed = -1 is out of range [0, 9223372036854775807]");
  j = base_scene();
  j["effects"]["fresnel"]["channels"][0]["kappa"] = -1;
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel/channels/0/kappa = -1 is out of range [0, 1000]");
  j["effects"]["fresnel"]["channels"][0]["kappa"] = 3;
  j["effects"]["fresnel"]["channels"][0]["eta"] = 0;
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel/channels/0/eta = 0 is out of range (0, 1000]");
  j = base_scene();
  j["effects"]["fresnel"] = json::parse(R"({"kind": "schlick", "channels": [{"name": "r", "F0": 1.5}]})");
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel/channels/0/F0 = 1.5 is out of range [0, 1]");
  j = base_scene();
  j["effects"]["record"] = {{"theta_o_histograms", {{"bins", 0}}}};
  EXPECT_EQ(error_of(j), "s.json: /effects/record/theta_o_histograms/bins = 0 is out of range [1, 100000]");
  j = base_scene();
  j["effects"]["max_bounces"] = 0;
  EXPECT_EQ(error_of(j), "s.json: /effects/max_bounces = 0 is out of range [1, 100000000]");
  j = base_scene();
  j["geometry"] = json::parse(R"({"kind": "microsurface", "ndf": "ggx", "alpha": 0, "grooves": 10})");
  EXPECT_EQ(error_of(j), "s.json: /geometry/alpha = 0 is out of range [0.01, 2]");
  j["geometry"]["alpha"] = 0.5;
  j["geometry"]["grooves"] = 0;
  EXPECT_EQ(error_of(j), "s.json: /geometry/grooves = 0 is out of range [1, 10000000]");
  // A nonsymmetric groove whose facets meet with no opening.
  j = base_scene();
  j["geometry"] = json::parse(R"({"kind": "groove", "theta_l_deg": -90, "theta_r_deg": 90})");
  EXPECT_EQ(error_of(j),
            "s.json: /geometry: theta_l_deg = -90, theta_r_deg = 90 give the aperture 180 + theta_l - "
            "theta_r = 0 deg, out of range [0.001, 180]");
}

TEST(SceneSpec, NotOneOfTheChoices) {
  json j = base_scene();
  j["light"]["sampling"] = "sobol";
  EXPECT_EQ(error_of(j), "s.json: /light/sampling = \"sobol\" is not one of \"stratified\", \"random\"");
  j = base_scene();
  j["effects"]["fresnel"]["kind"] = "dielectric";
  EXPECT_EQ(error_of(j),
            "s.json: /effects/fresnel/kind = \"dielectric\" is not one of \"none\", \"conductor\", \"schlick\"");
  j = base_scene();
  j["geometry"]["kind"] = "sphere";
  EXPECT_EQ(error_of(j), "s.json: /geometry/kind = \"sphere\" is not one of \"groove\", \"microsurface\"");
}

TEST(SceneSpec, MissingRequiredKey) {
  json j = base_scene();
  j.erase("light");
  EXPECT_EQ(error_of(j), "s.json: /light is missing (required)");
  j = base_scene();
  j["light"].erase("rays");
  EXPECT_EQ(error_of(j), "s.json: /light/rays is missing (required)");
  j = base_scene();
  j["geometry"].erase("theta_v_deg");
  EXPECT_EQ(error_of(j), "s.json: /geometry/theta_l_deg is missing (required)");
  j = base_scene();
  j["effects"]["fresnel"].erase("channels");
  EXPECT_EQ(
      error_of(j),
      "s.json: /effects/fresnel/channels is missing (required: a conductor needs \"channels\" or \"wavelengths\")");
  j = base_scene();
  j["effects"].erase("fresnel");
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel is missing (required)");
}

TEST(SceneSpec, EmptyList) {
  json j = base_scene();
  j["light"]["theta_i_deg"] = json::array();
  EXPECT_EQ(error_of(j),
            "s.json: /light/theta_i_deg is an empty list (it needs at least one of incident angles in degrees, each in "
            "[-89.999, 89.999])");
  j = base_scene();
  j["effects"]["fresnel"]["channels"] = json::array();
  EXPECT_EQ(
      error_of(j),
      "s.json: /effects/fresnel/channels is an empty list (it needs at least one of {\"name\", \"eta\", \"kappa\"})");
}

TEST(SceneSpec, InconsistentCombinations) {
  json j = base_scene();
  j["geometry"]["theta_l_deg"] = -30;
  EXPECT_EQ(error_of(j),
            "s.json: /geometry/theta_v_deg cannot be combined with theta_l_deg/theta_r_deg (the aperture "
            "follows from them)");
  j = base_scene();
  j["effects"]["fresnel"]["wavelengths"] = json::parse(R"([{"lambda_nm": 500, "eta": 1, "kappa": 1}])");
  EXPECT_EQ(error_of(j),
            "s.json: /effects/fresnel/wavelengths cannot be combined with channels (give one list: named "
            "channels or wavelengths)");
  j = base_scene();
  j["effects"]["fresnel"]["channels"].push_back({{"name", "r"}, {"eta", 1.0}, {"kappa", 1.0}});
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel/channels/1 repeats the channel \"r\" (names must be unique)");
  j = base_scene();
  j["effects"]["fresnel"] = {{"kind", "none"}};
  j["effects"]["record"] = {{"energy_per_k", true}};
  EXPECT_EQ(error_of(j),
            "s.json: /effects/record/energy_per_k = true needs a Fresnel effect (with "
            "/effects/fresnel/kind = \"none\" every path keeps all its energy: the energy per k is the "
            "count per k)");
  j = base_scene();
  json many = json::array();
  for (int c = 0; c <= kMaxChannels; ++c)
    many.push_back({{"name", "c" + std::to_string(c)}, {"eta", 1.0}, {"kappa", 1.0}});
  j["effects"]["fresnel"]["channels"] = many;
  EXPECT_EQ(error_of(j), "s.json: /effects/fresnel/channels has 65 items, more than the 64 allowed");
}

// ---------------------------------------------------------------------------------------------
// Physics

Scene groove_scene(const std::string& geometry, const std::string& fresnel, long rays, const std::string& sampling) {
  json j = base_scene();
  j["geometry"] = json::parse(geometry);
  j["effects"]["fresnel"] = json::parse(fresnel);
  j["effects"]["record"] = {{"energy_per_k", true}, {"theta_o_histograms", {{"bins", 36}, {"max_k", 4}}}};
  j["light"] = {
      {"theta_i_deg", {-75, -40, -10, 0, 5, 30, 55, 80}}, {"rays", rays}, {"sampling", sampling}, {"seed", 7}};
  return parse_scene(j, "test");
}

const char* kTwoConductors =
    R"({"kind": "conductor", "channels": [{"name": "bright", "eta": 0.2, "kappa": 3.0},
                                          {"name": "dark", "eta": 1.5, "kappa": 0.5}]})";
const char* kSchlick = R"({"kind": "schlick", "channels": [{"name": "a", "F0": 0.04}, {"name": "b", "F0": 0.9}]})";
const char* kGrooves[] = {
    R"({"kind": "groove", "theta_v_deg": 30})",
    R"({"kind": "groove", "theta_v_deg": 73})",
    R"({"kind": "groove", "theta_v_deg": 120})",
    R"({"kind": "groove", "theta_l_deg": -20, "theta_r_deg": 50})",
    R"({"kind": "groove", "theta_l_deg": -70, "theta_r_deg": 15})",
};

// Traced energy per theta_i against the model's, with stratified rays.
//
// Tolerance. Every ray of a (first facet, n) bin keeps the same energy, the product of F at the
// local angles (analytic/kaleidoscope_fresnel.h; tests/validation/fresnel_groove_test.cpp shows
// tracer and model agree on it ray by ray to 1e-12 relative). So the traced energy per ray is a
// step function e(u) of the landing fraction u across the opening, with values in [0, 1], and the
// model's energy is its integral over u (the model's shares G f_a / width are the bins' widths).
// The steps: the left-first rays form one interval and the right-first ones another, each cut
// into at most 2 zones (Eq. 6, symmetric) or 4 (Eq. 7-9, nonsymmetric), so there are at most
// D = 3 (symmetric) or D = 7 (nonsymmetric) jumps, each of height at most 1. The midpoint rule
// over N equal strata is exact on every stratum without a jump, and a stratum holding one errs by
// at most (jump) / N; so |traced - model| <= D / N, plus 1e-12 for the per-ray agreement.
// The mean k is the integral of the step function k(u) likewise, with jumps of at most the
// largest k: |traced - model| <= D k_max / N.
TEST(Simulate, ConductorGrooveEnergyMatchesTheModelStratified) {
  constexpr long kN = 4000;
  for (const char* fresnel : {kTwoConductors, kSchlick})
    for (const char* geometry : kGrooves) {
      const Scene s = groove_scene(geometry, fresnel, kN, "stratified");
      const double D = s.geometry.groove.symmetric ? 3.0 : 7.0;
      const double tol = D / kN + 1e-12;
      const SimulationResult r = simulate(s, 2);
      for (std::size_t t = 0; t < r.tallies.size(); ++t) {
        const ThetaTally& ta = r.tallies[t];
        ASSERT_TRUE(r.model[t].available);
        EXPECT_EQ(ta.escaped, ta.rays) << geometry << " theta_i=" << r.theta_i[t];
        EXPECT_NEAR(ta.mean_k(), r.model[t].mean_k, D * static_cast<double>(ta.by_k.size() - 1) / kN) << geometry;
        for (std::size_t c = 0; c < s.channels.size(); ++c)
          EXPECT_NEAR(ta.energy[c] / static_cast<double>(ta.rays), r.model[t].energy[c], tol)
              << geometry << " " << fresnel << " theta_i=" << r.theta_i[t] * 180 / std::numbers::pi << " channel " << c;
      }
    }
}

// The same with random rays: the traced energy is the mean of N independent values in [0, 1],
// whose variance is at most 1/4, so sigma <= 1 / (2 sqrt(N)); 5 sigma, for 5 grooves x 8 angles x
// 2 channels x 2 reflectances = 160 comparisons (P(any beyond 5 sigma) < 160 x 5.7e-7 = 1e-4).
TEST(Simulate, ConductorGrooveEnergyMatchesTheModelRandom) {
  constexpr long kN = 10000;
  const double tol = 5.0 * 0.5 / std::sqrt(static_cast<double>(kN));
  for (const char* fresnel : {kTwoConductors, kSchlick})
    for (const char* geometry : kGrooves) {
      const Scene s = groove_scene(geometry, fresnel, kN, "random");
      const SimulationResult r = simulate(s, 2);
      for (std::size_t t = 0; t < r.tallies.size(); ++t)
        for (std::size_t c = 0; c < s.channels.size(); ++c)
          EXPECT_NEAR(r.tallies[t].energy[c] / static_cast<double>(r.tallies[t].rays), r.model[t].energy[c], tol)
              << geometry << " " << fresnel << " theta_i=" << r.theta_i[t] * 180 / std::numbers::pi << " channel " << c;
    }
}

// What is recorded adds up: energy per k sums to the energy, the histograms to the escaped rays,
// the per-k rows to the total histogram, the counts per k to the escaped rays.
TEST(Simulate, RecordsAreConsistent) {
  const Scene s = groove_scene(kGrooves[0], kTwoConductors, 3000, "random");
  const SimulationResult r = simulate(s, 1);
  const std::size_t C = s.channels.size();
  for (const ThetaTally& t : r.tallies) {
    std::int64_t counted = 0;
    for (std::int64_t n : t.by_k) counted += n;
    EXPECT_EQ(counted, t.escaped);
    for (std::size_t c = 0; c < C; ++c) {
      double sum = 0.0;
      for (std::size_t k = 0; k * C + c < t.energy_by_k.size(); ++k) sum += t.energy_by_k[k * C + c];
      EXPECT_NEAR(sum, t.energy[c], 1e-12 * t.energy[c]);
    }
    std::int64_t hist = 0;
    for (std::int64_t n : t.theta_o) hist += n;
    EXPECT_EQ(hist, t.escaped);
    for (std::size_t b = 0; b < t.theta_o.size(); ++b) {
      std::int64_t rows = 0;
      for (std::size_t k = 0; k < 6; ++k) rows += t.theta_o_by_k[k * t.theta_o.size() + b];
      EXPECT_EQ(rows, t.theta_o[b]) << "bin " << b;
    }
  }
}

// A flat groove (theta_v = 180) at normal incidence is a mirror: every ray reflects once at
// cos theta = 1, so the energy is F(1) = ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2) exactly (written
// out here, not taken from optics/). N even, so no stratum midpoint lands on the apex (x = 0).
TEST(Simulate, FlatMirrorAtNormalIncidence) {
  json j = base_scene();
  j["geometry"] = {{"kind", "groove"}, {"theta_v_deg", 180}};
  j["light"] = {{"theta_i_deg", {0}}, {"rays", 1000}};
  j["effects"]["fresnel"] = json::parse(R"({"kind": "conductor", "channels": [
      {"name": "a", "eta": 0.2, "kappa": 3.0}, {"name": "b", "eta": 1.5, "kappa": 0.5},
      {"name": "c", "eta": 1.5, "kappa": 0}, {"name": "d", "eta": 0.05, "kappa": 7.5}]})");
  const Scene s = parse_scene(j, "test");
  const SimulationResult r = simulate(s, 1);
  const ThetaTally& t = r.tallies.at(0);
  EXPECT_EQ(t.escaped, 1000);
  ASSERT_EQ(t.by_k.size(), 2u);
  EXPECT_EQ(t.by_k[1], 1000);
  for (std::size_t c = 0; c < s.channels.size(); ++c) {
    const double n = s.channels[c].eta, k = s.channels[c].kappa;
    const double F = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    EXPECT_NEAR(t.energy[c] / 1000.0, F, 1e-12) << s.channels[c].name;
    EXPECT_NEAR(r.model[0].energy[c], F, 1e-12) << s.channels[c].name;
  }
}

// A right-angled groove (theta_v = 90) at normal incidence: every ray reflects twice, at 45 deg
// both times (its direction turns by 90 deg at the first facet and meets the second at 45 deg),
// so the energy is F(45 deg)^2. At 45 deg the p reflectance is the square of the s one (Abeles'
// relation: r_p = r_s^2 when cos^2 = sin^2), so F = (R_s + R_s^2) / 2 with
// R_s = |c - w|^2 / |c + w|^2, c = 1/sqrt(2), w = sqrt((eta + i kappa)^2 - 1/2): written out here
// with std::complex, independently of optics/.
TEST(Simulate, RightAngledGrooveAtNormalIncidence) {
  json j = base_scene();
  j["geometry"] = {{"kind", "groove"}, {"theta_v_deg", 90}};
  j["light"] = {{"theta_i_deg", {0}}, {"rays", 1000}};
  j["effects"]["fresnel"] = json::parse(R"({"kind": "conductor", "channels": [
      {"name": "a", "eta": 0.2, "kappa": 3.0}, {"name": "b", "eta": 1.5, "kappa": 0.5}, {"name": "c", "eta": 1.5, "kappa": 0}]})");
  const Scene s = parse_scene(j, "test");
  const SimulationResult r = simulate(s, 1);
  const ThetaTally& t = r.tallies.at(0);
  ASSERT_EQ(t.by_k.size(), 3u);
  EXPECT_EQ(t.by_k[2], 1000);
  for (std::size_t c = 0; c < s.channels.size(); ++c) {
    const std::complex<double> n(s.channels[c].eta, s.channels[c].kappa);
    const double cos45 = std::sqrt(0.5);
    const std::complex<double> w = std::sqrt(n * n - 0.5);
    const double Rs = std::norm(cos45 - w) / std::norm(cos45 + w);
    const double F = 0.5 * (Rs + Rs * Rs);
    EXPECT_NEAR(t.energy[c] / 1000.0, F * F, 1e-12) << s.channels[c].name;
    EXPECT_NEAR(r.model[0].energy[c], F * F, 1e-12) << s.channels[c].name;
  }
}

// A microsurface scene over several ray chunks and angles: threads 1 and 2 give the same JSON
// (the energy sums included) but for the run's wall time and thread count.
TEST(Simulate, BitIdenticalForAnyThreadCount) {
  json j = base_scene();
  j["geometry"] =
      json::parse(R"({"kind": "microsurface", "ndf": "beckmann", "alpha": 0.7, "grooves": 500, "seed": 3})");
  j["light"] = {{"theta_i_deg", {-50, 0, 20, 70}}, {"rays", 2 * sim::kRaysPerChunk + 1000}, {"sampling", "random"}};
  j["effects"]["record"] = {{"energy_per_k", true}, {"theta_o_histograms", {{"bins", 30}}}};
  const Scene s = parse_scene(j, "test");
  json a = result_json(s, simulate(s, 1)), b = result_json(s, simulate(s, 2));
  for (json* x : {&a, &b}) x->erase("wall_s"), x->erase("threads");
  EXPECT_EQ(a.dump(), b.dump());
}

// With fresnel none the loop is the bare tracer: its counts are sim::trace_microsurface's (same
// surface, same landing points), and the result carries no energy.
TEST(Simulate, MicrosurfaceCountsMatchTraceMicrosurface) {
  json j = base_scene();
  j["geometry"] = json::parse(R"({"kind": "microsurface", "ndf": "ggx", "alpha": 0.9, "grooves": 300, "seed": 5})");
  j["light"] = {{"theta_i_deg", {35}}, {"rays", 20000}, {"sampling", "random"}, {"seed", 11}};
  j["effects"] =
      json::parse(R"({"fresnel": {"kind": "none"}, "record": {"theta_o_histograms": {"bins": 45, "max_k": 16}}})");
  const Scene s = parse_scene(j, "test");
  const SimulationResult r = simulate(s, 2);
  sim::MicrosurfaceOptions mo;
  mo.ndf = sim::NdfKind::ggx, mo.alpha = 0.9, mo.grooves = 300, mo.seed = 5;
  sim::MicrosurfaceTraceOptions to;
  to.theta_i = 35 * std::numbers::pi / 180, to.rays = 20000, to.sampling = sim::Sampling::random, to.seed = 11;
  to.theta_o_bins = 45, to.max_k = 16;
  const sim::MicrosurfaceTally ref = sim::trace_microsurface(sim::make_microsurface(mo), to);
  const ThetaTally& t = r.tallies.at(0);
  EXPECT_EQ(t.escaped, ref.escaped);
  EXPECT_EQ(t.bounces, ref.bounces);
  EXPECT_EQ(t.vertex_hits + t.bounce_limit + t.blocked + t.not_upward, ref.lost());
  for (int k = 0; k <= 16; ++k)
    EXPECT_EQ(static_cast<std::size_t>(k) < t.by_k.size() ? t.by_k[static_cast<std::size_t>(k)] : 0,
              ref.by_k[static_cast<std::size_t>(k)])
        << "k=" << k;
  EXPECT_EQ(t.theta_o, ref.theta_o);
  EXPECT_EQ(t.theta_o_by_k, ref.theta_o_by_k);
  const json out = result_json(s, r);
  EXPECT_FALSE(out["results"][0].contains("energy"));
  EXPECT_FALSE(out["results"][0].contains("energy_per_k"));
  EXPECT_FALSE(out["results"][0].contains("model"));  // a microsurface has no single-groove model
}

// Rays with more than kMaxKRow reflections share one row (memory stays bounded), while the mean k
// stays exact. A 0.03 deg groove at normal incidence: Eq. (4) gives about 180 / 0.03 = 6000
// reflections per ray, so every ray lands in the shared row.
TEST(Simulate, DeepPathsShareTheLastRow) {
  json j = base_scene();
  j["geometry"] = {{"kind", "groove"}, {"theta_v_deg", 0.03}};
  j["light"] = {{"theta_i_deg", {0}}, {"rays", 10}};
  j["effects"]["record"] = {{"energy_per_k", true}};
  const Scene s = parse_scene(j, "test");
  const SimulationResult r = simulate(s, 1);
  const ThetaTally& t = r.tallies.at(0);
  EXPECT_EQ(t.escaped, 10);
  ASSERT_EQ(t.by_k.size(), static_cast<std::size_t>(kMaxKRow) + 2);
  EXPECT_EQ(t.by_k.back(), 10);
  // The model k takes the values k - 1 and k on each facet: D = 3 jumps of 1 over N = 10 strata (see above).
  EXPECT_NEAR(t.mean_k(), r.model[0].mean_k, 3.0 / 10);
  EXPECT_GT(t.mean_k(), 5990.0);
  const json out = result_json(s, r);
  EXPECT_EQ(out["results"][0]["counts_per_k"], json::parse(R"({">4096": 10})"));
  EXPECT_NEAR(out["results"][0]["energy_per_k"]["r"][">4096"].get<double>(), t.energy[0] / 10, 1e-15);
}

TEST(SceneSpec, HistogramSizeIsBounded) {
  json j = base_scene();
  j["effects"]["record"] = {{"theta_o_histograms", {{"bins", 100000}, {"max_k", 16}}}};
  EXPECT_EQ(error_of(j),
            "s.json: /effects/record/theta_o_histograms: bins x (max_k + 2) = 1800000 histogram cells, "
            "out of range [1, 1000000]");
}

// ---------------------------------------------------------------------------------------------
// The command line

using testing_files::CliRun;
using testing_files::vgroove;

TEST(SimulateCli, BadInputWritesNothing) {
  TempDir dir;
  const std::string scene = dir.file("bad.json"), out = dir.file("out.json");
  json j = base_scene();
  j["light"]["rays"] = 0;
  write_text(scene, j.dump());
  const CliRun r = vgroove("simulate '" + scene + "' --out '" + out + "'");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "vgroove: error: " + scene + ": /light/rays = 0 is out of range [1, 1000000000]\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"bad.json"});
  // Not JSON at all.
  write_text(scene, "{\"scene\": ");
  const CliRun r2 = vgroove("simulate '" + scene + "' --out '" + out + "'");
  EXPECT_EQ(r2.status, 2);
  EXPECT_EQ(r2.err.find("vgroove: error: " + scene + ": not valid JSON: "), 0u) << r2.err;
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"bad.json"});
}

TEST(SimulateCli, WritesTheResultAndRefusesToOverwrite) {
  TempDir dir;
  const std::string scene = dir.file("s.json"), out = dir.file("out.json");
  json j = base_scene();
  j["light"]["rays"] = 200;
  write_text(scene, j.dump());
  const CliRun r = vgroove("simulate '" + scene + "' --out '" + out + "' --threads 2");
  ASSERT_EQ(r.status, 0) << r.err;
  const json res = json::parse(read_text(out));
  for (const char* key :
       {"tool", "version", "git", "scene", "scene_file", "seed", "threads", "wall_s", "rays", "bounces"})
    EXPECT_TRUE(res.contains(key)) << key;
  EXPECT_EQ(res["rays"], 400);
  EXPECT_EQ(res["results"].size(), 2u);
  const std::string before = read_text(out);
  const CliRun again = vgroove("simulate '" + scene + "' --out '" + out + "'");
  EXPECT_EQ(again.status, 2);
  EXPECT_EQ(read_text(out), before);
  EXPECT_EQ(vgroove("simulate '" + scene + "' --out '" + out + "' --force").status, 0);
  const CliRun threads = vgroove("simulate '" + scene + "' --threads -1");
  EXPECT_EQ(threads.status, 2);
  EXPECT_EQ(threads.err, "vgroove: error: --threads = -1 is out of range [0, 1024] (0: all cores)\n");
}

// The stratified midpoints of 5,000 rays on 10,000 grooves are the grooves' left ridges, every
// other one: placed there, 88 % of the rays hit a vertex and the run reported an albedo of 0.1146
// with F = 1. Now every ray lands inside a groove and leaves.
TEST(SimulateCli, StratifiedRaysOnAMicrosurfaceAllLeave) {
  TempDir dir;
  const std::string scene = dir.file("s.json"), out = dir.file("out.json");
  for (const auto& [grooves, rays] : {std::pair{10000, 5000}, std::pair{250000, 125000}, std::pair{3000, 3000}}) {
    const json j = {
        {"scene", "strat"},
        {"geometry", {{"kind", "microsurface"}, {"ndf", "ggx"}, {"alpha", 0.5}, {"grooves", grooves}, {"seed", 1}}},
        {"light", {{"theta_i_deg", {30}}, {"rays", rays}, {"sampling", "stratified"}, {"seed", 1}}},
        {"effects", {{"fresnel", {{"kind", "none"}}}}}};
    write_text(scene, j.dump());
    const CliRun r = vgroove("simulate '" + scene + "' --out '" + out + "' --force");
    ASSERT_EQ(r.status, 0) << grooves << " grooves, " << rays << " rays: " << r;
    const json res = json::parse(read_text(out))["results"][0];
    EXPECT_EQ(res["escaped"], rays) << res.dump();
    EXPECT_EQ(res["vertex_hit"], 0) << res.dump();
  }
}

// With max_bounces 1 every ray in a 60 deg groove is still inside after one reflection: the summary
// said "0 bounces" (those of the escaped rays) and "2000 lost (vertex hits, bounce limit, ...)";
// it says whose reflections it counts and why the rays were lost.
TEST(SimulateCli, TheSummarySaysWhyRaysWereLost) {
  TempDir dir;
  const std::string scene = dir.file("s.json");
  json j = base_scene();
  j["geometry"] = {{"kind", "groove"}, {"theta_v_deg", 60}};
  j["light"] = {{"theta_i_deg", {0, 30}}, {"rays", 1000}, {"sampling", "stratified"}, {"seed", 1}};
  j["effects"] = {{"fresnel", {{"kind", "none"}}}, {"max_bounces", 1}};
  write_text(scene, j.dump());
  const CliRun r = vgroove("simulate '" + scene + "'");
  EXPECT_EQ(r.status, 0) << r;
  EXPECT_NE(r.out.find("  2000 rays, 0 reflections of the escaped ones; 2000 lost (2000 at the bounce limit of 1, 0 "
                       "vertex hits, 0 blocked, 0 not upward); "),
            std::string::npos)
      << r.out;
}

// One stratified ray into a right-angled groove at normal incidence lands on its apex: a run that
// loses more than kMaxLostShare of its rays to vertices says so and writes nothing.
TEST(SimulateCli, ARunThatLosesRaysToVerticesFailsLoudly) {
  TempDir dir;
  const std::string scene = dir.file("s.json"), out = dir.file("out.json");
  json j = base_scene();
  j["geometry"] = {{"kind", "groove"}, {"theta_v_deg", 90}};
  j["light"] = {{"theta_i_deg", {0}}, {"rays", 1}, {"sampling", "stratified"}, {"seed", 1}};
  write_text(scene, j.dump());
  const CliRun r = vgroove("simulate '" + scene + "' --out '" + out + "'");
  EXPECT_EQ(r.status, 1) << r;
  EXPECT_EQ(r.out, "");
  EXPECT_EQ(r.err, "vgroove: error: " + scene +
                       ": theta_i 0 deg: 1 of 1 rays (100.00 %) lost (1 vertex hits, 0 blocked, 0 not upward), more "
                       "than the 0.1 % a run may lose: no result written\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"s.json"});
  // 1001 rays: the one at the apex is within the share.
  j["light"]["rays"] = 1001;
  write_text(scene, j.dump());
  const CliRun ok = vgroove("simulate '" + scene + "' --out '" + out + "'");
  EXPECT_EQ(ok.status, 0) << ok;
  EXPECT_EQ(json::parse(read_text(out))["results"][0]["vertex_hit"], 1);
}

}  // namespace
}  // namespace vgroove::scene

namespace vgroove::scene {
namespace {

// Published metals through a traced groove. In a 60 deg groove lit at theta_i = 60 deg the light
// falls along the right facet's normal (its normal is at +60 deg) and parallel to the left facet:
// every ray reflects once, at normal incidence, straight back. The traced energy is then the
// normal-incidence reflectance ((n-1)^2 + k^2) / ((n+1)^2 + k^2) of each published (n, k) in
// data/reference/metals.json (Johnson & Christy 1972; Rakic 1995), whose R_normal column was
// computed independently of the code (6 significant digits).
TEST(SceneMetals, PublishedConstantsThroughANormalIncidenceGroove) {
  const json ref =
      json::parse(testing_files::read_text(std::string(VGROOVE_SOURCE_DIR) + "/data/reference/metals.json"));
  json scene = {{"scene", "metals"},
                {"geometry", {{"kind", "groove"}, {"theta_v_deg", 60}}},
                {"light", {{"theta_i_deg", {60}}, {"rays", 1000}, {"sampling", "stratified"}, {"seed", 1}}},
                {"effects", {{"fresnel", {{"kind", "conductor"}, {"wavelengths", json::array()}}}}}};
  std::vector<double> expected;
  for (const auto& m : ref.at("metals"))
    for (const auto& s : m.at("samples")) {
      // Names must be unique: the same wavelength appears for several metals.
      scene["effects"]["fresnel"]["wavelengths"].push_back(
          {{"lambda_nm", s.at("lambda_nm").get<double>() + 1e-3 * static_cast<double>(expected.size())},
           {"eta", s.at("eta")},
           {"kappa", s.at("kappa")}});
      expected.push_back(s.at("R_normal").get<double>());
    }
  ASSERT_EQ(expected.size(), 12u);
  const Scene s = parse_scene(scene, "metals.json");
  const SimulationResult r = simulate(s, 1);
  ASSERT_EQ(r.tallies.size(), 1u);
  const ThetaTally& t = r.tallies[0];
  EXPECT_EQ(t.escaped, 1000);
  EXPECT_EQ(t.bounces, 1000);  // one reflection each
  for (std::size_t c = 0; c < expected.size(); ++c)
    EXPECT_NEAR(t.energy[c] / static_cast<double>(t.rays), expected[c], 5e-6 * expected[c]) << "sample " << c;
}

}  // namespace
}  // namespace vgroove::scene
