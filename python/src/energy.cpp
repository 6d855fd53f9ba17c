// vgroove Python module: energy_lobe_shape, the library call `vgroove energy --lobe-shape` makes
// (validation/energy_lobe_shape.h), returning its report as a dict.
#include "common.h"

#include "vgroove/common/ndf_kind.h"
#include "vgroove/validation/energy_lobe_shape.h"
#include "vgroove/validation/ranges.h"

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

}  // namespace

void bind_energy(py::module_& m) {
  m.def("energy_lobe_shape", &energy_lobe_shape, py::arg("ndf"), py::arg("alpha"), py::arg("theta_i_deg"),
        py::arg("rays"), py::arg("grooves"), py::arg("seed"), py::arg("theta_bins"), py::arg("phi_bins"),
        py::arg("sigmas"), py::arg("threads"), py::arg("verbose"));
}

}  // namespace vgroove::python
