#include "vgroove/validation/model_table.h"

#include "vgroove/common/angles.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/traced_lobe.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <tuple>

namespace vgroove::validation {

namespace {

using Clock = std::chrono::steady_clock;

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

}  // namespace

nlohmann::json bin_layout_json(const BrdfSuite& s) {
  constexpr double pi = std::numbers::pi;
  nlohmann::json j = provenance();
  j["kind"] = "bin_layout";
  j["suite"] = s.name;
  j["suite_file"] = s.file;
  j["rays"] = s.rays;
  j["grooves"] = s.grooves;
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
      char want[160];
      std::snprintf(want, sizeof want, "ndf %s, alpha %g, theta_i_deg %g, dimension %s", ndf_name(k.ndf), k.alpha,
                    output_deg(k.theta_i), surface_dim_name(k.dim));
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

ModelTableRun run_model_table(const BrdfSuite& s, const ModelTable& t, long rays, int threads,
                              const std::atomic<bool>* cancel) {
  ModelTableRun run;
  run.threads = support::resolve_threads(threads);
  run.rays = rays > 0 ? rays : s.rays;
  run.cases.resize(s.cases());
  const auto t0 = Clock::now();
  // One trace per surface (ndf, alpha, dimension) over its incidences.
  std::map<std::tuple<int, double, int>, std::vector<std::size_t>> groups;
  for (std::size_t c = 0; c < s.cases(); ++c) {
    const BrdfCase k = s.case_at(c);
    groups[{static_cast<int>(k.ndf), k.alpha, static_cast<int>(k.dim)}].push_back(c);
  }
  run.pass = true;
  for (const auto& [key, members] : groups) {
    const BrdfCase first = s.case_at(members.front());
    LobeSetup setup;
    setup.ndf = first.ndf, setup.alpha = first.alpha, setup.dim = first.dim, setup.rays = run.rays;
    setup.grooves = s.grooves, setup.seed = s.seed;
    setup.theta_bins = s.theta_bins, setup.phi_bins = s.phi_bins, setup.flatland_bins = s.flatland_bins;
    std::vector<double> theta_i;
    for (std::size_t c : members) theta_i.push_back(s.case_at(c).theta_i);
    const std::vector<TracedLobe> traced = trace_lobes(setup, theta_i, run.threads, cancel);
    if (traced.size() != members.size()) {
      run.interrupted = true;
      return run;
    }
    for (std::size_t m = 0; m < members.size(); ++m) {
      const std::size_t c = members[m];
      CheckBrdfCase out = compare_lobes(traced[m].flux, t.flux[c], static_cast<double>(traced[m].rays), s.grooves,
                                        s.sigmas, tolerance(s, first.dim));
      out.theta_i_deg = output_deg(theta_i[m]);
      out.rays = traced[m].rays;
      out.sim_wall_s = traced[m].thread_s;
      out.worst = worst_bins(traced[m].flux, t.flux[c], first.dim, s.theta_bins, s.phi_bins, s.flatland_bins);
      run.pass = run.pass && out.pass;
      run.cases[c] = std::move(out);
    }
  }
  run.wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
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
  j["grooves"] = s.grooves;
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
  os << support::format("%s against the model table %s (%s): %zu cases, %ld rays x %d grooves each\n",
                        support::printable(s.name).c_str(), support::printable(t.file).c_str(),
                        t.model.empty() ? "no name" : support::printable(t.model).c_str(), run.cases.size(), run.rays,
                        s.grooves);
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
