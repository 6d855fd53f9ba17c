#include "validation/report.h"

#include "vgroove_version.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace vgroove::validation {

namespace {
double deg(double rad) { return output_deg(rad); }

const char* form_name(analytic::Eq6Form f) { return f == analytic::Eq6Form::corrected ? "corrected" : "printed"; }

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}
}  // namespace

double output_deg(double rad) { return std::round(rad * (180.0 / M_PI) * 1e9) / 1e9 + 0.0; }

const char* version_string() { return VGROOVE_VERSION; }
const char* git_revision() { return VGROOVE_GIT; }

nlohmann::json provenance() {
  return {{"tool", "vgroove"}, {"version", VGROOVE_VERSION}, {"git", VGROOVE_GIT}};
}

nlohmann::json report_json(const Suite& suite, const SuiteRun& run) {
  const Summary& s = run.summary;
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
  for (const CaseOutcome& c : run.cases) {
    nlohmann::json jc = {{"theta_v_deg", deg(c.theta_v)}, {"theta_i_deg", deg(c.theta_i)}, {"l1", c.l1},
                         {"rays", c.rays}, {"bounces", c.bounces}, {"theta_o_error_rad", c.theta_o_error}};
    for (int f = 0; f < 2; ++f) {
      const FacetOutcome& fo = c.facet[f];
      const char* name = f == 0 ? "left" : "right";
      if (!fo.compared) {
        jc[name] = nullptr;  // the light does not reach this facet
        continue;
      }
      jc[name] = {{"l1", fo.l1}, {"k", fo.k}, {"rays", fo.rays}, {"vertex_hits", fo.vertex_hits},
                  {"bounce_limit", fo.bounce_limit}, {"wrong_first_facet", fo.wrong_first}};
    }
    cases.push_back(std::move(jc));
  }
  j["cases"] = std::move(cases);
  const CaseOutcome& worst = run.cases.empty() ? CaseOutcome{} : run.cases[s.worst_case];
  j["summary"] = {{"cases", s.cases},
                  {"facets_compared", s.facets_compared},
                  {"max_l1", s.max_l1},
                  {"mean_l1", s.mean_l1},
                  {"worst_case", {{"theta_v_deg", deg(worst.theta_v)}, {"theta_i_deg", deg(worst.theta_i)}}},
                  {"max_theta_o_error_rad", s.max_theta_o_error},
                  {"rays", s.rays},
                  {"rays_per_case", s.rays_per_case},
                  {"bounces", s.bounces},
                  {"vertex_hits", s.vertex_hits},
                  {"bounce_limit", s.bounce_limit},
                  {"wrong_first_facet", s.wrong_first},
                  {"wall_s", s.wall_s},
                  {"bounces_per_s", s.bounces_per_s}};
  j["thresholds"] = {{"max_l1", suite.thresholds.max_l1},
                     {"mean_l1", suite.thresholds.mean_l1},
                     {"max_theta_o_error_rad", suite.thresholds.max_theta_o_error_rad}};
  if (suite.paper)
    j["paper"] = {{"source", suite.paper->source}, {"max_l1", suite.paper->max_l1}, {"mean_l1", suite.paper->mean_l1}};
  j["pass"] = s.pass();
  return j;
}

void print_table(std::ostream& os, const Suite& suite, const SuiteRun& run) {
  const Summary& s = run.summary;
  os << "vgroove " << VGROOVE_VERSION << " (git " << VGROOVE_GIT << ")  suite " << suite.name << ": " << s.cases
     << " cases, " << run.options.rays << " rays per lit facet, " << sim::sampling_name(run.options.sampling)
     << ", seed " << run.options.seed << ", Eq. 6 " << form_name(run.options.form) << ", " << run.threads
     << " threads\n";
  os << "                      max L1      mean L1     max |theta_o err|\n";
  if (suite.paper)
    os << "  paper              " << fmt("%10.4g", suite.paper->max_l1) << "  " << fmt("%10.4g", suite.paper->mean_l1)
       << "   -          (" << suite.paper->source << ")\n";
  os << "  vgroove            " << fmt("%10.4g", s.max_l1) << "  " << fmt("%10.4g", s.mean_l1) << "  "
     << fmt("%10.3g", s.max_theta_o_error) << " rad\n";
  os << "  threshold          " << fmt("%10.4g", suite.thresholds.max_l1) << "  "
     << fmt("%10.4g", suite.thresholds.mean_l1) << "  " << fmt("%10.3g", suite.thresholds.max_theta_o_error_rad)
     << " rad\n";
  os << "  " << (s.pass_max_l1 ? "ok   " : "FAIL ") << "          " << (s.pass_mean_l1 ? "  ok  " : "  FAIL")
     << "      " << (s.pass_theta_o ? "   ok" : " FAIL") << "\n";
  const CaseOutcome& w = run.cases[s.worst_case];
  os << "  worst case: theta_v " << deg(w.theta_v) << " deg, theta_i " << deg(w.theta_i) << " deg (L1 "
     << fmt("%.4g", w.l1) << ")\n";
  os << "  rays " << s.rays << ", bounces " << s.bounces << ", vertex hits " << s.vertex_hits << ", bounce limit "
     << s.bounce_limit << ", wall " << fmt("%.3f", s.wall_s) << " s, " << fmt("%.1f", s.bounces_per_s / 1e6)
     << " M bounces/s\n";
  os << (s.pass() ? "PASS" : "FAIL") << "\n";
}

}  // namespace vgroove::validation
