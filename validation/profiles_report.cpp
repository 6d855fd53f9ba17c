// The report JSON and the table of the "profiles" suite (validation/profiles_suite.h).
#include "vgroove/common/angles.h"
#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"
#include "vgroove/validation/profiles_suite.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/table_frame.h"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace vgroove::validation {

namespace {

// Rows of a joint (row, bin) vector, for plotting: [row][bin].
nlohmann::json rows_of(const std::vector<double>& joint, int rows, int bins) {
  nlohmann::json out = nlohmann::json::array();
  for (int r = 0; r < rows; ++r)
    out.push_back(std::vector<double>(joint.begin() + static_cast<std::ptrdiff_t>(r) * bins,
                                      joint.begin() + static_cast<std::ptrdiff_t>(r + 1) * bins));
  return out;
}

nlohmann::json distance_json(const ModelDistance& d) {
  return {{"mean_abs", d.mean_abs}, {"noise", d.noise}, {"max_abs_z", d.max_abs_z}};
}

nlohmann::json lobe_distance_json(const LobeDistance& d) {
  return {{"l1_by_k", d.l1},       {"expected_by_k", d.expected},   {"sd_by_k", d.sd},  {"z_by_k", d.z},
          {"l1", d.l1_total},      {"expected", d.expected_total},  {"sd", d.sd_total}, {"z", d.z_total},
          {"max_z_by_k", d.max_z}, {"within_noise", d.within_noise}};
}

// traced_se is the error of z_vcavity (the ray counting; the predictions are each profile's own),
// realization_se the traced value's spread over the surfaces.
nlohmann::json lit_json(const ProfilesCase& c, const LitFraction& l) {
  return {{"light_deg", output_deg(-c.theta)},
          {"traced", l.traced},
          {"traced_se", l.se},
          {"realization_se", l.realization_se},
          {"smith", l.smith},
          {"vcavity", l.vcavity},
          {"z_vcavity", l.z_vcavity}};
}

nlohmann::json chi_json(const OrderedChiSquare& c) { return {{"stat", c.stat}, {"dof", c.dof}, {"p", c.p}}; }

std::vector<double> edges_deg(int bins) {
  std::vector<double> e;
  for (int b = 0; b <= bins; ++b) e.push_back(output_deg(-0.5 * std::numbers::pi + b * std::numbers::pi / bins));
  return e;
}

nlohmann::json surface_json(const ProfilesSuite& suite, const ProfilesCase& c, const SurfaceOutcome& s) {
  const int rows = suite.max_k + 2, bins = suite.lobe_bins;
  return {{"surface", profile_surface_name(s.surface)},
          {"rays", s.rays},
          {"lost", s.lost},
          {"shadow_rays_at_vertices", s.shadow_vertex},
          {"bounces", s.bounces},
          {"albedo", s.albedo},
          {"wall_s", s.wall_s},
          {"identity",
           {{"g1_identity", s.g1_identity},
            {"largest_relative_error", s.identity_error},
            {"smith_average", s.g1_smith},
            {"vcavity_average", s.g1_average_vcavity},
            {"holds", s.identity_holds}}},
          {"g1",
           {{"view_deg", output_deg(c.theta)},
            {"weight", s.g1_weight.mean},
            {"traced", s.g1_traced.mean},
            {"traced_se", s.g1_se},
            {"realization_se", s.g1_traced.se},
            {"counting_se", s.g1_counting_se},
            {"smith", s.g1_smith},
            {"vcavity", s.g1_vcavity.mean},
            {"distance", {{"smith", distance_json(s.g1_d_smith)}, {"vcavity", distance_json(s.g1_d_vcavity)}}},
            {"chi2_vcavity", chi_json(s.g1_chi2)}}},
          {"g2",
           {{"light_deg", output_deg(-c.theta)},
            {"view_deg", output_deg(c.theta)},
            {"weight", s.g2_weight.mean},
            {"traced", s.g2_traced.mean},
            {"traced_se", s.g2_se},
            {"realization_se", s.g2_traced.se},
            {"counting_se", s.g2_counting_se},
            {"smith_separable", s.g2_smith_separable},
            {"smith_height_correlated", s.g2_smith_correlated},
            {"vcavity", s.g2_vcavity.mean},
            {"distance",
             {{"smith_separable", distance_json(s.g2_d_separable)},
              {"smith_height_correlated", distance_json(s.g2_d_correlated)},
              {"vcavity", distance_json(s.g2_d_vcavity)}}},
            {"chi2_vcavity", chi_json(s.g2_chi2)}}},
          {"lit_fraction", lit_json(c, s.lit)},
          {"lit_fraction_arc_length", lit_json(c, s.lit_arc)},
          {"lobe",
           {{"incident_deg", output_deg(c.theta)},
            {"traced_by_k", rows_of(s.lobe.mean, rows, bins)},
            {"traced_se_by_k", rows_of(s.lobe.se, rows, bins)},
            {"traced_k_fractions", s.by_k},
            {"distance", {{"walk", lobe_distance_json(s.d_walk)}, {"vgroove_model", lobe_distance_json(s.d_vgroove)}}},
            {"vgroove_model_pooled_l1", s.l1_pooled},
            {"vgroove_model_pooled_threshold", s.l1_pooled_threshold}}},
          {"pass", s.pass}};
}

}  // namespace

nlohmann::json profiles_report_json(const ProfilesSuite& suite, const ProfilesRun& run) {
  nlohmann::json j =
      report_header({suite.name, suite.file, "profiles", suite.description, suite.seed}, run.threads, run.wall_s);
  nlohmann::json ndfs = nlohmann::json::array(), theta = nlohmann::json::array(), surfaces = nlohmann::json::array();
  for (auto n : suite.ndfs) ndfs.push_back(analytic::ndf_name(n));
  for (double t : suite.theta) theta.push_back(output_deg(t));
  for (auto s : suite.surfaces) surfaces.push_back(profile_surface_name(s));
  j["inputs"] = {{"ndf", ndfs},
                 {"alpha", suite.alphas},
                 {"theta_deg", theta},
                 {"surfaces", surfaces},
                 {"realizations", suite.realizations},
                 {"segments", suite.segments},
                 {"samples_per_length", suite.samples_per_length},
                 {"rays", suite.rays},
                 {"walk_paths", suite.walk_paths},
                 {"normal_bins", suite.normal_bins},
                 {"lobe_bins", suite.lobe_bins},
                 {"max_k", suite.max_k}};
  std::vector<int> k_rows;
  for (int k = 0; k <= suite.max_k + 1; ++k) k_rows.push_back(k);
  j["bins"] = {{"normal_deg_edges", edges_deg(suite.normal_bins)},
               {"exit_deg_edges", edges_deg(suite.lobe_bins)},
               {"k_rows", k_rows},
               {"k_rows_note", "row max_k + 1 holds every k > max_k"},
               {"lobe_unit", "fraction of the incident flux per exit-angle bin"}};
  nlohmann::json cases = nlohmann::json::array();
  std::size_t passed = 0;
  std::int64_t rays = 0, lost = 0;
  const int rows = suite.max_k + 2, bins = suite.lobe_bins;
  for (const ProfilesOutcome& o : run.cases) {
    passed += o.pass;
    nlohmann::json sj = nlohmann::json::array();
    for (const SurfaceOutcome& s : o.surfaces)
      sj.push_back(surface_json(suite, o.c, s)), rays += s.rays, lost += s.lost;
    cases.push_back(
        {{"ndf", analytic::ndf_name(o.c.ndf)},
         {"alpha", o.c.alpha},
         {"theta_deg", output_deg(o.c.theta)},
         {"walk",
          {{"paths", o.walk_paths},
           {"left", o.walk_left},
           {"wall_s", o.walk_wall_s},
           {"lobe_by_k", rows_of(o.walk_lobe, rows, bins)},
           {"k_fractions", o.walk_by_k}}},
         {"vgroove_model", {{"lobe_by_k", rows_of(o.model_lobe, rows, bins)}, {"k_fractions", o.model_by_k}}},
         {"surfaces", sj},
         {"non_finite", o.non_finite},
         {"pass", o.pass}});
  }
  j["cases"] = std::move(cases);
  j["summary"] = {
      {"cases", run.cases.size()}, {"passed", passed}, {"rays", rays}, {"lost", lost}, {"wall_s", run.wall_s}};
  j["thresholds"] = {
      {"rule",
       "every profile: no ray lost and the projected-area identity to 1e-12; V-groove profiles: V-cavity "
       "G1 and G2 chi-square p >= p_min / tests, lit fraction of arc length |z| <= sigmas, V-groove model lobe L1 <= "
       "expected + sigmas sd + model_tolerance; model distances on other surfaces are results"},
      {"p_min", suite.p_min},
      {"tests", suite.verdict_tests()},
      {"sigmas", suite.sigmas},
      {"model_tolerance", suite.model_tolerance}};
  j["pass"] = run.pass;
  return j;
}

void print_profiles_table(std::ostream& os, const ProfilesSuite& suite, const ProfilesRun& run) {
  print_table_title(os, suite.name, "profiles",
                    support::format("%zu cases x %zu surfaces, %d realizations of %d segments, %ld rays per beam, %ld "
                                    "walk paths",
                                    run.cases.size(), suite.surfaces.size(), suite.realizations, suite.segments,
                                    suite.rays, suite.walk_paths),
                    run.threads);
  os << "  G1, G2: projected-area-weighted mean |traced - model| over the normal bins (noise: what a right model "
        "shows)\n  lobe: the largest z over k of the L1 distance of each k's lobe (<= sigmas: within noise)\n";
  os << "  lit: the lit fraction per unit macro length, traced (its error) / Smith / V-cavity; arc: per unit arc "
        "length, traced (its error) / V-cavity\n";
  os << support::format(
      "  %-8s %5s %5s %-7s %8s %8s %8s %8s %8s %8s %8s | %7s %7s %7s %7s | %7s %7s %7s | %7s %7s | %4s\n", "ndf",
      "alpha", "theta", "surface", "G1 noise", "Smith", "V-cav", "G2 noise", "sep", "h-corr", "V-cav", "lit", "(se)",
      "Smith", "V-cav", "arc", "(se)", "V-cav", "z walk", "z vgrv", "pass");
  for (const ProfilesOutcome& o : run.cases)
    for (const SurfaceOutcome& s : o.surfaces) {
      os << support::format(
          "  %-8s %5.2f %5.1f %-7s %8.5f %8.5f %8.5f %8.5f %8.5f %8.5f %8.5f | %7.4f %7.4f %7.4f %7.4f | %7.4f %7.4f "
          "%7.4f | %7.1f %7.1f | %4s\n",
          analytic::ndf_name(o.c.ndf), o.c.alpha, output_deg(o.c.theta), profile_surface_name(s.surface),
          s.g1_d_smith.noise, s.g1_d_smith.mean_abs, s.g1_d_vcavity.mean_abs, s.g2_d_separable.noise,
          s.g2_d_separable.mean_abs, s.g2_d_correlated.mean_abs, s.g2_d_vcavity.mean_abs, s.lit.traced, s.lit.se,
          s.lit.smith, s.lit.vcavity, s.lit_arc.traced, s.lit_arc.se, s.lit_arc.vcavity, s.d_walk.max_z,
          s.d_vgroove.max_z, s.pass ? "yes" : "NO");
    }
  std::size_t passed = 0;
  for (const auto& o : run.cases) passed += o.pass;
  print_table_close(os, passed, run.cases.size(), run.wall_s);
}

}  // namespace vgroove::validation
