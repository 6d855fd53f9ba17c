#include "vgroove/validation/energy_lobe_shape.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/compensation.h"
#include "vgroove/analytic/ndf.h"
#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/format.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/seconds_since.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/lobe_comparison.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/traced_lobe.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::validation {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::uint64_t kLobeWalkStream = 0x6c6f62655f77616cULL;  // "lobe_wal"
// The V-groove model's orders: one pass visits only those Eq. (4) allows, so this costs nothing.
constexpr int kAllOrders = 1'000'000;
// The walk's grooves in the noise bound: none (1/G = 0 to rounding).
constexpr double kNoGrooves = 1e300;

// The Smith walk's exits from wi = dir3(theta_i, pi), binned as the traced surface's
// (sim::Microsurface3dTally's bins), one item per (incidence, chunk of kRaysPerChunk walks); k = 1
// apart, as trace_lobes gives it with LobeSetup::k1.
std::vector<TracedLobe> walk_lobes(const LobeShapeOptions& o, double alpha, const std::vector<double>& theta_i,
                                   int threads) {
  const std::int64_t chunks = (static_cast<std::int64_t>(o.rays) + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
  const std::size_t items = theta_i.size() * static_cast<std::size_t>(chunks);
  std::vector<sim::Microsurface3dTally> tallies(items);
  std::vector<double> secs(items, 0.0);
  const bool complete = support::parallel_for(
      items, threads,
      [&](std::size_t item) {
        const auto t0 = support::Clock::now();
        const std::size_t c = item / static_cast<std::size_t>(chunks);
        const std::int64_t chunk = static_cast<std::int64_t>(item % static_cast<std::size_t>(chunks));
        const analytic::Dir3 wi = analytic::dir3(theta_i[c], kPi);
        sim::Microsurface3dTally t(o.theta_bins, o.phi_bins, 1);
        sim::Rng rng(sim::splitmix64(o.seed ^ kLobeWalkStream), c, static_cast<std::uint64_t>(chunk));
        auto uniform = [&rng] { return sim::uniform_open(rng); };
        const std::int64_t first = chunk * sim::kRaysPerChunk,
                           last = std::min<std::int64_t>(o.rays, first + sim::kRaysPerChunk);
        for (std::int64_t p = first; p < last; ++p) {
          const analytic::Walk3d w = analytic::smith_walk_3d(o.ndf, alpha, wi, uniform);
          if (!w.left) {
            t.count(sim::Termination::bounce_limit, w.k, false);
            continue;
          }
          const int tb = t.theta_bin_of(analytic::polar_angle(w.o));
          const int pb = t.phi_bin_of(std::atan2(w.o.y, w.o.x));
          t.add_binned(sim::Termination::escaped, w.k, true, tb, pb);
        }
        tallies[item] = std::move(t);
        secs[item] = support::seconds_since(t0);
      },
      {}, o.cancel, 1);
  if (!complete) return {};
  const std::size_t bins = static_cast<std::size_t>(o.theta_bins) * static_cast<std::size_t>(o.phi_bins);
  std::vector<TracedLobe> out(theta_i.size());
  for (std::size_t c = 0; c < theta_i.size(); ++c) {
    std::vector<std::int64_t> sum(bins, 0), sum_k1(bins, 0);
    for (std::int64_t k = 0; k < chunks; ++k) {
      const std::size_t item = c * static_cast<std::size_t>(chunks) + static_cast<std::size_t>(k);
      const sim::Microsurface3dTally& t = tallies[item];
      for (std::size_t n = 0; n < bins; ++n) sum[n] += t.hist[n], sum_k1[n] += t.hist_by_k[bins + n];
      out[c].rays += t.rays;
      out[c].thread_s += secs[item];
    }
    out[c].flux = fractions(sum, static_cast<double>(out[c].rays));
    out[c].flux_k1 = fractions(sum_k1, static_cast<double>(out[c].rays));
  }
  return out;
}

}  // namespace

const char* compensated_lobe_name(CompensatedLobe lobe) {
  switch (lobe) {
    case CompensatedLobe::single:
      return "single";
    case CompensatedLobe::kulla_conty:
      return "kulla_conty";
    case CompensatedLobe::view_scaled:
      return "view_scaled";
  }
  return "?";
}

double AlbedoCurve::operator()(double mu) const {
  const double x = std::sqrt(std::clamp(mu, 0.0, 1.0)) * static_cast<double>(E.size() - 1);
  const std::size_t j = std::min(static_cast<std::size_t>(x), E.size() - 2);
  const double f = x - static_cast<double>(j);
  return (1.0 - f) * E[j] + f * E[j + 1];
}

AlbedoCurve albedo_curve(const analytic::MicrofacetModel& m, double alpha, int points) {
  AlbedoCurve c;
  const double step = 1.0 / (points - 1);
  const auto E = [&](double x) { return analytic::albedo_single(m, alpha, std::max(x * x, 1e-6 * step)).value; };
  for (int j = 0; j < points; ++j) c.E.push_back(E(j * step));
  for (int j = 0; j + 1 < points; ++j) {
    const double x = (j + 0.5) * step;
    c.interpolation_error = std::max(c.interpolation_error, std::abs(c(x * x) - E(x)));
  }
  c.E_avg = analytic::albedo_average(m, alpha).value;
  return c;
}

double single_scattering_brdf(const analytic::MicrofacetModel& m, double alpha, const analytic::Dir3& i,
                              const analytic::Dir3& o) {
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  if (m.masking == analytic::MaskingKind::vcavity) return analytic::cook_torrance(i, o, m.ndf, alpha);
  const analytic::Dir3 h{i.x + o.x, i.y + o.y, i.z + o.z};
  const double g2 = 1.0 / (1.0 + analytic::Lambda(m.ndf, analytic::polar_angle(i), alpha) +
                           analytic::Lambda(m.ndf, analytic::polar_angle(o), alpha));
  return analytic::D(m.ndf, analytic::polar_angle(h), alpha) * g2 / (4.0 * i.z * o.z);
}

double compensated_brdf(CompensatedLobe lobe, const analytic::MicrofacetModel& m, double alpha,
                        const AlbedoCurve& curve, const analytic::Dir3& i, const analytic::Dir3& o) {
  const double f = single_scattering_brdf(m, alpha, i, o);
  if (i.z <= 0.0 || o.z <= 0.0) return 0.0;
  switch (lobe) {
    case CompensatedLobe::single:
      return f;
    case CompensatedLobe::kulla_conty:
      return f + analytic::kulla_conty_f_ms(curve(o.z), curve(i.z), curve.E_avg);
    case CompensatedLobe::view_scaled:
      // Turquin's 1 + F0 (1 - E_o) / E_o at F0 = 1 (analytic::turquin_factor).
      return f * analytic::turquin_factor(1.0, curve(o.z));
  }
  return 0.0;
}

namespace {

CheckBrdfOptions check_options_of(const LobeShapeOptions& opt) {
  CheckBrdfOptions base;
  base.ndf = opt.ndf, base.theta_i_deg = opt.theta_i_deg, base.dim = SurfaceDim::three_d;
  base.rays = opt.rays, base.grooves = opt.grooves, base.seed = opt.seed;
  base.theta_bins = opt.theta_bins, base.phi_bins = opt.phi_bins;
  base.sigmas = opt.sigmas, base.model_tolerance = opt.model_tolerance, base.threads = opt.threads;
  base.cancel = opt.cancel;
  return base;
}

}  // namespace

void check_lobe_shape_options(const LobeShapeOptions& opt) {
  if (opt.ndf != NdfKind::ggx && opt.ndf != NdfKind::beckmann)
    throw support::UserError(std::string("ndf = ") + ndf_name(opt.ndf) +
                             ": the lobe shapes take ggx or beckmann (the Smith walk's Lambda)");
  if (opt.alpha.empty()) throw support::UserError("alpha: give at least one roughness");
  CheckBrdfOptions o = check_options_of(opt);
  for (double a : opt.alpha) {
    o.alpha = a;
    check_options(o);
  }
}

LobeShapeResult audit_lobe_shapes(const LobeShapeOptions& opt) {
  check_lobe_shape_options(opt);
  const CheckBrdfOptions base = check_options_of(opt);

  LobeShapeResult res;
  res.options = opt;
  const auto t0 = support::Clock::now();
  const int threads = support::resolve_threads(opt.threads);
  std::vector<double> theta_i;
  for (double d : opt.theta_i_deg) theta_i.push_back(deg_to_rad(d));
  const std::vector<CompensatedLobe> lobes = {CompensatedLobe::single, CompensatedLobe::kulla_conty,
                                              CompensatedLobe::view_scaled};
  res.controls_pass = true;
  for (double alpha : opt.alpha) {
    CheckBrdfOptions o = base;
    o.alpha = alpha;
    const analytic::MicrofacetModel vcavity{opt.ndf, analytic::MaskingKind::vcavity};
    const analytic::MicrofacetModel smith{opt.ndf, analytic::MaskingKind::smith_height_correlated};
    const AlbedoCurve curve_v = albedo_curve(vcavity, alpha), curve_s = albedo_curve(smith, alpha);
    res.max_interpolation_error =
        std::max({res.max_interpolation_error, curve_v.interpolation_error, curve_s.interpolation_error});

    // The models, one work item per (incidence, model): the three lobes over each reference's
    // f_ss, and the V-groove model.
    struct Model {
      const char* reference;
      std::string lobe;
      BrdfFn f;
    };
    std::vector<Model> models;
    for (CompensatedLobe l : lobes) {
      models.push_back({"vgroove_surface", compensated_lobe_name(l), [=, &curve_v](const auto& i, const auto& w) {
                          return compensated_brdf(l, vcavity, alpha, curve_v, i, w);
                        }});
      models.push_back({"smith_walk", compensated_lobe_name(l), [=, &curve_s](const auto& i, const auto& w) {
                          return compensated_brdf(l, smith, alpha, curve_s, i, w);
                        }});
    }
    models.push_back({"vgroove_surface", "vgroove_model", [=, ndf = opt.ndf](const auto& i, const auto& w) {
                        return analytic::vgroove_brdf(i, w, ndf, alpha, kAllOrders);
                      }});
    const std::size_t M = models.size(), items = theta_i.size() * M;
    std::vector<ModelLobe> integrated(items);
    const bool complete = support::parallel_for(
        items, threads,
        [&](std::size_t item) {
          integrated[item] = integrate_model_lobe(batch_of(models[item % M].f), opt.theta_i_deg[item / M], o);
        },
        {}, opt.cancel, 1);
    LobeSetup setup;
    setup.ndf = opt.ndf, setup.alpha = alpha, setup.dim = SurfaceDim::three_d, setup.rays = opt.rays;
    setup.grooves = opt.grooves, setup.seed = opt.seed, setup.theta_bins = opt.theta_bins;
    setup.phi_bins = opt.phi_bins, setup.k1 = true;
    const std::vector<TracedLobe> traced =
        complete ? trace_lobes(setup, theta_i, threads, opt.cancel) : std::vector<TracedLobe>{};
    const std::vector<TracedLobe> walked =
        traced.size() == theta_i.size() ? walk_lobes(opt, alpha, theta_i, threads) : std::vector<TracedLobe>{};
    if (walked.size() != theta_i.size() || support::cancelled(opt.cancel)) {
      res.interrupted = true;
      res.wall_s = support::seconds_since(t0);
      return res;
    }
    for (std::size_t c = 0; c < theta_i.size(); ++c) {
      // A row of every light that left (F = 1: all N rays), or of the k = 1 lobe alone (`k1`): its
      // normalized shape rests on the N E_1 rays that left after one reflection, not on N, so it is
      // compared as a distribution of those, and its energy E_1 apart, as a fraction of the N.
      auto add = [&](const std::string& reference, const std::string& lobe, const std::vector<double>& sim, double rays,
                     double grooves, double thread_s, const ModelLobe& m, bool k1) {
        LobeShapeRow row;
        row.reference = reference, row.lobe = lobe, row.alpha = alpha;
        const double tol = opt.model_tolerance + m.error;
        if (k1) {
          const double e_sim = sum(sim), e_model = sum(m.flux);
          row.c = check_lobes(normalized(sim), normalized(m.flux), rays * e_sim, grooves, opt.sigmas, tol / e_model);
          row.c.albedo_sim = e_sim, row.c.albedo_model = e_model;
          row.c.albedo_threshold = albedo_threshold(e_model, rays, grooves, opt.sigmas, tol);
          row.c.pass = row.c.pass && std::abs(e_sim - e_model) <= row.c.albedo_threshold;
        } else {
          row.c = check_lobes(sim, m.flux, rays, grooves, opt.sigmas, tol);
        }
        row.c.theta_i_deg = opt.theta_i_deg[c], row.c.rays = static_cast<std::int64_t>(rays);
        row.c.model_error = m.error, row.c.model_evals = m.evals, row.c.sim_wall_s = thread_s;
        row.c.worst = worst_bins(sim, m.flux, SurfaceDim::three_d, opt.theta_bins, opt.phi_bins, 0);
        res.rows.push_back(std::move(row));
      };
      for (std::size_t k = 0; k < M; ++k) {
        const Model& m = models[k];
        const ModelLobe& ml = integrated[c * M + k];
        const bool surface = std::string(m.reference) == "vgroove_surface";
        const TracedLobe& ref = surface ? traced[c] : walked[c];
        const double N = static_cast<double>(ref.rays), G = surface ? opt.grooves : kNoGrooves;
        add(m.reference, m.lobe, ref.flux, N, G, ref.thread_s, ml, false);
        // The controls: the V-groove model on its surface, f_ss on each reference's k = 1 lobe.
        if (m.lobe == "vgroove_model") res.controls_pass = res.controls_pass && res.rows.back().c.pass;
        if (m.lobe == "single") {
          add(std::string(m.reference) + "_k1", m.lobe, ref.flux_k1, N, G, 0.0, ml, true);
          res.controls_pass = res.controls_pass && res.rows.back().c.pass;
        }
      }
    }
  }
  res.wall_s = support::seconds_since(t0);
  return res;
}

void print_lobe_shapes(std::ostream& os, const LobeShapeResult& r) {
  os << support::format("lobe shapes: %s, F = 1, %ld rays (walks) per theta_i, %d x %d bins, %.1f s\n",
                        ndf_name(r.options.ndf), r.options.rays, r.options.theta_bins, r.options.phi_bins, r.wall_s);
  os << support::format("%-20s %-14s %6s %6s %9s %9s %9s %9s %9s  %s\n", "reference", "lobe", "alpha", "theta_i",
                        "L1 shape", "expected", "threshold", "albedo", "model", "within noise");
  for (const LobeShapeRow& x : r.rows)
    os << support::format("%-20s %-14s %6.3g %6.1f %9.4f %9.4f %9.4f %9.4f %9.4f  %s\n", x.reference.c_str(),
                          x.lobe.c_str(), x.alpha, x.c.theta_i_deg, x.c.l1, x.c.l1_expected, x.c.l1_threshold,
                          x.c.albedo_sim, x.c.albedo_model, x.c.pass ? "yes" : "no");
  os << "controls (vgroove_model on its surface, single on each k = 1 lobe): "
     << (r.controls_pass ? "within noise" : "FAILED") << "; albedo table interpolation error "
     << support::format("%.2g", r.max_interpolation_error) << "\n";
}

nlohmann::json LobeShapeResult::to_json() const {
  nlohmann::json j = provenance();
  j["kind"] = "energy_lobe_shape";
  j["seed"] = options.seed;
  j["wall_s"] = wall_s;
  j["inputs"] = {
      {"ndf", ndf_name(options.ndf)}, {"alpha", options.alpha},     {"theta_i_deg", options.theta_i_deg},
      {"rays", options.rays},         {"grooves", options.grooves}, {"theta_bins", options.theta_bins},
      {"phi_bins", options.phi_bins}, {"sigmas", options.sigmas},   {"model_tolerance", options.model_tolerance}};
  nlohmann::json rs = nlohmann::json::array();
  for (const LobeShapeRow& r : rows)
    rs.push_back({{"reference", r.reference},
                  {"lobe", r.lobe},
                  {"alpha", r.alpha},
                  {"theta_i_deg", r.c.theta_i_deg},
                  {"rays", r.c.rays},
                  {"albedo_sim", r.c.albedo_sim},
                  {"albedo_model", r.c.albedo_model},
                  {"albedo_threshold", r.c.albedo_threshold},
                  {"l1", r.c.l1},
                  {"l1_threshold", r.c.l1_threshold},
                  {"l1_flux", r.c.l1_flux},
                  {"l1_flux_threshold", r.c.l1_flux_threshold},
                  {"model_integration_error", r.c.model_error},
                  {"sim_thread_s", r.c.sim_wall_s},
                  {"within_noise", r.c.pass}});
  j["rows"] = rs;
  j["albedo_interpolation_error"] = max_interpolation_error;
  j["interrupted"] = interrupted;
  j["controls_pass"] = controls_pass;
  return j;
}

}  // namespace vgroove::validation
