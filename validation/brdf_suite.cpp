#include "vgroove/validation/brdf_suite.h"

#include "vgroove/validation/part_fields.h"

#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"
#include "vgroove/validation/lobe_bins.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The procedural surface of one (NDF, alpha): flatland or 3D options have the same fields.
template <class Options>
Options surface_options(analytic::NdfKind ndf, double alpha, int grooves, std::uint64_t seed) {
  Options o;
  o.ndf = ndf;
  o.alpha = alpha;
  o.grooves = grooves;
  o.seed = seed;
  return o;
}

// The comparison shared by both dimensions, from the per-(row, bin) fractions of the incident flux.
void compare(BrdfOutcome& out, const BrdfSuite& suite, const std::vector<double>& sim_joint,
             const std::vector<double>& model_joint, int bins, double model_tolerance) {
  const int rows = suite.max_k + 2;
  std::vector<double> sim_total(static_cast<std::size_t>(bins), 0.0), model_total(static_cast<std::size_t>(bins), 0.0);
  for (int r = 0; r < rows; ++r)
    for (int b = 0; b < bins; ++b) {
      const std::size_t n = static_cast<std::size_t>(r) * bins + b;
      sim_total[static_cast<std::size_t>(b)] += sim_joint[n];
      model_total[static_cast<std::size_t>(b)] += model_joint[n];
    }
  const double N = static_cast<double>(out.rays), G = static_cast<double>(suite.grooves);
  const std::vector<double> p = normalized(model_total);
  out.l1 = l1(normalized(sim_total), p);
  const ExpectedL1 e = expected_l1(p, N, G);
  out.l1_expected = e.mean;
  out.l1_threshold = e.mean + suite.sigmas * e.sd + model_tolerance;
  out.l1_k = l1(sim_joint, model_joint);
  const ExpectedL1 ek = expected_l1(model_joint, N, G);
  out.l1_k_expected = ek.mean;
  out.l1_k_threshold = ek.mean + suite.sigmas * ek.sd + model_tolerance;
  // The albedo: a binomial fraction of the same N rays over G grooves, plus one ray's worth
  // (the count is an integer) and the model's tolerance.
  const double a = std::clamp(out.albedo_model, 0.0, 1.0);
  out.albedo_threshold = suite.sigmas * std::sqrt(a * (1.0 - a) * (1.0 / N + 1.0 / G)) + 1.0 / N + model_tolerance;
  out.non_finite = !(std::isfinite(out.l1) && std::isfinite(out.l1_k) && std::isfinite(out.albedo_model) &&
                     std::isfinite(out.albedo_single) && all_finite(model_joint));
  const bool albedo_ok = std::abs(out.albedo_sim - out.albedo_model) <= out.albedo_threshold;
  out.pass = !out.non_finite && albedo_ok && out.l1 <= out.l1_threshold && out.l1_k <= out.l1_k_threshold;
}

// The counts of a traced case.
void take_counts(BrdfOutcome& out, const BinnedTally& t) {
  out.rays = t.rays, out.escaped = t.escaped, out.lost = t.lost(), out.bounces = t.bounces;
  out.max_k_seen = t.max_k_seen;
  out.in_flight = t.bounce_limit;
  out.albedo_sim = static_cast<double>(t.escaped) / static_cast<double>(t.rays);
}

sim::MicrosurfaceTraceOptions flatland_trace(const BrdfSuite& suite, const BrdfCase& c, long rays) {
  sim::MicrosurfaceTraceOptions to;
  to.theta_i = c.theta_i;
  to.rays = rays;
  to.sampling = sim::Sampling::random;
  to.seed = suite.seed;
  to.theta_o_bins = suite.flatland_bins;
  to.max_k = suite.max_k;
  return to;
}

sim::Microsurface3dTraceOptions trace_3d(const BrdfSuite& suite, const BrdfCase& c, long rays) {
  sim::Microsurface3dTraceOptions to;
  to.theta_i = c.theta_i;
  to.rays = rays;
  to.seed = suite.seed;
  to.theta_bins = suite.theta_bins;
  to.phi_bins = suite.phi_bins;
  to.max_k = suite.max_k;
  return to;
}

BrdfOutcome finish_flatland(const BrdfSuite& suite, const BrdfCase& c, const BinnedTally& t, const BrdfModel& lobe) {
  BrdfOutcome out;
  out.c = c;
  const int bins = suite.flatland_bins;
  out.sim_wall_s = t.thread_s;
  take_counts(out, t);
  out.model_wall_s = lobe.wall_s;
  out.albedo_model = lobe.albedo;
  out.albedo_single = lobe.single_albedo;
  const double N = static_cast<double>(t.rays);
  out.by_k_sim = fractions(t.by_k, N);
  out.by_k_model = lobe.by_k;
  compare(out, suite, fractions(t.hist_by_k, N), lobe.hist_by_k, bins, suite.model_tolerance_flatland);

  const double width = std::numbers::pi / bins;
  for (int b = 0; b < bins; ++b) {
    out.plane_theta_deg.push_back(output_deg(-0.5 * std::numbers::pi + (b + 0.5) * width));
    out.plane_sim.push_back(static_cast<double>(t.hist[static_cast<std::size_t>(b)]) / N / width);
    out.plane_model.push_back(lobe.hist[static_cast<std::size_t>(b)] / width);
    out.plane_single.push_back(lobe.single_hist[static_cast<std::size_t>(b)] / width);
  }
  for (int k = 1; k <= std::min(kPlotK, suite.max_k); ++k) {
    std::vector<double> s, m;
    for (int b = 0; b < bins; ++b) {
      s.push_back(static_cast<double>(t.hist_by_k[static_cast<std::size_t>(k) * bins + b]) / N / width);
      m.push_back(lobe.hist_by_k[static_cast<std::size_t>(k) * bins + b] / width);
    }
    out.plane_sim_k.push_back(std::move(s));
    out.plane_model_k.push_back(std::move(m));
  }
  return out;
}

BrdfOutcome finish_3d(const BrdfSuite& suite, const BrdfCase& c, const BinnedTally& t, const BrdfModel& lobe) {
  BrdfOutcome out;
  out.c = c;
  const int tb = suite.theta_bins, pb = suite.phi_bins, bins = tb * pb;
  out.sim_wall_s = t.thread_s;
  take_counts(out, t);
  out.model_wall_s = lobe.wall_s;
  out.albedo_model = lobe.albedo;
  out.albedo_single = lobe.single_albedo;
  const double N = static_cast<double>(t.rays);
  out.by_k_sim = fractions(t.by_k, N);
  out.by_k_model = lobe.by_k;
  compare(out, suite, fractions(t.hist_by_k, N), lobe.hist_by_k, bins, suite.model_tolerance_3d);

  // The plane of incidence: phi bin pb/2 (towards the light, signed angle +theta) and phi bin 0
  // (the mirror side, -theta), as fractions per steradian of each bin.
  const double dt = 0.5 * std::numbers::pi / tb, dp = 2.0 * std::numbers::pi / pb;
  auto solid_angle = [&](int t_) { return dp * (std::cos(t_ * dt) - std::cos((t_ + 1) * dt)); };
  auto push = [&](int t_, int p_) {
    const std::size_t n = static_cast<std::size_t>(t_) * pb + p_;
    const double w = solid_angle(t_);
    out.plane_sim.push_back(static_cast<double>(t.hist[n]) / N / w);
    out.plane_model.push_back(lobe.hist[n] / w);
    out.plane_single.push_back(lobe.single_hist[n] / w);
  };
  for (int t_ = tb - 1; t_ >= 0; --t_) out.plane_theta_deg.push_back(output_deg(-(t_ + 0.5) * dt)), push(t_, 0);
  for (int t_ = 0; t_ < tb; ++t_) out.plane_theta_deg.push_back(output_deg((t_ + 0.5) * dt)), push(t_, pb / 2);
  for (int k = 1; k <= std::min(kPlotK, suite.max_k); ++k) {
    std::vector<double> s, m;
    auto pushk = [&](int t_, int p_) {
      const std::size_t n = (static_cast<std::size_t>(k) * tb + t_) * pb + p_;
      s.push_back(static_cast<double>(t.hist_by_k[n]) / N / solid_angle(t_));
      m.push_back(lobe.hist_by_k[n] / solid_angle(t_));
    };
    for (int t_ = tb - 1; t_ >= 0; --t_) pushk(t_, 0);
    for (int t_ = 0; t_ < tb; ++t_) pushk(t_, pb / 2);
    out.plane_sim_k.push_back(std::move(s));
    out.plane_model_k.push_back(std::move(m));
  }
  return out;
}

// Cost estimates (ns of one core; they only balance the work): rays per second on the procedural
// surfaces (README: 6-7 M/s flatland, 4-5 M/s 3D) and their reflections; the models (fig11's
// per-case times: flatland ~0.01 s, 3D 1-2 s at 30 x 24 bins).
std::int64_t brdf_ray_cost_ns(const BrdfCase& c) { return c.dim == SurfaceDim::flatland ? 160 : 230; }
std::int64_t brdf_model_cost_ns(const BrdfSuite& s, const BrdfCase& c) {
  return c.dim == SurfaceDim::flatland ? 20'000'000 : 2'000'000 * static_cast<std::int64_t>(s.theta_bins) * s.phi_bins;
}

nlohmann::json suite_inputs(const BrdfSuite& s) {
  nlohmann::json dims = nlohmann::json::array(), ti = nlohmann::json::array();
  for (auto d : s.dims) dims.push_back(surface_dim_name(d));
  for (double t : s.theta_i) ti.push_back(output_deg(t));
  nlohmann::json in = {{"alpha", s.alphas},
                       {"theta_i_deg", ti},
                       {"dimensions", dims},
                       {"grooves", s.grooves},
                       {"flatland_bins", s.flatland_bins},
                       {"theta_bins", s.theta_bins},
                       {"phi_bins", s.phi_bins},
                       {"max_k", s.max_k},
                       {"sigmas", s.sigmas},
                       {"model_tolerance", {{"flatland", s.model_tolerance_flatland}, {"3d", s.model_tolerance_3d}}}};
  put_ndfs(in, s.ndfs);
  return in;
}

}  // namespace

const char* surface_dim_name(SurfaceDim d) { return d == SurfaceDim::flatland ? "flatland" : "3d"; }

BrdfCase grid_case(const std::vector<analytic::NdfKind>& ndfs, const std::vector<double>& alphas,
                   const std::vector<double>& theta_i, const std::vector<SurfaceDim>& dims, std::size_t c) {
  BrdfCase out;
  const std::size_t nt = theta_i.size(), na = alphas.size(), nn = ndfs.size();
  out.theta_i = theta_i[c % nt];
  out.alpha = alphas[(c / nt) % na];
  out.ndf = ndfs[(c / (nt * na)) % nn];
  out.dim = dims[c / (nt * na * nn)];
  return out;
}

BrdfCase BrdfSuite::case_at(std::size_t c) const { return grid_case(ndfs, alphas, theta_i, dims, c); }

BrdfSuite parse_brdf_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  BrdfSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  s.kind = root.one_of("kind", {"brdf"});
  s.ndfs = read_ndfs(root, true);
  s.alphas = read_numbers(root, "alpha", kMinAlpha, true, kMaxAlpha, true);
  for (double d : read_numbers(root, "theta_i_deg", 0.0, true, kMaxSurfaceThetaIDeg, true))
    s.theta_i.push_back(d * kRadPerDeg);
  for (const auto& d : read_names(root, "dimensions", {"flatland", "3d"}))
    s.dims.push_back(d == "flatland" ? SurfaceDim::flatland : SurfaceDim::three_d);
  s.rays = static_cast<long>(root.integer("rays", 1, kMaxRays));
  s.grooves = static_cast<int>(root.integer("grooves", 1, kMaxGrooves));
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, kMaxSeed));
  {
    const bool flat = std::find(s.dims.begin(), s.dims.end(), SurfaceDim::flatland) != s.dims.end();
    const bool three = std::find(s.dims.begin(), s.dims.end(), SurfaceDim::three_d) != s.dims.end();
    const LobeBins bins = read_lobe_bins(root, {s.flatland_bins, s.theta_bins, s.phi_bins, s.max_k}, flat, three);
    s.flatland_bins = bins.flatland_bins, s.theta_bins = bins.theta_bins, s.phi_bins = bins.phi_bins;
    s.max_k = bins.max_k;
  }
  {
    support::JsonObject t = root.object("thresholds");
    s.sigmas = t.number("sigmas", 0.0, false, 100.0, true);
    support::JsonObject m = t.object("model_tolerance");
    s.model_tolerance_flatland = m.number("flatland", 0.0, true, 2.0, true);
    s.model_tolerance_3d = m.number("3d", 0.0, true, 2.0, true);
    m.finish();
    t.finish();
  }
  root.finish();
  return s;
}

double brdf_run_memory_bytes(const BrdfSuite& suite, int threads, bool report) {
  constexpr double kNumberBytes = 64;  // a double in the report: its JSON node, vector slot and text
  const double rows = suite.max_k + 2.0;
  double cells = 0.0, groove = 0.0, plane = 0.0;
  for (SurfaceDim d : suite.dims) {
    const bool flat = d == SurfaceDim::flatland;
    cells =
        std::max(cells, rows * (flat ? suite.flatland_bins : static_cast<double>(suite.theta_bins) * suite.phi_bins));
    groove = std::max(groove, sizeof(sim::Groove) + (flat ? 8.0 : 8.0 + 8.0 + sizeof(sim::GrooveFrame3d)));
    plane = std::max(plane, (flat ? suite.flatland_bins : 2.0 * suite.theta_bins) * (3.0 + 2.0 * kPlotK));
  }
  const double cases = static_cast<double>(suite.cases());
  const double workers = std::min<double>(support::resolve_threads(threads), cases);
  // Per worker: the surface; two tallies (a chunk's and the item's); the lobes (multiple scattering
  // and Cook-Torrance) and the comparison's copies: about ten arrays of the joint (k, bin) cells.
  // Per case: its merged tally and model (joint cells each), held twice while the parts are
  // merged, then its outcome.
  const double per_worker = suite.grooves * groove + 10.0 * cells * 8.0;
  const double per_case = sizeof(BrdfOutcome) + 4.0 * cells * 8.0 + (2.0 * rows + plane) * 8.0 +
                          (report ? (2.0 * rows + plane) * kNumberBytes : 0.0);
  return workers * per_worker + cases * per_case;
}

std::shared_ptr<const BrdfWork::Context> BrdfWork::prepare(std::size_t n) const {
  const BrdfCase c = suite.case_at(n);
  auto ctx = std::make_shared<Context>();
  if (c.dim == SurfaceDim::flatland)
    ctx->flat =
        sim::make_microsurface(surface_options<sim::MicrosurfaceOptions>(c.ndf, c.alpha, suite.grooves, suite.seed));
  else
    ctx->three_d = sim::make_microsurface3d(
        surface_options<sim::Microsurface3dOptions>(c.ndf, c.alpha, suite.grooves, suite.seed));
  return ctx;
}

BinnedTally BrdfWork::run_chunks(const Context& ctx, std::size_t n, std::int64_t begin, std::int64_t end) const {
  const auto t0 = Clock::now();
  const BrdfCase c = suite.case_at(n);
  BinnedTally out;
  if (c.dim == SurfaceDim::flatland) {
    const sim::MicrosurfaceTraceOptions to = flatland_trace(suite, c, rays);
    sim::MicrosurfaceTally t(to.theta_o_bins, to.max_k);
    for (std::int64_t k = begin; k < end && !support::cancelled(cancel); ++k)
      sim::trace_microsurface_chunk(ctx.flat, to, k, t);
    static_cast<sim::RayFates&>(out) = t;
    out.by_k = std::move(t.by_k), out.hist = std::move(t.theta_o), out.hist_by_k = std::move(t.theta_o_by_k);
  } else {
    const sim::Microsurface3dTraceOptions to = trace_3d(suite, c, rays);
    sim::Microsurface3dTally t(to.theta_bins, to.phi_bins, to.max_k);
    for (std::int64_t k = begin; k < end && !support::cancelled(cancel); ++k)
      sim::trace_microsurface3d_chunk(ctx.three_d, to, k, t);
    static_cast<sim::RayFates&>(out) = t;
    out.by_k = std::move(t.by_k), out.hist = std::move(t.hist), out.hist_by_k = std::move(t.hist_by_k);
  }
  out.thread_s = seconds_since(t0);
  return out;
}

BrdfModel BrdfWork::run_fixed(std::size_t n) const {
  const auto t0 = Clock::now();
  const BrdfCase c = suite.case_at(n);
  BrdfModel m;
  if (c.dim == SurfaceDim::flatland) {
    analytic::FlatlandLobe lobe = analytic::flatland_lobe(c.ndf, c.alpha, c.theta_i, suite.flatland_bins, suite.max_k);
    analytic::FlatlandLobe single = analytic::flatland_single_lobe(c.ndf, c.alpha, c.theta_i, suite.flatland_bins);
    m.by_k = std::move(lobe.by_k), m.hist = std::move(lobe.theta_o), m.hist_by_k = std::move(lobe.theta_o_by_k);
    m.albedo = lobe.albedo, m.single_hist = std::move(single.theta_o), m.single_albedo = single.albedo;
  } else {
    analytic::Lobe3dOptions lo;
    lo.cancel = cancel;
    analytic::Lobe3d lobe =
        analytic::vgroove_lobe_3d(c.ndf, c.alpha, c.theta_i, suite.theta_bins, suite.phi_bins, suite.max_k, lo);
    // Cook-Torrance (V-cavity G) is the lobe's k = 1 row (Eq. 25): no second integration.
    analytic::Lobe3d single = analytic::cook_torrance_lobe_3d_from(lobe);
    m.by_k = std::move(lobe.by_k), m.hist = std::move(lobe.hist), m.hist_by_k = std::move(lobe.hist_by_k);
    m.albedo = lobe.albedo, m.single_hist = std::move(single.hist), m.single_albedo = single.albedo;
  }
  m.wall_s = seconds_since(t0);
  return m;
}

void BrdfWork::merge(Tally& into, const Tally& from) {
  into.merge_fates(from);
  for (std::size_t i = 0; i < into.by_k.size(); ++i) into.by_k[i] += from.by_k[i];
  for (std::size_t i = 0; i < into.hist.size(); ++i) into.hist[i] += from.hist[i];
  for (std::size_t i = 0; i < into.hist_by_k.size(); ++i) into.hist_by_k[i] += from.hist_by_k[i];
  into.thread_s += from.thread_s;
}

nlohmann::json BrdfWork::tally_json(const Tally& t) {
  nlohmann::json j = fates_json(t);
  j["by_k"] = t.by_k, j["hist"] = t.hist, j["hist_by_k"] = t.hist_by_k, j["thread_s"] = t.thread_s;
  return j;
}

namespace {
// The rows (k = 0..max_k and one for more) and bins of case c's histograms.
std::pair<std::size_t, std::size_t> lobe_shape(const BrdfSuite& suite, const BrdfCase& c) {
  const std::size_t bins = c.dim == SurfaceDim::flatland
                               ? static_cast<std::size_t>(suite.flatland_bins)
                               : static_cast<std::size_t>(suite.theta_bins) * static_cast<std::size_t>(suite.phi_bins);
  return {static_cast<std::size_t>(suite.max_k) + 2, bins};
}
}  // namespace

BinnedTally BrdfWork::read_tally(support::JsonObject& j, std::size_t n, const std::vector<ChunkRun>& runs) const {
  const auto [rows, bins] = lobe_shape(suite, suite.case_at(n));
  BinnedTally t;
  read_fates(j, t, rays_in_chunks(runs, rays, sim::kRaysPerChunk), sim::TraceOptions{}.max_bounces);
  t.by_k = read_counts(j, "by_k", rows, t.escaped);
  check_sum(j, "by_k", t.by_k, t.escaped, "escaped rays");
  t.hist = read_counts(j, "hist", bins, t.escaped);
  check_sum(j, "hist", t.hist, t.escaped, "escaped rays");
  t.hist_by_k = read_counts(j, "hist_by_k", rows * bins, t.escaped);
  check_margins(j, "hist_by_k", t.hist_by_k, t.by_k, "by_k", t.hist, "hist");
  t.thread_s = j.number("thread_s", 0.0, true, std::numeric_limits<double>::max(), true);
  return t;
}

nlohmann::json BrdfWork::fixed_json(const Fixed& m) {
  return {{"by_k", exact_json(m.by_k)},
          {"hist", exact_json(m.hist)},
          {"hist_by_k", exact_json(m.hist_by_k)},
          {"single_hist", exact_json(m.single_hist)},
          {"albedo", exact_json(m.albedo)},
          {"single_albedo", exact_json(m.single_albedo)},
          {"wall_s", m.wall_s}};
}

BrdfModel BrdfWork::read_fixed(support::JsonObject& j, std::size_t n) const {
  const auto [rows, bins] = lobe_shape(suite, suite.case_at(n));
  BrdfModel m;
  m.by_k = read_exact_doubles(j, "by_k", rows);
  m.hist = read_exact_doubles(j, "hist", bins);
  m.hist_by_k = read_exact_doubles(j, "hist_by_k", rows * bins);
  m.single_hist = read_exact_doubles(j, "single_hist", bins);
  m.albedo = read_exact_double(j, "albedo");
  m.single_albedo = read_exact_double(j, "single_albedo");
  m.wall_s = j.number("wall_s", 0.0, true, std::numeric_limits<double>::max(), true);
  return m;
}

Job<BrdfWork> brdf_job(const BrdfSuite& suite, long rays, nlohmann::json descriptor) {
  const long n_rays = rays > 0 ? rays : suite.rays;
  std::vector<support::WorkUnit> units(suite.cases());
  for (std::size_t n = 0; n < units.size(); ++n) {
    const BrdfCase c = suite.case_at(n);
    units[n].chunks = (n_rays + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
    units[n].chunk_cost = brdf_ray_cost_ns(c) * std::min<std::int64_t>(n_rays, sim::kRaysPerChunk);
    units[n].has_fixed = true;
    units[n].fixed_cost = brdf_model_cost_ns(suite, c);
  }
  return make_job(BrdfWork{suite, n_rays}, std::move(units), std::move(descriptor));
}

BrdfRun brdf_run_from(const BrdfSuite& suite, long, const std::vector<UnitResult<BrdfWork>>& results) {
  BrdfRun run;
  for (std::size_t n = 0; n < results.size(); ++n) {
    const BrdfCase c = suite.case_at(n);
    run.cases.push_back(c.dim == SurfaceDim::flatland ? finish_flatland(suite, c, results[n].tally, *results[n].fixed)
                                                      : finish_3d(suite, c, results[n].tally, *results[n].fixed));
  }
  run.pass = std::all_of(run.cases.begin(), run.cases.end(), [](const BrdfOutcome& o) { return o.pass; });
  return run;
}

BrdfOutcome run_brdf_case(const BrdfSuite& suite, const BrdfCase& c, long rays, support::CancelFlag cancel) {
  BrdfSuite one = suite;
  one.ndfs = {c.ndf}, one.alphas = {c.alpha}, one.theta_i = {c.theta_i}, one.dims = {c.dim};
  auto job = brdf_job(one, rays, {});
  job.work.cancel = cancel;
  const auto results = run_job(job, 1, {}, cancel);
  if (!results) {  // cancelled: an empty outcome
    BrdfOutcome out;
    out.c = c;
    return out;
  }
  return brdf_run_from(one, rays, *results).cases.front();
}

BrdfRun run_brdf_suite(const BrdfSuite& suite, long rays, int threads, const support::ProgressFn& progress,
                       const std::atomic<bool>* cancel) {
  const auto t0 = Clock::now();
  auto job = brdf_job(suite, rays, {});
  job.work.cancel = cancel;
  const auto results = run_job(job, threads, progress, cancel);
  BrdfRun run;
  if (results) run = brdf_run_from(suite, rays, *results);
  run.threads = support::resolve_threads(threads);
  run.wall_s = seconds_since(t0);
  run.interrupted = !results;
  return run;
}

nlohmann::json brdf_report_json(const BrdfSuite& suite, const BrdfRun& run) {
  nlohmann::json j = provenance();
  j["suite"] = suite.name;
  j["suite_file"] = suite.file;
  j["kind"] = suite.kind;
  j["description"] = suite.description;
  j["seed"] = suite.seed;
  j["threads"] = run.threads;
  j["wall_s"] = run.wall_s;
  j["inputs"] = suite_inputs(suite);
  nlohmann::json cases = nlohmann::json::array();
  std::int64_t rays = 0, bounces = 0;
  double worst_ratio = 0.0, worst_albedo = 0.0, worst_single = 1.0;
  std::size_t passed = 0;
  for (const BrdfOutcome& o : run.cases) {
    rays += o.rays, bounces += o.bounces;
    passed += o.pass;
    worst_ratio = std::max({worst_ratio, o.l1 / o.l1_threshold, o.l1_k / o.l1_k_threshold});
    worst_albedo = std::max(worst_albedo, std::abs(o.albedo_sim - o.albedo_model));
    worst_single = std::min(worst_single, o.albedo_single);
    nlohmann::json c = {{"ndf", analytic::ndf_name(o.c.ndf)},
                        {"alpha", o.c.alpha},
                        {"theta_i_deg", output_deg(o.c.theta_i)},
                        {"dimension", surface_dim_name(o.c.dim)},
                        {"rays", o.rays},
                        {"escaped", o.escaped},
                        {"lost", o.lost},
                        {"in_flight_at_bounce_limit", o.in_flight},
                        {"bounces", o.bounces},
                        {"max_k_seen", o.max_k_seen},
                        {"sim_wall_s", o.sim_wall_s},
                        {"model_wall_s", o.model_wall_s},
                        {"albedo_sim", o.albedo_sim},
                        {"albedo_model", o.albedo_model},
                        {"albedo_cook_torrance", o.albedo_single},
                        {"cook_torrance_energy_lost", 1.0 - o.albedo_single},
                        {"albedo_difference", o.albedo_sim - o.albedo_model},
                        {"albedo_threshold", o.albedo_threshold},
                        {"by_k_sim", o.by_k_sim},
                        {"by_k_model", o.by_k_model},
                        {"non_finite", o.non_finite},
                        {"pass", o.pass}};
    put_gamma(c, o.c.ndf);
    {
      c["l1"] = o.l1;
      c["l1_expected"] = o.l1_expected;
      c["l1_threshold"] = o.l1_threshold;
      c["l1_by_k"] = o.l1_k;
      c["l1_by_k_expected"] = o.l1_k_expected;
      c["l1_by_k_threshold"] = o.l1_k_threshold;
      c["plane"] = {{"theta_deg", o.plane_theta_deg},
                    {"unit", o.c.dim == SurfaceDim::flatland ? "fraction of the flux per radian"
                                                             : "fraction of the flux per steradian"},
                    {"sim", o.plane_sim},
                    {"model", o.plane_model},
                    {"cook_torrance", o.plane_single},
                    {"sim_by_k", o.plane_sim_k},
                    {"model_by_k", o.plane_model_k}};
    }
    cases.push_back(std::move(c));
  }
  j["cases"] = std::move(cases);
  j["summary"] = {{"cases", run.cases.size()},
                  {"passed", passed},
                  {"rays", rays},
                  {"bounces", bounces},
                  {"worst_error_over_threshold", worst_ratio},
                  {"largest_albedo_difference", worst_albedo},
                  {"lowest_cook_torrance_albedo", worst_single},
                  {"wall_s", run.wall_s}};
  j["thresholds"] = {{"rule", "expected L1 + sigmas x its standard deviation + model tolerance (per case)"},
                     {"sigmas", suite.sigmas}};
  j["pass"] = run.pass;
  return j;
}

void print_brdf_table(std::ostream& os, const BrdfSuite& suite, const BrdfRun& run) {
  os << support::format("%s (%s): %zu cases, %ld rays x %d grooves each, vgroove %s (git %s), %d threads\n",
                        support::printable(suite.name).c_str(), suite.kind.c_str(), run.cases.size(), suite.rays,
                        suite.grooves, version_string(), git_revision(), run.threads);
  os << support::format("  %-8s %-8s %5s %7s %9s %9s %9s %9s %10s %9s %8s %5s\n", "dim", "ndf", "alpha", "theta_i",
                        "L1", "L1 thr", "L1 by k", "thr", "albedo", "CT alb", "wall s", "pass");
  for (const BrdfOutcome& o : run.cases) {
    os << support::format("  %-8s %-8s %5.2f %7.2f %9.5f %9.5f %9.5f %9.5f %10.7f %9.5f %8.3f %5s\n",
                          surface_dim_name(o.c.dim), ndf_label(o.c.ndf).c_str(), o.c.alpha, output_deg(o.c.theta_i),
                          o.l1, o.l1_threshold, o.l1_k, o.l1_k_threshold, o.albedo_sim, o.albedo_single,
                          o.sim_wall_s + o.model_wall_s, o.pass ? "yes" : "NO");
  }
  std::size_t passed = 0;
  for (const auto& o : run.cases) passed += o.pass;
  os << support::format("  %zu/%zu cases pass; wall %.2f s\n", passed, run.cases.size(), run.wall_s);
}

}  // namespace vgroove::validation
