#include "vgroove/validation/heightfield_suite.h"

#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/seconds_since.h"
#include "vgroove/validation/check_brdf.h"
#include "vgroove/validation/energy_lobe_shape.h"
#include "vgroove/validation/heightfield_lobe.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

// Streams of the suite's seed: fields, rays, walks.
constexpr std::uint64_t kFieldSeeds = 0x6866666965ULL, kRaySeeds = 0x6866726179ULL, kWalkSeeds = 0x686677616bULL;
// Tracer rows k = 0..kMaxK and one beyond: k = 1, 2 and 3+ are rows 1..3.
constexpr int kMaxK = kHeightfieldRows - 1;
// The smallest field: the correlation length's range [2, n / 8] is not empty.
constexpr int kMinFieldSize = 16;

struct CaseIndex {
  std::size_t ndf, aspect, alpha, theta;
};
CaseIndex index_of(const HeightfieldSuite& s, std::size_t c) {
  const std::size_t nt = s.theta_i_deg.size(), na = s.alphas.size(), nr = s.aspects.size();
  return {c / (nt * na * nr), (c / (nt * na)) % nr, (c / nt) % na, c % nt};
}

// Smith walk height distributions by name ("walk_heights"), in analytic::WalkHeights order.
const std::vector<std::string> kWalkHeightNames = {"log_c1", "uniform", "gaussian"};

// Per-bin mean over the fields ([r][b]) and standard error: the fields' spread, at least the
// multinomial error of all `rays` (p the mean).
void mean_and_se(const std::vector<std::vector<double>>& v, double rays, std::vector<double>& mean,
                 std::vector<double>& se) {
  const std::size_t nb = v.front().size();
  const double n = static_cast<double>(v.size());
  mean.assign(nb, 0.0), se.assign(nb, 0.0);
  for (std::size_t b = 0; b < nb; ++b) {
    double s = 0.0;
    for (const auto& r : v) s += r[b];
    const double m = s / n;
    double var = 0.0;
    for (const auto& r : v) var += (r[b] - m) * (r[b] - m);
    const double spread = v.size() >= 2 ? std::sqrt(var / (n - 1.0) / n) : 0.0;
    const double p = std::clamp(m, 0.0, 1.0);
    mean[b] = m;
    se[b] = std::max(spread, std::sqrt(p * (1.0 - p) / rays));
  }
}

std::vector<double> multinomial_var(const std::vector<double>& p, double n) {
  std::vector<double> v;
  for (double q : p) v.push_back(std::max(0.0, q * (1.0 - q)) / n);
  return v;
}

std::vector<double> row_sums(const std::vector<double>& joint, int rows, int bins) {
  std::vector<double> e(static_cast<std::size_t>(rows), 0.0);
  for (int r = 0; r < rows; ++r)
    for (int b = 0; b < bins; ++b) e[static_cast<std::size_t>(r)] += joint[static_cast<std::size_t>(r * bins + b)];
  return e;
}

}  // namespace

const char* heightfield_model_name(HeightfieldModel m) {
  switch (m) {
    case HeightfieldModel::smith_walk:
      return "smith_walk";
    case HeightfieldModel::cook_torrance_smith:
      return "cook_torrance_smith";
    case HeightfieldModel::vgroove:
      return "vgroove";
  }
  return "?";
}

HeightfieldCase HeightfieldSuite::case_at(std::size_t c) const {
  const CaseIndex ix = index_of(*this, c);
  return {ndfs[ix.ndf], alphas[ix.alpha], theta_i_deg[ix.theta], aspects[ix.aspect]};
}

HeightfieldSuite parse_heightfield_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  HeightfieldSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"heightfield"});
  for (const auto& n : read_names(root, "ndf", {"beckmann", "ggx"}))
    s.ndfs.push_back(n == "ggx" ? analytic::NdfKind::ggx : analytic::NdfKind::beckmann);
  s.alphas = read_numbers(root, "alpha", kMinAlpha, true, kMaxAlpha, true);
  s.theta_i_deg = read_numbers(root, "theta_i_deg", 0.0, true, kMaxSurfaceThetaIDeg, true);
  s.field_size = static_cast<int>(root.integer("field_size", kMinFieldSize, 65536));
  if ((s.field_size & (s.field_size - 1)) != 0)
    root.fail("field_size", "= " + std::to_string(s.field_size) + " must be a power of two in [16, 65536]");
  const std::string gaussian = "gaussian";
  if (root.one_of("surface", {"gaussian", "grooves"}, &gaussian) == "grooves")
    s.surface = HeightfieldSurfaceKind::grooves;
  s.correlation_length = root.number("correlation_length", 2.0, true, s.field_size / 8.0, true);
  if (s.surface == HeightfieldSurfaceKind::grooves && s.field_size > 4096)
    root.fail("field_size",
              "= " + std::to_string(s.field_size) +
                  " must be a power of two in [16, 4096] with surface grooves (sim/heightfield_grooves.h)");
  if (s.surface == HeightfieldSurfaceKind::grooves && s.correlation_length > s.field_size / 12.0)
    root.fail("correlation_length",
              support::format("= %g must be in [2, %g] (field_size / 12) with surface grooves: grooves 3 l long "
                              "and 3 l apart, at most field_size / 4",
                              s.correlation_length, s.field_size / 12.0));
  s.aspect_list = root.has("aspect") && root.raw("aspect").is_array();
  s.aspects = s.aspect_list ? read_numbers(root, "aspect", 0.25, true, 4.0, true)
                            : std::vector<double>{root.number_or("aspect", 1.0, 0.25, true, 4.0, true)};
  for (std::size_t q = 0; q < s.aspects.size(); ++q) {
    const double aspect = s.aspects[q];
    if (aspect == 1.0) continue;
    const auto fail = [&](const std::string& why) {
      const std::string what = support::format("= %g (anisotropic) ", aspect) + why;
      if (s.aspect_list) root.fail_at("aspect", q, what);
      root.fail("aspect", what);
    };
    for (auto n : s.ndfs)
      if (n != analytic::NdfKind::beckmann) fail("needs ndf [\"beckmann\"] only: the GGX fields are isotropic");
    if (s.surface != HeightfieldSurfaceKind::gaussian) fail("needs surface gaussian: the groove fields are isotropic");
    for (double a : s.alphas) {
      sim::GaussianHeightfieldOptions o;
      o.n = s.field_size, o.alpha_x = a, o.alpha_y = a * aspect, o.correlation_length = s.correlation_length;
      try {
        (void)sim::gaussian_heightfield_parameters(o);
      } catch (const std::invalid_argument& e) {
        fail(support::format("with alpha %g and correlation_length %g: ", a, s.correlation_length) + e.what());
      }
    }
  }
  if (root.has("walk_heights")) {
    const std::vector<std::string> names = read_names(root, "walk_heights", kWalkHeightNames);
    s.walk_heights.clear();
    for (std::size_t n = 0; n < names.size(); ++n) {
      const auto h = static_cast<analytic::WalkHeights>(
          std::find(kWalkHeightNames.begin(), kWalkHeightNames.end(), names[n]) - kWalkHeightNames.begin());
      if (std::find(s.walk_heights.begin(), s.walk_heights.end(), h) != s.walk_heights.end())
        root.fail_at("walk_heights", n, "= \"" + names[n] + "\" is given twice: each distribution once");
      s.walk_heights.push_back(h);
    }
  }
  s.fields = static_cast<int>(root.integer("fields", 2, 1000));
  s.rays = static_cast<long>(root.integer("rays", 1, kMaxRays));
  s.walk_paths = static_cast<long>(root.integer("walk_paths", 1, kMaxRays));
  s.theta_bins = static_cast<int>(root.integer_or("theta_bins", s.theta_bins, 1, kMaxCheckBrdfThetaBins));
  s.phi_bins = static_cast<int>(root.integer_or("phi_bins", s.phi_bins, 2, kMaxCheckBrdfPhiBins));
  if (s.phi_bins % 2 != 0)
    root.fail("phi_bins",
              "= " + std::to_string(s.phi_bins) + " must be even (the plane of incidence runs through two bins)");
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, kMaxSeed));
  {
    support::JsonObject t = root.object("thresholds");
    s.sigmas = t.number("sigmas", 0.0, false, kMaxSigmas, true);
    s.model_tolerance = t.number_or("model_tolerance", s.model_tolerance, 0.0, true, 1.0, true);
    t.finish();
  }
  if (root.has("controls")) {
    const nlohmann::json& cs = root.raw("controls");
    if (!cs.is_array()) root.fail("controls", "must be an array of {model, ndf, alpha, theta_i_deg}");
    for (std::size_t n = 0; n < cs.size(); ++n) {
      support::JsonObject c(cs[n], file, root.path("controls") + "/" + std::to_string(n));
      const std::string model = c.one_of("model", {"smith_walk", "cook_torrance_smith", "vgroove"});
      const std::string ndf = c.one_of("ndf", {"beckmann", "ggx"});
      const double alpha = c.number("alpha", kMinAlpha, true, kMaxAlpha, true);
      const double theta = c.number("theta_i_deg", 0.0, true, kMaxSurfaceThetaIDeg, true);
      // Its aspect: required when the suite has several.
      const double aspect = c.number_or("aspect", s.aspects.front(), 0.25, true, 4.0, true);
      if (s.aspects.size() > 1 && !c.has("aspect"))
        root.fail_at("controls", n, "needs an aspect: the suite has several");
      c.finish();
      HeightfieldControl ctl;
      ctl.model = model == "smith_walk"            ? HeightfieldModel::smith_walk
                  : model == "cook_torrance_smith" ? HeightfieldModel::cook_torrance_smith
                                                   : HeightfieldModel::vgroove;
      bool found = false;
      for (std::size_t k = 0; k < s.cases() && !found; ++k) {
        const HeightfieldCase hc = s.case_at(k);
        if (analytic::ndf_name(hc.ndf) == ndf && hc.alpha == alpha && hc.theta_i_deg == theta && hc.aspect == aspect)
          ctl.case_index = k, found = true;
      }
      if (!found)
        root.fail_at("controls", n,
                     "names no case of the suite (ndf " + ndf + ", alpha " + support::number_text(alpha) +
                         ", theta_i_deg " + support::number_text(theta) +
                         (s.aspects.size() > 1 ? ", aspect " + support::number_text(aspect) : std::string()) +
                         "): a control must be one of its cases");
      if (aspect != 1.0 && ctl.model != HeightfieldModel::smith_walk)
        root.fail_at("controls", n,
                     "model " + model + " is skipped when aspect != 1 (isotropic here): only smith_walk");
      s.controls.push_back(ctl);
    }
  }
  if (root.has("masking")) {
    if (s.anisotropic())
      root.fail("masking", "is not measured when aspect != 1 (its models are isotropic here): drop it or set aspect 1");
    support::JsonObject m = root.object("masking");
    s.masking = parse_heightfield_masking(m, s);
  }
  root.finish();
  return s;
}

HeightfieldMiss heightfield_miss(const std::vector<double>& lobe, const std::vector<double>& lobe_se,
                                 const std::vector<double>& energy, const std::vector<double>& energy_se,
                                 const std::vector<double>& model, const std::vector<double>& model_var,
                                 const std::vector<double>& model_energy, const std::vector<double>& model_energy_var,
                                 int rows, int bins, double sigmas, double tolerance) {
  HeightfieldMiss m;
  double mean_t = 0.0, var_t = 0.0;
  m.within_noise = true;
  for (int r = 0; r < rows; ++r) {
    double l1_r = 0.0, mean_r = 0.0, var_r = 0.0;
    for (int b = 0; b < bins; ++b) {
      const auto n = static_cast<std::size_t>(r * bins + b);
      const double v = lobe_se[n] * lobe_se[n] + (model_var.empty() ? 0.0 : model_var[n]);
      l1_r += std::abs(lobe[n] - model[n]);
      mean_r += std::sqrt(2.0 * v / std::numbers::pi);
      var_r += (1.0 - 2.0 / std::numbers::pi) * v;
    }
    const double thr = mean_r + sigmas * std::sqrt(var_r) + tolerance;
    m.l1.push_back(l1_r), m.l1_expected.push_back(mean_r), m.l1_threshold.push_back(thr);
    m.l1_total += l1_r, mean_t += mean_r, var_t += var_r;
    const auto q = static_cast<std::size_t>(r);
    const double ev = energy_se[q] * energy_se[q] + (model_energy_var.empty() ? 0.0 : model_energy_var[q]);
    const double diff = energy[q] - model_energy[q], ethr = sigmas * std::sqrt(ev) + tolerance;
    m.energy.push_back(model_energy[q]), m.energy_diff.push_back(diff), m.energy_threshold.push_back(ethr);
    // NaN (a non-finite side) is never within.
    m.within_noise = m.within_noise && l1_r <= thr && std::abs(diff) <= ethr;
  }
  m.l1_total_expected = mean_t;
  m.l1_total_threshold = mean_t + sigmas * std::sqrt(var_t) + tolerance * rows;
  m.within_noise = m.within_noise && m.l1_total <= m.l1_total_threshold;
  return m;
}

HeightfieldOutcome run_heightfield_case(const HeightfieldSuite& suite, std::size_t case_index, long rays,
                                        const std::atomic<bool>* cancel) {
  HeightfieldOutcome out;
  out.c = suite.case_at(case_index);
  const CaseIndex ix = index_of(suite, case_index);
  const double theta_i = deg_to_rad(out.c.theta_i_deg);
  const int bins = suite.bins(), rows = kHeightfieldRows;
  const HeightfieldFieldSpec spec{out.c.ndf,     out.c.alpha, suite.field_size, suite.correlation_length,
                                  suite.surface, out.c.aspect};

  // The fields: one at a time, each from its own seed (the same fields at every theta_i).
  std::vector<std::vector<double>> lobes, energies;
  HeightfieldMaskingFields masking;
  for (int r = 0; r < suite.fields; ++r) {
    if (support::cancelled(cancel)) return out;
    auto t0 = Clock::now();
    // The first aspect's keys are the keys before "aspect" was a list.
    const std::uint64_t key = ((static_cast<std::uint64_t>(ix.aspect) * 16 + ix.ndf) * 4096 + ix.alpha) * 65536 +
                              static_cast<std::uint64_t>(r);
    const sim::HeightfieldSurface s = make_field_surface(spec, sim::derived_seed(suite.seed, kFieldSeeds, key));
    out.field_s += seconds_since(t0);
    t0 = Clock::now();
    const sim::HeightfieldTally t = trace_field(
        s, theta_i, rays, sim::derived_seed(suite.seed, kRaySeeds, case_index * 65536 + static_cast<std::uint64_t>(r)),
        suite.theta_bins, suite.phi_bins, kMaxK, cancel);
    out.trace_s += seconds_since(t0);
    if (suite.masking) {
      t0 = Clock::now();
      trace_masking_field(suite, case_index, r, s, masking, cancel);
      out.masking_s += seconds_since(t0);
    }
    if (support::cancelled(cancel)) return out;
    out.rays += t.rays, out.lost += t.lost, out.bounce_limit += t.bounce_limit;
    out.edge_hits += t.edge_hits, out.vertex_hits += t.vertex_hits, out.bounces += t.bounces;
    lobes.push_back(joint_fractions(t, 1));
    std::vector<double> e;
    for (int q = 1; q <= rows; ++q)
      e.push_back(t.energy_by_k[static_cast<std::size_t>(q)] / static_cast<double>(t.rays));
    energies.push_back(std::move(e));
  }
  const double n_rays = static_cast<double>(out.rays);
  mean_and_se(lobes, n_rays, out.lobe, out.lobe_se);
  mean_and_se(energies, n_rays, out.energy, out.energy_se);
  {
    std::vector<std::vector<double>> albedos;
    for (const auto& e : energies) albedos.push_back({sum(e)});
    std::vector<double> a, ase;
    mean_and_se(albedos, n_rays, a, ase);
    out.albedo = a[0], out.albedo_se = ase[0];
  }

  // The Smith walk, once per height distribution, each from its own stream (log C1's the stream
  // before "walk_heights" existed): independent walks, so that their agreement is a measurement.
  const bool anisotropic = out.c.aspect != 1.0;
  const auto walk_of = [&](analytic::WalkHeights h) {
    const std::uint64_t walk_seed =
        sim::derived_seed(suite.seed, kWalkSeeds, case_index + (static_cast<std::uint64_t>(h) << 40));
    if (!anisotropic && h == analytic::WalkHeights::log_c1)
      return walk_lobe(out.c.ndf, out.c.alpha, theta_i, suite.walk_paths, walk_seed, suite.theta_bins, suite.phi_bins,
                       kMaxK, cancel);
    return walk_lobe(analytic::Roughness{out.c.ndf, out.c.alpha, out.c.alpha * out.c.aspect}, h, theta_i,
                     suite.walk_paths, walk_seed, suite.theta_bins, suite.phi_bins, kMaxK, cancel);
  };
  auto t0 = Clock::now();
  const sim::HeightfieldTally w = walk_of(suite.walk_heights.front());
  if (support::cancelled(cancel)) return out;
  out.walk_paths = w.rays, out.walk_left = w.escaped;
  out.walk_lobe = joint_fractions(w, 1);
  out.walk_energy = row_sums(out.walk_lobe, rows, bins);
  const double first_paths = static_cast<double>(out.walk_paths);
  std::vector<double> first_se = multinomial_var(out.walk_lobe, first_paths),
                      first_energy_se = multinomial_var(out.walk_energy, first_paths);
  for (double& v : first_se) v = std::sqrt(v);
  for (double& v : first_energy_se) v = std::sqrt(v);
  for (std::size_t h = 1; h < suite.walk_heights.size(); ++h) {
    const sim::HeightfieldTally wh = walk_of(suite.walk_heights[h]);
    if (support::cancelled(cancel)) return out;
    HeightfieldOtherWalk ow;
    ow.heights = analytic::walk_heights_name(suite.walk_heights[h]);
    ow.paths = wh.rays, ow.left = wh.escaped;
    ow.lobe = joint_fractions(wh, 1);
    ow.energy = row_sums(ow.lobe, rows, bins);
    const double p = static_cast<double>(ow.paths);
    const std::vector<double> var = multinomial_var(ow.lobe, p), energy_var = multinomial_var(ow.energy, p);
    // The first walk's rule, model_tolerance included (without it a smooth field's E_1 = 1 with no
    // spread would have a threshold of 0).
    ow.against_traced = heightfield_miss(out.lobe, out.lobe_se, out.energy, out.energy_se, ow.lobe, var, ow.energy,
                                         energy_var, rows, bins, suite.sigmas, suite.model_tolerance);
    ow.against_first = heightfield_miss(out.walk_lobe, first_se, out.walk_energy, first_energy_se, ow.lobe, var,
                                        ow.energy, energy_var, rows, bins, suite.sigmas, suite.model_tolerance);
    out.other_walks.push_back(std::move(ow));
  }
  out.walk_s = seconds_since(t0);
  bool walks_finite = all_finite(out.walk_lobe);
  for (const HeightfieldOtherWalk& ow : out.other_walks) walks_finite = walks_finite && all_finite(ow.lobe);

  // Cook-Torrance with Smith's height-correlated G, over the bins as check_brdf integrates it, and
  // the V-groove model's lobe (Eq. 16, k = 1, 2, 3+): isotropic, skipped when the suite is not.
  const double tol = suite.model_tolerance;
  const double paths = static_cast<double>(out.walk_paths);
  out.walk = heightfield_miss(out.lobe, out.lobe_se, out.energy, out.energy_se, out.walk_lobe,
                              multinomial_var(out.walk_lobe, paths), out.walk_energy,
                              multinomial_var(out.walk_energy, paths), rows, bins, suite.sigmas, 0.0);
  if (anisotropic) {
    out.non_finite = !(all_finite(out.lobe) && walks_finite && std::isfinite(out.albedo));
    out.pass = out.lost == 0 && !out.non_finite;
    return out;
  }
  t0 = Clock::now();
  CheckBrdfOptions co;
  co.ndf = out.c.ndf, co.alpha = out.c.alpha, co.theta_i_deg = {out.c.theta_i_deg};
  co.theta_bins = suite.theta_bins, co.phi_bins = suite.phi_bins, co.model_tolerance = suite.model_tolerance;
  co.threads = 1, co.cancel = cancel;
  const analytic::MicrofacetModel smith{out.c.ndf, analytic::MaskingKind::smith_height_correlated};
  const double alpha = out.c.alpha;
  const BrdfFn ct = [&](const analytic::Dir3& i, const analytic::Dir3& o) {
    return single_scattering_brdf(smith, alpha, i, o);
  };
  const ModelLobe ml = integrate_model_lobe(batch_of(ct), out.c.theta_i_deg, co);
  if (support::cancelled(cancel)) return out;
  out.ct_lobe = ml.flux, out.ct_error = ml.error;
  analytic::Lobe3dOptions lo;
  lo.cancel = cancel;
  const analytic::Lobe3d v =
      analytic::vgroove_lobe_3d(out.c.ndf, out.c.alpha, theta_i, suite.theta_bins, suite.phi_bins, kMaxK, lo);
  if (support::cancelled(cancel)) return out;
  out.vgroove_lobe.assign(v.hist_by_k.begin() + bins, v.hist_by_k.end());
  out.vgroove_energy.assign(v.by_k.begin() + 1, v.by_k.end());
  out.model_s = seconds_since(t0);

  out.cook_torrance = heightfield_miss(out.lobe, out.lobe_se, out.energy, out.energy_se, out.ct_lobe, {},
                                       {sum(out.ct_lobe)}, {}, 1, bins, suite.sigmas, tol + out.ct_error);
  out.vgroove = heightfield_miss(out.lobe, out.lobe_se, out.energy, out.energy_se, out.vgroove_lobe, {},
                                 out.vgroove_energy, {}, rows, bins, suite.sigmas, tol);
  if (suite.masking) {
    t0 = Clock::now();
    finish_masking(suite, masking, out);
    out.masking_s += seconds_since(t0);
  }
  bool masking_finite = true;
  for (const auto* list : {&out.g1, &out.g2})
    for (const HeightfieldMaskingValue& mv : *list) masking_finite = masking_finite && std::isfinite(mv.g);
  out.non_finite =
      !masking_finite || !(all_finite(out.lobe) && walks_finite && all_finite(out.ct_lobe) &&
                           all_finite(out.vgroove_lobe) && all_finite(out.vgroove_energy) && std::isfinite(out.albedo));
  out.pass = out.lost == 0 && out.masking_lost == 0 && !out.non_finite;
  return out;
}

double heightfield_run_memory_bytes(const HeightfieldSuite& suite, int threads) {
  const double cases = static_cast<double>(suite.cases());
  const double workers = std::min<double>(support::resolve_threads(threads), cases);
  check_field_fits(suite.field_size, workers, suite.file + ": /field_size", kMinFieldSize);
  const double joint = static_cast<double>(suite.bins()) * (kHeightfieldRows + 1) * 8.0;
  // Per worker its field and hierarchy (also the synthesis' peak) and tallies; per case its lobes.
  // The masking tallies: 5 doubles per bin per field and theta_o or pair, and the outcome's values.
  const double masking = suite.masking
                             ? static_cast<double>(suite.masking->bins()) * 48.0 *
                                   static_cast<double>(suite.masking->theta_o_deg.size() + suite.masking->pairs()) *
                                   (suite.fields + 8.0)
                             : 0.0;
  const double walks = static_cast<double>(suite.walk_heights.size());
  return workers * (sim::heightfield_bytes(suite.field_size) + 4.0 * joint + masking) +
         cases * (joint * (6.0 + 2.0 * walks + 2.0 * suite.fields) + masking);
}

Job<HeightfieldWork> heightfield_job(const HeightfieldSuite& suite, long rays, nlohmann::json descriptor,
                                     const std::atomic<bool>* cancel) {
  const long n_rays = rays > 0 ? rays : suite.rays;
  return item_job<HeightfieldOutcome>(
      suite.cases(), [suite, n_rays, cancel](std::size_t c) { return run_heightfield_case(suite, c, n_rays, cancel); },
      [suite](support::JsonObject& o, std::size_t c, HeightfieldOutcome& out) {
        out.c = suite.case_at(c);
        const std::size_t joint = static_cast<std::size_t>(kHeightfieldRows) * static_cast<std::size_t>(suite.bins());
        const std::size_t bins = static_cast<std::size_t>(suite.bins()), rows = kHeightfieldRows;
        const std::size_t iso = out.c.aspect != 1.0 ? 0 : 1;  // the isotropic models: skipped
        bool walks_shaped = out.other_walks.size() + 1 == suite.walk_heights.size();
        for (const HeightfieldOtherWalk& w : out.other_walks)
          walks_shaped = walks_shaped && w.lobe.size() == joint && w.energy.size() == rows &&
                         w.against_traced.l1.size() == rows && w.against_first.l1.size() == rows;
        if (out.lobe.size() != joint || out.lobe_se.size() != joint || out.walk_lobe.size() != joint ||
            out.vgroove_lobe.size() != iso * joint || out.ct_lobe.size() != iso * bins || out.energy.size() != rows ||
            out.energy_se.size() != rows || out.walk_energy.size() != rows || out.vgroove_energy.size() != iso * rows ||
            out.g1.size() != (suite.masking ? suite.masking->theta_o_deg.size() : 0) ||
            out.g2.size() != (suite.masking ? suite.masking->pairs() : 0) || !walks_shaped)
          o.fail(
              "outcome",
              "/lobe, /walk_lobe, /vgroove_lobe, /ct_lobe an energy, /g1, /g2 or /other_walks is not of the suite's " +
                  std::to_string(kHeightfieldRows) + " rows x " + std::to_string(bins) + " bins");
      },
      std::move(descriptor),
      [&suite, n_rays](std::size_t) {
        // A masking point costs about one ray (G1) or two (G2), a short one.
        const std::int64_t mask =
            suite.masking
                ? static_cast<std::int64_t>(suite.masking->points) * suite.fields *
                      static_cast<std::int64_t>(suite.masking->theta_o_deg.size() + 2 * suite.masking->pairs()) / 4
                : 0;
        return static_cast<std::int64_t>(n_rays) * suite.fields +
               static_cast<std::int64_t>(suite.walk_paths) * static_cast<std::int64_t>(suite.walk_heights.size()) +
               mask;
      });
}

HeightfieldRun heightfield_run_from(const HeightfieldSuite& suite,
                                    const std::vector<UnitResult<HeightfieldWork>>& results) {
  HeightfieldRun run;
  for (const auto& r : results) run.cases.push_back(r.tally);
  run.pass = std::all_of(run.cases.begin(), run.cases.end(), [](const HeightfieldOutcome& o) { return o.pass; });
  for (const HeightfieldControl& c : suite.controls) {
    const HeightfieldOutcome& o = run.cases[c.case_index];
    const HeightfieldMiss& m = c.model == HeightfieldModel::smith_walk            ? o.walk
                               : c.model == HeightfieldModel::cook_torrance_smith ? o.cook_torrance
                                                                                  : o.vgroove;
    run.controls_hold.push_back(m.within_noise);
    run.pass = run.pass && m.within_noise;
  }
  if (suite.masking)
    for (const HeightfieldMaskingControl& c : suite.masking->controls) {
      const bool held = masking_control_holds(c, run.cases[c.case_index]);
      run.masking_controls_hold.push_back(held);
      run.pass = run.pass && held;
    }
  return run;
}

HeightfieldRun run_heightfield_suite(const HeightfieldSuite& suite, long rays, int threads,
                                     const support::ProgressFn& progress, const std::atomic<bool>* cancel) {
  const auto t0 = Clock::now();
  const auto results = run_job(heightfield_job(suite, rays, {}, cancel), threads, progress, cancel);
  HeightfieldRun run;
  if (results) run = heightfield_run_from(suite, *results);
  run.threads = support::resolve_threads(threads);
  run.wall_s = seconds_since(t0);
  run.interrupted = !results;
  run.pass = run.pass && !run.interrupted;
  return run;
}

}  // namespace vgroove::validation
