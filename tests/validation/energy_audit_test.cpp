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
//   everywhere; a broken walk tally (one path's white energy short) fails the white furnace check.
#include "vgroove/validation/energy_audit.h"
#include "tests/stats.h"
#include "tests/test_files.h"
#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/albedo_vgroove.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/effects.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/sim/rng.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
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
  // A walk tally one unit short in one path's white energy fails the white furnace.
  auto broken = *results;
  const int C = ChannelSet(s.grey_F0, s.metals).size();
  broken[0].tally.energy[static_cast<std::size_t>(1) * C + white] -= 1;
  EXPECT_FALSE(energy_audit_run_from(s, broken).pass);
}

}  // namespace
}  // namespace vgroove::validation
