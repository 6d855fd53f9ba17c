#include "vgroove/validation/brdf_suite.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/validation/detail/part_fields.h"

#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"
#include "vgroove/validation/lobe_bins.h"
#include "vgroove/validation/lobe_comparison.h"
#include "vgroove/validation/model_table.h"
#include "vgroove/validation/plane_cut.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/table_frame.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

// The traced lobe against the model's, from the per-(row, bin) fractions of the incident flux.
void compare(BrdfOutcome& out, const BrdfSuite& suite, const std::vector<double>& sim_joint,
             const std::vector<double>& model_joint, int bins, double model_tolerance) {
  const double N = static_cast<double>(out.rays), G = static_cast<double>(suite.grooves);
  const bool holds =
      take_comparison(out, compare_lobes(sim_joint, model_joint, bins, N, G, suite.sigmas, model_tolerance), N, G,
                      suite.sigmas, model_tolerance);
  out.non_finite = !(std::isfinite(out.l1) && std::isfinite(out.l1_k) && std::isfinite(out.albedo_model) &&
                     std::isfinite(out.albedo_single) && all_finite(model_joint));
  out.pass = !out.non_finite && holds;
}

// A case's rays and bins as the suite sets them.
CaseRays case_rays(const BrdfSuite& suite, const BrdfCase& c, long rays) {
  CaseRays r;
  r.theta_i = c.theta_i, r.rays = rays, r.seed = suite.seed;
  r.flatland_bins = suite.flatland_bins, r.theta_bins = suite.theta_bins, r.phi_bins = suite.phi_bins;
  r.max_k = suite.max_k;
  return r;
}

PlaneCut plane_cut(const BrdfSuite& suite, SurfaceDim dim) {
  return dim == SurfaceDim::flatland ? PlaneCut::flatland(suite.flatland_bins)
                                     : PlaneCut::three_d(suite.theta_bins, suite.phi_bins);
}

BrdfOutcome finish(const BrdfSuite& suite, const BrdfCase& c, const BinnedTally& t, const BrdfModel& lobe) {
  BrdfOutcome out;
  out.c = c;
  const PlaneCut plane = plane_cut(suite, c.dim);
  const int bins = plane.bins();
  out.sim_wall_s = t.thread_s;
  take_counts(out, t);
  out.in_flight = t.bounce_limit;
  out.model_wall_s = lobe.wall_s;
  out.albedo_model = lobe.albedo;
  out.albedo_single = lobe.single_albedo;
  const double N = static_cast<double>(t.rays);
  out.by_k_sim = fractions(t.by_k, N);
  out.by_k_model = lobe.by_k;
  compare(out, suite, fractions(t.hist_by_k, N), lobe.hist_by_k, bins,
          c.dim == SurfaceDim::flatland ? suite.model_tolerance_flatland : suite.model_tolerance_3d);
  out.plane_theta_deg = plane.angles_deg();
  out.plane_sim = plane.cut([&](std::size_t n) { return static_cast<double>(t.hist[n]) / N; });
  out.plane_model = plane.cut([&](std::size_t n) { return lobe.hist[n]; });
  out.plane_single = plane.cut([&](std::size_t n) { return lobe.single_hist[n]; });
  for (int k = 1; k <= std::min(kPlotK, suite.max_k); ++k) {
    const std::size_t row = static_cast<std::size_t>(k) * bins;
    out.plane_sim_k.push_back(plane.cut([&](std::size_t n) { return static_cast<double>(t.hist_by_k[row + n]) / N; }));
    out.plane_model_k.push_back(plane.cut([&](std::size_t n) { return lobe.hist_by_k[row + n]; }));
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
  // The surface: check_brdf's names and options, its ranges checked by check_brdf itself
  // (check_suite_surface, below). A heightfield suite needs no grooves.
  static const std::string kVgroove = "vgroove";
  s.surface = root.one_of("surface", {"vgroove", "heightfield"}, &kVgroove) == "heightfield" ? CheckSurface::heightfield
                                                                                             : CheckSurface::vgroove;
  if (s.surface == CheckSurface::heightfield) {
    support::JsonObject h = root.object("heightfield");
    s.fields = static_cast<int>(h.integer("fields", 2, 1000));
    s.field_size = static_cast<int>(h.integer("field_size", 16, 65536));
    s.correlation_length = h.number("correlation_length", 2.0, true, 65536.0 / 8.0, true);
    h.finish();
  } else if (root.has("heightfield")) {
    root.fail("heightfield", "is given but surface is \"vgroove\" (set \"surface\": \"heightfield\")");
  }
  s.grooves =
      static_cast<int>(s.surface == CheckSurface::heightfield ? root.integer_or("grooves", s.grooves, 1, kMaxGrooves)
                                                              : root.integer("grooves", 1, kMaxGrooves));
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
    s.sigmas = t.number("sigmas", 0.0, false, kMaxSigmas, true);
    support::JsonObject m = t.object("model_tolerance");
    s.model_tolerance_flatland = m.number("flatland", 0.0, true, 2.0, true);
    s.model_tolerance_3d = m.number("3d", 0.0, true, 2.0, true);
    m.finish();
    t.finish();
  }
  root.finish();
  check_suite_surface(s, s.rays);
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
  // A heightfield suite holds one field per worker (sim::heightfield_bytes) in place of the grooves.
  const double surface =
      suite.surface == CheckSurface::heightfield ? sim::heightfield_bytes(suite.field_size) : suite.grooves * groove;
  const double per_worker = surface + 10.0 * cells * 8.0;
  const double per_case = sizeof(BrdfOutcome) + 4.0 * cells * 8.0 + (2.0 * rows + plane) * 8.0 +
                          (report ? (2.0 * rows + plane) * kNumberBytes : 0.0);
  return workers * per_worker + cases * per_case;
}

std::shared_ptr<const BrdfWork::Context> BrdfWork::prepare(std::size_t n) const {
  const BrdfCase c = suite.case_at(n);
  return std::make_shared<Context>(make_case_surface(c.dim, c.ndf, c.alpha, suite.grooves, suite.seed));
}

BinnedTally BrdfWork::run_chunks(const Context& ctx, std::size_t n, std::int64_t begin, std::int64_t end) const {
  return trace_case_chunks(ctx, case_rays(suite, suite.case_at(n), rays), begin, end, cancel);
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
  // Fractions of the incident flux, whose rows, bins and totals add up as the lobes add them
  // (analytic::flatland_lobe, vgroove_lobe_3d: by_k, hist and the albedo from hist_by_k).
  m.by_k = read_fractions(j, "by_k", rows);
  m.hist = read_fractions(j, "hist", bins);
  m.hist_by_k = read_fractions(j, "hist_by_k", rows * bins);
  m.single_hist = read_fractions(j, "single_hist", bins);
  m.albedo = read_fraction(j, "albedo");
  m.single_albedo = read_fraction(j, "single_albedo");
  check_model_margins(j, "hist_by_k", m.hist_by_k, m.by_k, "by_k", m.hist, "hist");
  check_model_sum(j, "by_k", m.by_k, m.albedo, "albedo");
  check_model_sum(j, "single_hist", m.single_hist, m.single_albedo, "single_albedo");
  if (suite.case_at(n).dim == SurfaceDim::three_d) {
    // In 3D Cook-Torrance is the lobe's k = 1 row (cook_torrance_lobe_3d_from), bit for bit.
    for (std::size_t b = 0; b < bins; ++b)
      if (m.single_hist[b] != m.hist_by_k[bins + b])
        j.fail_at("single_hist", b,
                  "= " + support::value_text(j.raw("single_hist")[b]) + " is not hist_by_k/" +
                      std::to_string(bins + b) + " (the k = 1 row)");
    if (m.single_albedo != m.by_k[1])
      j.fail("single_albedo", "= " + support::value_text(j.raw("single_albedo")) + " is not by_k/1");
  }
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
    run.cases.push_back(finish(suite, c, results[n].tally, *results[n].fixed));
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
  nlohmann::json j =
      report_header({suite.name, suite.file, suite.kind, suite.description, suite.seed}, run.threads, run.wall_s);
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
    nlohmann::json c = lobe_case_json(o, o.c.dim == SurfaceDim::flatland);
    c["ndf"] = analytic::ndf_name(o.c.ndf);
    c["alpha"] = o.c.alpha;
    c["theta_i_deg"] = output_deg(o.c.theta_i);
    c["dimension"] = surface_dim_name(o.c.dim);
    put_gamma(c, o.c.ndf);
    c["in_flight_at_bounce_limit"] = o.in_flight;
    c["albedo_cook_torrance"] = o.albedo_single;
    c["cook_torrance_energy_lost"] = 1.0 - o.albedo_single;
    c["albedo_difference"] = o.albedo_sim - o.albedo_model;
    c["plane"]["cook_torrance"] = o.plane_single;
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
  print_table_title(
      os, suite.name, suite.kind,
      support::format("%zu cases, %ld rays x %d grooves each", run.cases.size(), suite.rays, suite.grooves),
      run.threads);
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
  print_table_close(os, passed, run.cases.size(), run.wall_s);
}

}  // namespace vgroove::validation
