// Tests of analytic/sampling_dielectric.h: the sampler of the kaleidoscopic dielectric model against the
// model's own binned lobe (kaleidoscope_dielectric_lobe.h, deterministic quadrature, its error far below
// the counts' noise), by a chi-square test over the cells (side, k, exit-angle bin) plus one cell for
// the failures (upward transmitted, k > k_cap): validation/chi_square.h's test, cells expecting fewer
// than 5 pooled, the level 0.01 shared by the family (Sidak), fixed seeds. Power: a sampler drawing
// the first facet 50/50 instead of by its lit width, and one with Fresnel at 1.1 eta, must be rejected.
#include "vgroove/analytic/sampling_dielectric.h"

#include "vgroove/validation/chi_square.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace vgroove::analytic {
namespace {

constexpr double kPi = std::numbers::pi;
double deg(double d) { return d * kPi / 180.0; }

// SplitMix64 on a counter (tests/stats.h's stream): uniforms in (0, 1), not the code's own RNG.
struct Uniforms {
  std::uint64_t state;
  double operator()() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (static_cast<double>(z >> 11) + 0.5) * 0x1.0p-53;
  }
};

struct Case {
  NdfKind ndf;
  double alpha, eta, theta_i_deg;
  DielectricLightFrom from = DielectricLightFrom::above;
};

std::string describe(const Case& c) {
  std::ostringstream os;
  os << ndf_name(c.ndf) << " alpha=" << c.alpha << " eta=" << c.eta << " theta_i=" << c.theta_i_deg
     << (c.from == DielectricLightFrom::below ? " from below" : " from above");
  return os.str();
}

constexpr int kBins = 36;  // 5 deg
constexpr int kMaxK = 3;   // cells per k = 1..3 and one for k > 3

struct Outcome {
  validation::ChiSquareResult test;
  double failures = 0.0, expected_failures = 0.0;
  std::string text;
};

// n samples' expected counts in the cells [side][row k][bin] of the lobe's bins per k (side 0
// reflected), then the failures' cell: n times what the bins leave of 1.
std::vector<double> expected_counts(const DielectricLobe& L, int bins, long n) {
  const int rows = kMaxK + 2;
  std::vector<double> expected(2u * rows * bins + 1, 0.0);
  double mass = 0.0;
  for (int side = 0; side < 2; ++side)
    for (int row = 0; row < rows; ++row)
      for (int b = 0; b < bins; ++b) {
        const double v = (side == 0 ? L.reflected_by_k : L.transmitted_by_k)[row][b];
        expected[(side * rows + row) * bins + b] = n * v;
        mass += v;
      }
  expected.back() = n * (1.0 - mass);
  return expected;
}

Outcome run(const Case& c, long n, int tests, std::uint64_t seed, DielectricSamplerBreak broken) {
  DielectricLobeOptions lo;
  lo.from = c.from;
  const DielectricLobe L =
      kaleidoscope_dielectric_lobe_flatland(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), kBins, kMaxK, lo);
  const int rows = kMaxK + 2;
  const std::vector<double> expected = expected_counts(L, kBins, n);
  std::vector<double> observed(expected.size(), 0.0);
  DielectricSamplerOptions so;
  so.from = c.from;
  so.broken = broken;
  Uniforms rng{seed};
  for (long s = 0; s < n; ++s) {
    const std::array<double, 4> u{rng(), rng(), rng(), rng()};
    const DielectricSampleFlatland d =
        sample_vgroove_dielectric_flatland(deg(c.theta_i_deg), u, c.ndf, c.alpha, c.eta, so);
    if (d.weight == 0.0) {
      observed.back() += 1.0;
      continue;
    }
    const int b = std::clamp(static_cast<int>(std::floor((d.theta_o + 0.5 * kPi) / (kPi / kBins))), 0, kBins - 1);
    const int row = std::min(d.k, kMaxK + 1);
    observed[((d.reflected ? 0 : 1) * rows + row) * kBins + b] += 1.0;
  }
  Outcome o;
  o.test = validation::chi_square_test(observed, expected, 0.01, tests);
  o.failures = observed.back();
  o.expected_failures = expected.back();
  std::ostringstream os;
  os << describe(c) << ": N " << n << " R " << L.albedo_r << " T " << L.albedo_t << " failures " << o.failures
     << " (expected " << o.expected_failures << ") stat " << o.test.statistic << " dof " << o.test.dof << " p "
     << o.test.p_value << " level " << o.test.level << " lobe error " << L.error_estimate;
  o.text = os.str();
  return o;
}

const std::vector<Case>& cases() {
  static const std::vector<Case> c{
      {NdfKind::ggx, 0.3, 1.5, 30.0},
      {NdfKind::ggx, 0.7, 1.5, 60.0},
      {NdfKind::beckmann, 0.5, 1.5, -45.0},
      {NdfKind::ggx, 0.5, 1.0 / 1.5, 20.0},
      {NdfKind::beckmann, 0.3, 1.0 / 1.5, 0.0},
      {NdfKind::beckmann, 1.0, 1.0 / 1.5, 50.0},
      {NdfKind::ggx, 0.5, 1.5, 40.0, DielectricLightFrom::below},
  };
  return c;
}

constexpr long kSamples = 100000;

// Every case: the sample histogram is the lobe's (reflected and transmitted, by k and bin, failures).
// Split by eta to keep each test short; the family is all of cases().
void histogram_is_the_lobe(bool eta_above_one) {
  const int tests = static_cast<int>(cases().size());
  std::uint64_t seed = 11;
  for (const Case& c : cases()) {
    ++seed;
    if ((c.eta > 1.0) != eta_above_one) continue;
    const Outcome o = run(c, kSamples, tests, seed, DielectricSamplerBreak::none);
    std::printf("%s\n", o.text.c_str());
    EXPECT_FALSE(o.test.reject) << o.text;
    EXPECT_FALSE(o.test.samples_where_none_expected) << o.text;
  }
}

TEST(SamplingDielectric, FlatlandHistogramIsTheLobeEtaAboveOne) { histogram_is_the_lobe(true); }
TEST(SamplingDielectric, FlatlandHistogramIsTheLobeEtaBelowOne) { histogram_is_the_lobe(false); }

// The same test rejects a sampler with the first facet drawn 50/50 (light at 45 deg: the facets' lit
// widths differ by a factor ~3) and one with Fresnel at 1.1 eta (at eta 1 / 1.5 and 1.5).
TEST(SamplingDielectric, BrokenSamplersAreRejected) {
  const Case facet{NdfKind::beckmann, 0.5, 1.5, -45.0};
  const Outcome a = run(facet, kSamples, 1, 11, DielectricSamplerBreak::facet_uniform);
  std::printf("facet 50/50: %s\n", a.text.c_str());
  EXPECT_TRUE(a.test.reject) << a.text;
  const Case fresnel{NdfKind::ggx, 0.5, 1.0 / 1.5, 20.0};
  const Outcome b = run(fresnel, kSamples, 1, 12, DielectricSamplerBreak::fresnel_eta);
  std::printf("Fresnel at 1.1 eta: %s\n", b.text.c_str());
  EXPECT_TRUE(b.test.reject) << b.text;
  // At eta 1.5 no total internal reflection moves: only R (~4 % -> ~5 %) and T change.
  const Case fresnel_up{NdfKind::ggx, 0.3, 1.5, 30.0};
  const Outcome c = run(fresnel_up, kSamples, 1, 13, DielectricSamplerBreak::fresnel_eta);
  std::printf("Fresnel at 1.1 eta: %s\n", c.text.c_str());
  EXPECT_TRUE(c.test.reject) << c.text;
}

// ---- 3D: cells (side, k, theta bin, phi bin) of kaleidoscope_dielectric_lobe_3d ----------------------

constexpr int kThetaBins = 9, kPhiBins = 8;  // 10 deg x 45 deg

DielectricLobe lobe_3d(const Case& c, int phi_panels, bool error_estimate) {
  DielectricLobeOptions lo;
  lo.from = c.from;
  lo.phi_panels = phi_panels;
  lo.error_estimate = error_estimate;
  return kaleidoscope_dielectric_lobe_3d(c.ndf, c.alpha, c.eta, deg(c.theta_i_deg), kThetaBins, kPhiBins, kMaxK, lo);
}

Outcome run_3d(const Case& c, const DielectricLobe& L, long n, int tests, std::uint64_t seed,
               DielectricSamplerBreak broken) {
  const int rows = kMaxK + 2, bins = kThetaBins * kPhiBins;
  const std::vector<double> expected = expected_counts(L, bins, n);
  std::vector<double> observed(expected.size(), 0.0);
  DielectricSamplerOptions so;
  so.from = c.from;
  so.broken = broken;
  Uniforms rng{seed};
  const double dtheta = 0.5 * kPi / kThetaBins, dphi = 2.0 * kPi / kPhiBins;
  for (long s = 0; s < n; ++s) {
    const std::array<double, 5> u{rng(), rng(), rng(), rng(), rng()};
    const DielectricSample3d d = sample_vgroove_dielectric_3d(deg(c.theta_i_deg), u, c.ndf, c.alpha, c.eta, so);
    if (d.weight == 0.0) {
      observed.back() += 1.0;
      continue;
    }
    // The lobe's bins: theta from the exit side's normal, phi bins centred on phi = 0 (light at pi).
    const int t =
        std::min(kThetaBins - 1, static_cast<int>(std::atan2(std::hypot(d.o.x, d.o.y), std::abs(d.o.z)) / dtheta));
    int p = static_cast<int>(std::floor((std::atan2(d.o.y, d.o.x) + 0.5 * dphi) / dphi));
    p = ((p % kPhiBins) + kPhiBins) % kPhiBins;
    const int row = std::min(d.k, kMaxK + 1);
    observed[((d.reflected ? 0 : 1) * rows + row) * bins + t * kPhiBins + p] += 1.0;
  }
  Outcome o;
  o.test = validation::chi_square_test(observed, expected, 0.01, tests);
  o.failures = observed.back();
  o.expected_failures = expected.back();
  std::ostringstream os;
  os << "3D " << describe(c) << ": N " << n << " R " << L.albedo_r << " T " << L.albedo_t << " failures " << o.failures
     << " (expected " << o.expected_failures << ") stat " << o.test.statistic << " dof " << o.test.dof << " p "
     << o.test.p_value << " level " << o.test.level << " lobe error " << L.error_estimate;
  o.text = os.str();
  return o;
}

// One case by default, its lobe with 8 azimuth panels and no error estimate (measured: each bin within
// 0.84 sigma of 1e5 samples of the lobe with 32 panels, here and at 60 deg; 4 panels: 1.5 and 4.4
// sigma), the others in the long suite.
TEST(SamplingDielectric, ThreeDHistogramIsTheLobe) {
  const Case c{NdfKind::ggx, 0.5, 1.5, 40.0};
  const Outcome o = run_3d(c, lobe_3d(c, 8, false), kSamples, 1, 31, DielectricSamplerBreak::none);
  std::printf("%s\n", o.text.c_str());
  EXPECT_FALSE(o.test.reject) << o.text;
  EXPECT_FALSE(o.test.samples_where_none_expected) << o.text;
}

// Fresnel at the cross-section's local angle instead of the 3D one (the lifted law's point: at 60 deg
// the grooves along the plane of incidence see the light near their normal in the cross-section), and
// the first facet drawn 50/50.
TEST(SamplingDielectric, ThreeDBrokenSamplersAreRejected) {
  const Case c{NdfKind::ggx, 0.5, 1.5, 60.0};
  const DielectricLobe L = lobe_3d(c, 8, false);
  const Outcome a = run_3d(c, L, kSamples, 1, 41, DielectricSamplerBreak::fresnel_cross_section_angle);
  std::printf("Fresnel at the 2D angle: %s\n", a.text.c_str());
  EXPECT_TRUE(a.test.reject) << a.text;
  const Outcome b = run_3d(c, L, kSamples, 1, 42, DielectricSamplerBreak::facet_uniform);
  std::printf("facet 50/50: %s\n", b.text.c_str());
  EXPECT_TRUE(b.test.reject) << b.text;
}

// Long: eta 1 / 1.5, normal incidence, light from below; the lobes with 32 azimuth panels and their
// error estimate (printed). With 8 panels the lobe at 75 deg errs by 2.4e-3 a bin (its estimate) and
// the test rejects the sampler (p 0.001): the reference, not the sampler (32 panels: p 0.50).
TEST(SamplingDielectricLong, ThreeDHistogramIsTheLobe) {
  const std::vector<Case> cases{
      {NdfKind::ggx, 0.5, 1.5, 40.0},       {NdfKind::beckmann, 0.3, 1.0 / 1.5, 60.0},
      {NdfKind::beckmann, 0.7, 1.5, 0.0},   {NdfKind::ggx, 0.3, 1.5, 30.0, DielectricLightFrom::below},
      {NdfKind::ggx, 1.0, 1.0 / 1.5, 75.0},
  };
  const int tests = static_cast<int>(cases.size());
  std::uint64_t seed = 51;
  for (const Case& c : cases) {
    const Outcome o = run_3d(c, lobe_3d(c, 32, true), 400000, tests, seed++, DielectricSamplerBreak::none);
    std::printf("%s\n", o.text.c_str());
    EXPECT_FALSE(o.test.reject) << o.text;
    EXPECT_FALSE(o.test.samples_where_none_expected) << o.text;
  }
}

}  // namespace
}  // namespace vgroove::analytic
