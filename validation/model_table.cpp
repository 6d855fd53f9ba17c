#include "vgroove/validation/model_table.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/common/angles.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/detail/part_fields.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/report.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

int bins_of(const BrdfSuite& s, SurfaceDim d) {
  return d == SurfaceDim::flatland ? s.flatland_bins : s.theta_bins * s.phi_bins;
}

std::vector<double> edges_deg(double lo, double hi, int n) {
  std::vector<double> e;
  for (int i = 0; i <= n; ++i) e.push_back(output_deg(lo + (hi - lo) * i / n));
  return e;
}

// The suite's tolerance for the model's own integration, per dimension.
double tolerance(const BrdfSuite& s, SurfaceDim d) {
  return d == SurfaceDim::flatland ? s.model_tolerance_flatland : s.model_tolerance_3d;
}

bool heightfield(const BrdfSuite& s) { return s.surface == CheckSurface::heightfield; }

nlohmann::json surface_json(const BrdfSuite& s) {
  if (!heightfield(s)) return {{"surface", "vgroove"}, {"grooves", s.grooves}};
  return {{"surface", "heightfield"},
          {"heightfield",
           {{"fields", s.fields},
            {"field_size", s.field_size},
            {"correlation_length", s.correlation_length},
            {"field_bytes", sim::heightfield_bytes(s.field_size)}}}};
}

}  // namespace

CheckBrdfOptions case_check_options(const BrdfSuite& s, std::size_t c, long rays) {
  const BrdfCase k = s.case_at(c);
  CheckBrdfOptions o;
  o.name = s.name;
  o.ndf = k.ndf, o.alpha = k.alpha, o.dim = k.dim;
  o.theta_i_deg.clear();
  for (double t : s.theta_i) o.theta_i_deg.push_back(output_deg(t));
  o.rays = rays > 0 ? rays : s.rays;
  o.grooves = s.grooves;
  o.surface = s.surface;
  o.field_size = s.field_size, o.correlation_length = s.correlation_length, o.fields = s.fields;
  o.seed = s.seed;
  o.theta_bins = s.theta_bins, o.phi_bins = s.phi_bins, o.flatland_bins = s.flatland_bins;
  o.sigmas = s.sigmas;
  o.model_tolerance = tolerance(s, k.dim);
  return o;
}

void check_suite_surface(const BrdfSuite& s, long rays) {
  if (!heightfield(s)) return;
  for (std::size_t c = 0; c < s.cases(); ++c) {
    try {
      check_options(case_check_options(s, c, rays));
    } catch (const support::UserError& e) {
      throw support::UserError(s.file + ": surface heightfield: " + e.what());
    }
  }
}

nlohmann::json bin_layout_json(const BrdfSuite& s) {
  constexpr double pi = std::numbers::pi;
  nlohmann::json j = provenance();
  j["kind"] = "bin_layout";
  j["suite"] = s.name;
  j["suite_file"] = s.file;
  j["rays"] = s.rays;
  j.update(surface_json(s));
  j["seed"] = s.seed;
  j["frame"] =
      "n = (0, 0, 1); the light at polar angle theta_i and azimuth 180 deg, so its mirror direction is at "
      "azimuth 0; flux = the fraction of the incident light leaving into the bin, i.e. the integral over the bin "
      "of f(wi, wo) cos(theta_o) d omega_o (flatland: d theta_o, signed angles, positive towards the light)";
  const double dp = 360.0 / s.phi_bins;
  std::vector<double> phi_edges;
  for (int p = 0; p <= s.phi_bins; ++p) phi_edges.push_back(-0.5 * dp + p * dp);
  j["bins"] = {{"flatland",
                {{"count", s.flatland_bins}, {"theta_o_deg_edges", edges_deg(-0.5 * pi, 0.5 * pi, s.flatland_bins)}}},
               {"3d",
                {{"count", s.theta_bins * s.phi_bins},
                 {"theta_o_deg_edges", edges_deg(0.0, 0.5 * pi, s.theta_bins)},
                 {"phi_o_deg_edges", phi_edges},
                 {"order",
                  "index = theta_bin * phi_bins + phi_bin; phi bin p covers [p - 1/2, p + 1/2) x 360/phi_bins "
                  "deg, modulo 360"}}}};
  nlohmann::json cases = nlohmann::json::array();
  for (std::size_t c = 0; c < s.cases(); ++c) {
    const BrdfCase k = s.case_at(c);
    cases.push_back({{"case", c},
                     {"ndf", ndf_name(k.ndf)},
                     {"alpha", k.alpha},
                     {"theta_i_deg", output_deg(k.theta_i)},
                     {"dimension", surface_dim_name(k.dim)},
                     {"bins", bins_of(s, k.dim)}});
  }
  j["cases"] = cases;
  return j;
}

ModelTable parse_model_table(const nlohmann::json& j, const std::string& file, const BrdfSuite& s) {
  support::JsonObject root(j, file, "");
  ModelTable t;
  t.file = file;
  root.one_of("kind", {"model_table"});
  const std::string suite = root.string("suite");
  if (suite != s.name)
    root.fail("suite", "= \"" + suite + "\" names another suite; this table must be made for \"" + s.name + "\"");
  t.model = root.string_or("model", "");
  const nlohmann::json& list = root.raw("cases");
  root.finish();
  if (!list.is_array())
    throw support::UserError(file + ": /cases must be a list of the suite's " + std::to_string(s.cases()) + " cases");
  t.flux.assign(s.cases(), {});
  std::vector<bool> seen(s.cases(), false);
  for (std::size_t n = 0; n < list.size(); ++n) {
    const std::string at = "/cases/" + std::to_string(n);
    support::JsonObject o(list[n], file, at);
    const auto c = static_cast<std::size_t>(o.integer("case", 0, static_cast<long long>(s.cases()) - 1));
    if (seen[c]) o.fail("case", "= " + std::to_string(c) + " appears twice");
    seen[c] = true;
    const BrdfCase k = s.case_at(c);
    const std::string ndf = o.string("ndf");
    const double alpha = o.number("alpha", 0.0, false, 2.0, true);
    const double theta_i = o.number("theta_i_deg", 0.0, true, 90.0, false);
    const std::string dim = o.string("dimension");
    if (ndf != ndf_name(k.ndf) || alpha != k.alpha || theta_i != output_deg(k.theta_i) ||
        dim != surface_dim_name(k.dim)) {
      const std::string want = support::format("ndf %s, alpha %g, theta_i_deg %g, dimension %s", ndf_name(k.ndf),
                                               k.alpha, output_deg(k.theta_i), surface_dim_name(k.dim));
      o.fail("case", "= " + std::to_string(c) + " is " + want + " in the layout (`vgroove bins " + s.file + "`)");
    }
    const nlohmann::json& flux = o.raw("flux");
    o.finish();
    const std::size_t bins = static_cast<std::size_t>(bins_of(s, k.dim));
    if (!flux.is_array() || flux.size() != bins)
      throw support::UserError(file + ": " + at + "/flux must be a list of " + std::to_string(bins) +
                               " numbers (the layout's bins for " + surface_dim_name(k.dim) + "), found " +
                               (flux.is_array() ? std::to_string(flux.size()) + " values" : flux.type_name()));
    for (std::size_t b = 0; b < bins; ++b) {
      const nlohmann::json& v = flux[b];
      // A bin holds at most all the incident light: a larger value is no fraction of it (and
      // values near 1e308 would overflow the case's albedo).
      if (!v.is_number() || !(v.get<double>() >= 0.0 && v.get<double>() <= 1.0))
        throw support::UserError(file + ": " + at + "/flux/" + std::to_string(b) + " = " + support::value_text(v) +
                                 " must be a number in [0, 1] (a fraction of the incident flux)");
      t.flux[c].push_back(v.get<double>());
    }
  }
  for (std::size_t c = 0; c < s.cases(); ++c)
    if (!seen[c])
      throw support::UserError(file + ": /cases has no entry for case " + std::to_string(c) + " (" +
                               std::to_string(s.cases()) + " cases expected, see `vgroove bins " + s.file + "`)");
  return t;
}

std::size_t ModelTableWork::case_of(std::size_t u) const {
  return heightfield(suite) ? u / static_cast<std::size_t>(suite.fields) : u;
}
int ModelTableWork::field_of(std::size_t u) const {
  return heightfield(suite) ? static_cast<int>(u % static_cast<std::size_t>(suite.fields)) : 0;
}

std::shared_ptr<const ModelTableWork::Context> ModelTableWork::prepare(std::size_t u) const {
  const std::size_t c = case_of(u);
  auto ctx = std::make_shared<Context>();
  if (heightfield(suite)) {
    ctx->field = check_field(case_check_options(suite, c, rays), field_of(u));
  } else {
    const BrdfCase k = suite.case_at(c);
    ctx->grooves = make_case_surface(k.dim, k.ndf, k.alpha, suite.grooves, suite.seed);
  }
  return ctx;
}

LobeTally ModelTableWork::run_chunks(const Context& ctx, std::size_t u, std::int64_t begin, std::int64_t end) const {
  const std::size_t c = case_of(u);
  if (heightfield(suite)) {
    // check_brdf's rays of field r at incidence c % theta_i (check_field_trace), chunk by chunk.
    const auto t0 = Clock::now();
    const sim::HeightfieldTraceOptions to = check_field_trace(
        case_check_options(suite, c, rays), suite.case_at(c).theta_i, c % suite.theta_i.size(), field_of(u));
    LobeTally out;
    out.hist.assign(static_cast<std::size_t>(suite.theta_bins) * static_cast<std::size_t>(suite.phi_bins), 0);
    for (std::int64_t k = begin; k < end && !support::cancelled(cancel); ++k)
      out.rays += add_field_counts(sim::trace_heightfield_chunk(ctx.field, to, k), out.hist);
    out.thread_s = seconds_since(t0);
    return out;
  }
  CaseRays r;
  r.theta_i = suite.case_at(c).theta_i, r.rays = rays, r.seed = suite.seed;
  r.flatland_bins = suite.flatland_bins, r.theta_bins = suite.theta_bins, r.phi_bins = suite.phi_bins;
  r.max_k = 0;  // the histogram alone
  BinnedTally t = trace_case_chunks(ctx.grooves, r, begin, end, cancel);
  LobeTally out;
  out.hist = std::move(t.hist), out.rays = t.rays, out.thread_s = t.thread_s;
  return out;
}

ModelTableWork::Fixed ModelTableWork::run_fixed(std::size_t) const {
  throw std::logic_error("ModelTableWork: the model is the table's, nothing to run");
}

void ModelTableWork::merge(Tally& into, const Tally& from) {
  for (std::size_t n = 0; n < into.hist.size(); ++n) into.hist[n] += from.hist[n];
  into.rays += from.rays;
  into.thread_s += from.thread_s;
}

nlohmann::json ModelTableWork::tally_json(const Tally& t) {
  return {{"hist", t.hist}, {"rays", t.rays}, {"thread_s", t.thread_s}};
}

LobeTally ModelTableWork::read_tally(support::JsonObject& j, std::size_t u, const std::vector<ChunkRun>& runs) const {
  LobeTally t;
  const std::size_t c = case_of(u);
  const std::int64_t n =
      heightfield(suite)
          ? rays_in_chunks(runs, check_field_trace(case_check_options(suite, c, rays), 0.0, 0, field_of(u)).rays,
                           sim::kHeightfieldRaysPerChunk)
          : rays_in_chunks(runs, rays, sim::kRaysPerChunk);
  t.rays = j.integer("rays", n, n);
  t.hist = read_counts(j, "hist", static_cast<std::size_t>(bins_of(suite, suite.case_at(c).dim)), t.rays);
  std::int64_t escaped = 0;
  for (std::int64_t h : t.hist) escaped += h;  // each <= rays <= 2^62 over at most 10^9 bins: no overflow in practice
  if (escaped > t.rays)
    j.fail("hist", "holds " + std::to_string(escaped) + " rays, more than the " + std::to_string(t.rays) + " traced");
  t.thread_s = j.number("thread_s", 0.0, true, std::numeric_limits<double>::max(), true);
  return t;
}

ModelTableWork::Fixed ModelTableWork::read_fixed(support::JsonObject& j, std::size_t) const {
  throw support::UserError(j.file() + ": " + j.pointer() + " is given: a model-table case has no fixed part");
}

Job<ModelTableWork> model_table_job(const BrdfSuite& s, long rays, nlohmann::json descriptor,
                                    const std::atomic<bool>* cancel) {
  const long n_rays = rays > 0 ? rays : s.rays;
  ModelTableWork work{s, n_rays, cancel};
  if (heightfield(s)) {
    // A unit per case and field, its chunks those of the field's rays (cost: ~40 ray steps each).
    check_suite_surface(s, n_rays);
    std::vector<support::WorkUnit> units(s.cases() * static_cast<std::size_t>(s.fields));
    for (std::size_t u = 0; u < units.size(); ++u) {
      const sim::HeightfieldTraceOptions to =
          check_field_trace(case_check_options(s, work.case_of(u), n_rays), 0.0, 0, work.field_of(u));
      units[u].chunks = sim::heightfield_chunk_count(to);
      units[u].chunk_cost = 40;
    }
    return make_job(std::move(work), std::move(units), std::move(descriptor));
  }
  const std::int64_t chunks = (static_cast<std::int64_t>(n_rays) + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
  std::vector<support::WorkUnit> units(s.cases());
  for (std::size_t c = 0; c < s.cases(); ++c) {
    units[c].chunks = chunks;
    units[c].chunk_cost = s.case_at(c).dim == SurfaceDim::flatland ? 1 : 4;
  }
  return make_job(std::move(work), std::move(units), std::move(descriptor));
}

ModelTableRun model_table_run_from(const BrdfSuite& s, const ModelTable& t, long rays,
                                   const std::vector<UnitResult<ModelTableWork>>& results) {
  ModelTableRun run;
  run.rays = rays > 0 ? rays : s.rays;
  run.pass = true;
  const std::size_t F = heightfield(s) ? static_cast<std::size_t>(s.fields) : 1;
  for (std::size_t c = 0; c < results.size() / F; ++c) {
    const BrdfCase k = s.case_at(c);
    LobeTally traced;
    std::vector<double> flux;
    CheckBrdfCase out;
    if (heightfield(s)) {
      // The fields' tallies pooled, the noise from their spread: check_brdf's heightfield route.
      std::vector<std::vector<std::int64_t>> counts;
      std::vector<std::int64_t> rays_of;
      for (std::size_t r = 0; r < F; ++r) {
        const LobeTally& f = results[c * F + r].tally;
        counts.push_back(f.hist), rays_of.push_back(f.rays);
        traced.rays += f.rays, traced.thread_s += f.thread_s;
      }
      const FieldLobe pooled = pool_fields(counts, rays_of);
      flux = pooled.flux;
      out = check_lobes_with_variance(flux, t.flux[c], pooled.var, pooled.albedo_var, static_cast<double>(traced.rays),
                                      s.sigmas, tolerance(s, k.dim));
    } else {
      traced = results[c].tally;
      flux = fractions(traced.hist, static_cast<double>(traced.rays));
      out = check_lobes(flux, t.flux[c], static_cast<double>(traced.rays), s.grooves, s.sigmas, tolerance(s, k.dim));
    }
    out.theta_i_deg = output_deg(k.theta_i);
    out.rays = traced.rays;
    out.sim_wall_s = traced.thread_s;
    out.worst = worst_bins(flux, t.flux[c], k.dim, s.theta_bins, s.phi_bins, s.flatland_bins);
    run.pass = run.pass && out.pass;
    run.cases.push_back(std::move(out));
  }
  return run;
}

ModelTableRun run_model_table(const BrdfSuite& s, const ModelTable& t, long rays, int threads,
                              const std::atomic<bool>* cancel) {
  const auto t0 = Clock::now();
  const auto results = run_job(model_table_job(s, rays, {}, cancel), threads, {}, cancel);
  ModelTableRun run;
  if (results) run = model_table_run_from(s, t, rays, *results);
  run.rays = rays > 0 ? rays : s.rays;
  run.threads = support::resolve_threads(threads);
  run.wall_s = seconds_since(t0);
  run.interrupted = !results;
  run.pass = run.pass && !run.interrupted;
  return run;
}

nlohmann::json model_table_report_json(const BrdfSuite& s, const ModelTable& t, const ModelTableRun& run) {
  nlohmann::json j = provenance();
  j["kind"] = "model_table";
  j["suite"] = s.name;
  j["suite_file"] = s.file;
  j["model_table"] = t.file;
  j["model"] = t.model;
  j["seed"] = s.seed;
  j["rays"] = run.rays;
  j.update(surface_json(s));
  j["threads"] = run.threads;
  j["wall_s"] = run.wall_s;
  j["thresholds"] = {{"sigmas", s.sigmas},
                     {"model_tolerance", {{"flatland", s.model_tolerance_flatland}, {"3d", s.model_tolerance_3d}}}};
  nlohmann::json cs = nlohmann::json::array();
  for (std::size_t c = 0; c < run.cases.size(); ++c) {
    const BrdfCase k = s.case_at(c);
    const CheckBrdfCase& r = run.cases[c];
    nlohmann::json worst = nlohmann::json::array();
    for (const WorstBin& w : r.worst)
      worst.push_back({{"theta_o_deg", w.theta_o_deg}, {"phi_o_deg", w.phi_o_deg}, {"sim", w.sim}, {"model", w.model}});
    cs.push_back({{"case", c},
                  {"ndf", ndf_name(k.ndf)},
                  {"alpha", k.alpha},
                  {"theta_i_deg", output_deg(k.theta_i)},
                  {"dimension", surface_dim_name(k.dim)},
                  {"rays", r.rays},
                  {"albedo_sim", r.albedo_sim},
                  {"albedo_model", r.albedo_model},
                  {"albedo_threshold", r.albedo_threshold},
                  {"l1", r.l1},
                  {"l1_expected", r.l1_expected},
                  {"l1_threshold", r.l1_threshold},
                  {"l1_flux", r.l1_flux},
                  {"l1_flux_threshold", r.l1_flux_threshold},
                  {"worst_bins", worst},
                  {"non_finite", r.non_finite},
                  {"pass", r.pass}});
  }
  j["cases"] = cs;
  j["pass"] = run.pass;
  return j;
}

void print_model_table(std::ostream& os, const BrdfSuite& s, const ModelTable& t, const ModelTableRun& run) {
  const std::string surface =
      heightfield(s) ? support::format("%ld rays over %d heightfields of %d^2 cells (correlation length %g) each",
                                       run.rays, s.fields, s.field_size, s.correlation_length)
                     : support::format("%ld rays x %d grooves each", run.rays, s.grooves);
  os << support::format("%s against the model table %s (%s): %zu cases, %s\n", support::printable(s.name).c_str(),
                        support::printable(t.file).c_str(),
                        t.model.empty() ? "no name" : support::printable(t.model).c_str(), run.cases.size(),
                        surface.c_str());
  os << support::format("  %-8s %-8s %6s %7s %9s %9s %9s %9s %9s %9s  %s\n", "dim", "ndf", "alpha", "theta_i", "albedo",
                        "traced", "L1", "L1 thr", "flux L1", "thr", "pass");
  for (std::size_t c = 0; c < run.cases.size(); ++c) {
    const BrdfCase k = s.case_at(c);
    const CheckBrdfCase& r = run.cases[c];
    os << support::format("  %-8s %-8s %6.2f %7.2f %9.5f %9.5f %9.5f %9.5f %9.5f %9.5f  %s\n", surface_dim_name(k.dim),
                          ndf_name(k.ndf), k.alpha, output_deg(k.theta_i), r.albedo_model, r.albedo_sim, r.l1,
                          r.l1_threshold, r.l1_flux, r.l1_flux_threshold, r.pass ? "yes" : "NO");
  }
  os << support::format("  wall %.2f s on %d threads\n%s\n", run.wall_s, run.threads, run.pass ? "PASS" : "FAIL");
}

}  // namespace vgroove::validation
