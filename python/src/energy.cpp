// vgroove Python module: energy_lobe_shape and glass_energy, the library calls `vgroove energy
// --lobe-shape` and `vgroove energy --eta` make (validation/energy_lobe_shape.h,
// validation/glass_energy.h), returning their reports as dicts.
#include "common.h"

#include "vgroove/common/ndf_kind.h"
#include "vgroove/validation/energy_lobe_shape.h"
#include "vgroove/validation/glass_energy.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/run_options.h"

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
  if (verbose) {
    std::ostringstream os;
    validation::print_glass_table(os, *t);
    py::print(os.str(), py::arg("end") = "");
  }
  return to_python(validation::glass_table_json(*t));
}

}  // namespace

void bind_energy(py::module_& m) {
  m.def("glass_energy", &glass_energy, py::arg("eta"), py::arg("alpha"), py::arg("mu"), py::arg("ndf"), py::arg("dim"),
        py::arg("side"), py::arg("rays"), py::arg("grooves"), py::arg("seed"), py::arg("max_k"), py::arg("threads"),
        py::arg("verbose"), py::arg("reference") = "vgroove", py::arg("progress") = py::none());
  m.def("energy_lobe_shape", &energy_lobe_shape, py::arg("ndf"), py::arg("alpha"), py::arg("theta_i_deg"),
        py::arg("rays"), py::arg("grooves"), py::arg("seed"), py::arg("theta_bins"), py::arg("phi_bins"),
        py::arg("sigmas"), py::arg("threads"), py::arg("verbose"));
}

}  // namespace vgroove::python
