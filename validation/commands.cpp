#include "validation/commands.h"

#include "analytic/kaleidoscope.h"
#include "sim/beam.h"
#include "sim/tally.h"
#include "validation/atomic_file.h"
#include "validation/cost_curve.h"
#include "validation/json_reader.h"
#include "validation/microsurface_case.h"
#include "validation/plot.h"
#include "validation/report.h"
#include "validation/suite_run.h"
#include "validation/user_error.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <unistd.h>

namespace vgroove::validation {

namespace {

constexpr double kRad = M_PI / 180.0;
constexpr long kMaxRays = 1'000'000'000;

// A run stopped by Ctrl-C: nothing is written, and the exit status says why.
int interrupted_no_report() {
  std::cerr << "\nvgroove: interrupted; no report written\n";
  return kExitInterrupted;
}


void check_seed(long long seed, const std::string& what) {
  if (seed < 0)
    throw UserError(what + " = " + std::to_string(seed) + " is out of range [0, " +
                    std::to_string(std::numeric_limits<long long>::max()) + "]");
}

void check_rays(long rays, const std::string& what) {
  if (rays < 1 || rays > kMaxRays)
    throw UserError(what + " = " + std::to_string(rays) + " is out of range [1, " + std::to_string(kMaxRays) + "]");
}

sim::Sampling parse_sampling(const std::string& s, const std::string& what) {
  if (s == "stratified") return sim::Sampling::stratified;
  if (s == "random") return sim::Sampling::random;
  throw UserError(what + " = \"" + s + "\" is not one of \"stratified\", \"random\"");
}

analytic::Eq6Form parse_form(const std::string& s, const std::string& what) {
  if (s == "corrected") return analytic::Eq6Form::corrected;
  if (s == "printed") return analytic::Eq6Form::printed;
  throw UserError(what + " = \"" + s + "\" is not one of \"corrected\", \"printed\"");
}

// One row of the trace/analytic JSON: the same shape from both, so the two can be diffed.
nlohmann::json bounce_row(const char* facet, int k, double fraction, double theta_o) {
  return {{"first_facet", facet}, {"k", k}, {"fraction", fraction}, {"theta_o_deg", output_deg(theta_o)}};
}

void print_rows(const nlohmann::json& rows) {
  std::printf("  first facet    k   fraction      theta_o (deg)\n");
  for (const auto& r : rows)
    std::printf("  %-11s %4d   %-12.6g  %.9g\n", r["first_facet"].get<std::string>().c_str(), r["k"].get<int>(),
                r["fraction"].get<double>(), r["theta_o_deg"].get<double>());
}

// Progress on stderr, only when it is a terminal and the run takes a while.
ProgressFn terminal_progress(const std::string& label) {
  if (!::isatty(STDERR_FILENO)) return {};
  auto start = std::chrono::steady_clock::now();
  auto last = std::make_shared<std::chrono::steady_clock::time_point>(start);
  auto mu = std::make_shared<std::mutex>();
  return [=](std::size_t done, std::size_t total) {
    std::lock_guard<std::mutex> lock(*mu);
    const auto now = std::chrono::steady_clock::now();
    if (done < total && now - *last < std::chrono::milliseconds(250)) return;
    if (now - start < std::chrono::seconds(1) && done < total) return;
    *last = now;
    std::fprintf(stderr, "\r%s: %zu/%zu cases (%.0f%%)%s", label.c_str(), done, total,
                 100.0 * static_cast<double>(done) / static_cast<double>(total), done == total ? "\n" : "");
  };
}

// The groove the options name, checked; nonsymmetric grooves need both facet angles.
GrooveParams groove_from(const GrooveArgs& g) {
  if (!g.nonsymmetric) {
    check_theta_v(g.theta_v_deg, "--theta-v-deg");
    return GrooveParams::make_symmetric(g.theta_v_deg * kRad);
  }
  if (g.theta_v_given)
    throw UserError("--theta-v-deg cannot be combined with --theta-l-deg/--theta-r-deg (the aperture follows from them)");
  check_theta_l(g.theta_l_deg, "--theta-l-deg");
  check_theta_r(g.theta_r_deg, "--theta-r-deg");
  GrooveParams p = GrooveParams::make_nonsymmetric(g.theta_l_deg * kRad, g.theta_r_deg * kRad);
  const double v = 180.0 + g.theta_l_deg - g.theta_r_deg;
  if (p.degenerate() || v < kMinApertureDeg)
    throw UserError("--theta-l-deg = " + number_text(g.theta_l_deg) + " with --theta-r-deg = " +
                    number_text(g.theta_r_deg) + " gives the aperture theta_v = 180 + theta_l - theta_r = " +
                    number_text(v) + ", out of range [" + number_text(kMinApertureDeg) + ", 180]");
  return p;
}

}  // namespace

int cmd_trace(const TraceArgs& a) {
  const GrooveParams params = groove_from(a.groove);
  check_theta_i(a.theta_i_deg, "--theta-i-deg");
  check_rays(a.rays, "--rays");
  if (a.max_bounces < 1) throw UserError("--max-bounces = " + std::to_string(a.max_bounces) + " is out of range [1, 2147483647]");
  const sim::Sampling sampling = parse_sampling(a.sampling, "--sampling");
  check_seed(a.seed, "--seed");
  if (a.dry_run) return 0;
  const double theta_i = a.theta_i_deg * kRad;
  const sim::Groove g = make_groove(params);
  const sim::Interval open = sim::opening(g);
  const sim::Vec2 dir = sim::beam_direction(theta_i);
  sim::Rng rng(static_cast<std::uint64_t>(a.seed), 0, 0);
  sim::Tally tally;
  for (long j = 0; j < a.rays; ++j)
    tally.add(sim::trace(g, sim::beam_ray(g, dir, sim::sample_position(sampling, open, j, a.rays, rng)),
                         sim::TraceOptions{a.max_bounces}));
  nlohmann::json rows = nlohmann::json::array();
  double max_spread = 0.0;
  for (int f = 0; f < 2; ++f)
    for (std::size_t k = 0; k < tally.bins[f].size(); ++k) {
      const sim::BounceBin& b = tally.bins[f][k];
      if (b.count == 0) continue;
      rows.push_back(bounce_row(f == 0 ? "left" : "right", static_cast<int>(k),
                                static_cast<double>(b.count) / static_cast<double>(a.rays), b.theta_o()));
      max_spread = std::max(max_spread, b.spread());
    }
  nlohmann::json j = provenance();
  j["inputs"] = groove_json(params);
  j["inputs"].update({{"theta_i_deg", a.theta_i_deg}, {"rays", a.rays}, {"sampling", a.sampling}, {"seed", a.seed},
                      {"max_bounces", a.max_bounces}});
  j["bounces"] = rows;
  j["rays"] = tally.rays;
  j["buckets"] = {{"escaped", tally.escaped}, {"blocked", tally.blocked}, {"vertex_hit", tally.vertex_hits},
                  {"bounce_limit", tally.bounce_limit}};
  j["max_exit_spread_rad"] = max_spread;
  if (a.json) {
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("trace: %s, theta_i %g deg, %ld rays (%s, seed %lld); fractions of the beam entering the opening\n",
                groove_text(params).c_str(), a.theta_i_deg, a.rays, a.sampling.c_str(),
                a.seed);
    print_rows(rows);
    std::printf("  escaped %lld, vertex hits %lld, bounce limit %lld; largest exit-angle spread in a bin %.3g rad\n",
                static_cast<long long>(tally.escaped), static_cast<long long>(tally.vertex_hits),
                static_cast<long long>(tally.bounce_limit), max_spread);
  }
  return 0;
}

int cmd_analytic(const AnalyticArgs& a) {
  const GrooveParams params = groove_from(a.groove);
  check_theta_i(a.theta_i_deg, "--theta-i-deg");
  const analytic::Eq6Form form = parse_form(a.eq6_form, "--eq6-form");
  if (a.dry_run) return 0;
  const double theta_i = a.theta_i_deg * kRad;
  nlohmann::json rows = nlohmann::json::array();
  nlohmann::json facets = nlohmann::json::object();
  // G is normalized by each facet's projected width f_a; the beam entering the opening is as wide
  // as the two facets' unshadowed parts together, f_a - f_b summed.
  ModelShares m[2];
  double width = 0.0;
  for (sim::Side side : {sim::Side::left, sim::Side::right}) {
    m[static_cast<int>(side)] = model_shares(params, theta_i, side, form);
    const ModelShares& p = m[static_cast<int>(side)];
    if (p.lit) width += p.f_a * (1.0 - p.shadow);
  }
  for (sim::Side side : {sim::Side::left, sim::Side::right}) {
    const ModelShares& p = m[static_cast<int>(side)];
    const char* name = sim::side_name(side);
    if (!p.lit) {
      facets[name] = nullptr;
      continue;
    }
    // Zones that share a bounce count (k_b - 1 = 1 when k_b = 2) are one row.
    std::map<int, std::pair<double, double>> by_n;  // n -> (G, theta_o)
    for (int z = 0; z < p.shares; ++z) {
      auto& e = by_n[p.share[z].n];
      e.first += p.share[z].G;
      e.second = p.share[z].theta_o;
    }
    nlohmann::json G = nlohmann::json::object();
    for (const auto& [n, e] : by_n) {
      G[std::to_string(n)] = e.first;
      if (e.first != 0.0) rows.push_back(bounce_row(name, n, e.first * p.f_a / width, e.second));
    }
    facets[name] = {{"k", p.k}, {"f_a", p.f_a}, {"G", G}, {"shadow", p.shadow}};
  }
  nlohmann::json j = provenance();
  j["inputs"] = groove_json(params);
  j["inputs"].update({{"theta_i_deg", a.theta_i_deg}, {"eq6_form", a.eq6_form}});
  j["bounces"] = rows;
  j["facets"] = facets;
  if (a.json) {
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("analytic (Lee et al. 2018, %s): %s, theta_i %g deg; fractions of the beam entering the opening\n",
                params.symmetric ? (a.eq6_form == "printed" ? "Eq. 4-6 as printed" : "Eq. 4-6") : "Eq. 7-9",
                groove_text(params).c_str(), a.theta_i_deg);
    print_rows(rows);
  }
  return 0;
}

namespace {
CaseOptions options_with_overrides(const Suite& suite, long rays, const std::string& sampling,
                                   const std::string& form, long long seed) {
  CaseOptions o = suite.options;
  if (rays != kUnset) check_rays(rays, "--rays"), o.rays = rays;
  if (!sampling.empty()) o.sampling = parse_sampling(sampling, "--sampling");
  if (!form.empty()) o.form = parse_form(form, "--eq6-form");
  if (seed != kUnsetSeed) check_seed(seed, "--seed"), o.seed = static_cast<std::uint64_t>(seed);
  return o;
}
void check_threads(int threads) {
  if (threads < 0 || threads > 1024)
    throw UserError("--threads = " + std::to_string(threads) + " is out of range [0, 1024] (0: all cores)");
}
}  // namespace

namespace {
// Suites of procedural microsurfaces: "kind" brdf (Fig. 11), furnace, table2.
bool is_microsurface_suite(const nlohmann::json& j) {
  if (!j.is_object() || !j.contains("kind") || !j["kind"].is_string()) return false;
  const std::string k = j["kind"].get<std::string>();
  return k == "brdf" || k == "furnace" || k == "table2";
}

int validate_microsurface(const ValidateArgs& a, const nlohmann::json& j) {
  const std::string kind = j["kind"].get<std::string>();
  if (!a.sampling.empty())
    throw UserError("--sampling applies to single-groove suites; " + a.suite + " (kind " + kind +
                    ") lands its rays at random points of the surface");
  if (!a.eq6_form.empty())
    throw UserError("--eq6-form applies to single-groove suites; " + a.suite + " (kind " + kind +
                    ") uses the corrected Eq. 6 throughout");
  if (a.rays != kUnset) check_rays(a.rays, "--rays");
  if (a.seed != kUnsetSeed) check_seed(a.seed, "--seed");
  const long rays = a.rays != kUnset ? a.rays : 0;
  auto with_seed = [&](auto suite) {
    if (a.seed != kUnsetSeed) suite.seed = static_cast<std::uint64_t>(a.seed);
    return suite;
  };
  std::string report;
  bool pass = false;
  if (kind == "table2") {
    const Table2Suite suite = with_seed(parse_table2_suite(j, a.suite));
    if (!a.out.empty()) check_writable_target(a.out, a.force);
    if (a.dry_run) return 0;
    const Table2Run run = run_table2_suite(suite, rays, a.threads, a.cancel);
    if (run.interrupted) return interrupted_no_report();
    print_table2(std::cout, suite, run);
    report = table2_report_json(suite, run).dump(1) + "\n";
    pass = run.pass;
  } else {
    const BrdfSuite suite = with_seed(parse_brdf_suite(j, a.suite));
    if (!a.out.empty()) check_writable_target(a.out, a.force);
    if (a.dry_run) return 0;
    const BrdfRun run = run_brdf_suite(suite, rays, a.threads, terminal_progress("validate " + suite.name), a.cancel);
    if (run.interrupted) return interrupted_no_report();
    print_brdf_table(std::cout, suite, run);
    report = brdf_report_json(suite, run).dump(1) + "\n";
    pass = run.pass;
  }
  if (!a.out.empty()) {
    write_file_atomically(a.out, report, a.force);
    std::cout << "report: " << a.out << "\n";
  }
  return pass ? 0 : 1;
}
}  // namespace

int cmd_validate(const ValidateArgs& a) {
  check_threads(a.threads);
  if (const nlohmann::json j = read_json_file(a.suite); is_microsurface_suite(j)) return validate_microsurface(a, j);
  const SuiteSet set = load_suite_set(a.suite);
  std::vector<CaseOptions> opts;
  for (const Suite& suite : set.suites) opts.push_back(options_with_overrides(suite, a.rays, a.sampling, a.eq6_form, a.seed));
  if (!a.out.empty()) check_writable_target(a.out, a.force);  // fail before the work, not after
  if (a.dry_run) return 0;
  std::vector<SuiteRun> runs;
  bool pass = true;
  for (std::size_t n = 0; n < set.suites.size(); ++n) {
    runs.push_back(
        run_suite(set.suites[n], opts[n], a.threads, terminal_progress("validate " + set.suites[n].name), a.cancel));
    if (runs.back().interrupted) return interrupted_no_report();
    pass = pass && runs.back().summary.pass();
  }
  print_set_table(std::cout, set, runs);
  if (!a.out.empty()) {
    write_file_atomically(a.out, report_json(set, runs).dump(1) + "\n", a.force);
    std::cout << "report: " << a.out << "\n";
  }
  return pass ? 0 : 1;
}

int cmd_bench_accuracy(const AccuracyArgs& a) {
  check_threads(a.threads);
  const SuiteSet set = load_suite_set(a.suite);
  if (set.suites.size() != 1)
    throw UserError(a.suite + ": is a set of " + std::to_string(set.suites.size()) +
                    " suites; `bench accuracy` takes one suite file (e.g. data/suites/table1_symmetric.json)");
  const Suite& suite = set.suites.front();
  for (long r : a.rays) check_rays(r, "--rays");
  std::vector<sim::Sampling> samplings;
  for (const auto& s : a.samplings) samplings.push_back(parse_sampling(s, "--sampling"));
  if (!a.out.empty()) check_writable_target(a.out, a.force);
  if (a.dry_run) return 0;

  nlohmann::json runs = nlohmann::json::array();
  std::printf("accuracy against rays: suite %s (%zu cases), vgroove %s (git %s)\n", suite.name.c_str(), suite.cases(),
              version_string(), git_revision());
  std::printf("  %-10s %10s %12s %12s %12s %10s %8s\n", "sampling", "rays/facet", "max L1", "mean L1", "rays",
              "wall s", "pass");
  int threads_used = 0;
  for (sim::Sampling smp : samplings)
    for (long rays : a.rays) {
      CaseOptions o = suite.options;
      o.rays = rays;
      o.sampling = smp;
      const SuiteRun run = run_suite(
          suite, o, a.threads, terminal_progress(std::string(sim::sampling_name(smp)) + " " + std::to_string(rays)),
          a.cancel);
      if (run.interrupted) return interrupted_no_report();
      threads_used = run.threads;
      const Summary& s = run.summary;
      std::printf("  %-10s %10ld %12.4g %12.4g %12lld %10.3f %8s\n", sim::sampling_name(smp), rays, s.max_l1,
                  s.mean_l1, static_cast<long long>(s.rays), s.wall_s, s.pass() ? "yes" : "no");
      std::fflush(stdout);
      runs.push_back({{"sampling", sim::sampling_name(smp)}, {"rays_per_facet", rays}, {"max_l1", s.max_l1},
                      {"mean_l1", s.mean_l1}, {"max_theta_o_error_rad", s.max_theta_o_error}, {"rays", s.rays},
                      {"bounces", s.bounces}, {"wall_s", s.wall_s}, {"bounces_per_s", s.bounces_per_s},
                      {"pass", s.pass()}});
    }
  // Which placement reaches the suite's thresholds first, in wall time.
  std::string fastest = "none";
  double fastest_s = 0.0;
  for (const auto& r : runs)
    if (r["pass"].get<bool>() && (fastest == "none" || r["wall_s"].get<double>() < fastest_s))
      fastest = r["sampling"].get<std::string>() + " at " + std::to_string(r["rays_per_facet"].get<long>()) +
                " rays per facet",
      fastest_s = r["wall_s"].get<double>();
  std::printf("  reaches the thresholds (max L1 <= %g, mean L1 <= %g) soonest: %s\n", suite.thresholds.max_l1,
              suite.thresholds.mean_l1, fastest.c_str());
  // The tracer's cost grows like pi / theta_v; the model's does not (one thread, theta_i = 30 deg).
  const double kTheta_i = 30.0 * kRad;
  const std::vector<double> apertures_deg = {1, 2, 5, 10, 20, 45, 90, 135, 180};
  std::vector<double> apertures;
  for (double d : apertures_deg) apertures.push_back(d * kRad);
  const std::vector<CostPoint> cost = cost_vs_theta_v(apertures, kTheta_i, 20000);
  nlohmann::json cost_json = nlohmann::json::array();
  std::printf("  cost against theta_v (one thread, theta_i = 30 deg, 20000 stratified rays):\n");
  std::printf("  %10s %12s %14s %16s %13s\n", "theta_v", "bounces/ray", "tracer ns/ray", "model ns/eval", "tracer/model");
  for (const CostPoint& c : cost) {
    std::printf("  %10.0f %12.2f %14.1f %16.1f %13.3f\n", output_deg(c.theta_v), c.bounces_per_ray, c.tracer_ns_per_ray,
                c.model_ns_per_eval, c.tracer_ns_per_ray / c.model_ns_per_eval);
    cost_json.push_back({{"theta_v_deg", output_deg(c.theta_v)}, {"bounces_per_ray", c.bounces_per_ray},
                         {"tracer_ns_per_ray", c.tracer_ns_per_ray}, {"model_ns_per_eval", c.model_ns_per_eval}});
  }
  if (!a.out.empty()) {
    nlohmann::json j = provenance();
    j["suite"] = suite.name;
    j["suite_file"] = suite.file;
    j["seed"] = suite.options.seed;
    j["threads"] = threads_used;
    j["runs"] = runs;
    j["thresholds"] = {{"max_l1", suite.thresholds.max_l1}, {"mean_l1", suite.thresholds.mean_l1}};
    j["soonest_to_thresholds"] = fastest;
    j["cost_vs_theta_v"] = {{"theta_i_deg", 30.0}, {"rays", 20000}, {"threads", 1}, {"points", cost_json}};
    write_file_atomically(a.out, j.dump(1) + "\n", a.force);
    std::printf("report: %s\n", a.out.c_str());
  }
  return 0;
}

int cmd_plot(const PlotArgs& a) {
  const nlohmann::json report = read_json_file(a.report);
  std::string out = a.out;
  if (out.empty()) {
    out = a.report;
    const auto dot = out.rfind(".json");
    out = (dot != std::string::npos && dot + 5 == out.size() ? out.substr(0, dot) : out) + ".svg";
  }
  if (is_brdf_report(report)) {
    // The Fig. 11 grid: one SVG per (NDF, dimension), named after --out (or the report).
    const std::string base = out.size() > 4 && out.compare(out.size() - 4, 4, ".svg") == 0 ? out.substr(0, out.size() - 4) : out;
    const auto svgs = brdf_grid_svgs(report, a.report);
    for (const auto& [suffix, svg] : svgs) check_writable_target(base + "-" + suffix + ".svg", a.force);
    if (a.dry_run) return 0;
    for (const auto& [suffix, svg] : svgs) {
      write_file_atomically(base + "-" + suffix + ".svg", svg, a.force);
      std::printf("plot: %s\n", (base + "-" + suffix + ".svg").c_str());
    }
    return 0;
  }
  const std::string svg = accuracy_svg(report, a.report);
  const std::string cost = cost_svg(report);
  const std::string cost_out = (out.size() > 4 && out.compare(out.size() - 4, 4, ".svg") == 0 ? out.substr(0, out.size() - 4) : out) + "-cost.svg";
  check_writable_target(out, a.force);
  if (!cost.empty()) check_writable_target(cost_out, a.force);
  if (a.dry_run) return 0;
  write_file_atomically(out, svg, a.force);
  std::printf("plot: %s\n", out.c_str());
  if (!cost.empty()) {
    write_file_atomically(cost_out, cost, a.force);
    std::printf("plot: %s\n", cost_out.c_str());
  }
  return 0;
}

}  // namespace vgroove::validation
