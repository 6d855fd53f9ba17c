// vgroove Python module: BRDFs over arrays of directions (vgroove's Eq. 16-17 and Cook-Torrance,
// 3D and flatland) and check_brdf: a BRDF of the user's, a vectorized Python callable, held
// against the exact simulation (validation/check_brdf.h), a batch of directions per call.
#include "common.h"

#include "vgroove/validation/spec_lists.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/brdf_model.h"
#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/check_brdf.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/run_options.h"

#include <cmath>
#include <limits>
#include <mutex>

namespace vgroove::python {

namespace {

using validation::SurfaceDim;

using analytic::BrdfModel;

// The sums that cost O(max_k^2) and their largest max_k: `vgroove brdf`'s (validation/ranges.h;
// test_surfaces.py holds the two messages equal).
constexpr int kFlatlandMaxK = validation::kMaxFlatlandBrdfK;
constexpr int kNonsymmetricMaxK = validation::kMaxNonsymmetricBrdfK;

// max_k checked as `vgroove brdf --max-k` is: [1, 2^31 - 1], the O(max_k^2) sums bounded.
int brdf_orders(long long max_k, BrdfModel model, bool flat) {
  if (max_k < 1 || max_k > std::numeric_limits<int>::max())
    throw support::UserError("max_k = " + std::to_string(max_k) + " is out of range [1, " +
                             std::to_string(std::numeric_limits<int>::max()) + "]");
  if (model == BrdfModel::vgroove_nonsymmetric && max_k > kNonsymmetricMaxK)
    throw support::UserError("max_k = " + std::to_string(max_k) + " is out of range [1, " +
                             std::to_string(kNonsymmetricMaxK) +
                             "] with model vgroove-nonsymmetric (the sum costs O(max_k^2))");
  if (flat && model == BrdfModel::vgroove && max_k > kFlatlandMaxK)
    throw support::UserError("max_k = " + std::to_string(max_k) + " is out of range [1, " +
                             std::to_string(kFlatlandMaxK) + "] with dim flatland (the flatland sum costs O(max_k^2))");
  return static_cast<int>(max_k);
}

// Eq. (20)'s partner law exists for Phong below alpha = sqrt(2) only (ERRATA E-NS1): the command
// line's refusal.
void check_partner_law(BrdfModel model, NdfKind ndf, double alpha) {
  if (model == BrdfModel::vgroove_nonsymmetric && !analytic::partner_law_exists(ndf, alpha))
    throw support::UserError("alpha = " + support::number_text(alpha) + " is out of range " +
                             support::interval_text(0, false, std::sqrt(2.0), false) +
                             " with model vgroove-nonsymmetric ndf phong (Eq. 20's partner law needs alpha < "
                             "sqrt(2))");
}

// The cost of one direction relative to the 3D sum (which costs the same for any max_k): the
// flatland and nonsymmetric sums grow as max_k^2 (about 0.4 s per direction at max_k 4096).
double relative_cost(BrdfModel model, bool flat, int max_k) {
  if (model == BrdfModel::cook_torrance || (model == BrdfModel::vgroove && !flat)) return 1.0;
  return std::max(1.0, static_cast<double>(max_k) * max_k / 256.0);
}

// f(wi_j, wo_j) for j < n into out (per_k: out[j * max_k + k - 1] for k = 1..max_k). The cancel
// flag is read before each direction (one may take 0.4 s), so a chunk stops within one of them.
void evaluate(BrdfModel model, NdfKind ndf, double alpha, SurfaceDim dim, bool per_k, int max_k, const double* wi,
              const double* wo, std::size_t n, double* out, int threads, std::atomic<bool>& cancel) {
  const std::size_t chunk = 4096;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  const bool cheap = relative_cost(model, dim == SurfaceDim::flatland, max_k) == 1.0;
  analytic::BrdfEvalOptions opt;
  opt.ndf = ndf, opt.alpha = alpha, opt.flatland = dim == SurfaceDim::flatland, opt.max_k = max_k;
  opt.per_k = per_k ? max_k : 0;
  support::parallel_for(
      chunks, support::resolve_threads(threads),
      [&](std::size_t c) {
        const std::size_t end = std::min(n, (c + 1) * chunk);
        for (std::size_t j = c * chunk; j < end; ++j) {
          if (!cheap && cancel.load(std::memory_order_relaxed)) return;
          const double* a = wi + 3 * j;
          const double* b = wo + 3 * j;
          const analytic::Dir3 i{a[0], a[1], a[2]}, o{b[0], b[1], b[2]};
          if (model == BrdfModel::vgroove_nonsymmetric) {
            // Eq. 21-23 with the independent partner law of Eq. 20 (analytic/brdf_model.h).
            const analytic::BrdfValue v = analytic::evaluate_brdf(model, i, o, opt);
            if (per_k)
              std::copy(v.by_k.begin(), v.by_k.end(), out + j * static_cast<std::size_t>(max_k));
            else
              out[j] = v.value;
            continue;
          }
          if (dim == SurfaceDim::flatland) {
            const double ti = flat_angle(a), to = flat_angle(b);
            if (model == BrdfModel::cook_torrance) {
              out[j] = analytic::flatland_brdf_single(ndf, alpha, ti, to);
            } else if (per_k) {
              for (int k = 1; k <= max_k; ++k)
                out[j * static_cast<std::size_t>(max_k) + static_cast<std::size_t>(k - 1)] =
                    analytic::flatland_brdf_k(ndf, alpha, ti, to, k);
            } else {
              out[j] = analytic::flatland_brdf(ndf, alpha, ti, to, max_k);
            }
            continue;
          }
          if (model == BrdfModel::cook_torrance) {
            out[j] = analytic::cook_torrance(i, o, ndf, alpha);
          } else if (per_k) {
            for (int k = 1; k <= max_k; ++k)
              out[j * static_cast<std::size_t>(max_k) + static_cast<std::size_t>(k - 1)] =
                  analytic::vgroove_brdf_k(i, o, k, ndf, alpha);
          } else {
            out[j] = analytic::vgroove_brdf(i, o, ndf, alpha, max_k);
          }
        }
      },
      {}, &cancel, 1);
}

py::array_t<double> brdf(const std::string& model_name, const std::string& ndf_name, double alpha, DoubleArray wi,
                         DoubleArray wo, bool per_k, long long max_k_in, const std::string& dim_name, int threads) {
  const BrdfModel model = parse_brdf_model(model_name, true);
  const NdfKind ndf = parse_ndf(ndf_name);
  check_alpha(alpha);
  const SurfaceDim dim = parse_dim(dim_name);
  const bool flat = dim == SurfaceDim::flatland;
  check_partner_law(model, ndf, alpha);
  const int max_k = brdf_orders(max_k_in, model, flat);
  validation::check_threads(threads, "threads");
  if (wi.ndim() != 2 || wi.shape(1) != 3 || wo.ndim() != 2 || wo.shape(1) != 3 || wi.shape(0) != wo.shape(0))
    throw support::UserError("wi and wo must be arrays of shape (n, 3)");
  const std::size_t n = static_cast<std::size_t>(wi.shape(0));
  wi = unit_directions(wi, "wi", flat);
  wo = unit_directions(wo, "wo", flat);
  const int k_out = per_k ? (model == BrdfModel::cook_torrance ? 1 : max_k) : 1;
  if (per_k && static_cast<double>(n) * k_out > 1e9)
    throw support::UserError("per_k with max_k = " + std::to_string(max_k) + " over " + std::to_string(n) +
                             " directions needs more than 10^9 values");
  py::array_t<double> out = per_k ? new_array<double>({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(k_out)})
                                  : new_array<double>({static_cast<py::ssize_t>(n)});
  double* po = out.mutable_data();
  const double *pi = wi.data(), *pw = wo.data();
  run_interruptible(
      [&](std::atomic<bool>& cancel) {
        evaluate(model, ndf, alpha, dim, per_k && model != BrdfModel::cook_torrance, max_k, pi, pw, n, po, threads,
                 cancel);
        return 0;
      },
      static_cast<double>(n) * relative_cost(model, flat, max_k) < 2048.0);
  return out;
}

validation::CheckBrdfOptions check_options(const std::string& name, const std::string& ndf, double alpha,
                                           const std::vector<double>& theta_i_deg, const py::object& rays,
                                           const std::string& dim, const py::object& grooves, const py::object& seed,
                                           int theta_bins, int phi_bins, int flatland_bins, double sigmas,
                                           double model_tolerance, int quadrature_order, int threads) {
  validation::CheckBrdfOptions o;
  o.name = name;
  o.ndf = parse_ndf(ndf);
  o.alpha = alpha;
  o.theta_i_deg = theta_i_deg;
  o.rays = static_cast<long>(to_count(rays, "rays", 1, validation::kMaxRays));
  o.dim = parse_dim(dim);
  o.grooves = static_cast<int>(to_count(grooves, "grooves", 1, 10'000'000));
  o.seed = static_cast<std::uint64_t>(to_seed(seed, "seed"));
  o.theta_bins = theta_bins, o.phi_bins = phi_bins, o.flatland_bins = flatland_bins;
  o.sigmas = sigmas, o.model_tolerance = model_tolerance, o.quadrature_order = quadrature_order;
  o.threads = threads;
  validation::check_options(o);
  return o;
}

// f: a Python callable f(wi, wo) -> values, wi and wo float arrays of shape (n, 3); or the name
// of a built-in model (parse_brdf_model), evaluated in C++ one direction at a time.
py::object check_brdf(const py::object& f, long long max_k, const std::string& name, const std::string& ndf,
                      double alpha, const std::vector<double>& theta_i_deg, const py::object& rays,
                      const std::string& dim, const py::object& grooves, const py::object& seed, int theta_bins,
                      int phi_bins, int flatland_bins, double sigmas, double model_tolerance, int quadrature_order,
                      int threads) {
  validation::CheckBrdfOptions o =
      check_options(name, ndf, alpha, theta_i_deg, rays, dim, grooves, seed, theta_bins, phi_bins, flatland_bins,
                    sigmas, model_tolerance, quadrature_order, threads);
  if (py::isinstance<py::str>(f)) {
    const BrdfModel model = parse_brdf_model(f.cast<std::string>(), true);
    const bool flat = o.dim == SurfaceDim::flatland;
    check_partner_law(model, o.ndf, o.alpha);
    analytic::BrdfEvalOptions eval;
    eval.ndf = o.ndf, eval.alpha = alpha, eval.flatland = flat, eval.max_k = brdf_orders(max_k, model, flat);
    const NdfKind kind = o.ndf;
    const int mk = eval.max_k;
    const validation::BrdfFn fn = [=](const analytic::Dir3& i, const analytic::Dir3& w) {
      if (model == BrdfModel::vgroove_nonsymmetric) return analytic::evaluate_brdf(model, i, w, eval).value;
      if (flat) {
        const double ti = std::atan2(-i.x, i.z), to = std::atan2(-w.x, w.z);
        return model == BrdfModel::cook_torrance ? analytic::flatland_brdf_single(kind, alpha, ti, to)
                                                 : analytic::flatland_brdf(kind, alpha, ti, to, mk);
      }
      return model == BrdfModel::cook_torrance ? analytic::cook_torrance(i, w, kind, alpha)
                                               : analytic::vgroove_brdf(i, w, kind, alpha, mk);
    };
    const validation::CheckBrdfResult r = run_interruptible([&](std::atomic<bool>& cancel) {
      o.cancel = &cancel;
      return validation::check_brdf(fn, o);
    });
    return to_python(r.to_json());
  }
  if (!PyCallable_Check(f.ptr()))
    throw support::UserError("f = " + py::repr(f).cast<std::string>() +
                             " must be a callable f(wi, wo) -> values, or \"vgroove\", \"vgroove-nonsymmetric\" or "
                             "\"cook-torrance\"");
  std::mutex error_mu;
  std::exception_ptr error;
  std::atomic<bool> failed{false};
  std::atomic<bool>* stop = nullptr;
  const validation::BrdfBatchFn batch = [&](const double* wi, const double* wo, std::size_t n, double* out) {
    // After an error or Ctrl-C (the cancel flag, once run_interruptible set it) f is not called
    // again: the remaining nodes are zeros of a result that is discarded.
    if (failed.load() || (stop && stop->load())) return std::fill(out, out + n, 0.0);
    try {
      py::gil_scoped_acquire gil;
      const auto sn = static_cast<py::ssize_t>(n);
      py::array_t<double> a({sn, py::ssize_t{3}}), b({sn, py::ssize_t{3}});
      std::copy(wi, wi + 3 * n, a.mutable_data());
      std::copy(wo, wo + 3 * n, b.mutable_data());
      const py::object res = f(a, b);
      const auto v = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(res);
      if (!v || v.ndim() != 1 || static_cast<std::size_t>(v.shape(0)) != n) {
        std::string shape = "a " + std::string(py::str(py::type::of(res).attr("__name__")));
        if (v) {
          shape = "an array of shape (";
          for (py::ssize_t d = 0; d < v.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(v.shape(d));
          shape += v.ndim() == 1 ? ",)" : ")";
        }
        throw support::UserError("f returned " + shape + " for " + std::to_string(n) +
                                 " directions; it must return one value per direction, shape (" + std::to_string(n) +
                                 ",)");
      }
      std::copy(v.data(), v.data() + n, out);
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mu);
      if (!error) error = std::current_exception();
      failed.store(true);
      if (stop) stop->store(true);
      std::fill(out, out + n, 0.0);
    }
  };
  const validation::CheckBrdfResult r = run_interruptible([&](std::atomic<bool>& cancel) {
    stop = &cancel;
    o.cancel = &cancel;
    return validation::check_brdf(batch, o);
  });
  if (error) std::rethrow_exception(error);
  return to_python(r.to_json());
}

}  // namespace

void bind_brdfs(py::module_& m) {
  m.def("brdf", &brdf, py::arg("model"), py::arg("ndf"), py::arg("alpha"), py::arg("wi"), py::arg("wo"),
        py::arg("per_k"), py::arg("max_k"), py::arg("dim"), py::arg("threads"));
  m.def("check_brdf", &check_brdf, py::arg("f"), py::arg("max_k"), py::arg("name"), py::arg("ndf"), py::arg("alpha"),
        py::arg("theta_i_deg"), py::arg("rays"), py::arg("dim"), py::arg("grooves"), py::arg("seed"),
        py::arg("theta_bins"), py::arg("phi_bins"), py::arg("flatland_bins"), py::arg("sigmas"),
        py::arg("model_tolerance"), py::arg("quadrature_order"), py::arg("threads"));
}

}  // namespace vgroove::python
