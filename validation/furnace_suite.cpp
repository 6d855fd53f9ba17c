#include "vgroove/validation/furnace_suite.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/hemisphere_quadrature.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_flatland.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/printable.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/table_frame.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

// A stream per case, from its parameters (the results do not depend on the thread count).
sim::Rng case_rng(const FurnaceSuite& s, const BrdfCase& c) {
  // Student-T's gamma mixed in (0 for the other NDFs: their keys are as without it).
  const std::uint64_t key = std::bit_cast<std::uint64_t>(c.alpha) ^ (std::bit_cast<std::uint64_t>(c.theta_i) * 31u) ^
                            (std::bit_cast<std::uint64_t>(c.ndf.gamma) * 131u);
  return sim::Rng(s.seed, key, (static_cast<std::uint64_t>(c.dim) << 8) | static_cast<std::uint64_t>(c.ndf.family));
}

struct Mean {
  double sum = 0.0, sum2 = 0.0;
  long n = 0;
  void add(double w) { sum += w, sum2 += w * w, ++n; }
  double mean() const { return n > 0 ? sum / n : 0.0; }
  double standard_error() const {
    if (n < 2) return 0.0;
    const double m = mean();
    return std::sqrt(std::max(0.0, sum2 / n - m * m) / (n - 1));
  }
};

// What the 3D and flatland cases differ in: the BRDF under test and Cook-Torrance at an exit
// direction, the quadrature over exits, the sampler and its failure share, and the traced surface.
struct ThreeD {
  using Exit = analytic::Dir3;
  static auto rho(const FurnaceSuite& s, const BrdfCase& c, const BrdfUnderTest& brdf) {
    return [&s, &c, &brdf, i = analytic::dir3(c.theta_i, std::numbers::pi)](const Exit& o) {
      return brdf.rho3 ? brdf.rho3(i, o) : analytic::vgroove_brdf(i, o, c.ndf, c.alpha, s.max_k);
    };
  }
  static double cook_torrance(const BrdfCase& c, const Exit& o) {
    return analytic::cook_torrance(analytic::dir3(c.theta_i, std::numbers::pi), o, c.ndf, c.alpha);
  }
  static double cos_o(const Exit& o) { return o.z; }
  // The integral of f(o) cos(theta_o) over the exits, polar about the mirror direction.
  template <class F>
  static analytic::AdaptiveResult integrate(const FurnaceSuite& s, const BrdfCase& c, F&& f) {
    const analytic::Dir3 i = analytic::dir3(c.theta_i, std::numbers::pi);
    analytic::HemisphereOptions ho;
    ho.tol = s.tolerance_3d;
    ho.scale = c.alpha;
    return analytic::integrate_hemisphere(
        {-i.x, -i.y, i.z}, [&](const Exit& o) { return f(o) * o.z; }, ho);
  }
  // The light beyond max_k reflections, over the grooves: the V-cavity sampler's failure.
  static double beyond_max_k(const FurnaceSuite& s, const BrdfCase& c) {
    return analytic::sampler_failure_probability_3d(analytic::dir3(c.theta_i, std::numbers::pi), c.ndf, c.alpha,
                                                    analytic::SamplerOptions{analytic::FacetStrategy::vndf, s.max_k},
                                                    1e-8);
  }
  struct Drawn {
    int k;
    Exit o;
    double pdf;
  };
  static Drawn sample(const FurnaceSuite& s, const BrdfCase& c, const std::array<double, 4>& u) {
    const analytic::VgrooveSample3d x = analytic::sample_vgroove_3d(analytic::dir3(c.theta_i, std::numbers::pi), u,
                                                                    c.ndf, c.alpha, {s.strategy, s.max_k});
    return {x.k, x.o, x.pdf};
  }
  static sim::Microsurface3dTally trace(const FurnaceSuite& s, const BrdfCase& c) {
    sim::Microsurface3dOptions so;
    so.ndf = c.ndf, so.alpha = c.alpha, so.grooves = s.grooves, so.seed = s.seed;
    sim::Microsurface3dTraceOptions to;
    to.theta_i = c.theta_i, to.rays = s.rays, to.seed = s.seed;
    to.theta_bins = 1, to.phi_bins = 2, to.max_k = 1;
    return sim::trace_microsurface3d(sim::make_microsurface3d(so), to);
  }
};

struct Flatland {
  using Exit = double;  // theta_o
  static auto rho(const FurnaceSuite& s, const BrdfCase& c, const BrdfUnderTest& brdf) {
    return [&s, &c, &brdf](Exit to) {
      return brdf.rho2 ? brdf.rho2(c.theta_i, to)
                       : analytic::flatland_brdf_fast(c.ndf, c.alpha, c.theta_i, to, s.max_k);
    };
  }
  static double cook_torrance(const BrdfCase& c, Exit to) {
    return analytic::flatland_brdf_single(c.ndf, c.alpha, c.theta_i, to);
  }
  static double cos_o(Exit to) { return std::cos(to); }
  // A tenth of the tolerance is asked for: Gauss-Kronrod's estimates are not bounds at the BRDF's
  // jumps (errors up to twice the estimate were seen at 1e-9).
  template <class F>
  static analytic::AdaptiveResult integrate(const FurnaceSuite& s, const BrdfCase& c, F&& f) {
    return analytic::integrate_half_circle(
        c.theta_i, [&](Exit to) { return f(to) * std::cos(to); }, c.alpha, 0.1 * s.tolerance_flatland, 20000);
  }
  static double beyond_max_k(const FurnaceSuite& s, const BrdfCase& c) {
    return analytic::sampler_failure_probability_flatland(
        c.theta_i, c.ndf, c.alpha, analytic::SamplerOptions{analytic::FacetStrategy::vndf, s.max_k}, 1e-12);
  }
  struct Drawn {
    int k;
    Exit o;
    double pdf;
  };
  static Drawn sample(const FurnaceSuite& s, const BrdfCase& c, const std::array<double, 4>& u) {
    const analytic::VgrooveSampleFlatland x =
        analytic::sample_vgroove_flatland(c.theta_i, u, c.ndf, c.alpha, {s.strategy, s.max_k});
    return {x.k, x.theta_o, x.pdf};
  }
  static sim::MicrosurfaceTally trace(const FurnaceSuite& s, const BrdfCase& c) {
    sim::MicrosurfaceOptions so;
    so.ndf = c.ndf, so.alpha = c.alpha, so.grooves = s.grooves, so.seed = s.seed;
    sim::MicrosurfaceTraceOptions to;
    to.theta_i = c.theta_i, to.rays = s.rays, to.sampling = sim::Sampling::random, to.seed = s.seed;
    to.theta_o_bins = 1, to.max_k = 1;
    return sim::trace_microsurface(sim::make_microsurface(so), to);
  }
};

// One case's figures: (a) the pointwise BRDF by deterministic quadrature, (b) the importance-sampled
// estimator, and the sanity line of a traced procedural surface.
template <class Dim>
void run_case(const FurnaceSuite& s, FurnaceOutcome& out, const BrdfUnderTest& brdf) {
  const BrdfCase& c = out.c;
  const auto rho = Dim::rho(s, c, brdf);
  const auto t0 = Clock::now();
  const analytic::AdaptiveResult a = Dim::integrate(s, c, rho);
  const analytic::AdaptiveResult ct =
      Dim::integrate(s, c, [&](const typename Dim::Exit& o) { return Dim::cook_torrance(c, o); });
  out.albedo_quadrature = a.value;
  out.quadrature_error = a.error;
  out.cook_torrance_quadrature = ct.value;
  out.flux_beyond_max_k = Dim::beyond_max_k(s, c);
  out.quadrature_s = seconds_since(t0);
  const auto t1 = Clock::now();
  sim::Rng rng = case_rng(s, c);
  Mean m, mct;
  for (long n = 0; n < s.samples; ++n) {
    const std::array<double, 4> u{rng.uniform(), rng.uniform(), rng.uniform(), rng.uniform()};
    const typename Dim::Drawn x = Dim::sample(s, c, u);
    if (x.k == 0) {
      m.add(0.0), mct.add(0.0);
      continue;
    }
    const double cos_o = Dim::cos_o(x.o);
    m.add(rho(x.o) * cos_o / x.pdf);
    mct.add(Dim::cook_torrance(c, x.o) * cos_o / x.pdf);
  }
  out.albedo_estimate = m.mean();
  out.standard_error = m.standard_error();
  out.cook_torrance_estimate = mct.mean();
  out.cook_torrance_standard_error = mct.standard_error();
  out.estimate_s = seconds_since(t1);
  const auto t2 = Clock::now();
  const auto t = Dim::trace(s, c);
  out.rays = t.rays;
  out.in_flight = t.bounce_limit;
  out.albedo_sim = static_cast<double>(t.escaped + t.bounce_limit) / static_cast<double>(t.rays);
  out.sim_s = seconds_since(t2);
}

nlohmann::json suite_inputs(const FurnaceSuite& s) {
  nlohmann::json dims = nlohmann::json::array(), ti = nlohmann::json::array();
  for (auto d : s.dims) dims.push_back(surface_dim_name(d));
  for (double t : s.theta_i) ti.push_back(output_deg(t));
  nlohmann::json in = {
      {"alpha", s.alphas},    {"theta_i_deg", ti},
      {"dimensions", dims},   {"max_k", s.max_k},
      {"samples", s.samples}, {"strategy", analytic::strategy_name(s.strategy)},
      {"rays", s.rays},       {"grooves", s.grooves},
      {"sigmas", s.sigmas},   {"quadrature_tolerance", {{"flatland", s.tolerance_flatland}, {"3d", s.tolerance_3d}}}};
  put_ndfs(in, s.ndfs);
  return in;
}

}  // namespace

BrdfCase FurnaceSuite::case_at(std::size_t c) const { return grid_case(ndfs, alphas, theta_i, dims, c); }

FurnaceSuite parse_furnace_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  FurnaceSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"furnace"});
  s.ndfs = read_ndfs(root, true);
  s.alphas = read_numbers(root, "alpha", kMinAlpha, true, kMaxAlpha, true);
  for (double d : read_numbers(root, "theta_i_deg", 0.0, true, kMaxSurfaceThetaIDeg, true))
    s.theta_i.push_back(d * kRadPerDeg);
  for (const auto& d : read_names(root, "dimensions", {"flatland", "3d"}))
    s.dims.push_back(d == "flatland" ? SurfaceDim::flatland : SurfaceDim::three_d);
  s.max_k = static_cast<int>(root.integer("max_k", 1, kMaxSamplerK));
  s.samples = static_cast<long>(root.integer("samples", 1, kMaxRays));
  const std::string strategy = root.one_of("strategy", {"printed", "vndf", "smith-vndf", "bounded-vndf"});
  s.strategy = *analytic::strategy_from_name(strategy);
  for (analytic::NdfKind n : s.ndfs)
    for (SurfaceDim d : s.dims)
      if (!analytic::strategy_supports(s.strategy, n, d == SurfaceDim::flatland))
        root.fail("strategy", "= \"" + strategy + "\" does not exist for " + analytic::ndf_name(n) + " in " +
                                  surface_dim_name(d) +
                                  " (smith-vndf: GGX or Student-T only; bounded-vndf: GGX in 3D only)");
  s.rays = static_cast<long>(root.integer("rays", 1, kMaxRays));
  s.grooves = static_cast<int>(root.integer("grooves", 1, 10'000'000));
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, std::numeric_limits<long long>::max()));
  {
    support::JsonObject t = root.object("thresholds");
    s.sigmas = t.number("sigmas", 0.0, false, kMaxSigmas, true);
    support::JsonObject q = t.object("quadrature_tolerance");
    s.tolerance_flatland = q.number("flatland", 1e-15, true, 0.1, true);
    s.tolerance_3d = q.number("3d", 1e-15, true, 0.1, true);
    q.finish();
    t.finish();
  }
  root.finish();
  return s;
}

FurnaceOutcome run_furnace_case(const FurnaceSuite& suite, const BrdfCase& c, const BrdfUnderTest& brdf) {
  FurnaceOutcome out;
  out.c = c;
  if (c.dim == SurfaceDim::three_d)
    run_case<ThreeD>(suite, out, brdf);
  else
    run_case<Flatland>(suite, out, brdf);
  const double tol = c.dim == SurfaceDim::three_d ? suite.tolerance_3d : suite.tolerance_flatland;
  const double n = static_cast<double>(suite.samples), f = out.flux_beyond_max_k;
  out.finite = std::isfinite(out.albedo_quadrature) && std::isfinite(out.albedo_estimate) &&
               std::isfinite(out.standard_error) && std::isfinite(out.cook_torrance_quadrature) &&
               std::isfinite(out.cook_torrance_estimate) && std::isfinite(f);
  // (a) Energy: the quadrature's albedo and the light beyond max_k make 1.
  out.energy_ok = std::abs(out.albedo_quadrature + f - 1.0) <= tol;
  // (b) The estimator: within sigmas standard errors. Its weights can all be equal (the V-cavity
  // strategy with F = 1: 1 for every path, 0 beyond max_k), so the sample variance can be 0 when
  // no path beyond max_k was drawn; the standard error is then at least the Bernoulli one of that
  // event, sqrt(f (1 - f) / n). 1e-12 for rounding (a weight is a ratio of two sums).
  const double se = std::max(out.standard_error, std::sqrt(f * (1.0 - f) / n));
  out.estimate_ok = std::abs(out.albedo_estimate + f - 1.0) <= suite.sigmas * se + 1e-12 + tol;
  // Cook-Torrance's weights CT cos / pdf lie in [0, 1] (CT is the k = 1 term of Eq. 17, which the
  // V-cavity pdf equals); when fewer than 10 of the n samples are expected below 1 (CT's albedo
  // within 10/n of 1: smooth surfaces) the sample can miss them all, so the standard error is then
  // at least the bound of a [0, 1] weight, sqrt(a (1 - a) / n).
  const double a = std::clamp(out.cook_torrance_quadrature, 0.0, 1.0);
  const double se_ct = n * (1.0 - a) < 10.0 ? std::max(out.cook_torrance_standard_error, std::sqrt(a * (1.0 - a) / n))
                                            : out.cook_torrance_standard_error;
  out.cook_torrance_ok =
      std::abs(out.cook_torrance_estimate - out.cook_torrance_quadrature) <= suite.sigmas * se_ct + 1e-12 + tol;
  // The sanity line: at most one ray lost (a vertex hit is measure zero, but possible).
  out.sim_ok = std::abs(out.albedo_sim - 1.0) < 1.5 / static_cast<double>(std::max(1L, out.rays));
  out.pass = out.finite && out.energy_ok && out.estimate_ok && out.cook_torrance_ok && out.sim_ok;
  return out;
}

Job<FurnaceWork> furnace_job(const FurnaceSuite& suite, long samples, nlohmann::json descriptor) {
  FurnaceSuite s = suite;
  if (samples > 0) s.samples = samples;
  return item_job<FurnaceOutcome>(
      s.cases(), [s](std::size_t c) { return run_furnace_case(s, s.case_at(c)); },
      [s](support::JsonObject&, std::size_t c, FurnaceOutcome& o) { o.c = s.case_at(c); }, std::move(descriptor));
}

FurnaceRun furnace_run_from(const FurnaceSuite&, const std::vector<UnitResult<FurnaceWork>>& results) {
  FurnaceRun run;
  for (const auto& r : results) run.cases.push_back(r.tally);
  run.pass = std::all_of(run.cases.begin(), run.cases.end(), [](const FurnaceOutcome& o) { return o.pass; });
  return run;
}

nlohmann::json furnace_report_json(const FurnaceSuite& suite, const FurnaceRun& run) {
  nlohmann::json j =
      report_header({suite.name, suite.file, "furnace", suite.description, suite.seed}, run.threads, run.wall_s);
  j["inputs"] = suite_inputs(suite);
  j["columns"] = {
      {"albedo_quadrature",
       "int rho cos do of the pointwise Eq. (17), N = max_k, by adaptive quadrature over the hemisphere (not the "
       "binned lobes): tests the BRDF a renderer evaluates"},
      {"flux_beyond_max_k", "light leaving after more than max_k reflections, integrated over the grooves"},
      {"energy_error", "albedo_quadrature + flux_beyond_max_k - 1: within the quadrature tolerance"},
      {"albedo_estimate",
       "mean of rho cos / pdf over the sampler's directions: the same integral by importance sampling; "
       "albedo_estimate + flux_beyond_max_k - 1 within sigmas standard errors"},
      {"cook_torrance_quadrature / _estimate",
       "Eq. (1)-(3) with the V-cavity G by the same two routes; 1 - albedo is what single scattering loses"},
      {"albedo_sim",
       "sanity line: rays traced on a procedural surface that leave (or are still inside at the "
       "bounce limit) over rays; 1 by the surface's construction, it tests the tracer's bookkeeping"}};
  nlohmann::json cases = nlohmann::json::array();
  double worst_energy = 0.0, worst_estimate_sigmas = 0.0, lowest_ct = 1.0;
  std::size_t passed = 0;
  for (const FurnaceOutcome& o : run.cases) {
    passed += o.pass;
    const double energy = o.albedo_quadrature + o.flux_beyond_max_k - 1.0;
    worst_energy = std::max(worst_energy, std::abs(energy));
    if (o.standard_error > 0.0)
      worst_estimate_sigmas =
          std::max(worst_estimate_sigmas, std::abs(o.albedo_estimate + o.flux_beyond_max_k - 1.0) / o.standard_error);
    lowest_ct = std::min(lowest_ct, o.cook_torrance_quadrature);
    nlohmann::json c = {{"ndf", analytic::ndf_name(o.c.ndf)},
                        {"alpha", o.c.alpha},
                        {"theta_i_deg", output_deg(o.c.theta_i)},
                        {"dimension", surface_dim_name(o.c.dim)},
                        {"albedo_quadrature", o.albedo_quadrature},
                        {"quadrature_error_estimate", o.quadrature_error},
                        {"flux_beyond_max_k", o.flux_beyond_max_k},
                        {"energy_error", energy},
                        {"albedo_estimate", o.albedo_estimate},
                        {"standard_error", o.standard_error},
                        {"estimate_error", o.albedo_estimate + o.flux_beyond_max_k - 1.0},
                        {"cook_torrance_quadrature", o.cook_torrance_quadrature},
                        {"cook_torrance_estimate", o.cook_torrance_estimate},
                        {"cook_torrance_standard_error", o.cook_torrance_standard_error},
                        {"cook_torrance_energy_lost", 1.0 - o.cook_torrance_quadrature},
                        {"albedo_sim", o.albedo_sim},
                        {"rays", o.rays},
                        {"in_flight_at_bounce_limit", o.in_flight},
                        {"quadrature_s", o.quadrature_s},
                        {"estimate_s", o.estimate_s},
                        {"sim_s", o.sim_s},
                        {"energy_ok", o.energy_ok},
                        {"estimate_ok", o.estimate_ok},
                        {"cook_torrance_ok", o.cook_torrance_ok},
                        {"sim_ok", o.sim_ok},
                        {"pass", o.pass}};
    put_gamma(c, o.c.ndf);
    cases.push_back(std::move(c));
  }
  j["cases"] = std::move(cases);
  j["summary"] = {{"cases", run.cases.size()},
                  {"passed", passed},
                  {"largest_energy_error", worst_energy},
                  {"largest_estimate_error_in_standard_errors", worst_estimate_sigmas},
                  {"lowest_cook_torrance_albedo", lowest_ct},
                  {"wall_s", run.wall_s}};
  j["pass"] = run.pass;
  return j;
}

void print_furnace_table(std::ostream& os, const FurnaceSuite& suite, const FurnaceRun& run) {
  print_table_title(
      os, suite.name, "furnace",
      support::format("%zu cases; Eq. 17 (N = %d) by quadrature and by %ld samples (%s)", run.cases.size(), suite.max_k,
                      suite.samples, analytic::strategy_name(suite.strategy)),
      run.threads);
  os << support::format("  %-8s %-8s %5s %7s %12s %10s %10s %12s %10s %10s %10s %7s %5s\n", "dim", "ndf", "alpha",
                        "theta_i", "albedo quad", "beyond N", "energy-1", "albedo est", "est-1", "CT quad", "CT est",
                        "sim", "pass");
  for (const FurnaceOutcome& o : run.cases) {
    os << support::format("  %-8s %-8s %5.2f %7.2f %12.9f %10.3e %10.1e %12.9f %10.1e %10.6f %10.6f %7.5f %5s\n",
                          surface_dim_name(o.c.dim), ndf_label(o.c.ndf).c_str(), o.c.alpha, output_deg(o.c.theta_i),
                          o.albedo_quadrature, o.flux_beyond_max_k, o.albedo_quadrature + o.flux_beyond_max_k - 1.0,
                          o.albedo_estimate, o.albedo_estimate + o.flux_beyond_max_k - 1.0, o.cook_torrance_quadrature,
                          o.cook_torrance_estimate, o.albedo_sim, o.pass ? "yes" : "NO");
  }
  std::size_t passed = 0;
  for (const auto& o : run.cases) passed += o.pass;
  print_table_close(os, passed, run.cases.size(), run.wall_s);
}

}  // namespace vgroove::validation
