// vgroove Python module vgroove._vgroove: the extension under the package vgroove (python/vgroove).
#include "common.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"

#include <cmath>
#include <complex>
#include <new>

namespace vgroove::python {

py::object to_python(const nlohmann::json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      // A report file holds "nan", "inf" or "-inf" where the report has a non-finite number
      // (support/json_text.h, docs/conventions.md): the dict holds the same strings.
      const double x = j.get<double>();
      return std::isfinite(x) ? py::object(py::float_(x)) : py::object(py::str(support::non_finite_text(x)));
    }
    case nlohmann::json::value_t::string:
      return py::str(j.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& e : j) l.append(to_python(e));
      return l;
    }
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = to_python(v);
      return d;
    }
    default:
      return py::none();
  }
}

NdfKind parse_ndf(const std::string& name) {
  if (const auto k = ndf_from_name(name)) return *k;
  throw support::UserError("ndf = \"" + name + "\" is not one of \"beckmann\", \"ggx\", \"phong\"");
}

analytic::BrdfModel parse_brdf_model(const std::string& name, bool all) {
  const auto m = analytic::brdf_model_from_name(name == "cook_torrance" ? "cook-torrance" : name);
  if (m && (all || *m == analytic::BrdfModel::vgroove || *m == analytic::BrdfModel::cook_torrance)) return *m;
  throw support::UserError("model = \"" + name + "\" is not one of \"vgroove\", " +
                           (all ? "\"vgroove-nonsymmetric\", " : "") + "\"cook-torrance\"" +
                           (all ? ", \"walter\"" : ""));
}

validation::SurfaceDim parse_dim(const std::string& name) {
  if (name == "3d") return validation::SurfaceDim::three_d;
  if (name == "flatland") return validation::SurfaceDim::flatland;
  throw support::UserError("dim = \"" + name + "\" is not one of \"3d\", \"flatland\"");
}

long long to_count(const py::handle& v, const std::string& what, long long lo, long long hi) {
  if (!py::isinstance<py::int_>(v) || py::isinstance<py::bool_>(v))
    throw support::UserError(what + " = " + py::repr(v).cast<std::string>() + " must be an integer");
  const py::int_ n = py::reinterpret_borrow<py::int_>(v);
  const bool in_range = n >= py::int_(lo) && n <= py::int_(hi);
  if (!in_range)
    throw support::UserError(what + " = " + py::repr(n).cast<std::string>() + " is out of range [" +
                             std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return n.cast<long long>();
}

long long to_seed(const py::handle& v, const std::string& what) {
  return to_count(v, what, 0, std::numeric_limits<long long>::max());
}

DoubleArray unit_directions(const DoubleArray& w, const char* what, bool flatland) {
  const std::size_t n = static_cast<std::size_t>(w.shape(0));
  const double* p = w.data();
  // A first pass without branches or square roots: |len - 1| < 0.999 kExactUnit for certain when
  // len^2 lies within these bounds. Only when some direction falls outside does the exact pass below
  // run (it names the first one that breaks the rule).
  constexpr double lo = (1.0 - 0.999 * kExactUnit) * (1.0 - 0.999 * kExactUnit);
  constexpr double hi = (1.0 + 0.999 * kExactUnit) * (1.0 + 0.999 * kExactUnit);
  bool inside = true;
  for (std::size_t j = 0; j < n; ++j) {
    const double x = p[3 * j], y = p[3 * j + 1], z = p[3 * j + 2], len2 = x * x + y * y + z * z;
    inside &= (len2 >= lo) & (len2 <= hi) & (!flatland | (std::abs(y) <= kUnitTolerance));
  }
  if (inside) return w;
  std::optional<DoubleArray> copy;
  for (std::size_t j = 0; j < n; ++j) {
    const double x = p[3 * j], y = p[3 * j + 1], z = p[3 * j + 2];
    const double len = std::sqrt(x * x + y * y + z * z);
    auto text = [&] {
      return std::string(what) + "[" + std::to_string(j) + "] = (" + support::number_text(x) + ", " +
             support::number_text(y) + ", " + support::number_text(z) + ")";
    };
    const std::string tolerance = support::number_text(kUnitTolerance);
    if (!(std::abs(len - 1.0) <= kUnitTolerance))
      throw support::UserError(text() + " is not a unit vector (|len - 1| <= " + tolerance + ")");
    if (flatland && !(std::abs(y) <= kUnitTolerance))
      throw support::UserError(text() + " is not in the plane y = 0 (|y| <= " + tolerance +
                               "; flatland directions: (-sin t, 0, cos t))");
    if (std::abs(len - 1.0) <= kExactUnit) continue;
    if (!copy) {
      copy.emplace(std::vector<py::ssize_t>{static_cast<py::ssize_t>(n), 3});
      std::copy(p, p + 3 * n, copy->mutable_data());
    }
    double* q = copy->mutable_data() + 3 * j;
    q[0] = x / len, q[1] = y / len, q[2] = z / len;
  }
  return copy ? *copy : w;
}

Rows rows_of(const DoubleArray& w, const char* what, std::size_t n, bool flatland) {
  const bool one = w.ndim() == 2 && w.shape(0) == 1;
  if (w.ndim() != 2 || w.shape(1) != 3 || (!one && static_cast<std::size_t>(w.shape(0)) != n))
    throw support::UserError(std::string(what) +
                             " must be an array of shape (1, 3) or (n, 3) with n = " + std::to_string(n));
  return Rows{unit_directions(w, what, flatland), one ? std::size_t{0} : std::size_t{3}};
}

analytic::FresnelFn Conductor::fn() const {
  const double e = eta, k = kappa;
  return [e, k](double cos_theta) { return optics::fresnel_conductor(cos_theta, e, k); };
}

Conductor conductor_of(const py::object& eta) {
  const std::complex<double> z = eta.cast<std::complex<double>>();
  using validation::kMaxFresnelEta, validation::kMaxFresnelKappa;
  if (!(z.real() > 0.0 && z.real() <= kMaxFresnelEta && z.imag() >= 0.0 && z.imag() <= kMaxFresnelKappa))
    throw support::UserError("eta = " + support::number_text(z.real()) + " + " + support::number_text(z.imag()) +
                             "j is out of range: real part in " +
                             support::interval_text(0, false, kMaxFresnelEta, true) + ", imaginary part (kappa) in " +
                             support::interval_text(0, true, kMaxFresnelKappa, true));
  return Conductor{z.real(), z.imag()};
}

void check_alpha(double alpha) {
  if (!(alpha >= validation::kMinAlpha && alpha <= validation::kMaxAlpha))
    throw support::UserError("alpha = " + support::number_text(alpha) + " is out of range " +
                             support::interval_text(validation::kMinAlpha, true, validation::kMaxAlpha, true));
}

}  // namespace vgroove::python

PYBIND11_MODULE(_vgroove, m) {
  namespace py = pybind11;
  using namespace vgroove::python;
  m.doc() = "vgroove's C++ core (sim, analytic, validation); use the package vgroove, not this module.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const vgroove::support::UserError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const std::bad_alloc&) {
      // What the command line says (app/cli.cpp), where an estimate let an allocation through.
      PyErr_SetString(PyExc_MemoryError,
                      "out of memory: the run needs more memory than this process may use (fewer rays, cases, "
                      "grooves, bins or threads need less)");
    }
  });
  m.attr("__version__") = vgroove::validation::version_string();
  m.attr("git_revision") = vgroove::validation::git_revision();
  // The ranges the module enforces (validation/ranges.h), for the package's docstrings (python/
  // vgroove/_ranges.py fills them in; tests/python/test_docs.py holds this table against ranges.h).
  namespace v = vgroove::validation;
  py::dict ranges;
  ranges["min_aperture_deg"] = v::kMinApertureDeg;
  ranges["max_theta_i_deg"] = v::kMaxThetaIDeg;
  ranges["max_surface_theta_i_deg"] = v::kMaxSurfaceThetaIDeg;
  ranges["min_alpha"] = v::kMinAlpha;
  ranges["max_alpha"] = v::kMaxAlpha;
  ranges["max_rays"] = v::kMaxRays;
  ranges["max_seed"] = v::kMaxSeed;
  ranges["max_grooves"] = v::kMaxGrooves;
  ranges["default_max_bounces"] = v::kDefaultMaxBounces;
  ranges["max_bounces"] = v::kMaxBounces;
  ranges["max_threads"] = v::kMaxThreads;
  ranges["max_flatland_k"] = v::kMaxFlatlandBrdfK;
  ranges["max_nonsymmetric_k"] = v::kMaxNonsymmetricBrdfK;
  ranges["min_histogram_k"] = v::kMinHistogramK;
  ranges["max_histogram_k"] = v::kMaxHistogramK;
  ranges["max_flatland_bins"] = v::kMaxFlatlandBins;
  ranges["max_theta_bins"] = v::kMaxThetaBins;
  ranges["max_phi_bins"] = v::kMaxPhiBins;
  ranges["max_sampler_k"] = v::kMaxSamplerK;
  ranges["max_fresnel_eta"] = v::kMaxFresnelEta;
  ranges["max_fresnel_kappa"] = v::kMaxFresnelKappa;
  ranges["min_glass_eta"] = v::kMinGlassEta;
  ranges["max_glass_eta"] = v::kMaxGlassEta;
  ranges["max_glass_grooves"] = v::kMaxGlassGrooves;
  ranges["min_mu"] = v::kMinMu;
  ranges["max_energy_rays"] = v::kMaxEnergyRays;
  ranges["max_energy_k"] = v::kMaxEnergyK;
  ranges["unit_tolerance"] = kUnitTolerance;
  m.attr("ranges") = ranges;
  // The command line's directions (`vgroove brdf --theta-i-deg ... --phi-i-deg ...`): dir3 of the
  // angles in radians, deg * (pi / 180), so that the same degrees give the same bits.
  m.def(
      "direction",
      [](DoubleArray theta_deg, DoubleArray phi_deg) {
        if (theta_deg.ndim() != 1 || phi_deg.ndim() != 1 || theta_deg.shape(0) != phi_deg.shape(0))
          throw vgroove::support::UserError("theta_deg and phi_deg must be arrays of shape (n,)");
        const auto n = theta_deg.shape(0);
        auto out = new_array<double>({n, 3});
        double* p = out.mutable_data();
        for (py::ssize_t j = 0; j < n; ++j) {
          const vgroove::analytic::Dir3 d =
              vgroove::analytic::dir3(vgroove::deg_to_rad(theta_deg.data()[j]), vgroove::deg_to_rad(phi_deg.data()[j]));
          p[3 * j] = d.x, p[3 * j + 1] = d.y, p[3 * j + 2] = d.z;
        }
        return out;
      },
      py::arg("theta_deg"), py::arg("phi_deg"));
  m.def("output_deg", py::vectorize([](double rad) { return vgroove::validation::output_deg(rad); }),
        "Radians to degrees rounded to 1e-9 deg, as every report and --json output prints them.");
  bind_grooves(m);
  bind_surfaces(m);
  bind_brdfs(m);
  bind_suites(m);
  bind_sampling(m);
  bind_energy(m);
}
