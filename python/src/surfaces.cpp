// vgroove Python module: procedural rough surfaces (sim/microsurface.h, sim/microsurface3d.h), the
// light traced in them tallied into the suites' histograms, and the model's lobes over the same
// bins (analytic/brdf_flatland.h, analytic/lobe_3d.h).
#include "common.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/spec_lists.h"

#include <memory>

namespace vgroove::python {

namespace {

using validation::SurfaceDim;

// A procedural surface: flatland or 3D, built once, traced at any number of incident angles.
struct Surface {
  SurfaceDim dim = SurfaceDim::three_d;
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;
  int grooves = 0;
  long long seed = 0;
  sim::Microsurface flat;
  sim::Microsurface3d three;
};

std::shared_ptr<Surface> microsurface(const std::string& ndf, double alpha, const py::object& grooves,
                                      const py::object& seed, const std::string& dim) {
  auto s = std::make_shared<Surface>();
  s->ndf = parse_ndf(ndf);
  check_alpha(alpha);
  s->alpha = alpha;
  s->grooves = static_cast<int>(to_count(grooves, "grooves", 1, 10'000'000));
  s->seed = to_seed(seed, "seed");
  s->dim = parse_dim(dim);
  run_interruptible(
      [&](std::atomic<bool>&) {
        if (s->dim == SurfaceDim::flatland) {
          sim::MicrosurfaceOptions o;
          o.ndf = s->ndf, o.alpha = alpha, o.grooves = s->grooves, o.seed = static_cast<std::uint64_t>(s->seed);
          s->flat = sim::make_microsurface(o);
        } else {
          sim::Microsurface3dOptions o;
          o.ndf = s->ndf, o.alpha = alpha, o.grooves = s->grooves, o.seed = static_cast<std::uint64_t>(s->seed);
          s->three = sim::make_microsurface3d(o);
        }
        return 0;
      },
      true);
  return s;
}

py::array_t<double> degrees_of(const std::vector<double>& rad) {
  py::array_t<double> a(static_cast<py::ssize_t>(rad.size()));
  for (std::size_t j = 0; j < rad.size(); ++j) a.mutable_data()[j] = rad[j] * kDegPerRad;
  return a;
}

template <class Tally>
void put_fates(py::dict& d, const Tally& t) {
  d["rays"] = t.rays, d["escaped"] = t.escaped, d["blocked"] = t.blocked, d["vertex_hit"] = t.vertex_hits;
  d["bounce_limit"] = t.bounce_limit, d["not_upward"] = t.not_upward, d["bounces"] = t.bounces;
  d["max_k_seen"] = t.max_k_seen;
}

// The chunks of the trace on `threads` threads, each into its own tally, merged in chunk order:
// the counts do not depend on the thread count.
template <class Tally, class Chunk>
Tally trace_chunks(std::int64_t chunks, int threads, Tally total, const Chunk& chunk, std::atomic<bool>& cancel) {
  std::vector<Tally> parts(static_cast<std::size_t>(chunks));
  const bool complete = support::parallel_for(
      parts.size(), support::resolve_threads(threads),
      [&](std::size_t c) { parts[c] = chunk(static_cast<std::int64_t>(c)); }, {}, &cancel, 1);
  if (!complete) return total;
  for (const Tally& p : parts) total.merge(p);
  return total;
}

py::dict trace_microsurface(const Surface& s, double theta_i_deg, const py::object& rays_obj,
                            const py::object& seed_obj, const std::string& sampling, int flatland_bins, int theta_bins,
                            int phi_bins, int max_k, const py::object& max_bounces, int threads) {
  const long long rays = to_count(rays_obj, "rays", 1, validation::kMaxRays);
  const long long seed = seed_obj.is_none() ? s.seed : to_seed(seed_obj, "seed");
  const int mb = static_cast<int>(to_count(max_bounces, "max_bounces", 1, 2147483647));
  validation::check_threads(threads, "threads");
  if (!(max_k >= 1 && max_k <= 10000))
    throw support::UserError("max_k = " + std::to_string(max_k) + " is out of range [1, 10000]");
  py::dict d;
  if (s.dim == SurfaceDim::flatland) {
    validation::check_theta_i(theta_i_deg, "theta_i_deg");
    if (!(flatland_bins >= 1 && flatland_bins <= 100000))
      throw support::UserError("flatland_bins = " + std::to_string(flatland_bins) + " is out of range [1, 100000]");
    sim::MicrosurfaceTraceOptions o;
    o.theta_i = theta_i_deg * kRadPerDeg, o.rays = rays, o.seed = static_cast<std::uint64_t>(seed);
    o.sampling = validation::parse_sampling(sampling, "sampling");
    o.theta_o_bins = flatland_bins, o.max_k = max_k, o.trace.max_bounces = mb;
    const sim::MicrosurfaceTally t = run_interruptible([&](std::atomic<bool>& cancel) {
      return trace_chunks(
          sim::chunk_count(o), threads, sim::MicrosurfaceTally(o.theta_o_bins, o.max_k),
          [&](std::int64_t c) { return sim::trace_microsurface_chunk(s.flat, o, c); }, cancel);
    });
    put_fates(d, t);
    const auto rows = static_cast<py::ssize_t>(max_k + 2), bins = static_cast<py::ssize_t>(flatland_bins);
    d["by_k"] = array_of(t.by_k, {rows});
    d["theta_o"] = array_of(t.theta_o, {bins});
    d["theta_o_by_k"] = array_of(t.theta_o_by_k, {rows, bins});
    return d;
  }
  if (!(std::isfinite(theta_i_deg) && theta_i_deg >= 0.0 && theta_i_deg < 90.0))
    throw support::UserError("theta_i_deg = " + support::number_text(theta_i_deg) +
                             " is out of range [0, 90) (3D: the light's polar angle; its azimuth is 180 deg)");
  if (sampling != "random")
    throw support::UserError("sampling = \"" + sampling + "\": 3D surfaces land their rays at random points only");
  if (!(theta_bins >= 1 && theta_bins <= 10000))
    throw support::UserError("theta_bins = " + std::to_string(theta_bins) + " is out of range [1, 10000]");
  if (!(phi_bins >= 2 && phi_bins <= 10000 && phi_bins % 2 == 0))
    throw support::UserError("phi_bins = " + std::to_string(phi_bins) + " is out of range [2, 10000], even");
  sim::Microsurface3dTraceOptions o;
  o.theta_i = theta_i_deg * kRadPerDeg, o.rays = rays, o.seed = static_cast<std::uint64_t>(seed);
  o.theta_bins = theta_bins, o.phi_bins = phi_bins, o.max_k = max_k, o.trace.max_bounces = mb;
  const sim::Microsurface3dTally t = run_interruptible([&](std::atomic<bool>& cancel) {
    return trace_chunks(
        sim::chunk_count(o), threads, sim::Microsurface3dTally(o.theta_bins, o.phi_bins, o.max_k),
        [&](std::int64_t c) { return sim::trace_microsurface3d_chunk(s.three, o, c); }, cancel);
  });
  put_fates(d, t);
  const auto rows = static_cast<py::ssize_t>(max_k + 2), tb = static_cast<py::ssize_t>(theta_bins),
             pb = static_cast<py::ssize_t>(phi_bins);
  d["by_k"] = array_of(t.by_k, {rows});
  d["hist"] = array_of(t.hist, {tb, pb});
  d["hist_by_k"] = array_of(t.hist_by_k, {rows, tb, pb});
  return d;
}

// The model's lobe over the suites' bins: fractions of the incident flux.
py::dict lobe(const std::string& model, const std::string& ndf_name, double alpha, double theta_i_deg,
              const std::string& dim_name, int flatland_bins, int theta_bins, int phi_bins, int max_k) {
  const NdfKind ndf = parse_ndf(ndf_name);
  check_alpha(alpha);
  const SurfaceDim dim = parse_dim(dim_name);
  if (model != "vgroove" && model != "cook_torrance")
    throw support::UserError("model = \"" + model + "\" is not one of \"vgroove\", \"cook_torrance\"");
  const bool ct = model == "cook_torrance";
  if (!(max_k >= 1 && max_k <= 10000))
    throw support::UserError("max_k = " + std::to_string(max_k) + " is out of range [1, 10000]");
  py::dict d;
  if (dim == SurfaceDim::flatland) {
    validation::check_theta_i(theta_i_deg, "theta_i_deg");
    if (!(flatland_bins >= 1 && flatland_bins <= 100000))
      throw support::UserError("flatland_bins = " + std::to_string(flatland_bins) + " is out of range [1, 100000]");
    const analytic::FlatlandLobe l = run_interruptible([&](std::atomic<bool>&) {
      const double ti = theta_i_deg * kRadPerDeg;
      return ct ? analytic::flatland_single_lobe(ndf, alpha, ti, flatland_bins)
                : analytic::flatland_lobe(ndf, alpha, ti, flatland_bins, max_k);
    });
    const auto rows = static_cast<py::ssize_t>(l.max_k + 2), bins = static_cast<py::ssize_t>(l.bins);
    d["by_k"] = array_of(l.by_k, {rows});
    d["theta_o"] = array_of(l.theta_o, {bins});
    d["theta_o_by_k"] = array_of(l.theta_o_by_k, {rows, bins});
    d["albedo"] = l.albedo;
    return d;
  }
  if (!(std::isfinite(theta_i_deg) && theta_i_deg >= 0.0 && theta_i_deg < 90.0))
    throw support::UserError("theta_i_deg = " + support::number_text(theta_i_deg) + " is out of range [0, 90)");
  if (!(theta_bins >= 1 && theta_bins <= 10000))
    throw support::UserError("theta_bins = " + std::to_string(theta_bins) + " is out of range [1, 10000]");
  if (!(phi_bins >= 2 && phi_bins <= 10000 && phi_bins % 2 == 0))
    throw support::UserError("phi_bins = " + std::to_string(phi_bins) + " is out of range [2, 10000], even");
  const analytic::Lobe3d l = run_interruptible([&](std::atomic<bool>&) {
    const double ti = theta_i_deg * kRadPerDeg;
    return ct ? analytic::cook_torrance_lobe_3d(ndf, alpha, ti, theta_bins, phi_bins)
              : analytic::vgroove_lobe_3d(ndf, alpha, ti, theta_bins, phi_bins, max_k);
  });
  const auto rows = static_cast<py::ssize_t>(l.max_k + 2), tb = static_cast<py::ssize_t>(theta_bins),
             pb = static_cast<py::ssize_t>(phi_bins);
  d["by_k"] = array_of(l.by_k, {rows});
  d["hist"] = array_of(l.hist, {tb, pb});
  d["hist_by_k"] = array_of(l.hist_by_k, {rows, tb, pb});
  d["albedo"] = l.albedo;
  return d;
}

}  // namespace

void bind_surfaces(py::module_& m) {
  py::class_<Surface, std::shared_ptr<Surface>>(m, "Microsurface")
      .def_property_readonly("dim", [](const Surface& s) { return validation::surface_dim_name(s.dim); })
      .def_property_readonly("ndf", [](const Surface& s) { return ndf_name(s.ndf); })
      .def_readonly("alpha", &Surface::alpha)
      .def_readonly("grooves", &Surface::grooves)
      .def_readonly("seed", &Surface::seed)
      .def_property_readonly(
          "theta_m_deg",
          [](const Surface& s) { return degrees_of(s.dim == SurfaceDim::flatland ? s.flat.theta_m : s.three.theta_m); })
      .def_property_readonly("phi_a_deg",
                             [](const Surface& s) -> py::object {
                               if (s.dim == SurfaceDim::flatland) return py::none();
                               return degrees_of(s.three.phi_a);
                             })
      .def("__repr__", [](const Surface& s) {
        return "vgroove.Microsurface(ndf=\"" + std::string(ndf_name(s.ndf)) +
               "\", alpha=" + support::number_text(s.alpha) + ", grooves=" + std::to_string(s.grooves) +
               ", seed=" + std::to_string(s.seed) + ", dim=\"" + validation::surface_dim_name(s.dim) + "\")";
      });
  m.def("microsurface", &microsurface, py::arg("ndf"), py::arg("alpha"), py::arg("grooves"), py::arg("seed"),
        py::arg("dim"));
  m.def("trace_microsurface", &trace_microsurface, py::arg("surface"), py::arg("theta_i_deg"), py::arg("rays"),
        py::arg("seed"), py::arg("sampling"), py::arg("flatland_bins"), py::arg("theta_bins"), py::arg("phi_bins"),
        py::arg("max_k"), py::arg("max_bounces"), py::arg("threads"));
  m.def("lobe", &lobe, py::arg("model"), py::arg("ndf"), py::arg("alpha"), py::arg("theta_i_deg"), py::arg("dim"),
        py::arg("flatland_bins"), py::arg("theta_bins"), py::arg("phi_bins"), py::arg("max_k"));
}

}  // namespace vgroove::python
