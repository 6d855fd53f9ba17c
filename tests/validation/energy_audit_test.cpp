// Tests of the energy audit (validation/energy_audit.h) and what it reads:
// - the metals' constants are data/reference/metals.json's; a conductor's F_avg is its quadrature;
// - CIE Delta E 2000 at Sharma et al. 2005's published test pairs, and L* of the sRGB white;
// - the engines' tables as the engines read them: Cycles' lookup hits its nodes and is linear
//   between them; the half-float rounding; Filament's texel centres hold the next row's roughness;
// - the V-groove reference with a conductor's F against procedural V-grooves traced exactly (sim/,
//   every ray in a groove of its own, the 2D trace lifted as sim::trace_groove3d does), per bounce
//   order, within 5 standard errors;
// - a small audit: the references' checks pass; every formula fed with the exact E_ss keeps the
//   white furnace (F = 1) within rounding against the walk, whose white albedo is exactly 1; no
//   compensation loses energy
//   everywhere; a broken walk tally (one path's white energy short) fails the white furnace check;
// - the heightfield reference: its channels are the tracer's Fresnel traces of the same rays, its
//   tallies the same for any threads and shards, its white channel 1 exactly in the report.
#include "vgroove/validation/energy_audit.h"
#include "tests/stats.h"
#include "tests/test_files.h"
#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/albedo_vgroove.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/effects.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/user_error.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>

namespace vgroove::validation {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(EnergyMaterials, MetalsAreDataReferenceMetalsJson) {
  std::ifstream in(std::string(VGROOVE_SOURCE_DIR) + "/data/reference/metals.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_EQ(j.at("metals").size(), reference_metals().size());
  for (std::size_t m = 0; m < reference_metals().size(); ++m) {
    const ReferenceMetal& r = reference_metals()[m];
    const nlohmann::json& jm = j["metals"][m];
    EXPECT_EQ(jm.at("symbol").get<std::string>(), r.symbol);
    for (int b = 0; b < 3; ++b) {
      EXPECT_EQ(jm["samples"][b].at("lambda_nm").get<double>(), r.lambda_nm[b]) << r.symbol << " " << b;
      EXPECT_EQ(jm["samples"][b].at("eta").get<double>(), r.eta[b]) << r.symbol << " " << b;
      EXPECT_EQ(jm["samples"][b].at("kappa").get<double>(), r.kappa[b]) << r.symbol << " " << b;
    }
  }
}

TEST(EnergyMaterials, FresnelAveragesAreTheirIntegrals) {
  const ChannelSet set({0.04, 1.0}, {"Au", "Al"});
  for (int c = 0; c < set.size(); ++c) {
    const Channel& ch = set.channels()[c];
    const double q = test_stats::tanh_sinh([&](double mu) { return 2.0 * mu * ch.F(mu); }, 0.0, 1.0);
    EXPECT_NEAR(set.F_avg(c), q, 1e-12) << ch.name;
    double fast[64];
    for (double mu : {0.0, 0.013, 0.5, 0.97, 1.0}) {
      set.evaluate(mu, fast);
      EXPECT_NEAR(fast[c], ch.F(mu), 1e-12) << ch.name << " mu=" << mu;
    }
  }
  EXPECT_EQ(set.find_grey(0.04), 0);
  EXPECT_EQ(set.channels()[set.find("conductor", "Au", 2)].name, "Au 659.5 nm");
}

// Sharma, Wu, Dalal 2005, Table 1: pairs 1, 7, 17 and 25 with their printed Delta E 2000.
TEST(Colour, DeltaE2000AtSharmasTestPairs) {
  struct Pair {
    double a[3], b[3], dE;
  };
  const Pair pairs[] = {{{50.0, 2.6772, -79.7751}, {50.0, 0.0, -82.7485}, 2.0425},
                        {{50.0, 0.0, 0.0}, {50.0, -1.0, 2.0}, 2.3669},
                        {{50.0, 2.5, 0.0}, {73.0, 25.0, -18.0}, 27.1492},
                        {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644}};
  for (const Pair& p : pairs) {
    EXPECT_NEAR(delta_e_2000(p.a, p.b), p.dE, 5e-5) << p.a[0] << "," << p.a[1] << "," << p.a[2];
    EXPECT_NEAR(delta_e_2000(p.b, p.a), p.dE, 5e-5);
  }
  const double white[3] = {1.0, 1.0, 1.0};
  double lab[3];
  lab_from_linear_srgb(white, lab);
  EXPECT_NEAR(lab[0], 100.0, 1e-4);
  EXPECT_NEAR(lab[1], 0.0, 1e-3);
  EXPECT_NEAR(lab[2], 0.0, 1e-3);
}

TEST(EngineTables, CyclesLookupHitsItsNodesAndIsLinearBetween) {
  const CyclesTables t = read_cycles_tables(std::string(VGROOVE_SOURCE_DIR) + "/data/reference/cycles_ggx_albedo.json");
  // The compiled-in copy is the file's.
  EXPECT_EQ(published_cycles_tables().E, t.E);
  EXPECT_EQ(published_cycles_tables().E_avg, t.E_avg);
  for (int y : {0, 7, 31})
    for (int x : {1, 12, 31}) {
      const double r = x / 31.0, mu = y / 31.0;
      EXPECT_NEAR(cycles_E(t, r * r, mu), t.E[static_cast<std::size_t>(y) * 32 + x], 1e-15) << x << " " << y;
      const double r2 = (x - 0.5) / 31.0;  // half-way to the node below in r
      EXPECT_NEAR(cycles_E(t, r2 * r2, mu),
                  0.5 * (t.E[static_cast<std::size_t>(y) * 32 + x] + t.E[static_cast<std::size_t>(y) * 32 + x - 1]),
                  1e-15);
    }
  EXPECT_NEAR(cycles_E_avg(t, 1.0), t.E_avg[31], 1e-15);
}

TEST(EngineTables, HalfPrecisionRounding) {
  EXPECT_EQ(round_to_half(1.0), 1.0);
  EXPECT_EQ(round_to_half(0.1), 0.0999755859375);
  EXPECT_EQ(round_to_half(1.0 / 3.0), 0.333251953125);
  EXPECT_EQ(round_to_half(1.0 + 0x1.0p-11), 1.0);                 // a tie, to even
  EXPECT_EQ(round_to_half(1.0 + 3 * 0x1.0p-11), 1.0 + 0x1.0p-9);  // a tie, to even
  EXPECT_EQ(round_to_half(0x1.0p-20), 0x1.0p-20);                 // subnormal range, a multiple of 2^-24
}

// Filament: at the centre of texel (i, j) the bilinear lookup is that texel, which cmgen computed at
// NoV = (i + 1/2) / 128 and roughness coordinate (j + 3/2) / 128 (its rows written in reverse from
// saturate((h - y + 1/2) / h)), alpha = coord^2, stored in half precision.
TEST(EngineTables, FilamentTexelCentresHoldTheNextRowsRoughness) {
  const analytic::MicrofacetModel ggx{NdfKind::ggx, analytic::MaskingKind::smith_height_correlated};
  analytic::AlbedoOptions opt;
  opt.tol = 1e-10;
  for (auto [i, j] : {std::pair{3, 10}, {64, 64}, {120, 100}}) {
    const double mu = (i + 0.5) / 128.0, r = (j + 0.5) / 128.0;
    const float coord = (static_cast<float>(j) + 1.5f) / 128.0f;
    const double want = round_to_half(analytic::albedo_single(ggx, static_cast<double>(coord * coord),
                                                              static_cast<double>(static_cast<float>(mu)), opt)
                                          .value);
    EXPECT_NEAR(filament_dfg_y(r * r, mu), want, 1e-12) << i << " " << j;
    // And not the texel's own roughness (the offset moves it by more than half precision).
    const double own = analytic::albedo_single(ggx, r * r, mu, opt).value;
    EXPECT_GT(std::abs(filament_dfg_y(r * r, mu) - own), 1e-4) << i << " " << j;
  }
}

// The V-groove reference with gold's F against exact tracing: every ray falls into a groove of its
// own drawn from the NDF (sim::sample_theta_m_3d, azimuth uniform), traced in the cross-section by
// sim::trace with the Fresnel observer at the 3D cosine c |d . n| (c = |i projected|), per bounce
// order. Standard error per row from the weights' sample variance.
TEST(EnergyAudit, VgrooveReferenceWithAConductorIsTheTracedGrooves) {
  const double eta = 0.43, kappa = 2.455;  // gold near 550 nm
  const long kRays = 200000;
  const int max_k = 4;
  for (auto [ndf, alpha, mu] : {std::tuple{NdfKind::ggx, 0.5, 0.5}, {NdfKind::beckmann, 1.0, 0.2}}) {
    const analytic::VgrooveAlbedo model = analytic::vgroove_albedo(
        ndf, alpha, mu, 1, [&](double c, double* out) { out[0] = optics::fresnel_conductor(c, eta, kappa); }, max_k);
    const double si = std::sqrt((1.0 - mu) * (1.0 + mu));
    sim::Rng rng(7, static_cast<std::uint64_t>(alpha * 10), 3);
    std::vector<double> sum(max_k + 2, 0.0), sum2(max_k + 2, 0.0);
    for (long n = 0; n < kRays; ++n) {
      const double t =
          std::min(std::nextafter(0.5 * kPi, 0.0), sim::sample_theta_m_3d(ndf, alpha, sim::uniform_open(rng)));
      const double phi = kPi * sim::uniform_open(rng);
      const sim::Groove g = sim::make_symmetric_groove(kPi - 2.0 * t);
      // i = (-sin theta_i, 0, cos theta_i) in the frame of the groove at phi (sim::trace_groove3d).
      const double ia = -si * std::cos(phi), in = mu, c = std::hypot(ia, in);
      const sim::Vec2 d(-ia / c, -in / c);
      auto F3 = [&](double cos2d) { return optics::fresnel_conductor(c * cos2d, eta, kappa); };
      sim::FresnelEnergyObserver<decltype(F3)> obs{F3};
      const double xl = g.rim_x(Side::left), xr = g.rim_x(Side::right);
      const sim::TraceResult r = sim::trace(g, sim::beam_ray(g, d, xl + sim::uniform_open(rng) * (xr - xl)), {}, obs);
      ASSERT_EQ(r.how, sim::Termination::escaped);
      const int row = std::min(r.bounces, max_k + 1);
      for (int k = 0; k < max_k + 2; ++k) {
        const double w = k == row ? obs.throughput : 0.0;
        sum[k] += w, sum2[k] += w * w;
      }
    }
    for (int k = 1; k < max_k + 2; ++k) {
      const double m = sum[k] / kRays, se = std::sqrt(std::max(0.0, sum2[k] / kRays - m * m) / kRays);
      EXPECT_NEAR(m, model.row(k, 0), 5.0 * se + 1.0 / kRays)
          << ndf_name(ndf) << " alpha=" << alpha << " mu=" << mu << " k=" << k;
    }
  }
}

EnergyAuditSuite tiny_suite() {
  const nlohmann::json j = {{"name", "tiny"},
                            {"kind", "energy_audit"},
                            {"ndf", {"ggx", "beckmann"}},
                            {"alpha", {0.9}},
                            {"mu", {0.15, 0.7}},
                            {"walk_paths", 10000},
                            {"seed", 3},
                            {"max_k", 4},
                            {"grey_F0", {0.5}},
                            {"metals", {"Au", "Cu"}},
                            {"metalness", {0.25, 0.75}},
                            {"regions", {{"rough_alpha", 0.5}, {"grazing_mu", 0.2}}},
                            {"cycles_table", true},
                            {"thresholds", {{"sigmas", 5}, {"vgroove_furnace", 1e-7}}}};
  return parse_energy_audit(j, "<test>");
}

TEST(EnergyAudit, SmallAuditChecksPassAndEveryFormulaKeepsTheWhiteFurnace) {
  const EnergyAuditSuite s = tiny_suite();
  const Job<EnergyAuditWork> job = energy_audit_job(s, {{"command", "test"}});
  const auto results = run_job(job, 2);
  ASSERT_TRUE(results);
  const EnergyAuditRun run = energy_audit_run_from(s, *results);
  const nlohmann::json& b = run.body;
  EXPECT_TRUE(run.pass) << b["checks"].dump(1);
  const int white = ChannelSet(s.grey_F0, s.metals).find_grey(1.0);
  for (const auto& [variant, by_ref] : b["errors"].items()) {
    // Against the walk (white albedo 1 exactly) every formula gives 1 within rounding.
    const nlohmann::json& e = by_ref["smith_walk"];
    for (std::size_t n = 0; n < e.size(); ++n)
      for (std::size_t a = 0; a < e[n].size(); ++a)
        for (std::size_t m = 0; m < e[n][a].size(); ++m) {
          const nlohmann::json& x = e[n][a][m][white];
          if (x.is_string()) continue;  // a feed absent there (nan)
          if (variant == "single") {
            EXPECT_LT(x.get<double>(), 0.0) << "single scattering loses energy";
          } else if (variant.find('@') == std::string::npos) {
            // Fed with the exact E_ss: 1 by construction. An engine's table is not the exact E_ss,
            // so its furnace is a result (the report's figures), not an identity.
            EXPECT_NEAR(x.get<double>(), 0.0, 1e-12) << variant;
          }
        }
    if (variant != "single") continue;
    for (const char* ref : {"vgroove", "smith_walk"})
      for (const char* g : {"grey", "conductor", "metal_schlick"}) {
        EXPECT_LT(b["summary"]["single"][ref][g]["all"]["mean"].get<double>(), 0.0) << ref << " " << g;
      }
  }
  // The engine feeds exist against the walk for GGX only.
  EXPECT_FALSE(b["errors"]["filament@filament_lut"].contains("vgroove"));
  EXPECT_TRUE(b["errors"]["filament@filament_lut"].contains("smith_walk"));
  EXPECT_TRUE(b["errors"]["filament@filament_lut"]["smith_walk"][1][0][0][white].is_string());  // Beckmann: nan
  // MoonRay's tables exist for Beckmann too (errors [ndf][alpha][mu][channel], Beckmann second).
  const nlohmann::json& moonray = b["errors"]["kulla_conty@moonray_table"];
  EXPECT_FALSE(moonray.contains("vgroove"));
  for (std::size_t ndf : {0, 1})
    for (std::size_t m : {0, 1}) EXPECT_TRUE(moonray["smith_walk"][ndf][0][m][white].is_number()) << ndf << " " << m;
  // A walk tally one unit short in one path's white energy fails the white furnace.
  auto broken = *results;
  const int C = ChannelSet(s.grey_F0, s.metals).size();
  broken[0].tally.energy[static_cast<std::size_t>(1) * C + white] -= 1;
  EXPECT_FALSE(energy_audit_run_from(s, broken).pass);
}

EnergyAuditSuite tiny_heightfield_suite() {
  nlohmann::json j = energy_audit_json(tiny_suite());
  j["references"] = {"vgroove", "smith_walk", "heightfield"};
  j["heightfield"] = {{"fields", 2}, {"rays_per_field", 1500}, {"field_size", 64}, {"correlation_length", 4}};
  return parse_energy_audit(j, "<test>");
}

// The heightfield reference's tally of one cell (beckmann alpha 0.9, mu 0.15: ~6% of the rays
// reflect more than once) against the tracer run once per channel with HeightfieldRayOptions.fresnel
// set to that channel's reflectance, on the same fields and rays: per row and channel the same
// energy to one unit (2^-32) per ray (the audit evaluates conductors through their table, within
// 4.3e-13, and Schlick as (1 - c)^5 in its own order: rounding, not physics). The white channel
// is each row's count times 2^32 exactly. Deliberately broken: the weights taken at the macro
// normal's cosine, F_c(mu)^k, miss by far more than rounding.
TEST(EnergyAudit, HeightfieldChannelsAreTheFresnelTraces) {
  const EnergyAuditSuite s = tiny_heightfield_suite();
  const Job<EnergyAuditWork> job = energy_audit_job(s, {{"command", "test"}});
  const EnergyAuditWork& w = job.work;
  const std::size_t cell = 2;  // beckmann, alpha 0.9, mu 0.15
  ASSERT_EQ(s.cell_at(cell).ndf, NdfKind::beckmann);
  ASSERT_EQ(s.cell_at(cell).mu, 0.15);
  const AuditTally t = w.run_chunks(*w.prepare(cell), cell, s.walk_chunks(), s.chunks());
  const ChannelSet& set = *w.channels;
  const int C = set.size(), R = s.max_k + 2;
  ASSERT_EQ(t.hf_rays, s.hf_fields * s.hf_rays_per_field);
  ASSERT_EQ(t.hf_lost + t.hf_bounce_limit, 0);
  std::vector<double> traced(static_cast<std::size_t>(R) * C, 0.0), macro(traced.size(), 0.0);
  std::vector<std::int64_t> count(static_cast<std::size_t>(R), 0);
  std::vector<Eigen::Vector3d> origins;
  Eigen::Vector3d dir;
  for (int field = 0; field < s.hf_fields; ++field) {
    const sim::HeightfieldSurface f = audit_heightfield_field(s, cell, field);
    for (std::int64_t chunk = s.walk_chunks(); chunk < s.chunks(); ++chunk) {
      if (audit_heightfield_field_of(s, chunk) != field) continue;
      audit_heightfield_rays(s, f, cell, chunk, origins, dir);
      for (const Eigen::Vector3d& o : origins) {
        int row = -1;
        for (int c = 0; c < C; ++c) {
          const Channel& ch = set.channels()[static_cast<std::size_t>(c)];
          sim::HeightfieldRayOptions opt;
          opt.max_bounces = kHeightfieldMaxBounces;
          opt.fresnel = ch.kind == ChannelKind::schlick
                            ? sim::HeightfieldFresnel{sim::HeightfieldReflectance::schlick, 1.0, 0.0, ch.F0}
                            : sim::HeightfieldFresnel{sim::HeightfieldReflectance::conductor, ch.eta, ch.kappa};
          const sim::HeightfieldRayResult r = sim::trace_heightfield_ray(f, o, dir, opt);
          ASSERT_EQ(r.how, sim::HeightfieldFate::escaped);
          row = std::min(r.bounces, s.max_k + 1);
          traced[static_cast<std::size_t>(row) * C + c] += std::llround(r.throughput * 4294967296.0);
          macro[static_cast<std::size_t>(row) * C + c] +=
              std::llround(std::pow(ch.F(s.cell_at(cell).mu), r.bounces) * 4294967296.0);
        }
        ++count[static_cast<std::size_t>(row)];
      }
    }
  }
  EXPECT_EQ(t.hf_by_k, count);
  EXPECT_GT(static_cast<double>(t.hf_rays - count[1]), 0.04 * static_cast<double>(t.hf_rays));
  const int white = set.find_grey(1.0);
  double broken = 0.0;
  for (int k = 0; k < R; ++k)
    for (int c = 0; c < C; ++c) {
      const std::size_t i = static_cast<std::size_t>(k) * C + c;
      const double n = static_cast<double>(count[static_cast<std::size_t>(k)]);
      EXPECT_LE(std::abs(static_cast<double>(t.hf_energy[i]) - traced[i]), n)
          << "row " << k << " " << set.channels()[static_cast<std::size_t>(c)].name;
      if (c == white) {
        EXPECT_EQ(static_cast<double>(t.hf_energy[i]), n * 4294967296.0);
      }
      if (n > 0) broken = std::max(broken, std::abs(macro[i] - traced[i]) / (n * 4294967296.0));
    }
  EXPECT_GT(broken, 1e-3) << "the macro normal's cosine would pass for the facets'";
}

// Chunk items only (the fixed parts are quadratures, not the heightfield's): one thread, two
// threads, and two shards each written to JSON, read back strictly and merged in the other order,
// give every cell's tally bit for bit. Deliberately broken: another seed changes the tallies.
TEST(EnergyAudit, HeightfieldTallyIsTheSameForAnyThreadsAndShards) {
  EnergyAuditSuite s = tiny_heightfield_suite();
  s.hf_rays_per_field = 5000;  // two chunks per field
  s.walk_paths = 3000;
  s.ndfs = {NdfKind::beckmann};
  auto tallies = [](const EnergyAuditSuite& suite, int threads, int parts) {
    const Job<EnergyAuditWork> job = energy_audit_job(suite, {{"command", "test"}});
    std::vector<std::vector<std::size_t>> mine(static_cast<std::size_t>(parts));
    std::size_t n = 0;
    for (std::size_t i = 0; i < job.items.size(); ++i)
      if (!job.items[i].fixed()) mine[n++ % mine.size()].push_back(i);
    std::map<std::size_t, AuditTally> merged;
    for (std::size_t p = mine.size(); p-- > 0;) {
      const auto part = run_work_items(job.work, job.items, mine[p], threads);
      const nlohmann::json j = nlohmann::json::parse(part_results_json<EnergyAuditWork>(*part).dump());
      for (auto& [unit, u] : part_results_from_json(job.work, j, job.units, "part"))
        if (merged.count(unit))
          EnergyAuditWork::merge(merged[unit], *u.tally);
        else
          merged[unit] = *u.tally;
    }
    std::vector<nlohmann::json> out;
    for (const auto& [unit, t] : merged) out.push_back(EnergyAuditWork::tally_json(t));
    return out;
  };
  const auto one = tallies(s, 1, 1);
  ASSERT_EQ(one.size(), s.cells());
  EXPECT_EQ(one[0]["heightfield"]["rays"], 2 * 5000);
  EXPECT_EQ(tallies(s, 2, 1), one);
  EXPECT_EQ(tallies(s, 1, 2), one);
  s.seed = 4;
  EXPECT_NE(tallies(s, 1, 1), one);
}

// The whole audit with the heightfield reference: the references' checks pass, the heightfields'
// white channel is 1 exactly (every ray left), every formula fed with the exact E_ss keeps the
// white furnace against it within rounding; E_1 against Smith's E_ss is reported, not judged. The
// default suite's spec has no "references" (its runs are what they were). Deliberately broken:
// one unit short in one heightfield row's white energy fails the check.
TEST(EnergyAudit, HeightfieldReferenceInTheReport) {
  EXPECT_FALSE(energy_audit_json(tiny_suite()).contains("references"));
  nlohmann::json bad = energy_audit_json(tiny_suite());
  bad["references"] = {"vgroove", "heightfield"};
  EXPECT_THROW(parse_energy_audit(bad, "<test>"), support::UserError);
  EnergyAuditSuite s = tiny_heightfield_suite();
  s.ndfs = {NdfKind::beckmann};
  s.mus = {0.15};
  EXPECT_EQ(energy_audit_json(parse_energy_audit(energy_audit_json(s), "<again>")), energy_audit_json(s));
  const auto results = run_job(energy_audit_job(s, {{"command", "test"}}), 2);
  ASSERT_TRUE(results);
  const EnergyAuditRun run = energy_audit_run_from(s, *results);
  const nlohmann::json& b = run.body;
  EXPECT_TRUE(run.pass) << b["checks"].dump(1);
  EXPECT_TRUE(b["checks"]["heightfield_white_furnace"]["pass"].get<bool>());
  EXPECT_TRUE(b.contains("heightfield_single_scattering"));
  const int white = ChannelSet(s.grey_F0, s.metals).find_grey(1.0);
  for (std::size_t m = 0; m < s.mus.size(); ++m)
    EXPECT_EQ(b["references"]["heightfield"]["E"][0][0][m][white].get<double>(), 1.0);
  const nlohmann::json& e = b["errors"]["turquin"]["heightfield"];
  for (std::size_t m = 0; m < s.mus.size(); ++m) EXPECT_NEAR(e[0][0][m][white].get<double>(), 0.0, 1e-12);
  auto broken = *results;
  const int C = ChannelSet(s.grey_F0, s.metals).size();
  broken[0].tally.hf_energy[static_cast<std::size_t>(2) * C + white] -= 1;
  EXPECT_FALSE(energy_audit_run_from(s, broken).pass);
}

// The plan's memory counts the heightfield reference's fields: each worker holds up to two cells'
// fields (the job's own refusal assumes as much), each sim::heightfield_bytes of its size.
TEST(EnergyAudit, MemoryCountsTheHeightfieldReferencesFields) {
  EnergyAuditSuite s = tiny_heightfield_suite();
  ASSERT_TRUE(s.heightfield);
  const double with = energy_audit_memory_bytes(s, 3);
  EXPECT_GT(with, energy_audit_memory_bytes(s, 1));
  s.heightfield = false;
  EXPECT_GE(with - energy_audit_memory_bytes(s, 3), 2.0 * s.hf_fields * 3 * sim::heightfield_bytes(s.hf_field_size));
  EXPECT_EQ(energy_audit_memory_bytes(s, 3), energy_audit_memory_bytes(s, 1));  // no fields: no per-worker part
}

}  // namespace
}  // namespace vgroove::validation
