// The report JSON and the table of the "heightfield" suite (validation/heightfield_suite.h).
#include "vgroove/sim/heightfield.h"
#include "vgroove/support/format.h"
#include "vgroove/validation/heightfield_lobe.h"
#include "vgroove/validation/heightfield_suite.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/table_frame.h"

#include <cmath>
#include <string>

namespace vgroove::validation {

namespace {

const char* kRowNames[kHeightfieldRows] = {"1", "2", "3+"};

nlohmann::json rows_of(const std::vector<double>& joint, int rows, int bins) {
  nlohmann::json out = nlohmann::json::array();
  for (int r = 0; r < rows; ++r)
    out.push_back(std::vector<double>(joint.begin() + static_cast<std::ptrdiff_t>(r) * bins,
                                      joint.begin() + static_cast<std::ptrdiff_t>(r + 1) * bins));
  return out;
}

nlohmann::json miss_json(const HeightfieldMiss& m, const HeightfieldOutcome& o) {
  nlohmann::json rows = nlohmann::json::array();
  for (std::size_t r = 0; r < m.l1.size(); ++r)
    rows.push_back(
        {{"k", kRowNames[r]},
         {"l1", m.l1[r]},
         {"l1_expected", m.l1_expected[r]},
         {"l1_threshold", m.l1_threshold[r]},
         {"l1_excess", m.l1[r] - m.l1_expected[r]},
         {"energy_traced", o.energy[r]},
         {"energy_model", m.energy[r]},
         {"energy_diff", m.energy_diff[r]},
         {"energy_threshold", m.energy_threshold[r]},
         {"within_noise", m.l1[r] <= m.l1_threshold[r] && std::abs(m.energy_diff[r]) <= m.energy_threshold[r]}});
  return {{"rows", rows},
          {"l1", m.l1_total},
          {"l1_expected", m.l1_total_expected},
          {"l1_threshold", m.l1_total_threshold},
          {"within_noise", m.within_noise}};
}

// "within noise", or what misses most: the row whose L1 is furthest over its threshold, and the
// energy furthest over its own.
std::string miss_text(const HeightfieldMiss& m) {
  if (m.within_noise) return "within noise";
  std::string s = "misses:";
  for (std::size_t r = 0; r < m.l1.size(); ++r) {
    if (m.l1[r] > m.l1_threshold[r])
      s += support::format(" L1 k=%s %.4f > %.4f (%.1fx);", kRowNames[r], m.l1[r], m.l1_threshold[r],
                           m.l1[r] / m.l1_threshold[r]);
    if (!(std::abs(m.energy_diff[r]) <= m.energy_threshold[r]))
      s += support::format(" E%s %+.4f (> %.4f);", kRowNames[r], -m.energy_diff[r], m.energy_threshold[r]);
  }
  if (m.l1_total > m.l1_total_threshold) s += support::format(" L1 all %.4f > %.4f;", m.l1_total, m.l1_total_threshold);
  s.pop_back();
  return s;
}

nlohmann::json masking_value_json(const HeightfieldMaskingValue& v, bool g2) {
  nlohmann::json models = nlohmann::json::object();
  for (const HeightfieldMaskingMiss& m : v.models)
    models[m.model] = {{"value", m.value},
                       {"bins", m.bins},
                       {"diff", m.diff},
                       {"z", m.z},
                       {"worst_bin", m.worst_bin},
                       {"worst_bin_diff", m.worst_bin_diff},
                       {"worst_bin_z", m.worst_bin_z},
                       {"overall_within_noise", m.overall_within_noise},
                       {"within_noise", m.within_noise}};
  nlohmann::json j = {{"theta_o_deg", v.theta_o_deg},
                      {"traced", v.g},
                      {"traced_se", v.g_se},
                      {"bins", v.bins},
                      {"bins_se", v.bins_se},
                      {"bin_points", v.bin_points},
                      {"models", models}};
  if (g2) j["phi_deg"] = v.phi_deg, j["g1_i"] = v.g1_i, j["g1_o"] = v.g1_o;
  return j;
}

// Plainly: which models are within noise overall and which in every bin too, and how far each
// model is (model - traced overall, in standard errors, and its worst bin).
std::string masking_text(const HeightfieldMaskingValue& v) {
  std::string overall, every_bin, far;
  for (const HeightfieldMaskingMiss& m : v.models) {
    if (m.overall_within_noise) overall += (overall.empty() ? "" : ", ") + m.model;
    if (m.within_noise) every_bin += (every_bin.empty() ? "" : ", ") + m.model;
    if (m.within_noise) continue;
    far += support::format("; %s %+.4f (%.1f se", m.model.c_str(), -m.diff, std::abs(m.z));
    if (m.worst_bin >= 0)
      far += support::format(", bin %d %+.4f, %.1f se", m.worst_bin, -m.worst_bin_diff, std::abs(m.worst_bin_z));
    far += ")";
  }
  return support::format("%.4f(%.4f); within noise overall: %s; in every bin: %s", v.g, v.g_se,
                         overall.empty() ? "none" : overall.c_str(), every_bin.empty() ? "none" : every_bin.c_str()) +
         far;
}

// Why the isotropic models are not compared on an anisotropic case.
std::string skipped_text(double aspect) {
  return support::format("anisotropic roughness (alpha_y = %g alpha_x): the model is isotropic here", aspect);
}

// The walks of walk_heights[1..], side by side with the first.
nlohmann::json other_walks_json(const HeightfieldOutcome& o, int bins) {
  nlohmann::json out = nlohmann::json::array();
  for (const HeightfieldOtherWalk& w : o.other_walks)
    out.push_back({{"heights", w.heights},
                   {"paths", w.paths},
                   {"left", w.left},
                   {"energy_by_k", w.energy},
                   {"lobe_by_k", rows_of(w.lobe, kHeightfieldRows, bins)},
                   {"against_traced", miss_json(w.against_traced, o)},
                   {"against_first", miss_json(w.against_first, o)}});
  return out;
}

nlohmann::json walk_heights_names(const HeightfieldSuite& suite) {
  nlohmann::json out = nlohmann::json::array();
  for (analytic::WalkHeights h : suite.walk_heights) out.push_back(analytic::walk_heights_name(h));
  return out;
}

}  // namespace

nlohmann::json heightfield_report_json(const HeightfieldSuite& suite, const HeightfieldRun& run) {
  nlohmann::json j =
      report_header({suite.name, suite.file, "heightfield", suite.description, suite.seed}, run.threads, run.wall_s);
  nlohmann::json ndfs = nlohmann::json::array();
  for (auto n : suite.ndfs) ndfs.push_back(analytic::ndf_name(n));
  j["inputs"] = {{"ndf", ndfs},
                 {"alpha", suite.alphas},
                 {"theta_i_deg", suite.theta_i_deg},
                 {"surface", heightfield_surface_name(suite.surface)},
                 {"aspect", suite.aspect_list ? nlohmann::json(suite.aspects) : nlohmann::json(suite.aspects[0])},
                 {"walk_heights", walk_heights_names(suite)},
                 {"field_size", suite.field_size},
                 {"correlation_length", suite.correlation_length},
                 {"fields", suite.fields},
                 {"field_bytes", sim::heightfield_bytes(suite.field_size)},
                 {"rays", suite.rays},
                 {"walk_paths", suite.walk_paths},
                 {"theta_bins", suite.theta_bins},
                 {"phi_bins", suite.phi_bins},
                 {"rows", {"1", "2", "3+"}}};
  if (suite.surface == HeightfieldSurfaceKind::grooves) {
    const sim::GrooveFieldOptions g = groove_field_options(
        {analytic::NdfKind::beckmann, 1.0, suite.field_size, suite.correlation_length, suite.surface}, 0);
    j["inputs"]["grooves"] = {
        {"groove_length", g.groove_length},
        {"groove_spacing", g.groove_spacing},
        {"seed_step", g.seed_step},
        {"grooves_per_field", std::lround(static_cast<double>(g.n) * g.n / (g.groove_spacing * g.groove_spacing))}};
  } else {
    j["inputs"]["patches_per_field"] = heightfield_patches(suite.field_size, suite.correlation_length, 1);
  }
  if (suite.masking)
    j["inputs"]["masking"] = {
        {"theta_o_deg", suite.masking->theta_o_deg}, {"phi_deg", suite.masking->phi_deg},
        {"points", suite.masking->points},           {"theta_m_bins", suite.masking->theta_m_bins},
        {"phi_m_bins", suite.masking->phi_m_bins},   {"light_azimuth_deg", 0.0}};
  nlohmann::json cases = nlohmann::json::array();
  std::int64_t rays = 0, lost = 0;
  std::size_t passed = 0;
  for (const HeightfieldOutcome& o : run.cases) {
    const int bins = suite.bins();
    rays += o.rays, lost += o.lost, passed += o.pass;
    const bool case_is_anisotropic = o.c.aspect != 1.0;  // the isotropic models skipped
    cases.push_back({{"ndf", analytic::ndf_name(o.c.ndf)},
                     {"alpha", o.c.alpha},
                     {"theta_i_deg", o.c.theta_i_deg},
                     {"aspect", o.c.aspect},
                     {"rays", o.rays},
                     {"lost", o.lost},
                     {"bounce_limit", o.bounce_limit},
                     {"edge_hits", o.edge_hits},
                     {"vertex_hits", o.vertex_hits},
                     {"mean_bounces",
                      o.rays > o.lost ? static_cast<double>(o.bounces) / static_cast<double>(o.rays - o.lost) : 0.0},
                     {"traced",
                      {{"energy_by_k", o.energy},
                       {"energy_se_by_k", o.energy_se},
                       {"albedo", o.albedo},
                       {"albedo_se", o.albedo_se},
                       {"lobe_by_k", rows_of(o.lobe, kHeightfieldRows, bins)},
                       {"lobe_se_by_k", rows_of(o.lobe_se, kHeightfieldRows, bins)}}},
                     {"smith_walk",
                      {{"heights", analytic::walk_heights_name(suite.walk_heights.front())},
                       {"paths", o.walk_paths},
                       {"left", o.walk_left},
                       {"energy_by_k", o.walk_energy},
                       {"lobe_by_k", rows_of(o.walk_lobe, kHeightfieldRows, bins)},
                       {"against_traced", miss_json(o.walk, o)}}},
                     {"cook_torrance_smith", case_is_anisotropic
                                                 ? nlohmann::json{{"skipped", skipped_text(o.c.aspect)}}
                                                 : nlohmann::json{{"integration_error", o.ct_error},
                                                                  {"lobe_k1", o.ct_lobe},
                                                                  {"against_traced", miss_json(o.cook_torrance, o)}}},
                     {"vgroove", case_is_anisotropic
                                     ? nlohmann::json{{"skipped", skipped_text(o.c.aspect)}}
                                     : nlohmann::json{{"energy_by_k", o.vgroove_energy},
                                                      {"lobe_by_k", rows_of(o.vgroove_lobe, kHeightfieldRows, bins)},
                                                      {"against_traced", miss_json(o.vgroove, o)}}},
                     {"timing",
                      {{"field_s", o.field_s},
                       {"trace_s", o.trace_s},
                       {"walk_s", o.walk_s},
                       {"model_s", o.model_s},
                       {"masking_s", o.masking_s}}},
                     {"non_finite", o.non_finite},
                     {"pass", o.pass}});
    // The first distribution's walk is "smith_walk"; the others beside it, each against the traced
    // lobe and against the first walk.
    if (!o.other_walks.empty()) cases.back()["smith_walk_other_heights"] = other_walks_json(o, bins);
    if (suite.masking) {
      nlohmann::json g1 = nlohmann::json::array(), g2 = nlohmann::json::array();
      for (const auto& v : o.g1) g1.push_back(masking_value_json(v, false));
      for (const auto& v : o.g2) g2.push_back(masking_value_json(v, true));
      cases.back()["masking"] = {
          {"points", o.masking_points}, {"lost", o.masking_lost}, {"g1", std::move(g1)}, {"g2", std::move(g2)}};
    }
  }
  j["cases"] = std::move(cases);
  nlohmann::json controls = nlohmann::json::array();
  for (std::size_t n = 0; n < suite.controls.size(); ++n) {
    const HeightfieldCase c = suite.case_at(suite.controls[n].case_index);
    controls.push_back({{"model", heightfield_model_name(suite.controls[n].model)},
                        {"ndf", analytic::ndf_name(c.ndf)},
                        {"alpha", c.alpha},
                        {"theta_i_deg", c.theta_i_deg},
                        {"aspect", c.aspect},
                        {"within_noise", n < run.controls_hold.size() && run.controls_hold[n]}});
  }
  j["controls"] = std::move(controls);
  j["masking_controls"] = masking_controls_json(suite, run);
  j["summary"] = {
      {"cases", run.cases.size()}, {"passed", passed}, {"rays", rays}, {"lost", lost}, {"wall_s", run.wall_s}};
  j["thresholds"] = {
      {"rule",
       "every case: no ray lost, every value finite; each control's model within noise. A model is within noise "
       "when every row's L1 <= expected + sigmas sd + tolerance (per-bin variance: the traced mean's, its fields' "
       "spread but at least the rays' multinomial error, plus the walk's own) and every row's |E_traced - E_model| "
       "<= sigmas se + tolerance; the other models' distances are results, not verdicts"},
      {"masking_rule",
       "masking: a model is within noise when |traced - model| <= sigmas se + model_tolerance overall (and, for "
       "every_bin, in every facet-normal bin with points on every field; se: the fields' spread, at least the "
       "points' binomial error); each masking control's model within noise enters the verdict, the others are "
       "results"},
      {"sigmas", suite.sigmas},
      {"model_tolerance", suite.model_tolerance}};
  j["pass"] = run.pass;
  return j;
}

void print_heightfield_table(std::ostream& os, const HeightfieldSuite& suite, const HeightfieldRun& run) {
  const bool grooves = suite.surface == HeightfieldSurfaceKind::grooves;
  std::string aspects;
  for (double a : suite.aspects) aspects += (aspects.empty() ? "" : ", ") + support::number_text(a);
  const bool several_aspects = suite.aspects.size() > 1, several_walks = suite.walk_heights.size() > 1;
  const std::string first_walk = analytic::walk_heights_name(suite.walk_heights.front());
  print_table_title(
      os, suite.name, "heightfield",
      support::format("%zu cases, %d %sfields of %d^2 cells (correlation %g cells%s) per case, %ld rays per field, "
                      "%ld walk paths, %d x %d bins, F = 1",
                      run.cases.size(), suite.fields,
                      grooves           ? "random-orientation V-groove "
                      : several_aspects ? ("anisotropic (alpha_y = aspect alpha_x, aspect " + aspects + ") ").c_str()
                      : suite.anisotropic()
                          ? support::format("anisotropic (alpha_y = %g alpha_x) ", suite.aspects[0]).c_str()
                          : "",
                      suite.field_size, suite.correlation_length, grooves ? ": grooves 3 l long, 3 l apart" : "",
                      suite.rays, suite.walk_paths, suite.theta_bins, suite.phi_bins),
      run.threads);
  os << "  traced E_k over the fields (se); each model: within noise (L1 per k <= expected + sigmas sd, E_k within "
        "sigmas se), or where it misses (L1 over its threshold, model E_k minus traced)\n";
  for (const HeightfieldOutcome& o : run.cases) {
    os << support::format(
        "  %-8s%s alpha %.2f theta_i %4.1f: E_1 %.4f(%.4f) E_2 %.4f(%.4f) E_3+ %.4f(%.4f) albedo "
        "%.4f; %lld rays, lost %lld, %.2f s%s\n",
        analytic::ndf_name(o.c.ndf), several_aspects ? support::format(" aspect %g", o.c.aspect).c_str() : "",
        o.c.alpha, o.c.theta_i_deg, o.energy[0], o.energy_se[0], o.energy[1], o.energy_se[1], o.energy[2],
        o.energy_se[2], o.albedo, static_cast<long long>(o.rays), static_cast<long long>(o.lost),
        o.field_s + o.trace_s + o.walk_s + o.model_s, o.pass ? "" : "  FAIL (lost or not finite)");
    os << support::format("    %-20s %s\n", several_walks ? ("smith_walk " + first_walk).c_str() : "smith_walk",
                          miss_text(o.walk).c_str());
    for (const HeightfieldOtherWalk& w : o.other_walks)
      os << support::format("    %-20s %s; against %s: %s\n", ("smith_walk " + w.heights).c_str(),
                            miss_text(w.against_traced).c_str(), first_walk.c_str(),
                            miss_text(w.against_first).c_str());
    const bool skipped = o.c.aspect != 1.0;
    const std::string skip = "skipped: " + skipped_text(o.c.aspect);
    os << support::format("    %-20s %s\n", "cook_torrance_smith",
                          skipped ? skip.c_str() : miss_text(o.cook_torrance).c_str());
    os << support::format("    %-20s %s\n", "vgroove", skipped ? skip.c_str() : miss_text(o.vgroove).c_str());
    if (suite.masking) {
      os << support::format(
          "    masking (%lld points, lost %lld, %.2f s): traced G(se); the models within noise overall, "
          "and overall and in every facet-normal bin; each other's model - traced (se; its worst bin)\n",
          static_cast<long long>(o.masking_points), static_cast<long long>(o.masking_lost), o.masking_s);
      for (const auto& v : o.g1)
        os << support::format("      G1 theta_o %4.1f:             %s\n", v.theta_o_deg, masking_text(v).c_str());
      for (const auto& v : o.g2)
        os << support::format("      G2 theta_o %4.1f dphi %5.1f: %s\n", v.theta_o_deg, v.phi_deg,
                              masking_text(v).c_str());
    }
  }
  for (std::size_t n = 0; n < suite.controls.size(); ++n) {
    const HeightfieldCase c = suite.case_at(suite.controls[n].case_index);
    const bool held = n < run.controls_hold.size() && run.controls_hold[n];
    os << support::format("  control: %s on %s%s alpha %.2f theta_i %.1f: %s\n",
                          heightfield_model_name(suite.controls[n].model), analytic::ndf_name(c.ndf),
                          several_aspects ? support::format(" aspect %g", c.aspect).c_str() : "", c.alpha,
                          c.theta_i_deg, held ? "within noise" : "NOT within noise (fails the suite)");
  }
  print_masking_controls(os, suite, run);
  std::size_t passed = 0;
  for (const auto& o : run.cases) passed += o.pass;
  print_table_close(os, passed, run.cases.size(), run.wall_s);
}

}  // namespace vgroove::validation
