// vgroove Python module: procedural rough surfaces (sim/microsurface.h, sim/microsurface3d.h), the
// light traced in them tallied into the suites' histograms, and the model's lobes over the same
// bins (analytic/brdf_flatland.h, analytic/lobe_3d.h).
#include "common.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/memory.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/spec_lists.h"

#include <memory>
#include <mutex>
#include <optional>

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
  // The facet angles and groove azimuths in degrees, made on first access and then shared by the
  // read-only views returned (the surface is immutable).
  std::vector<double> theta_m_deg, phi_a_deg;
};

std::shared_ptr<Surface> microsurface(const std::string& ndf, double alpha, const py::object& grooves,
                                      const py::object& seed, const std::string& dim) {
  auto s = std::make_shared<Surface>();
  s->ndf = parse_ndf(ndf);
  check_alpha(alpha);
  s->alpha = alpha;
  s->grooves = static_cast<int>(to_count(grooves, "grooves", 1, validation::kMaxGrooves));
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

// A read-only view of `deg` (filled from `rad` on first access), kept alive by the surface `self`.
py::array_t<double> degrees_view(const py::object& self, std::vector<double>& deg, const std::vector<double>& rad) {
  if (deg.size() != rad.size()) {
    deg.resize(rad.size());
    for (std::size_t j = 0; j < rad.size(); ++j) deg[j] = rad[j] * kDegPerRad;
  }
  py::array_t<double> a({static_cast<py::ssize_t>(deg.size())}, {static_cast<py::ssize_t>(sizeof(double))}, deg.data(),
                        self);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

template <class Tally>
void put_fates(py::dict& d, const Tally& t) {
  d["rays"] = t.rays, d["escaped"] = t.escaped, d["blocked"] = t.blocked, d["vertex_hit"] = t.vertex_hits;
  d["bounce_limit"] = t.bounce_limit, d["not_upward"] = t.not_upward, d["bounces"] = t.bounces;
  d["max_k_seen"] = t.max_k_seen;
}

// The chunks of the trace on `workers` threads. Each chunk's tally is added to a sum taken from a
// pool (or a new one when every sum is in use) and returned to it, so that at most 2 x workers
// tallies are held at once, whatever the number of rays; the sums are merged at the end. The counts
// are integers: they do not depend on which chunks met in which sum, nor on the thread count.
template <class Tally, class Chunk>
Tally trace_chunks(std::int64_t chunks, int workers, Tally total, const Chunk& chunk, std::atomic<bool>& cancel,
                   const support::ProgressFn& progress) {
  std::mutex mu;
  std::vector<Tally> pool;
  const bool complete = support::parallel_for(
      static_cast<std::size_t>(chunks), workers,
      [&](std::size_t c) {
        Tally t = chunk(static_cast<std::int64_t>(c));
        std::optional<Tally> sum;
        {
          std::lock_guard<std::mutex> lock(mu);
          if (!pool.empty()) sum.emplace(std::move(pool.back())), pool.pop_back();
        }
        if (sum) sum->merge(t), t = std::move(*sum);
        std::lock_guard<std::mutex> lock(mu);
        pool.push_back(std::move(t));
      },
      progress, &cancel, 1);
  if (!complete) return total;
  for (const Tally& p : pool) total.merge(p);
  return total;
}

// The histogram's cells as the message names them: "theta_bins x phi_bins x (max_k + 2) = 30 x 24 x 18 = 12960".
std::string cells_text(bool flat, int flatland_bins, int theta_bins, int phi_bins, int max_k) {
  const long long rows = max_k + 2LL;
  if (flat)
    return "flatland_bins x (max_k + 2) = " + std::to_string(flatland_bins) + " x " + std::to_string(rows) + " = " +
           std::to_string(flatland_bins * rows);
  return "theta_bins x phi_bins x (max_k + 2) = " + std::to_string(theta_bins) + " x " + std::to_string(phi_bins) +
         " x " + std::to_string(rows) + " = " + std::to_string(static_cast<long long>(theta_bins) * phi_bins * rows);
}

// The bytes of one histogram (cells per k, the bins summed over k, the rows) of 8-byte numbers.
double histogram_bytes(bool flat, int flatland_bins, int theta_bins, int phi_bins, int max_k) {
  const double bins = flat ? flatland_bins : static_cast<double>(theta_bins) * phi_bins, rows = max_k + 2.0;
  return 8.0 * (bins * rows + bins + rows);
}

// The bins and max_k of a lobe or tally: the ranges of the "brdf" suites (validation/ranges.h,
// lobe_bins.h) without their bound on the cells, which the memory check replaces here.
// A rough surface's light: the suites' [0, 89.9] (validation::kMaxSurfaceThetaIDeg), in flatland
// signed, [-89.9, 89.9] (the mirror image), as `/theta_i_deg/0 = 89.95 is out of range [0, 89.9]`.
void check_surface_theta_i(double deg, bool flat) {
  if (std::isnan(deg)) throw support::UserError("theta_i_deg = \"nan\" is not a number");
  const double hi = validation::kMaxSurfaceThetaIDeg, lo = flat ? -hi : 0.0;
  if (!(deg >= lo && deg <= hi))
    throw support::UserError("theta_i_deg = " + support::number_text(deg) + " is out of range " +
                             support::interval_text(lo, true, hi, true));
}

void check_bins(bool flat, int flatland_bins, int theta_bins, int phi_bins, int max_k) {
  using namespace validation;
  if (!(max_k >= kMinHistogramK && max_k <= kMaxHistogramK))
    throw support::UserError("max_k = " + std::to_string(max_k) + " is out of range [" +
                             std::to_string(kMinHistogramK) + ", " + std::to_string(kMaxHistogramK) + "]");
  if (flat) {
    if (!(flatland_bins >= 1 && flatland_bins <= kMaxFlatlandBins))
      throw support::UserError("flatland_bins = " + std::to_string(flatland_bins) + " is out of range [1, " +
                               std::to_string(kMaxFlatlandBins) + "]");
    return;
  }
  if (!(theta_bins >= 1 && theta_bins <= kMaxThetaBins))
    throw support::UserError("theta_bins = " + std::to_string(theta_bins) + " is out of range [1, " +
                             std::to_string(kMaxThetaBins) + "]");
  if (!(phi_bins >= 2 && phi_bins <= kMaxPhiBins && phi_bins % 2 == 0))
    throw support::UserError("phi_bins = " + std::to_string(phi_bins) + " is out of range [2, " +
                             std::to_string(kMaxPhiBins) + "], even");
}

py::dict trace_microsurface(const Surface& s, double theta_i_deg, const py::object& rays_obj,
                            const py::object& seed_obj, const std::string& sampling, int flatland_bins, int theta_bins,
                            int phi_bins, int max_k, const py::object& max_bounces, int threads,
                            const py::object& progress) {
  const long long rays = to_count(rays_obj, "rays", 1, validation::kMaxRays);
  const long long seed = seed_obj.is_none() ? s.seed : to_seed(seed_obj, "seed");
  const int mb = static_cast<int>(to_count(max_bounces, "max_bounces", 1, validation::kMaxBounces));
  validation::check_threads(threads, "threads");
  const bool flat = s.dim == SurfaceDim::flatland;
  check_bins(flat, flatland_bins, theta_bins, phi_bins, max_k);
  ProgressRelay relay(progress);  // counts rays (by chunks)
  auto ray_progress = [&](std::int64_t chunks) {
    return relay.fn(static_cast<std::size_t>((rays + chunks - 1) / std::max<std::int64_t>(chunks, 1)),
                    static_cast<std::size_t>(rays));
  };
  py::dict d;
  // The tallies held at once (trace_chunks), checked against the memory this process may use.
  auto check_memory = [&](std::int64_t chunks) {
    const int workers = static_cast<int>(std::min<std::int64_t>(support::resolve_threads(threads), chunks));
    const int tallies = 2 * workers + 1;
    support::check_memory(tallies * histogram_bytes(flat, flatland_bins, theta_bins, phi_bins, max_k),
                          "trace_microsurface",
                          std::to_string(tallies) + " tallies (2 per thread and their sum) of " +
                              cells_text(flat, flatland_bins, theta_bins, phi_bins, max_k) + " histogram cells");
    return workers;
  };
  if (flat) {
    check_surface_theta_i(theta_i_deg, true);
    sim::MicrosurfaceTraceOptions o;
    o.theta_i = theta_i_deg * kRadPerDeg, o.rays = rays, o.seed = static_cast<std::uint64_t>(seed);
    o.sampling = validation::parse_sampling(sampling, "sampling");
    o.theta_o_bins = flatland_bins, o.max_k = max_k, o.trace.max_bounces = mb;
    const std::int64_t chunks = sim::chunk_count(o);
    const int workers = check_memory(chunks);
    sim::MicrosurfaceTally t = run_interruptible(
        [&](std::atomic<bool>& cancel) {
          return trace_chunks(
              chunks, workers, sim::MicrosurfaceTally(o.theta_o_bins, o.max_k),
              [&](std::int64_t c) { return sim::trace_microsurface_chunk(s.flat, o, c); }, cancel,
              ray_progress(chunks));
        },
        false, &relay);
    put_fates(d, t);
    const auto rows = static_cast<py::ssize_t>(max_k + 2), bins = static_cast<py::ssize_t>(flatland_bins);
    d["by_k"] = array_from(std::move(t.by_k), {rows});
    d["theta_o"] = array_from(std::move(t.theta_o), {bins});
    d["theta_o_by_k"] = array_from(std::move(t.theta_o_by_k), {rows, bins});
    return d;
  }
  check_surface_theta_i(theta_i_deg, false);
  if (sampling != "random")
    throw support::UserError("sampling = \"" + sampling + "\": 3D surfaces land their rays at random points only");
  sim::Microsurface3dTraceOptions o;
  o.theta_i = theta_i_deg * kRadPerDeg, o.rays = rays, o.seed = static_cast<std::uint64_t>(seed);
  o.theta_bins = theta_bins, o.phi_bins = phi_bins, o.max_k = max_k, o.trace.max_bounces = mb;
  const std::int64_t chunks = sim::chunk_count(o);
  const int workers = check_memory(chunks);
  sim::Microsurface3dTally t = run_interruptible(
      [&](std::atomic<bool>& cancel) {
        return trace_chunks(
            chunks, workers, sim::Microsurface3dTally(o.theta_bins, o.phi_bins, o.max_k),
            [&](std::int64_t c) { return sim::trace_microsurface3d_chunk(s.three, o, c); }, cancel,
            ray_progress(chunks));
      },
      false, &relay);
  put_fates(d, t);
  const auto rows = static_cast<py::ssize_t>(max_k + 2), tb = static_cast<py::ssize_t>(theta_bins),
             pb = static_cast<py::ssize_t>(phi_bins);
  d["by_k"] = array_from(std::move(t.by_k), {rows});
  d["hist"] = array_from(std::move(t.hist), {tb, pb});
  d["hist_by_k"] = array_from(std::move(t.hist_by_k), {rows, tb, pb});
  return d;
}

// The model's lobe over the suites' bins: fractions of the incident flux. Ctrl-C stops it between
// quadrature nodes (a 200 x 200-bin 3D lobe takes ~9 s, 10^5 flatland bins at max_k 1000 ~14 s).
// Progress: its start (0 of 1) and its end (1 of 1); the lobe's loops report nothing finer.
py::dict lobe(const std::string& model_name, const std::string& ndf_name, double alpha, double theta_i_deg,
              const std::string& dim_name, int flatland_bins, int theta_bins, int phi_bins, int max_k,
              const py::object& progress) {
  const NdfKind ndf = parse_ndf(ndf_name);
  check_alpha(alpha);
  const SurfaceDim dim = parse_dim(dim_name);
  const bool ct = parse_brdf_model(model_name, false) == analytic::BrdfModel::cook_torrance;
  const bool flat = dim == SurfaceDim::flatland;
  check_bins(flat, flatland_bins, theta_bins, phi_bins, max_k);
  check_surface_theta_i(theta_i_deg, flat);
  // Cook-Torrance is the vgroove lobe's k = 1 row (below): that lobe needs max_k >= 1.
  const int lobe_k = ct ? std::max(max_k, 1) : max_k;
  // What the lobe holds at once: its histogram (3D: twice, the high-k bands' accumulator beside
  // it, analytic/lobe_3d.cpp), and Cook-Torrance's three rows beside it.
  const double one = histogram_bytes(flat, flatland_bins, theta_bins, phi_bins, lobe_k);
  const double ct_rows = ct ? histogram_bytes(flat, flatland_bins, theta_bins, phi_bins, 1) : 0.0;
  support::check_memory((flat ? 1.0 : 2.0) * one + ct_rows, "lobe",
                        cells_text(flat, flatland_bins, theta_bins, phi_bins, lobe_k) + " histogram cells");
  const double ti = theta_i_deg * kRadPerDeg;
  ProgressRelay relay(progress);
  relay.set(0, 1);
  relay.flush();
  py::dict d;
  if (flat) {
    analytic::FlatlandLobe l = run_interruptible(
        [&](std::atomic<bool>& cancel) {
          analytic::FlatlandLobeOptions opt;
          opt.cancel = &cancel;
          analytic::FlatlandLobe r = ct ? analytic::flatland_single_lobe(ndf, alpha, ti, flatland_bins)
                                        : analytic::flatland_lobe(ndf, alpha, ti, flatland_bins, max_k, opt);
          relay.set(1, 1);
          return r;
        },
        false, &relay);
    const auto rows = static_cast<py::ssize_t>(l.max_k + 2), bins = static_cast<py::ssize_t>(l.bins);
    d["by_k"] = array_from(std::move(l.by_k), {rows});
    d["theta_o"] = array_from(std::move(l.theta_o), {bins});
    d["theta_o_by_k"] = array_from(std::move(l.theta_o_by_k), {rows, bins});
    d["albedo"] = l.albedo;
    return d;
  }
  analytic::Lobe3d l = run_interruptible(
      [&](std::atomic<bool>& cancel) {
        analytic::Lobe3dOptions opt;
        opt.cancel = &cancel;
        // Cook-Torrance (V-cavity G) is the vgroove lobe's k = 1 row (Eq. 25), as the "brdf" suites take it.
        analytic::Lobe3d v = analytic::vgroove_lobe_3d(ndf, alpha, ti, theta_bins, phi_bins, lobe_k, opt);
        relay.set(1, 1);
        if (ct) return analytic::cook_torrance_lobe_3d_from(v);
        return v;
      },
      false, &relay);
  const auto rows = static_cast<py::ssize_t>(l.max_k + 2), tb = static_cast<py::ssize_t>(theta_bins),
             pb = static_cast<py::ssize_t>(phi_bins);
  d["by_k"] = array_from(std::move(l.by_k), {rows});
  d["hist"] = array_from(std::move(l.hist), {tb, pb});
  d["hist_by_k"] = array_from(std::move(l.hist_by_k), {rows, tb, pb});
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
      .def_property_readonly("theta_m_deg",
                             [](const py::object& self) {
                               Surface& s = self.cast<Surface&>();
                               return degrees_view(self, s.theta_m_deg,
                                                   s.dim == SurfaceDim::flatland ? s.flat.theta_m : s.three.theta_m);
                             })
      .def_property_readonly("phi_a_deg",
                             [](const py::object& self) -> py::object {
                               Surface& s = self.cast<Surface&>();
                               if (s.dim == SurfaceDim::flatland) return py::none();
                               return degrees_view(self, s.phi_a_deg, s.three.phi_a);
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
        py::arg("max_k"), py::arg("max_bounces"), py::arg("threads"), py::arg("progress") = py::none());
  m.def("lobe", &lobe, py::arg("model"), py::arg("ndf"), py::arg("alpha"), py::arg("theta_i_deg"), py::arg("dim"),
        py::arg("flatland_bins"), py::arg("theta_bins"), py::arg("phi_bins"), py::arg("max_k"),
        py::arg("progress") = py::none());
}

}  // namespace vgroove::python
