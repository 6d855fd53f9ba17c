// The suite file, the report JSON and the table of the "heightfield_albedo" suite
// (validation/heightfield_albedo.h).
#include "vgroove/analytic/ndf.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/heightfield_albedo.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/table_frame.h"

#include <cmath>
#include <numbers>
#include <string>

namespace vgroove::validation {

namespace {

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

HeightfieldAlbedoSuite parse_heightfield_albedo_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  HeightfieldAlbedoSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"heightfield_albedo"});
  for (const auto& n : read_names(root, "ndf", {"beckmann", "ggx"}))
    s.ndfs.push_back(n == "ggx" ? NdfKind::ggx : NdfKind::beckmann);
  s.alphas = read_numbers(root, "alpha", kMinAlpha, true, kMaxAlpha, true);
  s.mus = read_numbers(root, "mu", kMinMu, true, 1.0, true);
  s.field_size = static_cast<int>(root.integer("field_size", 16, 65536));
  if ((s.field_size & (s.field_size - 1)) != 0)
    root.fail("field_size", "= " + std::to_string(s.field_size) + " must be a power of two in [16, 65536]");
  const std::string gaussian = "gaussian";
  if (root.one_of("surface", {"gaussian", "grooves"}, &gaussian) == "grooves")
    s.surface = HeightfieldSurfaceKind::grooves;
  const bool grooves = s.surface == HeightfieldSurfaceKind::grooves;
  if (grooves && s.field_size > 4096)
    root.fail("field_size",
              "= " + std::to_string(s.field_size) +
                  " must be a power of two in [16, 4096] with surface grooves (sim/heightfield_grooves.h)");
  s.correlation_length = root.number("correlation_length", 2.0, true, s.field_size / (grooves ? 12.0 : 8.0), true);
  s.fields = static_cast<int>(root.integer("fields", 2, 1000));
  s.rays = static_cast<long>(root.integer("rays", 1, kMaxRays));
  s.walk_paths = static_cast<long>(root.integer("walk_paths", 1, kMaxRays));
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, kMaxSeed));
  {
    support::JsonObject t = root.object("thresholds");
    s.sigmas = t.number("sigmas", 0.0, false, kMaxSigmas, true);
    s.model_tolerance = t.number_or("model_tolerance", s.model_tolerance, 0.0, true, 1.0, true);
    t.finish();
  }
  root.finish();
  return s;
}

std::string albedo_row_text(const AlbedoPoint& p, int row) {
  std::string within, far;
  for (int m = 0; m < kAlbedoModels; ++m) {
    const AlbedoComparison& c = p.models[m][row];
    if (!std::isfinite(c.value)) continue;  // the model has no such row
    if (c.within_noise) {
      within += (within.empty() ? "" : ", ") + std::string(kAlbedoModelNames[m]);
    } else {
      far += support::format("; %s %+.4f (%.1f se)", kAlbedoModelNames[m], -c.diff, std::abs(c.z));
    }
  }
  return "within noise: " + (within.empty() ? std::string("none") : within) + far;
}

nlohmann::json heightfield_albedo_report_json(const HeightfieldAlbedoSuite& suite, const HeightfieldAlbedoRun& run) {
  nlohmann::json j = report_header({suite.name, suite.file, "heightfield_albedo", suite.description, suite.seed},
                                   run.threads, run.wall_s);
  nlohmann::json ndfs = nlohmann::json::array();
  for (auto n : suite.ndfs) ndfs.push_back(analytic::ndf_name(n));
  j["inputs"] = {{"ndf", ndfs},
                 {"alpha", suite.alphas},
                 {"mu", suite.mus},
                 {"surface", heightfield_surface_name(suite.surface)},
                 {"field_size", suite.field_size},
                 {"correlation_length", suite.correlation_length},
                 {"fields", suite.fields},
                 {"field_bytes", sim::heightfield_bytes(suite.field_size)},
                 {"rays", suite.rays},
                 {"walk_paths", suite.walk_paths},
                 {"rows", kAlbedoRowNames},
                 {"models", kAlbedoModelNames},
                 {"fresnel", "F = 1"}};
  nlohmann::json points = nlohmann::json::array();
  for (const AlbedoPoint& p : run.points) {
    nlohmann::json models = nlohmann::json::object();
    for (int m = 0; m < kAlbedoModels; ++m) {
      nlohmann::json value = nlohmann::json::array(), diff = nlohmann::json::array(), thr = nlohmann::json::array(),
                     sd = nlohmann::json::array(), z = nlohmann::json::array(), within = nlohmann::json::array();
      for (int r = 0; r < kAlbedoRows; ++r) {
        const AlbedoComparison& c = p.models[m][r];
        const bool has = std::isfinite(c.value);
        value.push_back(number_or_null(c.value)), sd.push_back(has ? nlohmann::json(std::sqrt(c.var)) : nullptr);
        diff.push_back(number_or_null(c.diff)), thr.push_back(number_or_null(c.threshold));
        z.push_back(number_or_null(c.z)), within.push_back(has ? nlohmann::json(c.within_noise) : nullptr);
      }
      models[kAlbedoModelNames[m]] = {{"value", value},   {"value_sd", sd}, {"diff", diff},
                                      {"threshold", thr}, {"z", z},         {"within_noise", within}};
    }
    nlohmann::json text = nlohmann::json::object();
    for (int r = 0; r < kAlbedoRows; ++r) text[kAlbedoRowNames[r]] = albedo_row_text(p, r);
    points.push_back({{"ndf", analytic::ndf_name(p.ndf)},
                      {"alpha", p.alpha},
                      {"mu", p.mu},
                      {"theta_deg", output_deg(std::acos(std::min(1.0, p.mu)))},
                      {"traced", std::vector<double>(p.traced, p.traced + kAlbedoRows)},
                      {"traced_se", std::vector<double>(p.traced_se, p.traced_se + kAlbedoRows)},
                      {"models", models},
                      {"plainly", text}});
  }
  nlohmann::json items = nlohmann::json::array();
  std::int64_t rays = 0, lost = 0;
  std::size_t passed = 0;
  for (std::size_t i = 0; i < run.items.size(); ++i) {
    const HeightfieldAlbedoOutcome& o = run.items[i];
    rays += o.rays, lost += o.lost, passed += run.item_pass[i];
    items.push_back(
        {{"ndf", analytic::ndf_name(suite.ndf_of(i))},
         {"alpha", suite.alpha_of(i)},
         {"rays", o.rays},
         {"lost", o.lost},
         {"bounce_limit", o.bounce_limit},
         {"edge_hits", o.edge_hits},
         {"vertex_hits", o.vertex_hits},
         {"walk_paths_per_mu", o.walk_paths},
         {"ess_error", o.ess_error},
         {"timing", {{"field_s", o.field_s}, {"trace_s", o.trace_s}, {"walk_s", o.walk_s}, {"model_s", o.model_s}}},
         {"pass", run.item_pass[i]}});
  }
  j["points"] = std::move(points);
  j["items"] = std::move(items);
  j["summary"] = {
      {"items", run.items.size()}, {"passed", passed}, {"rays", rays}, {"lost", lost}, {"wall_s", run.wall_s}};
  j["thresholds"] = {
      {"rule",
       "every (ndf, alpha): every ray leaves (F = 1: E = 1 exactly), every value finite. A model is within noise in "
       "a row when |traced - model| <= sigmas sqrt(se^2 + var_model) + model_tolerance (+ E_ss's quadrature bound); "
       "se: the fields' spread, at least the rays' binomial error; var_model: the walk's multinomial variance. "
       "Reported, not a verdict"},
      {"sigmas", suite.sigmas},
      {"model_tolerance", suite.model_tolerance}};
  j["pass"] = run.pass;
  return j;
}

void print_heightfield_albedo_table(std::ostream& os, const HeightfieldAlbedoSuite& suite,
                                    const HeightfieldAlbedoRun& run) {
  print_table_title(os, suite.name, "heightfield_albedo",
                    support::format("%zu (ndf, alpha) x %zu mu, %d %sfields of %d^2 cells (correlation %g cells), "
                                    "%ld rays per field and mu, %ld walk paths, F = 1",
                                    run.items.size(), suite.mus.size(), suite.fields,
                                    suite.surface == HeightfieldSurfaceKind::grooves ? "V-groove " : "",
                                    suite.field_size, suite.correlation_length, suite.rays, suite.walk_paths),
                    run.threads);
  os << "  traced E, E_1, E_ms over the fields (se); per row the models within noise (sigmas sqrt(se^2 + var)), and "
        "each other's model - traced (z)\n";
  for (const AlbedoPoint& p : run.points) {
    os << support::format("  %-8s alpha %.2f mu %.4f (%4.1f deg): E %.4f(%.4f) E_1 %.4f(%.4f) E_ms %.4f(%.4f)\n",
                          analytic::ndf_name(p.ndf), p.alpha, p.mu,
                          std::acos(std::min(1.0, p.mu)) * 180.0 / std::numbers::pi, p.traced[0], p.traced_se[0],
                          p.traced[1], p.traced_se[1], p.traced[2], p.traced_se[2]);
    for (int r = 1; r < kAlbedoRows; ++r)
      os << support::format("    %-5s %s\n", kAlbedoRowNames[r], albedo_row_text(p, r).c_str());
  }
  std::size_t passed = 0;
  for (std::size_t i = 0; i < run.items.size(); ++i) {
    passed += run.item_pass[i];
    if (!run.item_pass[i])
      os << support::format("  %s alpha %.2f: FAIL (a ray lost or at the bounce limit, or a value not finite)\n",
                            analytic::ndf_name(suite.ndf_of(i)), suite.alpha_of(i));
  }
  print_table_close(os, passed, run.items.size(), run.wall_s, "(ndf, alpha) pass");
}

}  // namespace vgroove::validation
