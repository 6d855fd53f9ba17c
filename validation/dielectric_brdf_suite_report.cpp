// The report JSON and the table of the "dielectric_brdf" suite (validation/dielectric_brdf_suite.h).
#include "vgroove/common/angles.h"
#include "vgroove/support/format.h"
#include "vgroove/validation/dielectric_brdf_suite.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/table_frame.h"

#include <cmath>
#include <numbers>

namespace vgroove::validation {

namespace {

nlohmann::json rows_of(const std::vector<double>& joint, int rows, int bins) {
  nlohmann::json out = nlohmann::json::array();
  for (int r = 0; r < rows; ++r)
    out.push_back(std::vector<double>(joint.begin() + static_cast<std::ptrdiff_t>(r) * bins,
                                      joint.begin() + static_cast<std::ptrdiff_t>(r + 1) * bins));
  return out;
}

nlohmann::json lobe_json(const SideLobe& s, int rows, int bins) {
  return {{"energy", s.energy}, {"by_k", s.by_k}, {"lobe_by_k", rows_of(s.joint, rows, bins)}};
}

nlohmann::json fit_json(const SideLobe& traced, const SideFit& f) {
  const double tk1 = traced.by_k.size() > 1 ? traced.by_k[1] : 0.0;
  return {{"k1",
           {{"l1", f.l1_k1},
            {"l1_threshold", f.threshold_k1},
            {"energy_model", f.energy_k1},
            {"energy_traced", tk1},
            {"energy_se", f.se_k1},
            {"energy_threshold", f.energy_threshold_k1},
            {"matches", f.matches_k1}}},
          {"all",
           {{"l1", f.l1_all},
            {"l1_threshold", f.threshold_all},
            {"energy_model", f.energy_all},
            {"energy_traced", traced.energy},
            {"energy_se", f.se_all},
            {"energy_threshold", f.energy_threshold_all},
            {"matches", f.matches_all}}}};
}

std::string case_label(const DielectricBrdfCase& c) {
  return support::format("%s %s %s a=%.2f th=%.0f eta=%.3g %s", dielectric_surface_name(c.surface),
                         surface_dim_name(c.dim), analytic::ndf_name(c.ndf), c.alpha, output_deg(c.theta_i), c.eta,
                         sim::medium_name(c.side));
}

}  // namespace

nlohmann::json dielectric_brdf_report_json(const DielectricBrdfSuite& s, const DielectricBrdfRun& run) {
  nlohmann::json j = report_header({s.name, s.file, "dielectric_brdf", s.description, s.seed}, run.threads, run.wall_s);
  j["inputs"] = {{"cases", s.cases()},
                 {"models", s.models},
                 {"rays", s.rays},
                 {"walk_paths", s.walk_paths},
                 {"grooves", s.grooves},
                 {"realizations", s.realizations},
                 {"segments", s.segments},
                 {"samples_per_length", s.samples_per_length},
                 {"flatland_bins", s.flatland_bins},
                 {"theta_bins", s.theta_bins},
                 {"phi_bins", s.phi_bins},
                 {"max_k", s.max_k},
                 {"max_interactions", s.max_interactions}};
  j["bins"] = {{"flatland",
                "exit angle from the exit side's normal over (-90, 90) deg, counter-clockwise positive "
                "(sim::exit_angle), flatland_bins equal bins"},
               {"3d",
                "theta_o from the exit side's normal over [0, 90) deg in theta_bins, phi_o in phi_bins centred "
                "on 0 (the light at azimuth 180 deg), index theta * phi_bins + phi"},
               {"k_rows", "rows k = 0..max_k, row max_k + 1 holds every k > max_k"},
               {"unit", "fraction of the incident flux per bin"},
               {"reflected", "exits into the light's medium"},
               {"transmitted", "exits into the other medium"}};
  nlohmann::json cases = nlohmann::json::array();
  std::size_t passed = 0;
  std::int64_t rays = 0, unbalanced = 0;
  for (const DielectricBrdfOutcome& o : run.cases) {
    const int rows = s.rows(), bins = s.bins(o.c.dim);
    passed += o.pass, rays += o.rays, unbalanced += o.unbalanced;
    nlohmann::json models = nlohmann::json::object();
    nlohmann::json matching = nlohmann::json::array(), matching_k1 = nlohmann::json::array();
    for (const ModelOutcome& m : o.models) {
      models[m.name] = {{"paths", m.paths},
                        {"reflected", lobe_json(m.reflected, rows, bins)},
                        {"transmitted", lobe_json(m.transmitted, rows, bins)},
                        {"fit",
                         {{"reflected", fit_json(o.reflected, m.fit_reflected)},
                          {"transmitted", fit_json(o.transmitted, m.fit_transmitted)}}},
                        {"matches_k1", m.matches_k1},
                        {"matches_all", m.matches_all}};
      if (m.matches_all) matching.push_back(m.name);
      if (m.matches_k1) matching_k1.push_back(m.name);
    }
    nlohmann::json paths = nlohmann::json::array();
    for (const PathShare& p : o.paths) {
      nlohmann::json e = {{"path", p.path}, {"traced", p.traced}};
      if (p.walk >= 0.0) e["walk"] = p.walk;
      paths.push_back(std::move(e));
    }
    nlohmann::json cj = {
        {"surface", dielectric_surface_name(o.c.surface)},
        {"dimension", surface_dim_name(o.c.dim)},
        {"ndf", analytic::ndf_name(o.c.ndf)},
        {"alpha", o.c.alpha},
        {"theta_i_deg", output_deg(o.c.theta_i)},
        {"eta", o.c.eta},
        {"side", sim::medium_name(o.c.side)},
        {"traced",
         {{"rays", o.rays},
          {"interactions", o.interactions},
          {"grooves_eff", o.grooves_eff},
          {"reflected", lobe_json(o.reflected, rows, bins)},
          {"transmitted", lobe_json(o.transmitted, rows, bins)},
          {"cut", o.cut},
          {"bounce_limit", o.bounce_limit},
          {"vertex", o.vertex},
          {"energy_sum", o.reflected.energy + o.transmitted.energy + o.cut + o.bounce_limit + o.vertex},
          {"unbalanced_rays", o.unbalanced},
          {"largest_imbalance", o.largest_imbalance}}},
        {"models", models},
        {"matching_models", matching},
        {"matching_models_k1", matching_k1},
        {"paths", paths},
        {"non_finite", o.non_finite},
        {"wall_s", o.wall_s},
        {"pass", o.pass}};
    if (o.control)
      cj["walk_control"] = {{"against", s.break_control ? "walter_smith_correlated with 1 / eta (broken on purpose)"
                                                        : "walter_smith_correlated"},
                            {"reflected_k1",
                             {{"l1", o.control->l1_reflected},
                              {"l1_threshold", o.control->threshold_reflected},
                              {"energy_z", o.control->z_reflected}}},
                            {"transmitted_k1",
                             {{"l1", o.control->l1_transmitted},
                              {"l1_threshold", o.control->threshold_transmitted},
                              {"energy_z", o.control->z_transmitted}}},
                            {"holds", o.control->holds}};
    cases.push_back(std::move(cj));
  }
  j["cases"] = std::move(cases);
  j["summary"] = {{"cases", run.cases.size()},
                  {"passed", passed},
                  {"rays", rays},
                  {"unbalanced_rays", unbalanced},
                  {"wall_s", run.wall_s}};
  j["thresholds"] = {
      {"rule",
       "verdict: every ray's R + T + cut + bounce limit + vertex = 1 to 1e-12, every value finite, and the Smith "
       "walk's "
       "k = 1 lobes and energies equal to Walter-Smith height-correlated within the walk's noise (L1 <= expected + "
       "sigmas sd + tolerance; |energy difference| <= albedo_threshold). Each model's fit (k1: the k = 1 row; all: "
       "every k summed) is a result: matches when both sides' L1 and energies are within the thresholds of "
       "lobe_comparison.h at the traced rays over grooves_eff surface features (plus the walk's paths)"},
      {"sigmas", s.sigmas},
      {"model_tolerance_flatland", s.model_tolerance_flatland},
      {"model_tolerance_3d", s.model_tolerance_3d}};
  j["pass"] = run.pass;
  return j;
}

void print_dielectric_brdf_table(std::ostream& os, const DielectricBrdfSuite& s, const DielectricBrdfRun& run) {
  print_table_title(
      os, s.name, "dielectric_brdf",
      support::format("%zu cases, %ld rays and %ld walk paths per case", run.cases.size(), s.rays, s.walk_paths),
      run.threads);
  os << "  R, T: traced albedos; per model (WV Walter V-cavity, WS Smith separable, WH Smith height-correlated, walk "
        "the Smith walk, KD kaleidoscopic): L1/threshold of the reflected and transmitted lobes (all k), z of the R "
        "and T albedo misses; "
        "* = matches within noise\n";
  os << "  ctl: the walk's k = 1 share against Walter-Smith height-correlated (the verdict)\n";
  for (const DielectricBrdfOutcome& o : run.cases) {
    os << support::format("  %-52s R %.4f T %.4f", case_label(o.c).c_str(), o.reflected.energy, o.transmitted.energy);
    for (const ModelOutcome& m : o.models) {
      const double zr =
          m.fit_reflected.se_all > 0 ? (o.reflected.energy - m.fit_reflected.energy_all) / m.fit_reflected.se_all : 0.0;
      const double zt = m.fit_transmitted.se_all > 0
                            ? (o.transmitted.energy - m.fit_transmitted.energy_all) / m.fit_transmitted.se_all
                            : 0.0;
      const double lr = m.fit_reflected.l1_all / m.fit_reflected.threshold_all,
                   lt = m.fit_transmitted.l1_all / m.fit_transmitted.threshold_all;
      std::string tag = m.name == "walter_vcavity"            ? "WV"
                        : m.name == "walter_smith_separable"  ? "WS"
                        : m.name == "walter_smith_correlated" ? "WH"
                        : m.name == "kaleidoscopic"           ? "KD"
                                                              : "walk";
      os << support::format(" | %s%s L1/thr %.1f,%.1f z %+.0f,%+.0f", tag.c_str(), m.matches_all ? "*" : "", lr, lt, zr,
                            zt);
    }
    if (o.unbalanced) os << support::format(" | UNBALANCED %lld", static_cast<long long>(o.unbalanced));
    if (o.control) os << (o.control->holds ? " | ctl ok" : " | ctl FAILS");
    os << (o.pass ? "  pass\n" : "  FAIL\n");
  }
  std::size_t passed = 0;
  for (const auto& o : run.cases) passed += o.pass;
  print_table_close(os, passed, run.cases.size(), run.wall_s);
}

}  // namespace vgroove::validation
