#include "vgroove/validation/check_brdf.h"

#include "vgroove/analytic/quadrature.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <numeric>

namespace vgroove::validation {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

constexpr double kPi = std::numbers::pi;
constexpr int kWorstBins = 5;

void check_range(bool ok, const std::string& what, double v, const std::string& range) {
  if (!ok) throw support::UserError(what + " = " + support::number_text(v) + " is out of range " + range);
}

// The user's model integrated over the 3D bins: sum over nodes of f cos(theta) sin(theta) dtheta dphi.
// The nodes' values come from one batch call, then are summed in node order.
std::vector<double> model_bins_3d(const BrdfBatchFn& f, const analytic::Dir3& wi, int tb, int pb,
                                  const analytic::GaussLegendre& g) {
  std::vector<double> out(static_cast<std::size_t>(tb) * pb, 0.0);
  const double dt = 0.5 * kPi / tb, dp = 2.0 * kPi / pb;
  const std::size_t m = g.size(), nodes = out.size() * m * m;
  std::vector<double> wis(3 * nodes), wos(3 * nodes), vals(nodes);
  std::size_t j = 0;
  for (int t = 0; t < tb; ++t)
    for (int p = 0; p < pb; ++p) {
      const double t0 = t * dt, p0 = p * dp - 0.5 * dp;
      for (std::size_t a = 0; a < m; ++a) {
        const double theta = t0 + 0.5 * dt * (1.0 + g.x[a]);
        for (std::size_t b = 0; b < m; ++b, ++j) {
          const analytic::Dir3 wo = analytic::dir3(theta, p0 + 0.5 * dp * (1.0 + g.x[b]));
          wis[3 * j] = wi.x, wis[3 * j + 1] = wi.y, wis[3 * j + 2] = wi.z;
          wos[3 * j] = wo.x, wos[3 * j + 1] = wo.y, wos[3 * j + 2] = wo.z;
        }
      }
    }
  f(wis.data(), wos.data(), nodes, vals.data());
  j = 0;
  for (int t = 0; t < tb; ++t)
    for (int p = 0; p < pb; ++p) {
      const double t0 = t * dt;
      double s = 0.0;
      for (std::size_t a = 0; a < m; ++a) {
        const double theta = t0 + 0.5 * dt * (1.0 + g.x[a]);
        double row = 0.0;
        for (std::size_t b = 0; b < m; ++b, ++j) row += g.w[b] * vals[j];
        s += g.w[a] * row * std::cos(theta) * std::sin(theta);
      }
      out[static_cast<std::size_t>(t) * pb + p] = s * 0.25 * dt * dp;
    }
  return out;
}

// Flatland: bins over (-pi/2, pi/2) of the signed 2D angle; the direction at signed angle theta
// is (-sin theta, 0, cos theta), i.e. azimuth pi for theta > 0 and 0 for theta < 0.
std::vector<double> model_bins_flatland(const BrdfBatchFn& f, const analytic::Dir3& wi, int bins,
                                        const analytic::GaussLegendre& g) {
  std::vector<double> out(static_cast<std::size_t>(bins), 0.0);
  const double w = kPi / bins;
  const std::size_t m = g.size(), nodes = out.size() * m;
  std::vector<double> wis(3 * nodes), wos(3 * nodes), vals(nodes);
  for (std::size_t j = 0; j < nodes; ++j) {
    const double theta = -0.5 * kPi + static_cast<double>(j / m) * w + 0.5 * w * (1.0 + g.x[j % m]);
    wis[3 * j] = wi.x, wis[3 * j + 1] = wi.y, wis[3 * j + 2] = wi.z;
    wos[3 * j] = -std::sin(theta), wos[3 * j + 1] = 0.0, wos[3 * j + 2] = std::cos(theta);
  }
  f(wis.data(), wos.data(), nodes, vals.data());
  for (int b = 0; b < bins; ++b) {
    const double lo = -0.5 * kPi + b * w;
    double s = 0.0;
    for (std::size_t a = 0; a < m; ++a) {
      const double theta = lo + 0.5 * w * (1.0 + g.x[a]);
      s += g.w[a] * vals[static_cast<std::size_t>(b) * m + a] * std::cos(theta);
    }
    out[static_cast<std::size_t>(b)] = 0.5 * w * s;
  }
  return out;
}

// The centre of bin n for the worst-bin list, in degrees.
WorstBin bin_centre(const CheckBrdfOptions& o, std::size_t n) {
  WorstBin w;
  if (o.dim == SurfaceDim::flatland) {
    w.theta_o_deg = output_deg(-0.5 * kPi + (static_cast<double>(n) + 0.5) * kPi / o.flatland_bins);
    return w;
  }
  const std::size_t t = n / static_cast<std::size_t>(o.phi_bins), p = n % static_cast<std::size_t>(o.phi_bins);
  w.theta_o_deg = output_deg((static_cast<double>(t) + 0.5) * 0.5 * kPi / o.theta_bins);
  double phi = static_cast<double>(p) * 2.0 * kPi / o.phi_bins;
  if (phi > kPi) phi -= 2.0 * kPi;
  w.phi_o_deg = output_deg(phi);
  return w;
}

// One case's traced flux fractions per bin: chunk tallies merged in chunk order.
struct CaseTally {
  std::vector<std::int64_t> hist;
  std::int64_t rays = 0;
};

}  // namespace

void check_options(const CheckBrdfOptions& o) {
  check_range(o.alpha > 0.0 && o.alpha <= kMaxAlpha, "alpha", o.alpha, "(0, 2]");
  if (o.theta_i_deg.empty()) throw support::UserError("theta_i_deg: give at least one incident angle");
  for (double t : o.theta_i_deg) check_range(t >= 0.0 && t < 90.0, "theta_i_deg", t, "[0, 90)");
  check_range(o.rays >= 1 && o.rays <= kMaxRays, "rays", static_cast<double>(o.rays), "[1, 1000000000]");
  check_range(o.grooves >= 1 && o.grooves <= 10'000'000, "grooves", o.grooves, "[1, 10000000]");
  check_range(o.theta_bins >= 1 && o.theta_bins <= 1000, "theta_bins", o.theta_bins, "[1, 1000]");
  check_range(o.phi_bins >= 2 && o.phi_bins <= 1000 && o.phi_bins % 2 == 0, "phi_bins", o.phi_bins, "[2, 1000], even");
  check_range(o.flatland_bins >= 1 && o.flatland_bins <= 100'000, "flatland_bins", o.flatland_bins, "[1, 100000]");
  check_range(o.sigmas > 0.0 && o.sigmas <= 100.0, "sigmas", o.sigmas, "(0, 100]");
  check_range(o.model_tolerance >= 0.0 && o.model_tolerance <= 1.0, "model_tolerance", o.model_tolerance, "[0, 1]");
  check_range(o.quadrature_order >= 1 && o.quadrature_order <= 64, "quadrature_order", o.quadrature_order, "[1, 64]");
  check_range(o.threads >= 0 && o.threads <= 1024, "threads", o.threads, "[0, 1024]");
}

CheckBrdfCase compare_lobes(const std::vector<double>& sim, const std::vector<double>& model, double rays,
                            double grooves, double sigmas, double model_tolerance) {
  CheckBrdfCase c;
  c.albedo_sim = sum(sim);
  c.albedo_model = sum(model);
  c.non_finite = !all_finite(model) || std::any_of(model.begin(), model.end(), [](double v) { return v < 0.0; });
  const std::vector<double> p = normalized(model);
  c.l1 = l1(normalized(sim), p);
  const ExpectedL1 e = expected_l1(p, rays, grooves);
  c.l1_expected = e.mean;
  c.l1_threshold = e.mean + sigmas * e.sd + model_tolerance;
  std::vector<double> clamped(model.size());
  std::transform(model.begin(), model.end(), clamped.begin(), [](double v) { return std::clamp(v, 0.0, 1.0); });
  c.l1_flux = l1(sim, model);
  const ExpectedL1 ef = expected_l1(clamped, rays, grooves);
  c.l1_flux_expected = ef.mean;
  c.l1_flux_threshold = ef.mean + sigmas * ef.sd + model_tolerance;
  // The albedo: a binomial fraction of N rays over G grooves, plus one ray's worth and the tolerance.
  const double a = std::clamp(c.albedo_model, 0.0, 1.0);
  c.albedo_threshold = sigmas * std::sqrt(a * (1.0 - a) * (1.0 / rays + 1.0 / grooves)) + 1.0 / rays + model_tolerance;
  c.pass = !c.non_finite && std::isfinite(c.l1) && c.l1 <= c.l1_threshold && c.l1_flux <= c.l1_flux_threshold &&
           std::abs(c.albedo_sim - c.albedo_model) <= c.albedo_threshold;
  return c;
}

CheckBrdfResult check_brdf(const BrdfFn& f, const CheckBrdfOptions& opt) {
  return check_brdf(
      BrdfBatchFn([&f](const double* wi, const double* wo, std::size_t n, double* out) {
        for (std::size_t j = 0; j < n; ++j)
          out[j] = f({wi[3 * j], wi[3 * j + 1], wi[3 * j + 2]}, {wo[3 * j], wo[3 * j + 1], wo[3 * j + 2]});
      }),
      opt);
}

CheckBrdfResult check_brdf(const BrdfBatchFn& f, const CheckBrdfOptions& opt) {
  check_options(opt);
  CheckBrdfResult res;
  res.options = opt;
  res.threads = support::resolve_threads(opt.threads);
  const auto t0 = Clock::now();
  const bool flat = opt.dim == SurfaceDim::flatland;
  const std::size_t cases = opt.theta_i_deg.size();
  const int bins = flat ? opt.flatland_bins : opt.theta_bins * opt.phi_bins;

  // The surface: the same for every theta_i (Fig. 11's surfaces: seed, grooves, NDF, alpha).
  sim::Microsurface flat_surface;
  sim::Microsurface3d surface3d;
  if (flat) {
    sim::MicrosurfaceOptions so;
    so.ndf = opt.ndf, so.alpha = opt.alpha, so.grooves = opt.grooves, so.seed = opt.seed;
    flat_surface = sim::make_microsurface(so);
  } else {
    sim::Microsurface3dOptions so;
    so.ndf = opt.ndf, so.alpha = opt.alpha, so.grooves = opt.grooves, so.seed = opt.seed;
    surface3d = sim::make_microsurface3d(so);
  }
  // Work items: (case, chunk) of the trace, then one per case for the model's bins. Each writes
  // its own slot; tallies merge in chunk order, so nothing depends on the thread count.
  const std::int64_t chunks = (static_cast<std::int64_t>(opt.rays) + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
  std::vector<std::vector<std::int64_t>> chunk_hist(cases * static_cast<std::size_t>(chunks));
  std::vector<std::int64_t> chunk_rays(chunk_hist.size(), 0);
  std::vector<double> chunk_s(chunk_hist.size(), 0.0), model_s(cases, 0.0);
  std::vector<std::vector<double>> model(cases);
  const analytic::GaussLegendre rule = analytic::gauss_legendre(opt.quadrature_order);
  const std::size_t items = chunk_hist.size() + cases;
  const bool complete = support::parallel_for(
      items, res.threads,
      [&](std::size_t item) {
        const auto ti = Clock::now();
        if (item >= chunk_hist.size()) {
          const std::size_t c = item - chunk_hist.size();
          const double theta_i = deg_to_rad(opt.theta_i_deg[c]);
          const analytic::Dir3 wi = analytic::dir3(theta_i, kPi);
          model[c] =
              flat ? model_bins_flatland(f, wi, bins, rule) : model_bins_3d(f, wi, opt.theta_bins, opt.phi_bins, rule);
          model_s[c] = seconds_since(ti);
          return;
        }
        const std::size_t c = item / static_cast<std::size_t>(chunks);
        const std::int64_t chunk = static_cast<std::int64_t>(item % static_cast<std::size_t>(chunks));
        const double theta_i = deg_to_rad(opt.theta_i_deg[c]);
        if (flat) {
          sim::MicrosurfaceTraceOptions to;
          to.theta_i = theta_i, to.rays = opt.rays, to.seed = opt.seed, to.theta_o_bins = bins, to.max_k = 0;
          const sim::MicrosurfaceTally t = sim::trace_microsurface_chunk(flat_surface, to, chunk);
          chunk_hist[item] = t.theta_o, chunk_rays[item] = t.rays;
        } else {
          sim::Microsurface3dTraceOptions to;
          to.theta_i = theta_i, to.rays = opt.rays, to.seed = opt.seed;
          to.theta_bins = opt.theta_bins, to.phi_bins = opt.phi_bins, to.max_k = 0;
          const sim::Microsurface3dTally t = sim::trace_microsurface3d_chunk(surface3d, to, chunk);
          chunk_hist[item] = t.hist, chunk_rays[item] = t.rays;
        }
        chunk_s[item] = seconds_since(ti);
      },
      {}, opt.cancel, 1);
  res.wall_s = seconds_since(t0);
  if (!complete) {
    res.interrupted = true;
    return res;
  }
  res.pass = true;
  for (std::size_t c = 0; c < cases; ++c) {
    std::vector<std::int64_t> hist(static_cast<std::size_t>(bins), 0);
    std::int64_t rays = 0;
    double sim_s = 0.0;  // thread time, summed over the case's chunks
    for (std::int64_t k = 0; k < chunks; ++k) {
      const std::size_t item = c * static_cast<std::size_t>(chunks) + static_cast<std::size_t>(k);
      for (std::size_t n = 0; n < hist.size(); ++n) hist[n] += chunk_hist[item][n];
      rays += chunk_rays[item];
      sim_s += chunk_s[item];
    }
    const double N = static_cast<double>(rays);
    const std::vector<double> sim = fractions(hist, N);
    CheckBrdfCase out = compare_lobes(sim, model[c], N, opt.grooves, opt.sigmas, opt.model_tolerance);
    out.theta_i_deg = opt.theta_i_deg[c];
    out.rays = rays;
    out.sim_wall_s = sim_s;
    out.model_wall_s = model_s[c];
    std::vector<std::size_t> order(sim.size());
    std::iota(order.begin(), order.end(), 0);
    const std::size_t shown = std::min<std::size_t>(kWorstBins, order.size());
    std::partial_sort(
        order.begin(), order.begin() + static_cast<std::ptrdiff_t>(shown), order.end(),
        [&](std::size_t a, std::size_t b) { return std::abs(sim[a] - model[c][a]) > std::abs(sim[b] - model[c][b]); });
    for (std::size_t n = 0; n < shown; ++n) {
      WorstBin w = bin_centre(opt, order[n]);
      w.sim = sim[order[n]], w.model = model[c][order[n]];
      out.worst.push_back(w);
    }
    res.pass = res.pass && out.pass;
    res.cases.push_back(std::move(out));
  }
  return res;
}

nlohmann::json CheckBrdfResult::to_json() const {
  nlohmann::json j = provenance();
  j["kind"] = "check_brdf";
  j["name"] = options.name;
  j["seed"] = options.seed;
  j["threads"] = threads;
  j["wall_s"] = wall_s;
  j["inputs"] = {{"ndf", ndf_name(options.ndf)},
                 {"alpha", options.alpha},
                 {"dimension", surface_dim_name(options.dim)},
                 {"theta_i_deg", options.theta_i_deg},
                 {"rays", options.rays},
                 {"grooves", options.grooves},
                 {"theta_bins", options.theta_bins},
                 {"phi_bins", options.phi_bins},
                 {"flatland_bins", options.flatland_bins},
                 {"sigmas", options.sigmas},
                 {"model_tolerance", options.model_tolerance},
                 {"quadrature_order", options.quadrature_order}};
  nlohmann::json cs = nlohmann::json::array();
  for (const CheckBrdfCase& c : cases) {
    nlohmann::json worst = nlohmann::json::array();
    for (const WorstBin& w : c.worst)
      worst.push_back({{"theta_o_deg", w.theta_o_deg}, {"phi_o_deg", w.phi_o_deg}, {"sim", w.sim}, {"model", w.model}});
    cs.push_back({{"theta_i_deg", c.theta_i_deg},
                  {"rays", c.rays},
                  {"albedo_sim", c.albedo_sim},
                  {"albedo_model", c.albedo_model},
                  {"albedo_threshold", c.albedo_threshold},
                  {"l1", c.l1},
                  {"l1_expected", c.l1_expected},
                  {"l1_threshold", c.l1_threshold},
                  {"l1_flux", c.l1_flux},
                  {"l1_flux_expected", c.l1_flux_expected},
                  {"l1_flux_threshold", c.l1_flux_threshold},
                  {"worst_bins", worst},
                  {"sim_wall_s", c.sim_wall_s},
                  {"model_wall_s", c.model_wall_s},
                  {"non_finite", c.non_finite},
                  {"pass", c.pass}});
  }
  j["cases"] = cs;
  j["interrupted"] = interrupted;
  j["pass"] = pass;
  return j;
}

}  // namespace vgroove::validation
