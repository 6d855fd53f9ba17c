// vgroove Python module vgroove._vgroove: the extension under the package vgroove (python/vgroove).
#include "common.h"

#include "vgroove/common/angles.h"
#include "vgroove/support/json_text.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"

#include <cmath>
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

analytic::BrdfModel parse_brdf_model(const std::string& name, bool nonsymmetric) {
  const auto m = analytic::brdf_model_from_name(name == "cook_torrance" ? "cook-torrance" : name);
  if (m && (nonsymmetric || *m != analytic::BrdfModel::vgroove_nonsymmetric)) return *m;
  throw support::UserError("model = \"" + name + "\" is not one of \"vgroove\", " +
                           (nonsymmetric ? "\"vgroove-nonsymmetric\", " : "") + "\"cook-torrance\"");
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
  // The ranges the module enforces (validation/ranges.h), for the package's docstrings.
  py::dict ranges;
  ranges["min_aperture_deg"] = vgroove::validation::kMinApertureDeg;
  ranges["max_theta_i_deg"] = vgroove::validation::kMaxThetaIDeg;
  ranges["min_alpha"] = vgroove::validation::kMinAlpha;
  ranges["max_alpha"] = vgroove::validation::kMaxAlpha;
  ranges["max_surface_theta_i_deg"] = vgroove::validation::kMaxSurfaceThetaIDeg;
  ranges["unit_tolerance"] = kUnitTolerance;
  m.attr("ranges") = ranges;
  m.def("output_deg", py::vectorize([](double rad) { return vgroove::validation::output_deg(rad); }),
        "Radians to degrees rounded to 1e-9 deg, as every report and --json output prints them.");
  bind_grooves(m);
  bind_surfaces(m);
  bind_brdfs(m);
  bind_suites(m);
  bind_sampling(m);
}
