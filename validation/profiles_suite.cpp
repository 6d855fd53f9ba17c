#include "vgroove/validation/profiles_suite.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/smith_walk_flatland.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/profile_tally.h"
#include "vgroove/sim/profile_visibility.h"
#include "vgroove/sim/random_profile.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/profile_masking.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Streams of the suite's seeds: profiles, beams, walk paths.
constexpr std::uint64_t kProfileSeeds = 0x70726f66ULL, kBeamSeeds = 0x6265616dULL, kWalkSeeds = 0x77616c6bULL;
constexpr std::int64_t kWalkChunk = 1 << 16;

// Per-bin values of the realizations ([r][b]) to mean and standard error.
BinStat bin_stat(const std::vector<std::vector<double>>& v) {
  BinStat s;
  if (v.empty()) return s;
  const std::size_t nb = v.front().size();
  for (std::size_t b = 0; b < nb; ++b) {
    double sum = 0.0;
    int n = 0;
    for (const auto& r : v)
      if (std::isfinite(r[b])) sum += r[b], ++n;
    const double mean = n > 0 ? sum / n : kNaN;
    double var = 0.0;
    for (const auto& r : v)
      if (std::isfinite(r[b])) var += (r[b] - mean) * (r[b] - mean);
    s.mean.push_back(mean);
    s.se.push_back(n >= 2 ? std::sqrt(var / (n - 1) / n) : kNaN);
  }
  return s;
}

double mean_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? kNaN : s / static_cast<double>(v.size());
}

// The per-bin G values of a ratio seen / weight: their standard error is the realizations' spread,
// but at least the binomial noise of the rays, sqrt(p (1 - p) / rays) / weight with p = G weight.
struct BinErrors {
  std::vector<double> se, counting_se;  // NaN where the bin has no traced value or weight
};
BinErrors bin_errors(const BinStat& traced, const BinStat& weight, double rays) {
  BinErrors e;
  for (std::size_t b = 0; b < traced.mean.size(); ++b) {
    const double t = traced.mean[b], w = weight.mean[b];
    if (!(std::isfinite(t) && std::isfinite(w) && w > 0.0)) {
      e.se.push_back(kNaN), e.counting_se.push_back(kNaN);
      continue;
    }
    const double p = std::clamp(t * w, 0.0, 1.0);
    const double floor = std::sqrt(p * (1.0 - p) / rays) / w;
    e.counting_se.push_back(floor);
    e.se.push_back(std::isfinite(traced.se[b]) ? std::max(traced.se[b], floor) : floor);
  }
  return e;
}

ModelDistance model_distance(const BinStat& traced, const std::vector<double>& model, const BinStat& weight,
                             const BinErrors& err) {
  ModelDistance d;
  double w_sum = 0.0;
  for (std::size_t b = 0; b < traced.mean.size(); ++b) {
    const double t = traced.mean[b], m = model[b], w = weight.mean[b];
    if (!(std::isfinite(t) && std::isfinite(m) && std::isfinite(w) && w > 0.0)) continue;
    const double se = err.se[b];
    w_sum += w;
    d.mean_abs += w * std::abs(t - m);
    d.noise += w * std::sqrt(2.0 / std::numbers::pi) * se;
    if (se > 0.0) d.max_abs_z = std::max(d.max_abs_z, std::abs(t - m) / se);
  }
  if (w_sum > 0.0) d.mean_abs /= w_sum, d.noise /= w_sum;
  return d;
}

// The lit fraction over the realizations: traced[r], its counting sd[r], the predictions[r].
LitFraction lit_fraction(const std::vector<double>& traced, const std::vector<double>& sd,
                         const std::vector<double>& smith, const std::vector<double>& vcavity) {
  LitFraction l;
  std::vector<std::vector<double>> per_r;
  for (double x : traced) per_r.push_back({x});
  const BinStat b = bin_stat(per_r);
  l.traced = b.mean[0], l.realization_se = b.se[0];
  l.smith = mean_of(smith), l.vcavity = mean_of(vcavity);
  double num = 0.0, var = 0.0;
  for (std::size_t r = 0; r < traced.size(); ++r) num += traced[r] - vcavity[r], var += sd[r] * sd[r];
  // z = sum_r (traced - vcavity) / sqrt(sum_r sd^2) = (mean traced - mean vcavity) / se.
  const double R = static_cast<double>(traced.size());
  l.se = std::sqrt(var) / R;
  l.z_vcavity = var > 0.0 ? num / std::sqrt(var) : (num == 0.0 ? 0.0 : kNaN);
  return l;
}

// L1 of the traced lobe's mean from a model, per row and in total, against the L1 the noise
// alone gives: per bin the traced mean's variance, se^2 from the realizations' spread but at least
// the rays' own multinomial p (1 - p) / rays with p the larger of the traced and the model value
// (a spread of a few realizations can fall below it by chance, and an empty traced bin has no
// spread at all), plus model_var (the model's own).
LobeDistance lobe_distance(const BinStat& traced, const std::vector<double>& model,
                           const std::vector<double>& model_var, int rows, int bins, double sigmas, double rays) {
  LobeDistance d;
  double var_total = 0.0;
  for (int r = 0; r < rows; ++r) {
    double l1_r = 0.0, mean_r = 0.0, var_r = 0.0;
    for (int b = 0; b < bins; ++b) {
      const std::size_t n = static_cast<std::size_t>(r) * static_cast<std::size_t>(bins) + static_cast<std::size_t>(b);
      const double se = std::isfinite(traced.se[n]) ? traced.se[n] : 0.0;
      const double p = std::clamp(std::max(traced.mean[n], model[n]), 0.0, 1.0);
      const double v = std::max(se * se, p * (1.0 - p) / rays) + model_var[n];
      l1_r += std::abs(traced.mean[n] - model[n]);
      mean_r += std::sqrt(2.0 * v / std::numbers::pi);
      var_r += (1.0 - 2.0 / std::numbers::pi) * v;
    }
    d.l1.push_back(l1_r);
    d.expected.push_back(mean_r);
    d.sd.push_back(std::sqrt(var_r));
    d.z.push_back(var_r > 0.0 ? (l1_r - mean_r) / std::sqrt(var_r) : (l1_r > 0.0 ? kNaN : 0.0));
    d.l1_total += l1_r, d.expected_total += mean_r, var_total += var_r;
  }
  d.sd_total = std::sqrt(var_total);
  d.z_total = var_total > 0.0 ? (d.l1_total - d.expected_total) / d.sd_total : (d.l1_total > 0.0 ? kNaN : 0.0);
  for (double z : d.z) d.max_z = std::isnan(z) || std::isnan(d.max_z) ? kNaN : std::max(d.max_z, z);
  d.within_noise = d.max_z <= sigmas && d.z_total <= sigmas;
  return d;
}

OrderedChiSquare combine(const std::vector<OrderedChiSquare>& parts) {
  OrderedChiSquare c;
  for (const OrderedChiSquare& p : parts) c.stat += p.stat, c.dof += p.dof;
  c.p = c.dof > 0 ? gamma_q(0.5 * c.dof, 0.5 * c.stat) : 1.0;
  return c;
}

sim::Polyline make_profile(const ProfilesSuite& suite, const ProfilesCase& c, ProfileSurface surface,
                           std::uint64_t seed) {
  if (surface == ProfileSurface::random) {
    sim::RandomProfileOptions o;
    o.ndf = c.ndf, o.alpha = c.alpha, o.segments = suite.segments, o.samples_per_length = suite.samples_per_length;
    o.seed = seed;
    return sim::make_random_profile(o);
  }
  sim::MicrosurfaceOptions mo;
  mo.ndf = c.ndf, mo.alpha = c.alpha, mo.grooves = suite.segments / 2, mo.seed = seed;
  return sim::vgroove_polyline(sim::make_microsurface(mo).theta_m);
}

struct CaseIndex {
  std::size_t ndf, alpha, theta;
};
CaseIndex index_of(const ProfilesSuite& s, std::size_t c) {
  const std::size_t nt = s.theta.size(), na = s.alphas.size();
  return {c / (nt * na), (c / nt) % na, c % nt};
}

SurfaceOutcome run_surface(const ProfilesSuite& suite, std::size_t case_index, const ProfilesCase& c,
                           ProfileSurface surface, long rays, const std::vector<double>& walk_lobe,
                           const std::vector<double>& walk_var, const std::vector<double>& model_lobe,
                           support::CancelFlag cancel) {
  const auto t0 = Clock::now();
  SurfaceOutcome out;
  out.surface = surface;
  const CaseIndex ix = index_of(suite, case_index);
  const int rows = suite.max_k + 2, bins = suite.lobe_bins;
  const std::uint64_t surface_key = surface == ProfileSurface::random ? 0 : 1;
  std::vector<std::vector<double>> g1w, g1t, g1v, g2w, g2t, g2v, lobes;
  std::vector<double> identities, vc_averages, ident_err;
  std::vector<double> lit_t, lit_sd, lit_s, lit_v, arc_t, arc_sd, arc_s, arc_v;
  std::vector<OrderedChiSquare> chi1, chi2;
  std::vector<std::int64_t> pooled(static_cast<std::size_t>(rows * bins), 0), by_k(static_cast<std::size_t>(rows), 0);
  std::int64_t lobe_rays = 0, escaped = 0;
  for (int r = 0; r < suite.realizations; ++r) {
    if (support::cancelled(cancel)) return out;
    // One profile per (ndf, alpha, surface, realization): the same for every theta.
    const std::uint64_t key = ((ix.ndf * 64 + ix.alpha) * 65536 + static_cast<std::uint64_t>(r)) * 2 + surface_key;
    const sim::Polyline p = make_profile(suite, c, surface, sim::derived_seed(suite.seed, kProfileSeeds, key));
    const std::uint64_t beam_key = ((case_index * 65536 + static_cast<std::uint64_t>(r)) * 2 + surface_key) * 4;
    sim::VisibilityOptions vo;
    vo.theta_view = c.theta, vo.theta_light = -c.theta, vo.rays = rays;
    vo.seed = sim::derived_seed(suite.seed, kBeamSeeds, beam_key);
    sim::VisibilityOptions vi;
    vi.theta_view = -c.theta, vi.rays = rays, vi.seed = sim::derived_seed(suite.seed, kBeamSeeds, beam_key + 1);
    const sim::VisibilityTally from_o = sim::trace_visibility(p, vo, cancel);
    const sim::VisibilityTally from_i = sim::trace_visibility(p, vi, cancel);
    if (support::cancelled(cancel)) return out;  // the tallies are incomplete
    const MaskingMeasure m =
        measure_masking(p, MaskingCase{c.ndf, c.alpha, -c.theta, c.theta, suite.normal_bins}, from_o, from_i);
    sim::MicrosurfaceTraceOptions to;
    to.theta_i = c.theta, to.rays = rays, to.seed = sim::derived_seed(suite.seed, kBeamSeeds, beam_key + 2);
    to.theta_o_bins = bins, to.max_k = suite.max_k;
    const sim::MicrosurfaceTally t = sim::trace_profile(p, to, cancel);
    if (support::cancelled(cancel)) return out;

    out.rays += from_o.rays + from_i.rays + t.rays;
    out.lost += m.lost + from_i.vertex_hits + from_i.back_face + t.lost();
    out.shadow_vertex += from_o.shadow_vertex;
    out.bounces += t.bounces;
    g1w.push_back(m.g1_weight), g1t.push_back(m.g1_traced), g1v.push_back(m.g1_vcavity);
    g2w.push_back(m.g2_weight), g2t.push_back(m.g2_traced), g2v.push_back(m.g2_vcavity);
    out.g1_smith = m.g1_smith, out.g2_smith_separable = m.g2_smith_separable;
    out.g2_smith_correlated = m.g2_smith_correlated;
    identities.push_back(m.g1_identity), vc_averages.push_back(m.g1_average_vcavity);
    ident_err.push_back(std::abs(m.g1_average_traced - m.g1_identity) / m.g1_identity);
    lit_t.push_back(m.lit_traced), lit_sd.push_back(m.lit_traced_sd);
    lit_s.push_back(m.lit_smith), lit_v.push_back(m.lit_vcavity);
    arc_t.push_back(m.lit_arc_traced), arc_sd.push_back(m.lit_arc_traced_sd);
    arc_s.push_back(m.lit_arc_smith), arc_v.push_back(m.lit_arc_vcavity);
    chi1.push_back(m.g1_chi2), chi2.push_back(m.g2_chi2);
    lobes.push_back(fractions(t.theta_o_by_k, static_cast<double>(t.rays)));
    for (std::size_t n = 0; n < pooled.size(); ++n) pooled[n] += t.theta_o_by_k[n];
    for (std::size_t k = 0; k < by_k.size(); ++k) by_k[k] += t.by_k[k];
    lobe_rays += t.rays, escaped += t.escaped;
  }
  out.g1_weight = bin_stat(g1w), out.g1_traced = bin_stat(g1t), out.g1_vcavity = bin_stat(g1v);
  out.g2_weight = bin_stat(g2w), out.g2_traced = bin_stat(g2t), out.g2_vcavity = bin_stat(g2v);
  const std::size_t nb = static_cast<std::size_t>(suite.normal_bins);
  const double view_rays = static_cast<double>(rays) * suite.realizations;
  const BinErrors e1 = bin_errors(out.g1_traced, out.g1_weight, view_rays);
  const BinErrors e2 = bin_errors(out.g2_traced, out.g2_weight, view_rays);
  out.g1_se = e1.se, out.g1_counting_se = e1.counting_se, out.g2_se = e2.se, out.g2_counting_se = e2.counting_se;
  out.g1_d_smith = model_distance(out.g1_traced, std::vector<double>(nb, out.g1_smith), out.g1_weight, e1);
  out.g1_d_vcavity = model_distance(out.g1_traced, out.g1_vcavity.mean, out.g1_weight, e1);
  out.g2_d_separable =
      model_distance(out.g2_traced, std::vector<double>(nb, out.g2_smith_separable), out.g2_weight, e2);
  out.g2_d_correlated =
      model_distance(out.g2_traced, std::vector<double>(nb, out.g2_smith_correlated), out.g2_weight, e2);
  out.g2_d_vcavity = model_distance(out.g2_traced, out.g2_vcavity.mean, out.g2_weight, e2);
  out.g1_identity = mean_of(identities), out.g1_average_vcavity = mean_of(vc_averages);
  out.identity_error = *std::max_element(ident_err.begin(), ident_err.end());
  out.lit = lit_fraction(lit_t, lit_sd, lit_s, lit_v);
  out.lit_arc = lit_fraction(arc_t, arc_sd, arc_s, arc_v);
  out.g1_chi2 = combine(chi1), out.g2_chi2 = combine(chi2);

  out.lobe = bin_stat(lobes);
  out.by_k = fractions(by_k, static_cast<double>(lobe_rays));
  out.albedo = static_cast<double>(escaped) / static_cast<double>(lobe_rays);
  const double n_rays = static_cast<double>(lobe_rays);
  out.d_walk = lobe_distance(out.lobe, walk_lobe, walk_var, rows, bins, suite.sigmas, n_rays);
  out.d_vgroove = lobe_distance(out.lobe, model_lobe, std::vector<double>(model_lobe.size(), 0.0), rows, bins,
                                suite.sigmas, n_rays);
  // The V-groove model on V-grooves, the pooled histogram against the sample count (fig11's rule).
  const std::vector<double> pooled_f = fractions(pooled, static_cast<double>(lobe_rays));
  out.l1_pooled = l1(pooled_f, model_lobe);
  const ExpectedL1 e = expected_l1(model_lobe, static_cast<double>(lobe_rays),
                                   static_cast<double>(suite.segments / 2) * suite.realizations);
  out.l1_pooled_threshold = e.mean + suite.sigmas * e.sd + suite.model_tolerance;

  out.identity_holds = out.lost == 0 && out.identity_error <= 1e-12;
  const double p_thr = suite.p_min / std::max(1, suite.verdict_tests());
  const bool exact_model_holds = out.g1_chi2.p >= p_thr && out.g2_chi2.p >= p_thr &&
                                 std::abs(out.lit_arc.z_vcavity) <= suite.sigmas &&
                                 out.l1_pooled <= out.l1_pooled_threshold;
  out.pass = out.identity_holds && (surface == ProfileSurface::random || exact_model_holds);
  out.wall_s = seconds_since(t0);
  return out;
}

// The flatland Smith walk's per-k lobe: joint (row, bin) fractions, and their variance.
void run_walk(const ProfilesSuite& suite, std::size_t case_index, const ProfilesCase& c, ProfilesOutcome& out,
              support::CancelFlag cancel) {
  const int rows = suite.max_k + 2, bins = suite.lobe_bins;
  std::vector<std::int64_t> h(static_cast<std::size_t>(rows * bins), 0), by_k(static_cast<std::size_t>(rows), 0);
  const std::uint64_t seed = sim::derived_seed(suite.seed, kWalkSeeds, case_index);
  const double width = std::numbers::pi / bins;
  for (std::int64_t chunk = 0; chunk * kWalkChunk < suite.walk_paths; ++chunk) {
    if (support::cancelled(cancel)) return;
    sim::Rng rng(seed, kWalkSeeds, static_cast<std::uint64_t>(chunk));
    auto uniform = [&] { return sim::uniform_open(rng); };
    const std::int64_t end = std::min<std::int64_t>(suite.walk_paths, (chunk + 1) * kWalkChunk);
    for (std::int64_t n = chunk * kWalkChunk; n < end; ++n) {
      const analytic::FlatlandWalk w = analytic::smith_walk_flatland(c.ndf, c.alpha, c.theta, uniform);
      ++out.walk_paths;
      if (!w.left) continue;
      ++out.walk_left;
      const int row = std::min(w.k, suite.max_k + 1);
      const int b = std::clamp(static_cast<int>(std::floor((w.theta_o + 0.5 * std::numbers::pi) / width)), 0, bins - 1);
      ++h[static_cast<std::size_t>(row * bins + b)];
      ++by_k[static_cast<std::size_t>(row)];
    }
  }
  out.walk_lobe = fractions(h, static_cast<double>(out.walk_paths));
  out.walk_by_k = fractions(by_k, static_cast<double>(out.walk_paths));
}

}  // namespace

const char* profile_surface_name(ProfileSurface s) { return s == ProfileSurface::random ? "random" : "vgroove"; }

ProfilesCase ProfilesSuite::case_at(std::size_t c) const {
  const CaseIndex ix = index_of(*this, c);
  return {ndfs[ix.ndf], alphas[ix.alpha], theta[ix.theta]};
}

int ProfilesSuite::verdict_tests() const {
  const auto v = static_cast<int>(std::count(surfaces.begin(), surfaces.end(), ProfileSurface::vgroove));
  return static_cast<int>(cases()) * v * 2;
}

ProfilesSuite parse_profiles_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  ProfilesSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"profiles"});
  for (const auto& n : read_names(root, "ndf", {"beckmann", "ggx"}))
    s.ndfs.push_back(n == "ggx" ? analytic::NdfKind::ggx : analytic::NdfKind::beckmann);
  s.alphas = read_numbers(root, "alpha", kMinAlpha, true, kMaxAlpha, true);
  for (double d : read_numbers(root, "theta_deg", 0.0, true, 89.0, true)) s.theta.push_back(d * kRadPerDeg);
  for (const auto& n : read_names(root, "surfaces", {"random", "vgroove"}))
    s.surfaces.push_back(n == "random" ? ProfileSurface::random : ProfileSurface::vgroove);
  s.realizations = static_cast<int>(root.integer_or("realizations", s.realizations, 2, 1000));
  s.segments = static_cast<int>(root.integer_or("segments", s.segments, 1024, 1 << 24));
  s.samples_per_length = static_cast<int>(root.integer_or("samples_per_length", s.samples_per_length, 2, 1024));
  if (s.segments % 2 != 0) root.fail("segments", "= " + std::to_string(s.segments) + " must be even");
  if (s.segments < 2 * (8 * s.samples_per_length + 1))
    root.fail("segments", "= " + std::to_string(s.segments) + " must be at least 2 (8 samples_per_length + 1) = " +
                              std::to_string(2 * (8 * s.samples_per_length + 1)) + " (twice the profile's kernel)");
  s.rays = static_cast<long>(root.integer("rays", 1, kMaxRays));
  s.walk_paths = static_cast<long>(root.integer("walk_paths", 1, kMaxRays));
  s.normal_bins = static_cast<int>(root.integer_or("normal_bins", s.normal_bins, 1, 3600));
  s.lobe_bins = static_cast<int>(root.integer_or("lobe_bins", s.lobe_bins, 1, 100000));
  s.max_k = static_cast<int>(root.integer_or("max_k", s.max_k, 1, 1000));
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, std::numeric_limits<long long>::max()));
  {
    support::JsonObject t = root.object("thresholds");
    s.p_min = t.number("p_min", 0.0, false, 1.0, false);
    s.sigmas = t.number("sigmas", 0.0, false, 100.0, true);
    s.model_tolerance = t.number_or("model_tolerance", s.model_tolerance, 0.0, true, 2.0, true);
    t.finish();
  }
  root.finish();
  return s;
}

ProfilesOutcome run_profiles_case(const ProfilesSuite& suite, std::size_t case_index, long rays,
                                  const std::atomic<bool>* cancel) {
  ProfilesOutcome out;
  out.c = suite.case_at(case_index);
  const auto t0 = Clock::now();
  run_walk(suite, case_index, out.c, out, cancel);
  out.walk_wall_s = seconds_since(t0);
  if (support::cancelled(cancel)) return out;
  const analytic::FlatlandLobe lobe =
      analytic::flatland_lobe(out.c.ndf, out.c.alpha, out.c.theta, suite.lobe_bins, suite.max_k);
  out.model_lobe = lobe.theta_o_by_k;
  out.model_by_k = lobe.by_k;
  std::vector<double> walk_var;
  for (double p : out.walk_lobe) walk_var.push_back(p * (1.0 - p) / static_cast<double>(out.walk_paths));
  out.pass = true;
  for (ProfileSurface s : suite.surfaces) {
    if (support::cancelled(cancel)) return out;
    out.surfaces.push_back(
        run_surface(suite, case_index, out.c, s, rays, out.walk_lobe, walk_var, out.model_lobe, cancel));
    out.pass = out.pass && out.surfaces.back().pass;
  }
  out.non_finite = !(all_finite(out.walk_lobe) && all_finite(out.model_lobe));
  for (const SurfaceOutcome& so : out.surfaces)
    out.non_finite = out.non_finite || !all_finite(so.lobe.mean) || !std::isfinite(so.lit_arc.traced) ||
                     !std::isfinite(so.lit.traced) || !std::isfinite(so.g1_identity);
  out.pass = out.pass && !out.non_finite;
  return out;
}

double profiles_run_memory_bytes(const ProfilesSuite& suite, int threads) {
  const double cases = static_cast<double>(suite.cases());
  const double workers = std::min<double>(support::resolve_threads(threads), cases);
  const double lobe = static_cast<double>(suite.lobe_bins) * (suite.max_k + 2) * 8.0;
  const double per_case = lobe * (4.0 + 3.0 * suite.realizations * static_cast<double>(suite.surfaces.size())) +
                          suite.normal_bins * 64.0 * suite.realizations;
  return workers * 200.0 * suite.segments + cases * per_case;
}

Job<ProfilesWork> profiles_job(const ProfilesSuite& suite, long rays, nlohmann::json descriptor,
                               const std::atomic<bool>* cancel) {
  const long n_rays = rays > 0 ? rays : suite.rays;
  // A case's realizations run in order on one thread from its own seeds: where it runs does not
  // change its numbers.
  return item_job<ProfilesOutcome>(
      suite.cases(), [suite, n_rays, cancel](std::size_t c) { return run_profiles_case(suite, c, n_rays, cancel); },
      [suite](support::JsonObject& o, std::size_t c, ProfilesOutcome& out) {
        out.c = suite.case_at(c);
        const std::size_t joint = static_cast<std::size_t>(suite.max_k + 2) * static_cast<std::size_t>(suite.lobe_bins);
        if (out.surfaces.size() != suite.surfaces.size())
          o.fail("outcome", "/surfaces: " + std::to_string(out.surfaces.size()) + " surfaces, not the suite's " +
                                std::to_string(suite.surfaces.size()));
        bool shaped = out.walk_lobe.size() == joint && out.model_lobe.size() == joint;
        for (std::size_t n = 0; n < out.surfaces.size(); ++n) {
          out.surfaces[n].surface = suite.surfaces[n];
          shaped = shaped && out.surfaces[n].lobe.mean.size() == joint && out.surfaces[n].lobe.se.size() == joint;
        }
        if (!shaped)
          o.fail("outcome", "/walk_lobe, /model_lobe or a surface's /lobe is not of the suite's (max_k + 2) x " +
                                std::to_string(suite.lobe_bins) + " cells");
      },
      std::move(descriptor));
}

ProfilesRun profiles_run_from(const ProfilesSuite&, const std::vector<UnitResult<ProfilesWork>>& results) {
  ProfilesRun run;
  for (const auto& r : results) run.cases.push_back(r.tally);
  run.pass = std::all_of(run.cases.begin(), run.cases.end(), [](const ProfilesOutcome& o) { return o.pass; });
  return run;
}

ProfilesRun run_profiles_suite(const ProfilesSuite& suite, long rays, int threads, const support::ProgressFn& progress,
                               const std::atomic<bool>* cancel) {
  const auto t0 = Clock::now();
  const auto results = run_job(profiles_job(suite, rays, {}, cancel), threads, progress, cancel);
  ProfilesRun run;
  if (results) run = profiles_run_from(suite, *results);
  run.threads = support::resolve_threads(threads);
  run.wall_s = seconds_since(t0);
  run.interrupted = !results;
  run.pass = run.pass && !run.interrupted;
  return run;
}

}  // namespace vgroove::validation
