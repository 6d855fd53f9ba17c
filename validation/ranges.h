// vgroove validation: the one range of each quantity, shared by suite files, scene files and the
// command line (every reader checks against these constants, so a value accepted in one place is
// accepted in all, and each range is one where the model and the tracer are tested to agree).
#pragma once

#include <cstddef>
#include <limits>

namespace vgroove::validation {

// The narrowest aperture accepted (degrees). The tracer's rounding shifts the boundaries between
// bounce counts by about 2.6e-9 (0.01 deg / theta_v)^2 of the opening (its reflections are not
// exactly orthogonal, and over pi / theta_v of them the error grows): at 1e-3 deg by 3e-7, so the
// trace agrees with the model within the stratified bound 1/N up to N ~ 10^6 rays per facet
// (already 2 x 10^11 reflections); at 1e-6 deg by 0.3, which no N can hide.
inline constexpr double kMinApertureDeg = 1e-3;
// The most grazing light on a single groove (degrees; symmetric range [-89.999, 89.999]). The
// opening's projected width is w = 2 sin(theta_v/2) cos(theta_i): at 89.999 deg the N <= 10^9
// stratified positions across it stay 150 ulps apart, and the traced zone widths agree with the
// model's to 6e-7 of w at the narrowest aperture (7e-6 at 89.9999 deg). Closer to 90 deg both lose
// the opening to rounding (at 89.99999999999999 deg 30 % of the rays hit a rim).
inline constexpr double kMaxThetaIDeg = 89.999;
// The most grazing light on a rough surface (brdf and furnace suites, polar angle in [0, 89.9]):
// the BRDF lobes conserve energy to their tolerance there for every NDF and alpha (at 89.99 deg the
// flatland Phong lobe of alpha 2 loses 4e-7 of it).
inline constexpr double kMaxSurfaceThetaIDeg = 89.9;
// The same light as mu = cos theta_i (energy tables): cos(89.9 deg), rounded to the nearest double
// (tests/validation/ranges_test.cpp). Below it the model's 3D lobe splits its albedo between the
// orders wrongly (Phong alpha 2 at mu = 1.2e-4: E_1 16 standard errors off the trace, 4 x 10^5
// rays), and below mu ~ 1e-16 acos(mu) rounds to 90 deg: every ray runs along the horizon.
inline constexpr double kMinMu = 0.0017453283658983088;
// Rays per case, facet or incident angle.
inline constexpr long kMaxRays = 1'000'000'000;
// Seeds: every non-negative 64-bit signed value.
inline constexpr long long kMaxSeed = std::numeric_limits<long long>::max();
// Roughness of procedural surfaces: the range the slope samplers and the BRDFs are tested on.
inline constexpr double kMinAlpha = 0.01;
inline constexpr double kMaxAlpha = 2.0;
// Student-T's tail gamma (analytic/detail/ndf_student_t.h): above 1.5, where its mean slope and Smith's
// Lambda are finite; up to 10^4, where it lies within x^2 / 2 10^-4 of Beckmann (x = tan^2 / alpha^2)
// and its forms are tested (tests/analytic/ndf_student_t_test.cpp).
inline constexpr double kMinStudentTGamma = 1.5;  // exclusive
inline constexpr double kMaxStudentTGamma = 1e4;
// Grooves of a procedural surface.
inline constexpr int kMaxGrooves = 10'000'000;
// The tracer's bounce limit: its default, and the largest a file or option may set.
inline constexpr int kDefaultMaxBounces = 100'000;
inline constexpr int kMaxBounces = 100'000'000;
// Table 2's paper values (a suite's /paper/max_bounces): bounce counts in [1, kMaxPaperBounces].
inline constexpr int kMaxPaperBounces = 1'000'000;
// A conductor's complex index eta + i kappa (Python's vgroove.BRDF(eta=...)): eta in (0, 1000],
// kappa in [0, 1000] (the scenes' Fresnel channels take the same).
inline constexpr double kMaxFresnelEta = 1000.0;
inline constexpr double kMaxFresnelKappa = 1000.0;
// Worker threads (0: all cores).
inline constexpr int kMaxThreads = 1024;
// A threshold's standard deviations (suites' and check_brdf's sigmas), in (0, kMaxSigmas].
inline constexpr double kMaxSigmas = 100.0;
// Point BRDF evaluations' largest max_k (`vgroove brdf`, Python brdf): the flatland sum (one pass
// over its facet solutions, a few us a pair for any max_k) and the nonsymmetric sum (O(max_k^2),
// about 3 ms a pair at 64).
inline constexpr int kMaxFlatlandBrdfK = 4096;
inline constexpr int kMaxNonsymmetricBrdfK = 1024;
// `vgroove brdf --per-k`: the orders printed one by one (--per-k-max).
inline constexpr int kMaxPrintedK = 1000;
// The nonsymmetric sampler's partner table (Python sample/pdf of vgroove-nonsymmetric): its
// relative tolerance per integrated piece.
inline constexpr double kMinPartnerTolerance = 1e-12;
inline constexpr double kMaxPartnerTolerance = 1e-2;
// Histogram cells (bins x bounce-count rows) of one tally: each work item holds its own. Rows
// k = 0..max_k (and one for larger k), max_k at most kMaxHistogramK.
inline constexpr long long kMaxHistogramCells = 1'000'000;
inline constexpr int kMinHistogramK = 0;
inline constexpr int kMaxHistogramK = 1000;
// Exit-direction bins of a lobe histogram: theta_o in flatland, theta_o x phi_o in 3D (phi even).
inline constexpr int kMaxFlatlandBins = 100'000;
inline constexpr int kMaxThetaBins = 10'000;
inline constexpr int kMaxPhiBins = 10'000;
// The samplers' max_k: `vgroove sample --max-k`, the sampling and furnace suites' max_k, Python's
// sample and pdf (the default: analytic/sampling_3d.h, kSamplerMaxK).
inline constexpr int kMaxSamplerK = 100'000;
// `vgroove sample`'s chi-square cells: cos theta_o and phi_o (even) in 3D, theta_o in flatland.
inline constexpr int kMaxSampleCosBins = 1000;
inline constexpr int kMaxSamplePhiBins = 1000;
inline constexpr int kMaxSampleThetaBins = 10'000;
// check_brdf: its 3D lobe's theta_o and phi_o cells (each integrated by a Gauss-Legendre rule of
// at most kMaxGaussLegendreOrder points per axis).
inline constexpr int kMaxCheckBrdfThetaBins = 1000;
inline constexpr int kMaxCheckBrdfPhiBins = 1000;
inline constexpr int kMaxGaussLegendreOrder = 64;

// `vgroove energy`'s grid (check_energy_grid, named by the command line's flags): traced rays per
// cell, the bounce orders, the cells.
inline constexpr long long kMaxEnergyRays = 10'000'000'000LL;
inline constexpr int kMaxEnergyK = 1000;
inline constexpr std::size_t kMaxGridPoints = 4096;
// `vgroove energy --eta`'s glass tables (validation/glass_energy.h): eta = n2 / n1, and the grooves
// of a cell's surface (about 70 bytes each, one surface per work unit and thread).
inline constexpr double kMinGlassEta = 0.1;
inline constexpr double kMaxGlassEta = 10.0;
inline constexpr int kMaxGlassGrooves = 1'000'000;
// --mu-points: the smallest midpoint 0.5 / n stays >= kMinMu.
inline constexpr int kMaxMuPoints = 286;
// --alpha-points: the midpoints (j + 1/2)/n stay in the alpha range (0.5/n >= kMinAlpha).
inline constexpr int kMaxAlphaPoints = 50;
// --audit: walk paths per cell (the energy sums stay below 2^63 / 2^32 per row) and bounce orders.
inline constexpr long long kMaxAuditPaths = 1'000'000'000;
inline constexpr int kMaxAuditK = 64;
// --export's texels per axis, and its F0 axis's values (--ms-F0).
inline constexpr int kMaxExportSize = 1024;
inline constexpr std::size_t kMaxExportF0 = 64;

}  // namespace vgroove::validation
