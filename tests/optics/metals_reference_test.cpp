// Tests of optics/fresnel.h against PUBLISHED optical constants of metals.
//
// data/reference/metals.json holds, for gold, silver, copper (Johnson & Christy, Phys. Rev. B 6,
// 4370 (1972)) and aluminium (Rakic, Appl. Opt. 34, 4755 (1995)), three rows near 450, 550 and
// 650 nm copied as printed from the refractiveindex.info database (CC0; file paths and commits are
// in the JSON), and R_normal = ((n-1)^2 + k^2)/((n+1)^2 + k^2) computed independently (Python, 6
// significant digits). Here: fresnel_conductor reproduces R_normal, and the reflectances show the
// known physics of those measured constants (gold and copper redder than blue, silver and
// aluminium above 0.85 across the visible, R -> 1 at grazing incidence, R_p <= F <= R_s).
#include "vgroove/optics/fresnel.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace vgroove::optics {
namespace {

struct Sample {
  double lambda_nm = 0.0;
  double eta = 0.0;
  double kappa = 0.0;
  double R_normal = 0.0;
};

struct Metal {
  std::string name;
  std::string symbol;
  std::vector<Sample> samples;
};

const nlohmann::json& reference_json() {
  static const nlohmann::json j = [] {
    const std::string path = std::string(VGROOVE_SOURCE_DIR) + "/data/reference/metals.json";
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::stringstream ss;
    ss << in.rdbuf();
    return nlohmann::json::parse(ss.str());
  }();
  return j;
}

const std::vector<Metal>& metals() {
  static const std::vector<Metal> m = [] {
    std::vector<Metal> out;
    for (const auto& jm : reference_json().at("metals")) {
      Metal metal;
      metal.name = jm.at("name").get<std::string>();
      metal.symbol = jm.at("symbol").get<std::string>();
      for (const auto& js : jm.at("samples"))
        metal.samples.push_back({js.at("lambda_nm").get<double>(), js.at("eta").get<double>(),
                                 js.at("kappa").get<double>(), js.at("R_normal").get<double>()});
      out.push_back(std::move(metal));
    }
    return out;
  }();
  return m;
}

const Metal& metal(const std::string& symbol) {
  for (const Metal& m : metals())
    if (m.symbol == symbol) return m;
  throw std::runtime_error("metal " + symbol + " not in metals.json");
}

// The sample whose tabulated wavelength is nearest to lambda_nm.
const Sample& nearest(const Metal& m, double lambda_nm) {
  return *std::min_element(m.samples.begin(), m.samples.end(), [&](const Sample& a, const Sample& b) {
    return std::abs(a.lambda_nm - lambda_nm) < std::abs(b.lambda_nm - lambda_nm);
  });
}

double closed_form(double eta, double kappa) {
  return ((eta - 1) * (eta - 1) + kappa * kappa) / ((eta + 1) * (eta + 1) + kappa * kappa);
}

TEST(MetalsReference, FileHasProvenanceAndThreeVisibleSamplesPerMetal) {
  const nlohmann::json& j = reference_json();
  EXPECT_FALSE(j.at("provenance").get<std::string>().empty());
  ASSERT_EQ(metals().size(), 4u);
  for (const char* sym : {"Au", "Ag", "Cu", "Al"}) EXPECT_NO_THROW(metal(sym)) << sym;
  for (const auto& jm : j.at("metals")) {
    EXPECT_FALSE(jm.at("source").get<std::string>().empty());
    EXPECT_FALSE(jm.at("database_file").get<std::string>().empty());
    EXPECT_EQ(jm.at("commit").get<std::string>().size(), 40u);
  }
  for (const Metal& m : metals()) {
    ASSERT_EQ(m.samples.size(), 3u) << m.name;
    for (double target : {450.0, 550.0, 650.0})
      EXPECT_LT(std::abs(nearest(m, target).lambda_nm - target), 20.0) << m.name << " " << target;
    for (const Sample& s : m.samples) {
      EXPECT_GT(s.eta, 0.0) << m.name;
      EXPECT_GT(s.kappa, 0.0) << m.name;
    }
  }
}

TEST(MetalsReference, NormalIncidenceMatchesPublishedReflectance) {
  for (const Metal& m : metals())
    for (const Sample& s : m.samples) {
      const double F = fresnel_conductor(1.0, s.eta, s.kappa);
      // R_normal in the file is rounded to 6 significant digits.
      EXPECT_NEAR(F, s.R_normal, 5e-6 * s.R_normal) << m.name << " " << s.lambda_nm << " nm";
      const double exact = closed_form(s.eta, s.kappa);
      EXPECT_NEAR(F, exact, 1e-12 * exact) << m.name << " " << s.lambda_nm << " nm";
      EXPECT_NEAR(fresnel_normal_incidence(s.eta, s.kappa), exact, 1e-12 * exact) << m.name;
    }
}

TEST(MetalsReference, GoldAndCopperReflectRedMoreThanBlue) {
  for (const char* sym : {"Au", "Cu"}) {
    const Metal& m = metal(sym);
    const Sample& blue = nearest(m, 450.0);
    const Sample& red = nearest(m, 650.0);
    EXPECT_GT(fresnel_conductor(1.0, red.eta, red.kappa), fresnel_conductor(1.0, blue.eta, blue.kappa)) << m.name;
  }
}

TEST(MetalsReference, SilverAndAluminiumReflectAbove085AcrossTheVisible) {
  for (const char* sym : {"Ag", "Al"})
    for (const Sample& s : metal(sym).samples)
      EXPECT_GT(fresnel_conductor(1.0, s.eta, s.kappa), 0.85) << sym << " " << s.lambda_nm << " nm";
}

TEST(MetalsReference, GoldReflectsAbove09InTheRed) {
  const Sample& red = nearest(metal("Au"), 650.0);
  EXPECT_GT(fresnel_conductor(1.0, red.eta, red.kappa), 0.9) << red.lambda_nm << " nm";
}

TEST(MetalsReference, GrazingIncidenceReflectanceTendsToOne) {
  // 1 - R is first order in cos theta_i (a few times cos for these indices), so at cos = 1e-9
  // it is below 1e-8; R decreases toward the normal value as cos grows.
  for (const Metal& m : metals())
    for (const Sample& s : m.samples) {
      const double grazing = fresnel_conductor(1e-9, s.eta, s.kappa);
      EXPECT_LE(grazing, 1.0 + 1e-15) << m.name << " " << s.lambda_nm;
      EXPECT_GT(grazing, 1.0 - 1e-7) << m.name << " " << s.lambda_nm;
      const PolarizedReflectance pr = fresnel_conductor_polarized(1e-9, s.eta, s.kappa);
      EXPECT_GT(pr.s, 1.0 - 1e-7) << m.name << " " << s.lambda_nm;
      EXPECT_GT(pr.p, 1.0 - 1e-7) << m.name << " " << s.lambda_nm;
      EXPECT_GT(grazing, fresnel_conductor(1e-3, s.eta, s.kappa)) << m.name << " " << s.lambda_nm;
      EXPECT_GT(fresnel_conductor(1e-3, s.eta, s.kappa), s.R_normal) << m.name << " " << s.lambda_nm;
    }
}

TEST(MetalsReference, UnpolarizedAt45DegreesLiesBetweenPAndS) {
  const double c45 = std::cos(std::numbers::pi / 4.0);
  for (const Metal& m : metals())
    for (const Sample& s : m.samples) {
      const PolarizedReflectance pr = fresnel_conductor_polarized(c45, s.eta, s.kappa);
      const double F = fresnel_conductor(c45, s.eta, s.kappa);
      EXPECT_NEAR(F, pr.unpolarized(), 1e-15) << m.name << " " << s.lambda_nm;
      // Off normal, a metal reflects the s polarization more than p (p dips toward the
      // pseudo-Brewster angle).
      EXPECT_LT(pr.p, pr.s) << m.name << " " << s.lambda_nm;
      EXPECT_GE(F, pr.p) << m.name << " " << s.lambda_nm;
      EXPECT_LE(F, pr.s) << m.name << " " << s.lambda_nm;
    }
}

}  // namespace
}  // namespace vgroove::optics
