#include "vgroove/validation/sampling_suite.h"

#include "vgroove/common/angles.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/printable.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/table_frame.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace vgroove::validation {

namespace {

// One listed case's common fields: "dimension", "ndf", "alpha", "theta_i_deg", and Student-T's
// "gamma".
BrdfCase read_case(support::JsonObject& o) {
  BrdfCase c;
  c.dim = o.one_of("dimension", {"flatland", "3d"}) == "flatland" ? SurfaceDim::flatland : SurfaceDim::three_d;
  const std::string ndf = o.one_of("ndf", {"ggx", "beckmann", "phong", "student_t"});
  const double gamma = ndf == "student_t" ? o.number("gamma", kMinStudentTGamma, false, kMaxStudentTGamma, true) : 0.0;
  c.ndf = *ndf_from_name(ndf, gamma);
  c.alpha = o.number("alpha", kMinAlpha, true, kMaxAlpha, true);
  c.theta_i = o.number("theta_i_deg", 0.0, true, kMaxSurfaceThetaIDeg, true) * kRadPerDeg;
  return c;
}

analytic::FacetStrategy read_strategy(support::JsonObject& o, const BrdfCase& c) {
  const std::string name = o.one_of("strategy", {"printed", "vndf", "smith-vndf", "bounded-vndf"});
  const analytic::FacetStrategy s = *analytic::strategy_from_name(name);
  if (!analytic::strategy_supports(s, c.ndf, c.dim == SurfaceDim::flatland))
    o.fail("strategy", "= \"" + name + "\" does not exist for " + analytic::ndf_name(c.ndf) + " in " +
                           surface_dim_name(c.dim) +
                           " (smith-vndf: GGX or Student-T only; bounded-vndf: GGX in 3D only)");
  return s;
}

// "model": "vgroove" (the default, symmetric) or "vgroove-nonsymmetric" (Eq. 23, the independent
// partner law; its table needs Phong alpha <= 1, analytic/partner_table.h).
bool read_nonsymmetric(support::JsonObject& o, const BrdfCase& c) {
  const std::string fallback = "vgroove";
  const bool ns = o.one_of("model", {"vgroove", "vgroove-nonsymmetric"}, &fallback) == "vgroove-nonsymmetric";
  if (ns && c.ndf == analytic::NdfKind::student_t)
    o.fail("model", "= \"vgroove-nonsymmetric\" has no partner law for student_t (vgroove only)");
  if (ns && c.ndf == analytic::NdfKind::phong && c.alpha > 1.0)
    o.fail("alpha", "= " + std::to_string(c.alpha) +
                        " is out of range for model vgroove-nonsymmetric with phong (the partner law's table needs "
                        "alpha <= 1)");
  return ns;
}

// The elements of the list `key`, each as a strict object.
template <class Fn>
void for_each_listed(support::JsonObject& parent, const std::string& key, Fn&& fn) {
  const nlohmann::json& list = parent.raw(key);
  if (!list.is_array() || list.empty()) parent.fail(key, "must be a non-empty list of objects");
  for (std::size_t n = 0; n < list.size(); ++n) {
    support::JsonObject o(list[n], parent.file(), parent.path(key) + "/" + std::to_string(n));
    fn(o);
    o.finish();
  }
}

}  // namespace

SamplingSuite parse_sampling_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  SamplingSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"sampling"});
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, std::numeric_limits<long long>::max()));
  const int max_k = static_cast<int>(root.integer("max_k", 1, kMaxSamplerK));
  {
    support::JsonObject c = root.object("chi_square");
    const double level = c.number("level", 0.0, false, 0.5, true);
    support::JsonObject samples = c.object("samples");
    const long n3 = static_cast<long>(samples.integer("3d", 100, kMaxRays));
    const long n2 = static_cast<long>(samples.integer("flatland", 100, kMaxRays));
    samples.finish();
    const int cos_bins = static_cast<int>(c.integer("cos_bins", 1, 1000));
    const int phi_bins = static_cast<int>(c.integer("phi_bins", 2, 1000));
    if (phi_bins % 2 != 0) c.fail("phi_bins", "= " + std::to_string(phi_bins) + " must be even");
    const int theta_bins = static_cast<int>(c.integer("theta_bins", 1, 10000));
    for_each_listed(c, "cases", [&](support::JsonObject& o) {
      const BrdfCase bc = read_case(o);
      Chi2Spec spec;
      spec.dim = bc.dim, spec.ndf = bc.ndf, spec.alpha = bc.alpha, spec.theta_i = bc.theta_i;
      spec.strategy = read_strategy(o, bc);
      spec.nonsymmetric = read_nonsymmetric(o, bc);
      spec.max_k = max_k;
      spec.samples = bc.dim == SurfaceDim::three_d ? n3 : n2;
      spec.seed = s.seed;
      spec.cos_bins = cos_bins, spec.phi_bins = phi_bins, spec.theta_bins = theta_bins;
      spec.level = level;
      s.chi_square.push_back(spec);
    });
    for (Chi2Spec& spec : s.chi_square) spec.tests = static_cast<int>(s.chi_square.size());
    c.finish();
  }
  {
    support::JsonObject v = root.object("variance");
    const long n = static_cast<long>(v.integer("samples", 100, kMaxRays));
    const std::vector<double> f0s = read_numbers(v, "schlick_f0", 0.0, true, 1.0, true);
    for_each_listed(v, "cases", [&](support::JsonObject& o) {
      const BrdfCase bc = read_case(o);
      const bool ns = read_nonsymmetric(o, bc);
      const long case_n = static_cast<long>(o.integer_or("samples", n, 100, kMaxRays));
      for (double f0 : f0s) {
        if (f0 < 1.0 && bc.dim == SurfaceDim::flatland) continue;  // the flatland sampler has F = 1 only
        VarianceSpec spec;
        spec.dim = bc.dim, spec.ndf = bc.ndf, spec.alpha = bc.alpha, spec.theta_i = bc.theta_i;
        spec.max_k = max_k;
        spec.samples = case_n;
        spec.seed = s.seed;
        spec.schlick_f0 = f0;
        spec.nonsymmetric = ns;
        s.variance.push_back(spec);
      }
    });
    v.finish();
  }
  {
    support::JsonObject f = root.object("furnace");
    FurnaceSuite& fs = s.furnace;
    fs.file = file;
    fs.name = s.name + "/furnace";
    fs.max_k = static_cast<int>(f.integer("max_k", 1, kMaxSamplerK));
    fs.samples = static_cast<long>(f.integer("samples", 1, kMaxRays));
    fs.strategy = *analytic::strategy_from_name(f.one_of("strategy", {"printed", "vndf"}));
    fs.rays = static_cast<long>(f.integer("rays", 1, kMaxRays));
    fs.grooves = static_cast<int>(f.integer("grooves", 1, 10'000'000));
    fs.seed = s.seed;
    fs.sigmas = f.number("sigmas", 0.0, false, 100.0, true);
    support::JsonObject q = f.object("quadrature_tolerance");
    fs.tolerance_flatland = q.number("flatland", 1e-15, true, 0.1, true);
    fs.tolerance_3d = q.number("3d", 1e-15, true, 0.1, true);
    q.finish();
    for_each_listed(f, "cases", [&](support::JsonObject& o) { s.furnace_cases.push_back(read_case(o)); });
    f.finish();
  }
  root.finish();
  return s;
}

Job<SamplingWork> sampling_job(const SamplingSuite& suite, nlohmann::json descriptor, const std::atomic<bool>* cancel) {
  const std::size_t n1 = suite.chi_square.size(), n2 = n1 + suite.variance.size(), n = n2 + suite.furnace_cases.size();
  // Each item's numbers come from its own seeded stream: where it runs does not change them.
  return item_job<SamplingItem>(
      n,
      [suite, n1, n2, cancel](std::size_t k) {
        SamplingItem item;
        if (k < n1)
          item.chi_square = run_chi2(suite.chi_square[k], nullptr, cancel);
        else if (k < n2)
          item.variance = run_variance(suite.variance[k - n1], cancel);
        else
          item.furnace = run_furnace_case(suite.furnace, suite.furnace_cases[k - n2]);
        return item;
      },
      [suite, n1, n2](support::JsonObject& o, std::size_t k, SamplingItem& item) {
        const char* const want = k < n1 ? "chi_square" : k < n2 ? "variance" : "furnace";
        if ((item.chi_square.has_value() + item.variance.has_value() + item.furnace.has_value()) != 1 ||
            (k < n1   ? !item.chi_square
             : k < n2 ? !item.variance
                      : !item.furnace))
          o.fail("outcome", std::string("must hold exactly the item's ") + want + " outcome");
        if (item.chi_square) {
          item.chi_square->spec = suite.chi_square[k];
          if (const std::string e = chi2_table_shape_error(item.chi_square->spec, item.chi_square->table); !e.empty())
            o.fail("outcome", "/chi_square/table " + e);
        }
        if (item.variance) item.variance->spec = suite.variance[k - n1];
        if (item.furnace) item.furnace->c = suite.furnace_cases[k - n2];
      },
      std::move(descriptor));
}

SamplingRun sampling_run_from(const SamplingSuite&, const std::vector<UnitResult<SamplingWork>>& results) {
  SamplingRun run;
  for (const auto& r : results) {
    if (r.tally.chi_square) run.chi_square.push_back(*r.tally.chi_square);
    if (r.tally.variance) run.variance.push_back(*r.tally.variance);
    if (r.tally.furnace) run.furnace.push_back(*r.tally.furnace);
  }
  // An item stopped inside its loops says so: the run is then incomplete.
  run.interrupted =
      std::any_of(run.chi_square.begin(), run.chi_square.end(), [](const auto& o) { return o.interrupted; }) ||
      std::any_of(run.variance.begin(), run.variance.end(), [](const auto& o) { return o.interrupted; });
  run.pass = !run.interrupted &&
             std::all_of(run.chi_square.begin(), run.chi_square.end(), [](const Chi2Outcome& o) { return o.pass; }) &&
             std::all_of(run.furnace.begin(), run.furnace.end(), [](const FurnaceOutcome& o) { return o.pass; });
  return run;
}

nlohmann::json sampling_report_json(const SamplingSuite& suite, const SamplingRun& run) {
  nlohmann::json j =
      report_header({suite.name, suite.file, "sampling", suite.description, suite.seed}, run.threads, run.wall_s);
  nlohmann::json chi = nlohmann::json::array(), var = nlohmann::json::array();
  for (const Chi2Outcome& o : run.chi_square) chi.push_back(chi2_json(o));
  for (const VarianceOutcome& o : run.variance) var.push_back(variance_json(o));
  j["chi_square"] = std::move(chi);
  j["variance"] = std::move(var);
  FurnaceRun fr;
  fr.cases = run.furnace;
  fr.threads = run.threads;
  fr.pass = std::all_of(run.furnace.begin(), run.furnace.end(), [](const FurnaceOutcome& o) { return o.pass; });
  const nlohmann::json f = furnace_report_json(suite.furnace, fr);
  j["furnace"] = {{"inputs", f["inputs"]}, {"columns", f["columns"]}, {"cases", f["cases"]}};
  std::size_t chi_pass = 0, furnace_pass = 0;
  for (const auto& o : run.chi_square) chi_pass += o.pass;
  for (const auto& o : run.furnace) furnace_pass += o.pass;
  j["summary"] = {{"chi_square_cases", run.chi_square.size()},
                  {"chi_square_passed", chi_pass},
                  {"variance_cases", run.variance.size()},
                  {"furnace_cases", run.furnace.size()},
                  {"furnace_passed", furnace_pass},
                  {"wall_s", run.wall_s}};
  j["pass"] = run.pass;
  return j;
}

void print_sampling_table(std::ostream& os, const SamplingSuite& suite, const SamplingRun& run) {
  print_table_title(os, suite.name, "sampling", "", run.threads);
  os << "  chi-square against the sampler's pdf (level " << (suite.chi_square.empty() ? 0.0 : suite.chi_square[0].level)
     << " over " << suite.chi_square.size() << " tests, Sidak)\n";
  os << support::format("  %-8s %-8s %5s %7s %-13s %9s %9s %5s %9s %10s %10s %5s\n", "dim", "ndf", "alpha", "theta_i",
                        "strategy", "samples", "stat", "dof", "p", "norm err", "mean w", "pass");
  for (const Chi2Outcome& o : run.chi_square) {
    const Chi2Spec& s = o.spec;
    os << support::format("  %-8s %-8s %5.2f %7.2f %-13s %9ld %9.1f %5d %9.3g %10.1e %10.6f %5s\n",
                          surface_dim_name(s.dim), ndf_label(s.ndf).c_str(), s.alpha, output_deg(s.theta_i),
                          analytic::strategy_name(s.strategy), s.samples, o.test.statistic, o.test.dof, o.test.p_value,
                          o.normalization_error, o.weight_mean, o.pass ? "yes" : "NO");
  }
  os << "  variance of the weight rho cos / pdf per strategy (F = 1 or Schlick F0), ns per sample\n";
  for (const VarianceOutcome& o : run.variance) {
    const VarianceSpec& s = o.spec;
    os << support::format("  %-8s %-8s %5.2f %7.2f F0 %4.2f:", surface_dim_name(s.dim), ndf_label(s.ndf).c_str(),
                          s.alpha, output_deg(s.theta_i), s.schlick_f0);
    for (const StrategyStats& r : o.rows) {
      os << support::format(" %s %.3g (%.0f ns)", r.strategy.c_str(), r.variance, r.ns_per_sample);
    }
    os << "; lowest variance " << o.lowest_variance << ", most efficient " << o.most_efficient << "\n";
  }
  FurnaceRun fr;
  fr.cases = run.furnace;
  fr.threads = run.threads;
  fr.wall_s = run.wall_s;
  print_furnace_table(os, suite.furnace, fr);
  std::size_t chi_pass = 0;
  for (const auto& o : run.chi_square) chi_pass += o.pass;
  print_table_close(os, chi_pass, run.chi_square.size(), run.wall_s, "chi-square cases pass");
}

}  // namespace vgroove::validation
