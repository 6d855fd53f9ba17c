#include "vgroove/analytic/brdf_model.h"
#include "vgroove/analytic/kaleidoscope_dielectric_lobe.h"
#include "vgroove/analytic/kaleidoscope_dielectric_point.h"
#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/app/cli_options.h"
#include "vgroove/app/commands.h"
#include "vgroove/app/progress.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <type_traits>
#include <vector>

namespace vgroove::app {

namespace {

// One pair of directions, in degrees as given.
struct Pair {
  double theta_i_deg, phi_i_deg, theta_o_deg, phi_o_deg;
};

constexpr std::size_t kMaxPairs = 10'000'000;
// The flatland and nonsymmetric sums' largest --max-k (validation/ranges.h; the defaults:
// analytic::default_max_k).
constexpr int kFlatlandMaxK = validation::kMaxFlatlandBrdfK;
constexpr int kNonsymmetricMaxK = validation::kMaxNonsymmetricBrdfK;

void check_angle(double v, double lo, bool lo_closed, double hi, bool hi_closed, const std::string& what) {
  const bool ok = std::isfinite(v) && (lo_closed ? v >= lo : v > lo) && (hi_closed ? v <= hi : v < hi);
  if (!ok)
    throw support::UserError(what + " = " + support::number_text(v) + " is out of range " +
                             support::interval_text(lo, lo_closed, hi, hi_closed));
}

// The ranges of the directions: 3D polar angles in [0, 90) towards the light and [0, 90] towards
// the viewer, azimuths in [-360, 360]; flatland signed angles in (-90, 90) and [-90, 90]. A BSDF
// (`both`: Walter's) takes the viewer on either side: [0, 180] in 3D, [-180, 180] in flatland.
// `where` + the name: the flag (--theta-i-deg) when where is "--", the file's key (theta_i_deg) else.
void check_pair(const Pair& p, bool flat, bool both, const std::string& where) {
  const bool flag = where == "--";
  auto name = [&](const char* key) {
    std::string n = key;
    if (flag) std::replace(n.begin(), n.end(), '_', '-');
    return where + n;
  };
  const double side = both ? 180.0 : 90.0;
  if (flat) {
    check_angle(p.theta_i_deg, -90, false, 90, false, name("theta_i_deg"));
    check_angle(p.theta_o_deg, -side, true, side, true, name("theta_o_deg"));
    return;
  }
  check_angle(p.theta_i_deg, 0, true, 90, false, name("theta_i_deg"));
  check_angle(p.theta_o_deg, 0, true, side, true, name("theta_o_deg"));
  check_angle(p.phi_i_deg, -360, true, 360, true, name("phi_i_deg"));
  check_angle(p.phi_o_deg, -360, true, 360, true, name("phi_o_deg"));
}

// Stops early (a partial list) once *cancel is set: the caller then reports the interruption.
std::vector<Pair> read_pairs(const std::string& file, bool flat, bool both, support::CancelFlag cancel) {
  const nlohmann::json j = support::read_json_file(file);
  support::JsonObject root(j, file, "");
  const nlohmann::json& list = root.raw("directions");
  root.finish();
  if (!list.is_array() || list.empty() || list.size() > kMaxPairs)
    throw support::UserError(file +
                             ": /directions must be a list of 1 to 10000000 objects {\"theta_i_deg\", "
                             "\"theta_o_deg\"[, \"phi_i_deg\", \"phi_o_deg\"]}");
  std::vector<Pair> out;
  out.reserve(list.size());
  for (std::size_t n = 0; n < list.size() && !support::cancelled(cancel); ++n) {
    support::JsonObject o(list[n], file, "/directions/" + std::to_string(n));
    // The keys first, so that a typo'd key is named as unknown rather than its intended key as missing.
    for (const char* key : {"theta_i_deg", "theta_o_deg", "phi_i_deg", "phi_o_deg"}) o.has(key);
    o.finish();
    Pair p{};
    p.theta_i_deg = o.number("theta_i_deg", -90, false, 90, false);
    p.theta_o_deg = o.number("theta_o_deg", -180, true, 180, true);
    p.phi_i_deg = o.number_or("phi_i_deg", 0.0, -360, true, 360, true);
    p.phi_o_deg = o.number_or("phi_o_deg", 180.0, -360, true, 360, true);
    o.finish();
    check_pair(p, flat, both, file + ": /directions/" + std::to_string(n) + "/");
    out.push_back(p);
  }
  return out;
}

analytic::Dir3 direction(double theta_deg, double phi_deg, bool flat) {
  // Flatland: the signed 2D angle theta is the direction (-sin theta, 0, cos theta) (|theta| > 90:
  // below the interface).
  if (flat) return {-std::sin(deg_to_rad(theta_deg)), 0.0, std::cos(deg_to_rad(theta_deg))};
  return analytic::dir3(deg_to_rad(theta_deg), deg_to_rad(phi_deg));
}

// The orders summed: --max-k checked against the model's range, or the model's default (the one
// table of every face, analytic/brdf_model.h).
int orders(const BrdfArgs& a, analytic::BrdfModel model, bool flat) {
  if (!a.max_k_given) return analytic::default_max_k(model, flat);
  if (a.max_k < 1)
    throw support::UserError("--max-k = " + std::to_string(a.max_k) + " is out of range [1, " +
                             std::to_string(std::numeric_limits<int>::max()) + "]");
  if (model == analytic::BrdfModel::vgroove_nonsymmetric) {
    if (a.max_k > kNonsymmetricMaxK)
      throw support::UserError("--max-k = " + std::to_string(a.max_k) + " is out of range [1, " +
                               std::to_string(kNonsymmetricMaxK) +
                               "] with --model vgroove-nonsymmetric (the sum costs O(max_k^2))");
    return a.max_k;
  }
  if (flat && model == analytic::BrdfModel::vgroove) {
    if (a.max_k > kFlatlandMaxK)
      throw support::UserError("--max-k = " + std::to_string(a.max_k) + " is out of range [1, " +
                               std::to_string(kFlatlandMaxK) + "] with --dim flatland");
  }
  return a.max_k;
}

// The options of vgroove-nonsymmetric (--alpha-y, --partner), refused with the other models.
void check_nonsymmetric_options(const BrdfArgs& a, analytic::BrdfModel model, NdfKind ndf, bool flat) {
  const bool nonsym = model == analytic::BrdfModel::vgroove_nonsymmetric;
  if (a.partner != "independent" && a.partner != "symmetric")
    throw support::UserError("--partner = \"" + a.partner + "\" is not one of \"independent\", \"symmetric\"");
  if (a.partner_given && !nonsym)
    throw support::UserError("--partner applies to --model vgroove-nonsymmetric only (--model = \"" + a.model + "\")");
  if (a.alpha_y_given) {
    if (!nonsym)
      throw support::UserError("--alpha-y applies to --model vgroove-nonsymmetric only (--model = \"" + a.model +
                               "\")");
    if (flat) throw support::UserError("--alpha-y applies to --dim 3d only (flatland has one roughness)");
    if (ndf == NdfKind::phong)
      throw support::UserError("--alpha-y applies to --ndf ggx and beckmann only (Phong has no elliptical form)");
    check_angle(a.alpha_y, validation::kMinAlpha, true, validation::kMaxAlpha, true, "--alpha-y");
  }
  // Eq. (20)'s partner law exists for Phong below alpha = sqrt(2) only (ERRATA E-NS1).
  if (nonsym && a.partner == "independent" && !analytic::partner_law_exists(ndf, a.alpha))
    throw support::UserError("--alpha = " + support::number_text(a.alpha) + " is out of range " +
                             support::interval_text(0, false, std::sqrt(2.0), false) +
                             " with --model vgroove-nonsymmetric --ndf phong --partner independent (Eq. 20's "
                             "partner law needs alpha < sqrt(2))");
}

// Walter's options (--eta, --masking), refused with the other models.
analytic::MaskingKind check_walter_options(const BrdfArgs& a, analytic::BrdfModel model, NdfKind ndf) {
  const bool walter = model == analytic::BrdfModel::walter;
  for (auto [given, flag] : {std::pair{a.eta_given, "--eta"}, std::pair{a.masking_given, "--masking"}})
    if (given && !walter)
      throw support::UserError(std::string(flag) + " applies to --model walter only (--model = \"" + a.model + "\")");
  const auto masking = analytic::masking_from_flag(a.masking);
  if (!masking)
    throw support::UserError("--masking = \"" + a.masking +
                             "\" is not one of \"smith\", \"smith_separable\", \"vcavity\"");
  check_angle(a.eta, 0, false, validation::kMaxFresnelEta, true, "--eta");
  if (walter && !analytic::masking_supported(*masking, ndf))
    throw support::UserError("--masking = \"" + a.masking +
                             "\" needs --ndf ggx or beckmann (Smith's Lambda has no closed form for phong); "
                             "--masking vcavity takes phong");
  return *masking;
}

// --model vgroove-dielectric with --theta-o-deg or --directions: the kaleidoscopic dielectric
// model's BSDF at a point (analytic/kaleidoscope_dielectric_point.h), the light above the interface
// in the near medium (as walter: eta < 1 is light from inside the denser medium), the viewer on
// either side (theta_o over 90: transmitted); f, f per k (rows k = 0..--per-k-max and one for every
// k > --per-k-max) and pdf = f |cos theta_o|, the density of analytic/sampling_dielectric's draws.
// Flatland: theta_o past 90 deg is measured from the lower normal, the library's theta_o = theta_o -
// 180 sign(theta_o) (the straight-through direction of theta_i is theta_i - 180 sign(theta_i)).
// The horizon (theta_o = 90 deg), where f = density / |cos theta_o| is not defined, is refused.
struct DielectricPoint {
  double f = 0.0, pdf = 0.0;
  std::vector<double> by_k;
};

DielectricPoint dielectric_point(NdfKind ndf, double alpha, double eta, const Pair& p, bool flat, int rows) {
  // pdf: the library's kaleidoscope_dielectric_pdf_* to the bit; without rows the same arithmetic on
  // the value (f, a sum over the rows, rounds by the rows' grouping).
  DielectricPoint r;
  analytic::DielectricPointValue v;
  if (flat) {
    const bool reflected = std::abs(p.theta_o_deg) < 90.0;
    const double ti = deg_to_rad(p.theta_i_deg);
    const double to = deg_to_rad(reflected ? p.theta_o_deg : p.theta_o_deg - std::copysign(180.0, p.theta_o_deg));
    v = analytic::kaleidoscope_dielectric_bsdf_flatland(ndf, alpha, eta, ti, to, reflected, rows);
    r.pdf = rows == 0 ? v.f * std::cos(to)
                      : analytic::kaleidoscope_dielectric_pdf_flatland(ndf, alpha, eta, ti, to, reflected);
  } else {
    const analytic::Dir3 i = direction(p.theta_i_deg, p.phi_i_deg, false);
    const analytic::Dir3 o = direction(p.theta_o_deg, p.phi_o_deg, false);
    v = analytic::kaleidoscope_dielectric_bsdf_3d(ndf, alpha, eta, i, o, rows);
    r.pdf = rows == 0 ? v.f * std::abs(o.z) : analytic::kaleidoscope_dielectric_pdf_3d(ndf, alpha, eta, i, o);
  }
  r.f = v.f;
  r.by_k = std::move(v.by_k);
  return r;
}

// theta_o on the horizon: `name` as check_pair names it.
void check_off_horizon(const Pair& p, bool flat, const std::string& name) {
  if (std::abs(p.theta_o_deg) == 90.0)
    throw support::UserError(name + " = " + support::number_text(p.theta_o_deg) + " is out of range " +
                             (flat ? "[-180, -90) or (-90, 90) or (90, 180]" : "[0, 90) or (90, 180]") +
                             " with --model vgroove-dielectric (on the horizon f = density / |cos theta_o| is not "
                             "defined)");
}

// The points to evaluate, checked: --directions FILE's (read_pairs) or the flags' one pair
// (check_pair); `both`: theta_o over 90 (transmitted) allowed. Also --per-k-max's range. Nothing
// when interrupted while reading the file.
std::optional<std::vector<Pair>> points_of(const BrdfArgs& a, bool flat, bool both) {
  if (a.per_k_max < 1 || a.per_k_max > validation::kMaxPrintedK)
    throw support::UserError("--per-k-max = " + std::to_string(a.per_k_max) + " is out of range [1, " +
                             std::to_string(validation::kMaxPrintedK) + "]");
  std::vector<Pair> pairs;
  if (!a.directions.empty()) {
    if (a.theta_o_given)
      throw support::UserError("--directions cannot be combined with --theta-o-deg (the file gives the directions)");
    pairs = read_pairs(a.directions, flat, both, a.cancel);
    if (support::cancelled(a.cancel)) return std::nullopt;
    return pairs;
  }
  if (!a.theta_o_given) throw support::UserError("--theta-o-deg is required (or --directions FILE)");
  pairs.push_back({a.theta_i_deg, a.phi_i_deg, a.theta_o_deg, a.phi_o_deg});
  check_pair(pairs.back(), flat, both, "--");
  return pairs;
}

// f at every point, in order. Up to 10^7 pairs, a pair up to ~20 ms (the nonsymmetric model at max_k
// 1024): progress on a terminal (app/progress.h) past one point, the flag read before each pair;
// nothing when interrupted.
template <class F>
auto evaluate_points(const std::vector<Pair>& pairs, support::CancelFlag cancel, F&& f)
    -> std::optional<std::vector<std::invoke_result_t<F&, const Pair&>>> {
  std::vector<std::invoke_result_t<F&, const Pair&>> values;
  values.reserve(pairs.size());
  const support::ProgressFn progress = pairs.size() > 1 ? terminal_progress("brdf") : support::ProgressFn{};
  for (const Pair& p : pairs) {
    if (support::cancelled(cancel)) return std::nullopt;
    values.push_back(f(p));
    if (progress) progress(values.size(), pairs.size());
  }
  if (support::cancelled(cancel)) return std::nullopt;
  return values;
}

int cmd_brdf_dielectric_point(const BrdfArgs& a, NdfKind ndf, bool flat) {
  check_angle(a.eta, 0, false, validation::kMaxFresnelEta, true, "--eta");
  const std::optional<std::vector<Pair>> read = points_of(a, flat, true);
  if (!read) return interrupted_no_report();
  const std::vector<Pair>& pairs = *read;
  for (std::size_t n = 0; n < pairs.size(); ++n)
    check_off_horizon(
        pairs[n], flat,
        a.directions.empty() ? "--theta-o-deg" : a.directions + ": /directions/" + std::to_string(n) + "/theta_o_deg");
  if (a.dry_run) return 0;
  const int rows = a.per_k ? a.per_k_max : 0;
  const auto evaluated = evaluate_points(
      pairs, a.cancel, [&](const Pair& p) { return dielectric_point(ndf, a.alpha, a.eta, p, flat, rows); });
  if (!evaluated) return interrupted_no_report();
  const std::vector<DielectricPoint>& values = *evaluated;
  const char* unit = flat ? "1/rad" : "1/sr";
  if (a.json) {
    nlohmann::json j = validation::provenance();
    j["kind"] = "brdf";
    j["inputs"] = {{"model", a.model}, {"ndf", a.ndf},       {"alpha", a.alpha},
                   {"eta", a.eta},     {"dimension", a.dim}, {"per_k", rows}};
    j["unit"] = unit;
    j["pdf"] =
        "f |cos theta_o|: the density of the sampler's directions (analytic/sampling_dielectric.h), in the "
        "unit, integrating to albedo_r + albedo_t";
    nlohmann::json points = nlohmann::json::array();
    for (std::size_t n = 0; n < pairs.size(); ++n) {
      nlohmann::json e = {{"theta_i_deg", pairs[n].theta_i_deg},
                          {"theta_o_deg", pairs[n].theta_o_deg},
                          {"value", values[n].f},
                          {"pdf", values[n].pdf}};
      if (!flat) e["phi_i_deg"] = pairs[n].phi_i_deg, e["phi_o_deg"] = pairs[n].phi_o_deg;
      if (rows > 0) e["by_k"] = values[n].by_k;
      points.push_back(std::move(e));
    }
    j["points"] = std::move(points);
    std::cout << support::json_text(j, 1) << "\n";
    return 0;
  }
  std::printf(
      "brdf vgroove-dielectric: %s alpha %g, eta %g, %s, k up to 32; value in %s (theta_o over 90 deg: "
      "transmitted), pdf = value |cos theta_o|\n",
      a.ndf.c_str(), a.alpha, a.eta, flat ? "flatland" : "3D", unit);
  std::printf("  %12s %10s %12s %10s  %-24s  %s\n", "theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg", "value",
              "pdf");
  for (std::size_t n = 0; n < pairs.size(); ++n) {
    std::printf("  %12.9g %10.9g %12.9g %10.9g  %-24.17g  %.17g\n", pairs[n].theta_i_deg,
                flat ? 0.0 : pairs[n].phi_i_deg, pairs[n].theta_o_deg, flat ? 0.0 : pairs[n].phi_o_deg, values[n].f,
                values[n].pdf);
    if (rows == 0) continue;
    for (int k = 0; k <= rows; ++k)
      std::printf("  %48s k = %-4d %.17g\n", "", k, values[n].by_k[static_cast<std::size_t>(k)]);
    std::printf("  %48s k > %-4d %.17g\n", "", rows, values[n].by_k[static_cast<std::size_t>(rows + 1)]);
  }
  return 0;
}

// --model vgroove-dielectric without --theta-o-deg or --directions: the kaleidoscopic dielectric
// model's binned lobe (analytic/kaleidoscope_dielectric_lobe.h) for light at --theta-i-deg,
// reflected and transmitted flux fractions per bin: flatland 90 bins over (-90, 90) deg; 3D 18
// theta bins over [0, 90) x 24 phi bins centred on phi = 0, the light at phi = 180 (--phi-i-deg does
// not apply). Rows k = 0..--per-k-max and one for every k > --per-k-max with --per-k.
constexpr int kDielectricFlatBins = 90, kDielectricThetaBins = 18, kDielectricPhiBins = 24;

int cmd_brdf_dielectric_lobe(const BrdfArgs& a, NdfKind ndf, bool flat) {
  // The other models' flags, refused at a point and for the lobe; the directions' azimuths for the lobe.
  const bool point = a.theta_o_given || !a.directions.empty();
  for (auto [given, flag] : {std::pair{a.masking_given, "--masking"}, std::pair{a.alpha_y_given, "--alpha-y"},
                             std::pair{a.partner_given, "--partner"}, std::pair{a.max_k_given, "--max-k"}})
    if (given)
      throw support::UserError(std::string(flag) + " does not apply to --model vgroove-dielectric" +
                               (!point                           ? " (it prints the binned lobe at --theta-i-deg)"
                                : std::string(flag) == "--max-k" ? " (f sums every k up to 32; --per-k splits it)"
                                                                 : ""));
  if (point) return cmd_brdf_dielectric_point(a, ndf, flat);
  for (auto [given, flag] : {std::pair{a.phi_i_given, "--phi-i-deg"}, std::pair{a.phi_o_given, "--phi-o-deg"}})
    if (given)
      throw support::UserError(std::string(flag) +
                               " does not apply to --model vgroove-dielectric without --theta-o-deg or --directions "
                               "(it prints the binned lobe at --theta-i-deg)");
  check_angle(a.eta, 0, false, validation::kMaxFresnelEta, true, "--eta");
  if (flat)
    check_angle(a.theta_i_deg, -90, false, 90, false, "--theta-i-deg");
  else
    check_angle(a.theta_i_deg, 0, true, 90, false, "--theta-i-deg");
  if (a.per_k_max < 1 || a.per_k_max > validation::kMaxPrintedK)
    throw support::UserError("--per-k-max = " + std::to_string(a.per_k_max) + " is out of range [1, " +
                             std::to_string(validation::kMaxPrintedK) + "]");
  if (a.dry_run) return 0;
  const int rows = a.per_k ? a.per_k_max : 0;
  const double ti = deg_to_rad(a.theta_i_deg);
  const analytic::DielectricLobe L =
      flat ? analytic::kaleidoscope_dielectric_lobe_flatland(ndf, a.alpha, a.eta, ti, kDielectricFlatBins, rows)
           : analytic::kaleidoscope_dielectric_lobe_3d(ndf, a.alpha, a.eta, ti, kDielectricThetaBins,
                                                       kDielectricPhiBins, rows);
  if (support::cancelled(a.cancel)) return interrupted_no_report();
  const int tb = flat ? kDielectricFlatBins : kDielectricThetaBins, pb = flat ? 1 : kDielectricPhiBins;
  const double dt = flat ? 180.0 / tb : 90.0 / tb, dp = 360.0 / pb;
  auto theta_lo = [&](int b) { return flat ? -90.0 + b * dt : (b / pb) * dt; };
  auto phi_lo = [&](int b) { return (b % pb) * dp - 0.5 * dp; };
  if (a.json) {
    nlohmann::json j = validation::provenance();
    j["kind"] = "brdf_lobe";
    j["inputs"] = {{"model", a.model}, {"ndf", a.ndf},       {"alpha", a.alpha},
                   {"eta", a.eta},     {"dimension", a.dim}, {"theta_i_deg", a.theta_i_deg}};
    j["bins"] = flat
                    ? nlohmann::json{{"theta_bins", tb}, {"theta_range_deg", {-90, 90}}}
                    : nlohmann::json{{"theta_bins", tb}, {"phi_bins", pb}, {"index", "theta_bin * phi_bins + phi_bin"}};
    j["reflected"] = L.reflected;
    j["transmitted"] = L.transmitted;
    if (rows > 0) j["reflected_by_k"] = L.reflected_by_k, j["transmitted_by_k"] = L.transmitted_by_k;
    j["albedo_r"] = L.albedo_r, j["albedo_t"] = L.albedo_t, j["shadow_or_unknown"] = L.shadow_or_unknown;
    j["upward"] = L.upward, j["unresolved"] = L.unresolved, j["error_estimate"] = L.error_estimate;
    std::cout << support::json_text(j, 1) << "\n";
    return 0;
  }
  std::printf(
      "brdf vgroove-dielectric: %s alpha %g, eta %g, %s, theta_i %g deg: the kaleidoscopic dielectric model's "
      "lobe, flux fractions per bin (%s)\n",
      a.ndf.c_str(), a.alpha, a.eta, flat ? "flatland" : "3D", a.theta_i_deg,
      flat ? "90 bins over (-90, 90) deg from the exit side's normal"
           : "18 theta bins from the exit side's normal x 24 phi bins, the light at phi 180");
  std::printf("  albedo_r %.9f  albedo_t %.9f  not binned %.3g (travelling back up %.3g, k > 32 %.3g)  error %.2g\n",
              L.albedo_r, L.albedo_t, L.shadow_or_unknown, L.upward, L.unresolved, L.error_estimate);
  std::printf("  %-12s %9s %9s%s  %s\n", "side", "theta_lo", "theta_hi", flat ? "" : "   phi_lo   phi_hi", "flux");
  for (int side = 0; side < 2; ++side) {
    const std::vector<double>& v = side == 0 ? L.reflected : L.transmitted;
    const auto& by_k = side == 0 ? L.reflected_by_k : L.transmitted_by_k;
    for (int b = 0; b < L.bins; ++b) {
      if (!(v[b] > 0.0)) continue;
      std::printf("  %-12s %9.3f %9.3f", side == 0 ? "reflected" : "transmitted", theta_lo(b), theta_lo(b) + dt);
      if (!flat) std::printf(" %8.2f %8.2f", phi_lo(b), phi_lo(b) + dp);
      std::printf("  %.9g\n", v[b]);
      for (int k = 1; k <= rows; ++k)
        std::printf("  %*s k = %-4d %.9g\n", flat ? 32 : 50, "", k, by_k[static_cast<std::size_t>(k)][b]);
    }
  }
  return 0;
}

}  // namespace

int cmd_brdf(const BrdfArgs& a) {
  if (a.model == "vgroove-dielectric") {
    const auto ndf = ndf_from_name(a.ndf);
    if (!ndf) throw support::UserError("--ndf = \"" + a.ndf + "\" is not one of \"ggx\", \"beckmann\", \"phong\"");
    if (a.dim != "3d" && a.dim != "flatland")
      throw support::UserError("--dim = \"" + a.dim + "\" is not one of \"3d\", \"flatland\"");
    check_angle(a.alpha, validation::kMinAlpha, true, validation::kMaxAlpha, true, "--alpha");
    return cmd_brdf_dielectric_lobe(a, *ndf, a.dim == "flatland");
  }
  const auto model = analytic::brdf_model_from_name(a.model);
  if (!model)
    throw support::UserError("--model = \"" + a.model +
                             "\" is not one of \"vgroove\", \"vgroove-nonsymmetric\", \"cook-torrance\", \"walter\", "
                             "\"vgroove-dielectric\"");
  const auto ndf = ndf_from_name(a.ndf);
  if (!ndf) throw support::UserError("--ndf = \"" + a.ndf + "\" is not one of \"ggx\", \"beckmann\", \"phong\"");
  if (a.dim != "3d" && a.dim != "flatland")
    throw support::UserError("--dim = \"" + a.dim + "\" is not one of \"3d\", \"flatland\"");
  const bool flat = a.dim == "flatland";
  check_angle(a.alpha, validation::kMinAlpha, true, validation::kMaxAlpha, true, "--alpha");
  check_nonsymmetric_options(a, *model, *ndf, flat);
  const analytic::MaskingKind masking = check_walter_options(a, *model, *ndf);
  const bool walter = *model == analytic::BrdfModel::walter;
  const int max_k = orders(a, *model, flat);
  const std::optional<std::vector<Pair>> read = points_of(a, flat, walter);
  if (!read) return interrupted_no_report();
  const std::vector<Pair>& pairs = *read;
  if (a.dry_run) return 0;

  analytic::BrdfEvalOptions opt;
  opt.ndf = *ndf;
  opt.alpha = a.alpha;
  opt.flatland = flat;
  opt.max_k = max_k;
  opt.per_k = a.per_k ? a.per_k_max : 0;
  opt.eta = a.eta;
  opt.masking = masking;
  const bool nonsym = *model == analytic::BrdfModel::vgroove_nonsymmetric;
  if (nonsym) {
    opt.alpha_y = a.alpha_y_given ? a.alpha_y : a.alpha;
    opt.symmetric_partner = a.partner == "symmetric";
  }
  nlohmann::json points = nlohmann::json::array();
  const auto evaluated = evaluate_points(pairs, a.cancel, [&](const Pair& p) {
    return analytic::evaluate_brdf(*model, direction(p.theta_i_deg, p.phi_i_deg, flat),
                                   direction(p.theta_o_deg, p.phi_o_deg, flat), opt);
  });
  if (!evaluated) return interrupted_no_report();
  const std::vector<analytic::BrdfValue>& values = *evaluated;
  const char* unit = flat ? "1/rad" : "1/sr";
  if (a.json) {
    nlohmann::json j = validation::provenance();
    j["kind"] = "brdf";
    j["inputs"] = {{"model", a.model},   {"ndf", a.ndf},       {"alpha", a.alpha},
                   {"dimension", a.dim}, {"max_k", opt.max_k}, {"per_k", opt.per_k}};
    if (nonsym) j["inputs"]["alpha_y"] = opt.alpha_y, j["inputs"]["partner"] = a.partner;
    if (walter) j["inputs"]["eta"] = opt.eta, j["inputs"]["masking"] = a.masking;
    j["unit"] = unit;
    for (std::size_t n = 0; n < pairs.size(); ++n) {
      nlohmann::json e = {
          {"theta_i_deg", pairs[n].theta_i_deg}, {"theta_o_deg", pairs[n].theta_o_deg}, {"value", values[n].value}};
      if (!flat) e["phi_i_deg"] = pairs[n].phi_i_deg, e["phi_o_deg"] = pairs[n].phi_o_deg;
      if (opt.per_k > 0) e["by_k"] = values[n].by_k;
      points.push_back(std::move(e));
    }
    j["points"] = std::move(points);
    std::cout << support::json_text(j, 1) << "\n";
    return 0;
  }
  // Cook-Torrance and Walter are single scattering whatever --max-k says.
  const std::string orders_text = *model == analytic::BrdfModel::cook_torrance || walter
                                      ? std::string("single scattering (k = 1)")
                                      : "orders 1.." + std::to_string(opt.max_k);
  if (nonsym)
    std::printf("brdf %s: %s alpha %g (x) %g (y), partner %s, %s, %s; value in %s\n", a.model.c_str(), a.ndf.c_str(),
                a.alpha, opt.alpha_y, a.partner.c_str(), flat ? "flatland" : "3D", orders_text.c_str(), unit);
  else if (walter)
    std::printf("brdf %s: %s alpha %g, eta %g, masking %s, %s, %s; value in %s (theta_o over 90 deg: transmitted)\n",
                a.model.c_str(), a.ndf.c_str(), a.alpha, a.eta, a.masking.c_str(), flat ? "flatland" : "3D",
                orders_text.c_str(), unit);
  else
    std::printf("brdf %s: %s alpha %g, %s, %s; value in %s\n", a.model.c_str(), a.ndf.c_str(), a.alpha,
                flat ? "flatland" : "3D", orders_text.c_str(), unit);
  std::printf("  %12s %10s %12s %10s  %s\n", "theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg", "value");
  for (std::size_t n = 0; n < pairs.size(); ++n) {
    std::printf("  %12.9g %10.9g %12.9g %10.9g  %.17g\n", pairs[n].theta_i_deg, flat ? 0.0 : pairs[n].phi_i_deg,
                pairs[n].theta_o_deg, flat ? 0.0 : pairs[n].phi_o_deg, values[n].value);
    for (int k = 1; k <= opt.per_k; ++k)
      std::printf("  %48s k = %-4d %.17g\n", "", k, values[n].by_k[static_cast<std::size_t>(k - 1)]);
  }
  return 0;
}

void add_brdf_command(CLI::App& app, Commands& commands) {
  using validation::kMaxAlpha;
  using validation::kMinAlpha;
  auto* brdf = app.add_subcommand(
      "brdf",
      "Evaluate a BRDF at a pair of directions (or every pair of a JSON file): vgroove's multiple-scattering "
      "model (Lee et al. 2018, Eq. 16-17), its nonsymmetric form (Eq. 21-23, partner facets by Eq. 20; "
      "anisotropic with --alpha-y) or Cook-Torrance (Eq. 1-3, V-cavity G), F = 1; or Walter et al. 2007's rough "
      "dielectric BSDF (--eta, --masking), reflected and transmitted; or the kaleidoscopic dielectric model's BSDF "
      "(--model vgroove-dielectric --eta, k up to 32) or its binned lobe. 3D: polar angles from the "
      "normal, azimuths about it (phi_o = phi_i + 180 is the mirror side; with --alpha-y from the --alpha "
      "axis); flatland: signed angles. Walter and vgroove-dielectric: the viewer's polar angle over 90 (flatland: "
      "|theta_o| over 90) "
      "is below the interface, in the far medium.");
  BrdfArgs& ba = commands.add(brdf, cmd_brdf);
  ba.cancel = commands.context().cancel;
  add_text(brdf, "--model", ba.model,
           "vgroove, vgroove-nonsymmetric, cook-torrance, walter, or vgroove-dielectric (the kaleidoscopic "
           "dielectric model, --eta: its BSDF at --theta-o-deg or --directions, reflected and transmitted as "
           "walter's, k up to 32, with \"pdf\" = value |cos theta_o|, the density of its sampler's directions; "
           "without them its binned lobe at --theta-i-deg)")
      ->capture_default_str();
  add_text(brdf, "--ndf", ba.ndf, "ggx, beckmann or phong")->capture_default_str();
  add_real(brdf, "--alpha", ba.alpha,
           "roughness, " + support::interval_text(kMinAlpha, true, kMaxAlpha, true) +
               "; vgroove-nonsymmetric with phong and --partner independent: below sqrt 2 (Eq. 20 needs it); "
               "alpha_x with --alpha-y")
      ->capture_default_str();
  auto* brdf_alpha_y =
      add_real(brdf, "--alpha-y", ba.alpha_y,
               "vgroove-nonsymmetric, 3D, ggx or beckmann only: the roughness across the --alpha "
               "axis, " +
                   support::interval_text(kMinAlpha, true, kMaxAlpha, true) + " (default: --alpha, isotropic)");
  auto* brdf_partner =
      add_text(brdf, "--partner", ba.partner,
               "vgroove-nonsymmetric only: the partner facet's tilt, independent (Eq. 20) or symmetric (equal to the "
               "first's: the symmetric model, anisotropic with --alpha-y)")
          ->capture_default_str();
  auto* brdf_eta =
      add_real(
          brdf, "--eta", ba.eta,
          "walter and vgroove-dielectric only: n_far / n_near, the light in the near medium (below 1: from inside the "
          "denser medium), " +
              support::interval_text(0, false, validation::kMaxFresnelEta, true))
          ->capture_default_str();
  auto* brdf_masking = add_text(brdf, "--masking", ba.masking,
                                "walter only: the G2, smith (height-correlated), smith_separable (Walter's Eq. 23) "
                                "or vcavity; smith ones need ggx or beckmann")
                           ->capture_default_str();
  add_text(brdf, "--dim", ba.dim, "3d or flatland")->capture_default_str();
  add_real(brdf, "--theta-i-deg", ba.theta_i_deg, "light: polar angle, [0, 90) (flatland: signed, (-90, 90))")
      ->capture_default_str();
  auto* phi_i = add_real(brdf, "--phi-i-deg", ba.phi_i_deg, "light: azimuth, [-360, 360] (3D only)");
  phi_i->capture_default_str();
  auto* theta_o =
      add_real(brdf, "--theta-o-deg", ba.theta_o_deg,
               "viewer: polar angle, [0, 90] (flatland: signed, [-90, 90]); walter: [0, 180] "
               "([-180, 180]), over 90 transmitted; vgroove-dielectric: the same but 90 (-90); required unless "
               "--directions (vgroove-dielectric: without either, the binned lobe)");
  auto* phi_o = add_real(brdf, "--phi-o-deg", ba.phi_o_deg, "viewer: azimuth, [-360, 360] (3D only)");
  phi_o->capture_default_str();
  auto* brdf_max_k =
      add_integer(brdf, "--max-k", ba.max_k,
                  "orders summed; vgroove 3D and cook-torrance: any, at no extra cost (default: all); vgroove "
                  "flatland: <= " +
                      std::to_string(kFlatlandMaxK) + ", one pass whatever max_k (default " +
                      std::to_string(analytic::default_max_k(analytic::BrdfModel::vgroove, true)) +
                      "); vgroove-nonsymmetric: <= " + std::to_string(kNonsymmetricMaxK) + ", O(max_k^2) (default " +
                      std::to_string(analytic::default_max_k(analytic::BrdfModel::vgroove_nonsymmetric, false)) + ")",
                  1, std::numeric_limits<int>::max());
  brdf->add_flag("--per-k", ba.per_k,
                 "also print each order k = 1..--per-k-max (vgroove-dielectric: rows k = 0..--per-k-max and k > "
                 "--per-k-max, summing to the value)");
  add_integer(brdf, "--per-k-max", ba.per_k_max, "orders printed one by one with --per-k", 1, validation::kMaxPrintedK)
      ->capture_default_str();
  add_text(brdf, "--directions", ba.directions,
           "JSON file {\"directions\": [{\"theta_i_deg\", \"theta_o_deg\"[, \"phi_i_deg\", "
           "\"phi_o_deg\"]}, ...]}: evaluate at every pair");
  brdf->add_flag("--json", ba.json, "print JSON");
  brdf->callback([&ba, theta_o, phi_i, phi_o, brdf_alpha_y, brdf_partner, brdf_max_k, brdf_eta, brdf_masking]() {
    ba.eta_given = brdf_eta->count() > 0;
    ba.masking_given = brdf_masking->count() > 0;
    ba.theta_o_given = theta_o->count() > 0;
    ba.phi_i_given = phi_i->count() > 0;
    ba.phi_o_given = phi_o->count() > 0;
    ba.alpha_y_given = brdf_alpha_y->count() > 0;
    ba.partner_given = brdf_partner->count() > 0;
    ba.max_k_given = brdf_max_k->count() > 0;
  });
}

}  // namespace vgroove::app
