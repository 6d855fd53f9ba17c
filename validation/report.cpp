#include "vgroove/validation/report.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"

#include "vgroove_version.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace vgroove::validation {

namespace {

const char* form_name(analytic::Eq6Form f) { return f == analytic::Eq6Form::corrected ? "corrected" : "printed"; }

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
}  // namespace

double output_deg(double rad) { return std::round(rad * kDegPerRad * 1e9) / 1e9 + 0.0; }

const char* version_string() { return VGROOVE_VERSION; }
const char* git_revision() { return VGROOVE_GIT; }

nlohmann::json provenance() {
  return {{"tool", "vgroove"},
          {"schema_version", kReportSchemaVersion},
          {"version", VGROOVE_VERSION},
          {"git", VGROOVE_GIT}};
}

nlohmann::json report_header(const SuiteHeader& suite, int threads, double wall_s) {
  nlohmann::json j = provenance();
  j["suite"] = suite.name;
  j["suite_file"] = suite.file;
  j["kind"] = suite.kind;
  j["description"] = suite.description;
  j["seed"] = suite.seed;
  j["threads"] = threads;
  j["wall_s"] = wall_s;
  return j;
}

nlohmann::json groove_json(const GrooveParams& g) {
  if (g.symmetric) return {{"theta_v_deg", output_deg(g.theta_v)}};
  return {{"theta_l_deg", output_deg(g.theta_l)},
          {"theta_r_deg", output_deg(g.theta_r)},
          {"theta_v_deg", output_deg(g.theta_v)}};
}

std::string groove_text(const GrooveParams& g) {
  char buf[128];
  if (g.symmetric)
    std::snprintf(buf, sizeof buf, "theta_v %.9g deg", output_deg(g.theta_v));
  else
    std::snprintf(buf, sizeof buf, "theta_l %.9g, theta_r %.9g deg (theta_v %.9g)", output_deg(g.theta_l),
                  output_deg(g.theta_r), output_deg(g.theta_v));
  return buf;
}

nlohmann::json case_json(const CaseOutcome& c) {
  nlohmann::json jc = groove_json(c.groove);
  jc["theta_i_deg"] = output_deg(c.theta_i);
  if (c.groove.degenerate()) {
    jc["degenerate"] = "zero aperture: no opening, no light enters; not compared";
    return jc;
  }
  jc["l1"] = c.l1;
  jc["rays"] = c.rays;
  jc["bounces"] = c.bounces;
  jc["theta_o_error_rad"] = c.theta_o_error;
  for (int f = 0; f < 2; ++f) {
    const FacetOutcome& fo = c.facet[f];
    const char* name = f == 0 ? "left" : "right";
    if (!fo.compared) {
      jc[name] = nullptr;  // the light does not reach this facet
      continue;
    }
    jc[name] = {{"l1", fo.l1},
                {"k", fo.k},
                {"rays", fo.rays},
                {"vertex_hits", fo.vertex_hits},
                {"bounce_limit", fo.bounce_limit},
                {"wrong_first_facet", fo.wrong_first}};
    // Breakpoint placement (sim/zones.h) finds at least one zone on every facet it compares.
    if (fo.zones > 0) {
      jc[name]["zones"] = fo.zones;
      jc[name]["narrowest_zone"] = fo.narrowest_zone;
      jc[name]["uncertified_cells"] = fo.uncertified_cells;
      jc[name]["missed_bound"] = fo.missed_bound;
    }
  }
  return jc;
}

nlohmann::json report_json(const GrooveSuite& suite, const GrooveSuiteRun& run) {
  const GrooveSuiteSummary& s = run.summary;
  nlohmann::json j = provenance();
  j["suite"] = suite.name;
  j["suite_file"] = suite.file;
  j["seed"] = run.options.seed;
  j["threads"] = run.threads;
  j["sampling"] = sim::sampling_name(run.options.sampling);
  j["rays_per_facet"] = run.options.rays;
  j["max_bounces"] = run.options.max_bounces;
  j["eq6_form"] = form_name(run.options.form);
  j["wall_s"] = s.wall_s;
  j["error_definition"] =
      "per lit facet: L1 over bounce counts (and a shadow bin) between the fractions of the rays aimed at the "
      "facet and G (Eq. 6); a case's error is the larger of its facets'";
  nlohmann::json cases = nlohmann::json::array();
  for (const CaseOutcome& c : run.cases) cases.push_back(case_json(c));
  j["cases"] = std::move(cases);
  const CaseOutcome& worst = run.cases.empty() ? CaseOutcome{} : run.cases[s.worst_case];
  nlohmann::json worst_j = groove_json(worst.groove);
  worst_j["theta_i_deg"] = output_deg(worst.theta_i);
  nlohmann::json degenerate = nlohmann::json::array();
  for (const CaseOutcome& c : run.cases)
    if (c.groove.degenerate() && (degenerate.empty() || degenerate.back() != groove_json(c.groove)))
      degenerate.push_back(groove_json(c.groove));
  j["summary"] = {{"cases", s.cases},
                  {"degenerate_cases", s.degenerate_cases},
                  {"degenerate_grooves", degenerate},
                  {"facets_compared", s.facets_compared},
                  {"max_l1", s.max_l1},
                  {"mean_l1", s.mean_l1},
                  {"worst_case", worst_j},
                  {"max_theta_o_error_rad", s.max_theta_o_error},
                  {"rays", s.rays},
                  {"rays_per_case", s.rays_per_case},
                  {"bounces", s.bounces},
                  {"vertex_hits", s.vertex_hits},
                  {"bounce_limit", s.bounce_limit},
                  {"wrong_first_facet", s.wrong_first},
                  {"non_finite_cases", s.non_finite_cases},
                  {"wall_s", s.wall_s},
                  {"bounces_per_s", s.bounces_per_s}};
  if (run.options.sampling == sim::Sampling::breakpoints)
    j["summary"]["breakpoints"] = {
        {"grid_rays", run.options.rays},
        {"definition",
         "per lit facet: a stratified grid of grid_rays rays and the two ends of the beam, then bisection "
         "between neighbours of different outcome (facet hit first, k, termination) down to adjacent doubles; "
         "fractions are the zones' measures. A zone can be missed only inside a grid cell whose ends have the "
         "same outcome and no certificate (the convexity lemma of sim/zones.h covers every cell but vertex "
         "hits; cells with vertex-hit ends are halved 8 times first); missed_bound = the uncertified cells' width, a "
         "fraction of the beam"},
        {"zones", s.zones},
        {"max_zones_per_facet", s.max_zones},
        {"narrowest_zone", s.narrowest_zone},
        {"uncertified_cells", s.uncertified_cells},
        {"max_missed_bound", s.max_missed_bound}};
  if (run.options.probe_vertices)
    j["summary"]["vertex_probes"] = {{"rays", s.probe_rays},
                                     {"escaped", s.probe_escaped},
                                     {"vertex_hit", s.probe_vertex_hits},
                                     {"blocked", s.probe_blocked},
                                     {"bounce_limit", s.probe_bounce_limit}};
  j["thresholds"] = {{"max_l1", suite.thresholds.max_l1},
                     {"mean_l1", suite.thresholds.mean_l1},
                     {"max_theta_o_error_rad", suite.thresholds.max_theta_o_error_rad}};
  if (suite.paper) {
    j["paper"] = {{"source", suite.paper->source}, {"max_l1", suite.paper->max_l1}, {"mean_l1", suite.paper->mean_l1}};
    if (!suite.paper->placement.empty()) {
      j["paper"]["consistent_with_placement"] = suite.paper->placement;
      j["paper"]["placement_evidence"] = suite.paper->placement_evidence;
    }
  }
  j["pass"] = s.pass();
  return j;
}

void print_table(std::ostream& os, const GrooveSuite& suite, const GrooveSuiteRun& run) {
  const GrooveSuiteSummary& s = run.summary;
  os << "vgroove " << VGROOVE_VERSION << " (git " << VGROOVE_GIT << ")  suite " << support::printable(suite.name)
     << ": " << s.cases << " cases"
     << (s.degenerate_cases ? " (+" + std::to_string(s.degenerate_cases) + " degenerate, not compared)" : "") << ", "
     << run.options.rays << " rays per lit facet, " << sim::sampling_name(run.options.sampling) << ", seed "
     << run.options.seed << ", Eq. 6 " << form_name(run.options.form) << ", " << run.threads << " threads\n";
  os << "                      max L1      mean L1     max |theta_o err|\n";
  if (suite.paper)
    os << "  paper              " << fmt("%10.4g", suite.paper->max_l1) << "  " << fmt("%10.4g", suite.paper->mean_l1)
       << "   -          (" << support::printable(suite.paper->source) << ")\n";
  os << "  vgroove            " << fmt("%10.4g", s.max_l1) << "  " << fmt("%10.4g", s.mean_l1) << "  "
     << fmt("%10.3g", s.max_theta_o_error) << " rad\n";
  os << "  threshold          " << fmt("%10.4g", suite.thresholds.max_l1) << "  "
     << fmt("%10.4g", suite.thresholds.mean_l1) << "  " << fmt("%10.3g", suite.thresholds.max_theta_o_error_rad)
     << " rad\n";
  os << "  " << (s.pass_max_l1 ? "ok   " : "FAIL ") << "          " << (s.pass_mean_l1 ? "  ok  " : "  FAIL")
     << "      " << (s.pass_theta_o ? "   ok" : " FAIL") << "\n";
  if (suite.paper && !suite.paper->placement.empty())
    os << "  the paper's figures are consistent with " << suite.paper->placement
       << " ray placement: " << support::printable(suite.paper->placement_evidence) << "\n";
  if (s.worst_case < run.cases.size()) {  // a run with no case has none
    const CaseOutcome& w = run.cases[s.worst_case];
    os << "  worst case: " << groove_text(w.groove) << ", theta_i " << output_deg(w.theta_i) << " deg (L1 "
       << fmt("%.4g", w.l1) << ")\n";
  }
  if (s.degenerate_cases) {
    os << "  degenerate (zero aperture, no opening; listed in the report, not compared):";
    std::string last;
    for (const CaseOutcome& c : run.cases)
      if (c.groove.degenerate() && groove_text(c.groove) != last) os << " " << (last = groove_text(c.groove)) << ";";
    os << "\n";
  }
  os << "  rays " << s.rays << ", bounces " << s.bounces << ", vertex hits " << s.vertex_hits << ", bounce limit "
     << s.bounce_limit << ", wall " << fmt("%.3f", s.wall_s) << " s, " << fmt("%.1f", s.bounces_per_s / 1e6)
     << " M bounces/s\n";
  if (run.options.sampling == sim::Sampling::breakpoints)
    os << "  breakpoints: grid of " << run.options.rays << " rays per lit facet, " << s.zones
       << " zones found (at most " << s.max_zones << " per facet, the narrowest " << fmt("%.3g", s.narrowest_zone)
       << " of its beam), " << s.uncertified_cells << " uncertified grid cells"
       << (s.uncertified_cells ? " (may hide up to " + fmt("%.3g", s.max_missed_bound) + " of a beam)" : "") << "\n";
  if (run.options.probe_vertices)
    os << "  rays aimed exactly at the apex and rims: " << s.probe_rays << " (escaped " << s.probe_escaped
       << ", vertex hits " << s.probe_vertex_hits << ", blocked " << s.probe_blocked << ", bounce limit "
       << s.probe_bounce_limit << "), every one accounted for\n";
  if (s.non_finite_cases) os << "  NaN or infinity in " << s.non_finite_cases << " cases\n";
  os << (s.pass() ? "PASS" : "FAIL") << "\n";
}

nlohmann::json report_json(const GrooveSuiteSet& set, const std::vector<GrooveSuiteRun>& runs) {
  if (set.suites.size() == 1) return report_json(set.suites.front(), runs.front());
  nlohmann::json j = provenance();
  j["suite"] = set.name;
  j["suite_file"] = set.file;
  j["threads"] = runs.empty() ? 0 : runs.front().threads;
  double wall = 0.0;
  bool pass = true;
  nlohmann::json parts = nlohmann::json::array();
  for (std::size_t n = 0; n < runs.size(); ++n) {
    parts.push_back(report_json(set.suites[n], runs[n]));
    wall += runs[n].summary.wall_s;
    pass = pass && runs[n].summary.pass();
  }
  j["wall_s"] = wall;
  j["suites"] = std::move(parts);
  j["pass"] = pass;
  return j;
}

void print_set_table(std::ostream& os, const GrooveSuiteSet& set, const std::vector<GrooveSuiteRun>& runs) {
  for (std::size_t n = 0; n < runs.size(); ++n) {
    if (n) os << "\n";
    print_table(os, set.suites[n], runs[n]);
  }
  if (runs.size() < 2) return;
  // The first column as wide as the longest suite name (22 at least).
  int width = 22;
  for (const GrooveSuite& su : set.suites) width = std::max(width, static_cast<int>(su.name.size()));
  os << "\n" << support::printable(set.name) << ": the paper's figures beside ours\n";
  os << "  " << std::string("column") + std::string(width - 6, ' ')
     << " paper max L1  ours max L1   paper mean L1  ours mean L1   cases   wall s\n";
  bool pass = true;
  for (std::size_t n = 0; n < runs.size(); ++n) {
    const GrooveSuite& su = set.suites[n];
    const GrooveSuiteSummary& s = runs[n].summary;
    pass = pass && s.pass();
    os << "  ";
    os << support::format("%-*s %12.4g %12.4g %14.4g %13.4g %7zu %8.3f\n", width, support::printable(su.name).c_str(),
                          su.paper ? su.paper->max_l1 : NAN, s.max_l1, su.paper ? su.paper->mean_l1 : NAN, s.mean_l1,
                          s.cases, s.wall_s);
  }
  os << (pass ? "PASS" : "FAIL") << "\n";
}

}  // namespace vgroove::validation
