// vgroove Python module: energy_lobe_shape, glass_energy and energy_audit, the library calls
// `vgroove energy --lobe-shape`, `vgroove energy --eta` and `vgroove energy --audit [--reference
// heightfield]` make (validation/energy_lobe_shape.h, validation/glass_energy.h,
// validation/energy_audit.h), returning their reports as dicts.
#include "common.h"

#include "vgroove/common/ndf_kind.h"
#include "vgroove/validation/energy_audit.h"
#include "vgroove/validation/energy_lobe_shape.h"
#include "vgroove/validation/energy_table.h"
#include "vgroove/validation/glass_energy.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/suite_kind.h"

#include <algorithm>
#include <limits>

#include <sstream>

namespace vgroove::python {

namespace {

py::object energy_lobe_shape(const std::string& ndf, const std::vector<double>& alpha,
                             const std::vector<double>& theta_i_deg, const py::object& rays, const py::object& grooves,
                             const py::object& seed, int theta_bins, int phi_bins, double sigmas, int threads,
                             bool verbose) {
  validation::LobeShapeOptions o;
  const auto k = ndf_from_name(ndf);
  if (!k || (*k != NdfKind::ggx && *k != NdfKind::beckmann))
    throw support::UserError("ndf = \"" + ndf + "\" is not one of \"ggx\", \"beckmann\" (the Smith walk needs Lambda)");
  o.ndf = *k;
  o.alpha = alpha;
  o.theta_i_deg = theta_i_deg;
  o.rays = static_cast<long>(to_count(rays, "rays", 1, validation::kMaxRays));
  o.grooves = static_cast<int>(to_count(grooves, "grooves", 1, validation::kMaxGrooves));
  o.seed = static_cast<std::uint64_t>(to_seed(seed, "seed"));
  o.theta_bins = theta_bins, o.phi_bins = phi_bins, o.sigmas = sigmas, o.threads = threads;
  validation::check_lobe_shape_options(o);
  const validation::LobeShapeResult r = run_interruptible([&](std::atomic<bool>& cancel) {
    o.cancel = &cancel;
    return validation::audit_lobe_shapes(o);
  });
  if (verbose) {
    std::ostringstream os;
    validation::print_lobe_shapes(os, r);
    py::print(os.str(), py::arg("end") = "");
  }
  return to_python(r.to_json());
}

py::object glass_energy(const std::vector<double>& eta, const std::vector<double>& alpha, const std::vector<double>& mu,
                        const std::vector<std::string>& ndfs, const std::vector<std::string>& dims,
                        const std::vector<std::string>& sides, const py::object& rays, const py::object& grooves,
                        const py::object& seed, int max_k, int threads, bool verbose, const std::string& reference,
                        const py::object& progress) {
  validation::GlassGrid g;
  validation::set_glass_axes(g, ndfs, dims, sides, "");
  g.reference = validation::glass_reference_from(reference, "");
  g.etas = eta, g.alphas = alpha, g.mus = mu;
  g.rays = to_count(rays, "rays", 1, validation::kMaxEnergyRays);
  g.grooves = static_cast<int>(to_count(grooves, "grooves", 1, validation::kMaxGlassGrooves));
  g.seed = static_cast<std::uint64_t>(to_seed(seed, "seed"));
  g.max_k = max_k;
  validation::check_threads(threads, "threads");
  validation::check_glass_grid(g, "");
  ProgressRelay relay(progress);
  const std::optional<validation::GlassTable> t = run_interruptible(
      [&](std::atomic<bool>& cancel) { return validation::run_glass_table(g, threads, relay.fn(), &cancel); }, false,
      &relay);
  if (!t) throw support::UserError("glass_energy: interrupted");
  const std::vector<validation::GlassCompensationRow> audit = validation::glass_compensation_audit(*t);
  if (verbose) {
    std::ostringstream os;
    validation::print_glass_table(os, *t, audit);
    py::print(os.str(), py::arg("end") = "");
  }
  return to_python(validation::glass_table_json(*t, audit));
}

// The ranges `vgroove energy` gives its flags (app/cmd_energy.cpp, add_integer), which the command
// line checks as it reads them, before the audit's own (narrower) ranges.
void check_flag_range(long long v, const std::string& name, long long hi, const std::string& note = "") {
  if (v < 1 || v > hi)
    throw support::UserError(name + " = " + std::to_string(v) + " is out of range [1, " + std::to_string(hi) + "]" +
                             note);
}

// `vgroove energy --audit [--reference heightfield]` (app/cmd_energy_tables.cpp, cmd_energy_audit):
// the same suite from the same arguments, checked in the same order with the same messages (the
// arguments' names for the flags, "energy_audit" for "--audit"; tests/python/test_energy_audit.py
// holds the two reports and messages equal); the report as a dict.
py::object energy_audit(const std::vector<std::string>& ndfs, const std::optional<std::vector<double>>& alpha,
                        const std::optional<std::vector<double>>& mu, int alpha_points, int mu_points,
                        const py::object& rays_obj, const py::object& seed_obj, int max_k,
                        const std::optional<std::string>& reference, int threads, bool verbose,
                        const py::object& progress) {
  using validation::kMaxAuditK, validation::kMaxAuditPaths;
  validation::check_threads(threads, "threads");
  const long long seed = to_seed(seed_obj, "seed");
  const long long rays =
      to_count(rays_obj, "rays", std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
  check_flag_range(rays, "rays", validation::kMaxEnergyRays);
  check_flag_range(max_k, "max_k", validation::kMaxEnergyK);
  check_flag_range(alpha_points, "alpha_points", validation::kMaxAlphaPoints,
                   " (the smallest midpoint 0.5/n stays >= 0.01)");
  check_flag_range(mu_points, "mu_points", validation::kMaxMuPoints,
                   " (the smallest midpoint 0.5/n stays >= cos 89.9 deg)");
  if (max_k < 1 || max_k > kMaxAuditK)
    throw support::UserError("max_k = " + std::to_string(max_k) + " is out of range [1, " + std::to_string(kMaxAuditK) +
                             "] with energy_audit");
  if (reference && *reference != "heightfield")
    throw support::UserError("reference = \"" + *reference +
                             "\" is not \"heightfield\" with energy_audit (the V-groove model and the Smith walk are "
                             "always audited; heightfield adds the random heightfields)");
  for (const std::string& n : ndfs)
    if (n != "ggx" && n != "beckmann")
      throw support::UserError("ndf = \"" + n +
                               "\" is not one of \"ggx\", \"beckmann\" (the audit's Smith walk needs Lambda in "
                               "closed form)");
  const nlohmann::json suite = validation::energy_audit_command_suite(
      ndfs, alpha ? *alpha : validation::midpoints(alpha_points), mu ? *mu : validation::midpoints(mu_points), rays,
      seed, max_k, reference.has_value());
  if (rays < 1 || rays > kMaxAuditPaths)
    throw support::UserError("rays = " + std::to_string(rays) + " is out of range [1, " +
                             std::to_string(kMaxAuditPaths) + "] (walk paths per cell with energy_audit)");
  const std::unique_ptr<validation::PlannedSuite> plan = validation::find_kind(suite).plan(suite, "energy_audit", {});
  // The command line's descriptor: the same job (its parts would merge with the command line's).
  const nlohmann::json descriptor = {{"command", "energy --audit"}, {"kind", "energy_audit"}, {"input", suite}};
  ProgressRelay relay(progress);
  const std::optional<validation::SuiteResult> r = run_interruptible(
      [&](std::atomic<bool>& cancel) {
        return plan->job(descriptor, &cancel)->run(threads, relay.fn(), &cancel, true);
      },
      false, &relay);
  if (!r) throw support::UserError("energy_audit: interrupted");
  if (verbose) py::print(r->table, py::arg("end") = "");
  return to_python(r->report);
}

}  // namespace

void bind_energy(py::module_& m) {
  m.def("energy_audit", &energy_audit, py::arg("ndf"), py::arg("alpha"), py::arg("mu"), py::arg("alpha_points"),
        py::arg("mu_points"), py::arg("rays"), py::arg("seed"), py::arg("max_k"), py::arg("reference"),
        py::arg("threads"), py::arg("verbose"), py::arg("progress") = py::none());
  // energy_audit's ranges beyond `ranges` (validation/ranges.h), for its docstring.
  py::dict audit_ranges;
  audit_ranges["max_alpha_points"] = validation::kMaxAlphaPoints;
  audit_ranges["max_mu_points"] = validation::kMaxMuPoints;
  audit_ranges["max_audit_paths"] = validation::kMaxAuditPaths;
  audit_ranges["max_audit_k"] = validation::kMaxAuditK;
  m.attr("audit_ranges") = audit_ranges;
  m.def("glass_energy", &glass_energy, py::arg("eta"), py::arg("alpha"), py::arg("mu"), py::arg("ndf"), py::arg("dim"),
        py::arg("side"), py::arg("rays"), py::arg("grooves"), py::arg("seed"), py::arg("max_k"), py::arg("threads"),
        py::arg("verbose"), py::arg("reference") = "vgroove", py::arg("progress") = py::none());
  m.def("energy_lobe_shape", &energy_lobe_shape, py::arg("ndf"), py::arg("alpha"), py::arg("theta_i_deg"),
        py::arg("rays"), py::arg("grooves"), py::arg("seed"), py::arg("theta_bins"), py::arg("phi_bins"),
        py::arg("sigmas"), py::arg("threads"), py::arg("verbose"));
}

}  // namespace vgroove::python
