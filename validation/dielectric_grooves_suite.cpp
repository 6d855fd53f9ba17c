#include "vgroove/validation/dielectric_grooves_suite.h"

#include "vgroove/common/angles.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/table_frame.h"

#include <algorithm>
#include <cmath>

namespace vgroove::validation {

namespace {

// The narrowest aperture read (dielectric_grooves_case.h: the tracer's signatures hold 64 hits).
constexpr double kMinDielectricApertureDeg = kMinComparedApertureDeg;
constexpr double kMinEta = 1e-3, kMaxEta = 1e3;  // 1 / kMaxFresnelEta .. kMaxFresnelEta
constexpr long kMaxSurfaceRays = 10'000'000;

}  // namespace

DielectricGrooveCase DielectricGroovesSuite::case_at(std::size_t c) const {
  if (c < above_cases()) {
    const std::size_t ni = theta_i.size(), nv = theta_v.size();
    return {theta_v[(c / ni) % nv], theta_i[c % ni], eta[c / (ni * nv)]};
  }
  c -= above_cases();
  const std::size_t ni = below_theta_i.size(), nv = below_theta_v.size();
  return {below_theta_v[(c / ni) % nv], below_theta_i[c % ni], eta[c / (ni * nv)], true};
}

DielectricGroovesSuite parse_dielectric_grooves_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  DielectricGroovesSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"dielectric_grooves"});
  for (double d : read_numbers(root, "theta_v_deg", kMinDielectricApertureDeg, true, 180.0, true))
    s.theta_v.push_back(d * kRadPerDeg);
  for (double d : read_numbers(root, "theta_i_deg", -kMaxThetaIDeg, true, kMaxThetaIDeg, true))
    s.theta_i.push_back(d * kRadPerDeg);
  if (root.has("from_below")) {
    support::JsonObject b = root.object("from_below");
    for (double d : read_numbers(b, "theta_v_deg", kMinDielectricApertureDeg, true, 180.0, true))
      s.below_theta_v.push_back(d * kRadPerDeg);
    for (double d : read_numbers(b, "theta_i_deg", -kMaxThetaIDeg, true, kMaxThetaIDeg, true))
      s.below_theta_i.push_back(d * kRadPerDeg);
    b.finish();
  }
  s.eta_given = read_numbers(root, "eta", kMinEta, true, kMaxEta, true);
  s.inverses = root.boolean_or("inverses", false);
  s.eta = s.eta_given;
  if (s.inverses)
    for (double e : s.eta_given) s.eta.push_back(1.0 / e);
  s.options.grid = static_cast<long>(root.integer("grid", 1, kMaxDielectricGrid));
  s.options.surface_rays = static_cast<long>(root.integer("surface_rays", 0, kMaxSurfaceRays));
  s.options.surface_min_weight = root.number("surface_min_weight", 0.0, false, 1.0, false);
  {
    support::JsonObject t = root.object("thresholds");
    s.max_l1 = t.number("max_l1", 0.0, true, 1.0, true);
    s.max_direction_error = t.number("max_direction_error_rad", 0.0, true, 3.141592653589793, true);
    t.finish();
  }
  root.finish();
  return s;
}

DielectricGroovesOutcome run_dielectric_grooves_case(const DielectricGroovesSuite& s, const DielectricGrooveCase& c) {
  const DielectricCaseOutcome r = run_dielectric_groove_case(c, s.options);
  DielectricGroovesOutcome o;
  o.c = c;
  o.k_left = r.facet[0].k, o.k_right = r.facet[1].k;
  o.l1 = r.l1, o.direction_error = r.direction_error, o.conservation = r.conservation;
  o.missed_bound = r.missed_bound;
  o.l1_bound = r.l1_bound, o.direction_bound = r.direction_bound;
  o.uncertified_cells = r.facet[0].uncertified_cells + r.facet[1].uncertified_cells;
  o.zones = r.facet[0].zones + r.facet[1].zones;
  o.reflected = r.reflected, o.transmitted = r.transmitted;
  o.unknown = r.unknown, o.unknown_model = r.unknown_model, o.unknown_recross = r.unknown_recross;
  o.surface_rays = r.surface_rays, o.surface_unknown = r.surface_unknown;
  o.surface_recross = r.surface_recross, o.surface_cut = r.surface_cut;
  o.rays = r.rays, o.interactions = r.interactions;
  o.non_finite = r.non_finite;
  o.wall_s = r.wall_s;
  const double l1_tolerance = s.max_l1 + o.l1_bound;
  o.pass = !o.non_finite && o.l1 <= l1_tolerance && o.direction_error <= s.max_direction_error + o.direction_bound &&
           std::abs(o.unknown - o.unknown_model) <= l1_tolerance && o.conservation <= s.max_l1 &&
           o.uncertified_cells == 0;
  return o;
}

Job<DielectricGroovesWork> dielectric_grooves_job(const DielectricGroovesSuite& s, nlohmann::json descriptor) {
  return item_job<DielectricGroovesOutcome>(
      s.cases(), [s](std::size_t c) { return run_dielectric_grooves_case(s, s.case_at(c)); },
      [s](support::JsonObject&, std::size_t c, DielectricGroovesOutcome& o) { o.c = s.case_at(c); },
      std::move(descriptor),
      [s](std::size_t c) {
        // The surface's paths grow as 1 / theta_v (from above only); the search's as the grid.
        const DielectricGrooveCase k = s.case_at(c);
        return static_cast<std::int64_t>(s.options.grid + (k.below ? 0.0 : s.options.surface_rays / k.theta_v));
      });
}

DielectricGroovesRun dielectric_grooves_run_from(const DielectricGroovesSuite&,
                                                 const std::vector<UnitResult<DielectricGroovesWork>>& results) {
  DielectricGroovesRun run;
  for (const auto& r : results) run.cases.push_back(r.tally);
  run.pass = std::all_of(run.cases.begin(), run.cases.end(), [](const DielectricGroovesOutcome& o) { return o.pass; });
  return run;
}

nlohmann::json dielectric_grooves_report_json(const DielectricGroovesSuite& s, const DielectricGroovesRun& run) {
  nlohmann::json j = report_header({s.name, s.file, "dielectric_grooves", s.description, 0}, run.threads, run.wall_s);
  nlohmann::json tv = nlohmann::json::array(), ti = nlohmann::json::array();
  for (double v : s.theta_v) tv.push_back(output_deg(v));
  for (double v : s.theta_i) ti.push_back(output_deg(v));
  nlohmann::json btv = nlohmann::json::array(), bti = nlohmann::json::array();
  for (double v : s.below_theta_v) btv.push_back(output_deg(v));
  for (double v : s.below_theta_i) bti.push_back(output_deg(v));
  j["inputs"] = {{"theta_v_deg", tv},
                 {"theta_i_deg", ti},
                 {"eta", s.eta_given},
                 {"inverses", s.inverses},
                 {"grid", s.options.grid},
                 {"surface_rays", s.options.surface_rays},
                 {"surface_min_weight", s.options.surface_min_weight},
                 {"thresholds", {{"max_l1", s.max_l1}, {"max_direction_error_rad", s.max_direction_error}}}};
  if (!s.below_theta_v.empty() || !s.below_theta_i.empty())
    j["inputs"]["from_below"] = {{"theta_v_deg", btv}, {"theta_i_deg", bti}};
  j["columns"] = {
      {"from",
       "the side the light comes from; from below l1 sums |traced - model| over every path signature (R/T per "
       "interaction, the side it leaves into) with the traced flat-first and lost shares, and the model knows "
       "every path (unknown 0, no surface)"},
      {"l1",
       "per lit facet, the largest over the two: |traced shadow - Eq. 6 shadow| + vertex/cut/limit + sum_n |traced "
       "pure "
       "R chain of n hits - G_n prod F| + sum_j |traced paths refracted first at hit j - lobe j| + sum_j |traced "
       "R^(j-1)T "
       "leaving at once - lobe j if it leaves at once (KD-4)|; exact by breakpoint search, so rounding"},
      {"direction_error", "largest angle between a model lobe's direction and a traced exit of its path, radians"},
      {"l1_bound / direction_bound",
       "the model's own change when theta_i moves by 64 ulps of pi either way (what rounding of the angles alone "
       "can do): a case passes with l1 <= max_l1 + l1_bound and direction_error <= max_direction_error_rad + "
       "direction_bound"},
      {"reflected / transmitted", "the model's shares of the rays entering the opening"},
      {"unknown",
       "traced, one groove with flat rims: rays refracted at some hit that meet the interface again (the rim's "
       "underside), share of the entering rays; unknown_model: the model's lobes that do not leave at once; "
       "unknown_recross: of unknown, crossing back into medium 1 at the next hit"},
      {"surface_unknown",
       "the periodic surface of the groove, stratified surface_rays over the opening: refracted light that meets a "
       "neighbouring ridge; surface_recross: crossing back at that hit; surface_cut: paths cut below "
       "surface_min_weight"}};
  nlohmann::json cases = nlohmann::json::array();
  double worst_l1 = 0.0, worst_dir = 0.0, worst_unknown = 0.0, worst_surface = 0.0;
  std::int64_t rays = 0;
  std::size_t passed = 0;
  for (const DielectricGroovesOutcome& o : run.cases) {
    passed += o.pass;
    worst_l1 = std::max(worst_l1, o.l1);
    worst_dir = std::max(worst_dir, o.direction_error);
    worst_unknown = std::max(worst_unknown, o.unknown);
    worst_surface = std::max(worst_surface, o.surface_unknown);
    rays += o.rays;
    cases.push_back({{"from", o.c.below ? "below" : "above"},
                     {"eta", o.c.eta},
                     {"theta_v_deg", output_deg(o.c.theta_v)},
                     {"theta_i_deg", output_deg(o.c.theta_i)},
                     {"k", {o.k_left, o.k_right}},
                     {"l1", o.l1},
                     {"direction_error_rad", o.direction_error},
                     {"l1_bound", o.l1_bound},
                     {"direction_bound_rad", o.direction_bound},
                     {"conservation", o.conservation},
                     {"zones", o.zones},
                     {"uncertified_cells", o.uncertified_cells},
                     {"missed_bound", o.missed_bound},
                     {"reflected", o.reflected},
                     {"transmitted", o.transmitted},
                     {"unknown", o.unknown},
                     {"unknown_model", o.unknown_model},
                     {"unknown_recross", o.unknown_recross},
                     {"surface_rays", o.surface_rays},
                     {"surface_unknown", o.surface_unknown},
                     {"surface_recross", o.surface_recross},
                     {"surface_cut", o.surface_cut},
                     {"rays", o.rays},
                     {"interactions", o.interactions},
                     {"wall_s", o.wall_s},
                     {"pass", o.pass}});
  }
  j["cases"] = std::move(cases);
  j["summary"] = {{"cases", run.cases.size()},
                  {"passed", passed},
                  {"largest_l1", worst_l1},
                  {"largest_direction_error_rad", worst_dir},
                  {"largest_unknown", worst_unknown},
                  {"largest_surface_unknown", worst_surface},
                  {"rays", rays},
                  {"wall_s", run.wall_s}};
  j["pass"] = run.pass;
  return j;
}

void print_dielectric_grooves_table(std::ostream& os, const DielectricGroovesSuite& s,
                                    const DielectricGroovesRun& run) {
  print_table_title(os, s.name, "dielectric_grooves",
                    support::format("%zu cases; the kaleidoscopic dielectric model against split tracing "
                                    "(breakpoints, grid %ld); surface %ld rays",
                                    run.cases.size(), s.options.grid, s.options.surface_rays),
                    run.threads);
  os << support::format("  %5s %6s %7s %7s %8s %8s %9s %9s %9s %9s %8s %9s %5s\n", "from", "eta", "theta_v", "theta_i",
                        "R", "T", "L1", "dir err", "unknown", "surface", "rays", "wall ms", "pass");
  for (const DielectricGroovesOutcome& o : run.cases)
    os << support::format("  %5s %6.4f %7.2f %7.2f %8.5f %8.5f %9.1e %9.1e %9.6f %9.6f %8lld %9.2f %5s\n",
                          o.c.below ? "below" : "above", o.c.eta, output_deg(o.c.theta_v), output_deg(o.c.theta_i),
                          o.reflected, o.transmitted, o.l1, o.direction_error, o.unknown, o.surface_unknown,
                          static_cast<long long>(o.rays), 1e3 * o.wall_s, o.pass ? "yes" : "NO");
  std::size_t passed = 0;
  for (const auto& o : run.cases) passed += o.pass;
  print_table_close(os, passed, run.cases.size(), run.wall_s);
}

}  // namespace vgroove::validation
