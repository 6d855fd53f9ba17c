// vgroove Python module: BRDFs over arrays of directions (vgroove's Eq. 16-17, its nonsymmetric
// form Eq. 21-23 and Cook-Torrance, 3D and flatland, with a conductor's Fresnel in 3D), the
// settings vgroove.BRDF checks when it is made, and check_brdf: a BRDF of the user's, a vectorized
// Python callable, held against the exact simulation (validation/check_brdf.h), a batch of
// directions per call; the kaleidoscopic dielectric model's binned lobe and its BSDF at a point
// (`vgroove brdf --model vgroove-dielectric`, without and with --theta-o-deg).
#include "common.h"

#include "vgroove/validation/spec_lists.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/brdf_model.h"
#include "vgroove/analytic/kaleidoscope_dielectric_lobe.h"
#include "vgroove/analytic/kaleidoscope_dielectric_point.h"
#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/common/angles.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/check_brdf.h"
#include "vgroove/validation/check_bsdf.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/run_options.h"

#include <cmath>
#include <limits>
#include <mutex>

namespace vgroove::python {

using analytic::BrdfModel;
using validation::SurfaceDim;

namespace {

// The flatland and nonsymmetric sums' largest max_k: `vgroove brdf`'s (validation/ranges.h;
// test_surfaces.py holds the two messages equal).
constexpr int kFlatlandMaxK = validation::kMaxFlatlandBrdfK;
constexpr int kNonsymmetricMaxK = validation::kMaxNonsymmetricBrdfK;

// max_k checked as `vgroove brdf --max-k` is: [1, 2^31 - 1], the flatland and nonsymmetric sums bounded.
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
                             std::to_string(kFlatlandMaxK) + "] with dim flatland");
  return static_cast<int>(max_k);
}

// The cost of one direction relative to the 3D sum (which costs the same for any max_k): the
// flatland and nonsymmetric sums grow as max_k^2 (about 0.4-2 s per direction at max_k 4096).
double relative_cost(BrdfModel model, bool flat, int max_k) {
  if (model == BrdfModel::cook_torrance || model == BrdfModel::walter || (model == BrdfModel::vgroove && !flat))
    return 1.0;
  return std::max(1.0, static_cast<double>(max_k) * max_k / 256.0);
}

// Walter's light arrives in the near medium: wi.z > 0 (the command line's theta_i in [0, 90)).
void check_light_above(const Rows& wi, std::size_t n) {
  for (std::size_t j = 0; j < (wi.step ? n : 1); ++j)
    if (!(wi.row(j)[2] > 0.0))
      throw support::UserError("wi[" + std::to_string(j) + "] = (" + support::number_text(wi.row(j)[0]) + ", " +
                               support::number_text(wi.row(j)[1]) + ", " + support::number_text(wi.row(j)[2]) +
                               ") is not above the interface (z > 0): with model walter the light is in the near "
                               "medium; light from the far side is eta -> 1 / eta");
}

}  // namespace

BrdfSettings brdf_settings(const std::string& model_name, const std::string& ndf_name, double alpha,
                           const std::string& dim_name, const py::object& max_k, const py::object& alpha_y,
                           const py::object& partner, const py::object& eta, const py::object& masking) {
  BrdfSettings s;
  s.model = parse_brdf_model(model_name, true);
  s.ndf = parse_ndf(ndf_name);
  check_alpha(alpha);
  s.alpha = alpha;
  s.flat = parse_dim(dim_name) == SurfaceDim::flatland;
  const bool nonsym = s.model == BrdfModel::vgroove_nonsymmetric;
  const std::string model_text = "(model = \"" + model_name + "\")";
  if (!partner.is_none()) {
    const std::string p = partner.cast<std::string>();
    if (p != "independent" && p != "symmetric")
      throw support::UserError("partner = \"" + p + "\" is not one of \"independent\", \"symmetric\"");
    if (!nonsym) throw support::UserError("partner applies to model vgroove-nonsymmetric only " + model_text);
    s.symmetric_partner = p == "symmetric";
  }
  if (!alpha_y.is_none()) {
    const double ay = alpha_y.cast<double>();
    if (!nonsym) throw support::UserError("alpha_y applies to model vgroove-nonsymmetric only " + model_text);
    if (s.flat) throw support::UserError("alpha_y applies to dim 3d only (flatland has one roughness)");
    if (s.ndf == NdfKind::phong)
      throw support::UserError("alpha_y applies to ndf ggx and beckmann only (Phong has no elliptical form)");
    if (!(ay >= validation::kMinAlpha && ay <= validation::kMaxAlpha))
      throw support::UserError("alpha_y = " + support::number_text(ay) + " is out of range " +
                               support::interval_text(validation::kMinAlpha, true, validation::kMaxAlpha, true));
    s.alpha_y = ay;
  }
  // Eq. (20)'s partner law exists for Phong below alpha = sqrt(2) only (ERRATA E-NS1): the command
  // line's refusal.
  if (nonsym && !s.symmetric_partner && !analytic::partner_law_exists(s.ndf, alpha))
    throw support::UserError("alpha = " + support::number_text(alpha) + " is out of range " +
                             support::interval_text(0, false, std::sqrt(2.0), false) +
                             " with model vgroove-nonsymmetric ndf phong (Eq. 20's partner law needs alpha < "
                             "sqrt(2))");
  s.max_k_given = !max_k.is_none();
  s.max_k = s.max_k_given ? brdf_orders(to_count(max_k, "max_k", std::numeric_limits<long long>::min(),
                                                 std::numeric_limits<long long>::max()),
                                        s.model, s.flat)
                          : analytic::default_max_k(s.model, s.flat);
  if (s.model == BrdfModel::walter) {
    // Walter's dielectric: eta = n_far / n_near, real, as `vgroove brdf --eta`; the G2 by its flag name.
    if (!eta.is_none()) {
      const std::complex<double> z = eta.cast<std::complex<double>>();
      if (!(z.imag() == 0.0 && z.real() > 0.0 && z.real() <= validation::kMaxFresnelEta))
        throw support::UserError("eta = " + support::number_text(z.real()) +
                                 (z.imag() == 0.0 ? "" : " + " + support::number_text(z.imag()) + "j") +
                                 " is out of range " +
                                 support::interval_text(0, false, validation::kMaxFresnelEta, true) +
                                 " with model walter (a dielectric's n_far / n_near, real)");
      s.dielectric_eta = z.real();
    }
    if (!masking.is_none()) {
      const std::string name = masking.cast<std::string>();
      const auto g = analytic::masking_from_flag(name);
      if (!g)
        throw support::UserError("masking = \"" + name +
                                 "\" is not one of \"smith\", \"smith_separable\", \"vcavity\"");
      if (!analytic::masking_supported(*g, s.ndf))
        throw support::UserError("masking = \"" + name +
                                 "\" needs ndf ggx or beckmann (Smith's Lambda has no closed form for phong); "
                                 "masking \"vcavity\" takes phong");
      s.masking = *g;
    } else if (!analytic::masking_supported(s.masking, s.ndf)) {
      throw support::UserError(
          "model walter with ndf phong needs masking = \"vcavity\" (its default, "
          "smith_separable, needs ggx or beckmann)");
    }
    return s;
  }
  if (!masking.is_none()) throw support::UserError("masking applies to model walter only " + model_text);
  if (!eta.is_none()) {
    if (s.flat) throw support::UserError("eta applies to dim 3d only (the flatland BRDFs have no Fresnel term)");
    s.fresnel = conductor_of(eta);
  }
  return s;
}

analytic::BrdfEvalOptions BrdfSettings::options() const {
  analytic::BrdfEvalOptions o;
  o.ndf = ndf, o.alpha = alpha, o.flatland = flat, o.max_k = max_k;
  if (model == BrdfModel::vgroove_nonsymmetric) o.alpha_y = alpha_y > 0.0 ? alpha_y : alpha;
  o.symmetric_partner = symmetric_partner;
  if (fresnel) o.fresnel = fresnel->fn();
  o.eta = dielectric_eta, o.masking = masking;
  return o;
}

namespace {

// f(j, i, o, wi_row, wo_row) for j < n in chunks of 4096 on `threads` threads, or one by one where
// a direction may be slow (0.4-2 s at flatland max_k 4096): the cancel flag is read before each of
// those, so the work stops within one of them, and progress counts directions as they are done.
template <class F>
void for_pairs(std::size_t n, int threads, const Rows& wi, const Rows& wo, bool cheap, ProgressRelay& relay,
               std::atomic<bool>& cancel, F&& f) {
  const std::size_t chunk = cheap ? 4096 : 1;
  support::parallel_for((n + chunk - 1) / chunk, support::resolve_threads(threads),
                        [&](std::size_t c) {
                          const std::size_t end = std::min(n, (c + 1) * chunk);
                          for (std::size_t j = c * chunk; j < end; ++j) {
                            if (!cheap && cancel.load(std::memory_order_relaxed)) return;
                            const double* a = wi.row(j);
                            const double* b = wo.row(j);
                            f(j, analytic::Dir3{a[0], a[1], a[2]}, analytic::Dir3{b[0], b[1], b[2]}, a, b);
                          }
                        },
                        relay.fn(chunk, n), &cancel, 1);
}

// out[j] = f(wi_j, wo_j) (per_k: out[j * per_k + k - 1] for k = 1..per_k): the calls
// `vgroove brdf` makes (analytic::evaluate_brdf), each case's loop on its own.
void evaluate(const BrdfSettings& s, int per_k, const Rows& wi, const Rows& wo, std::size_t n, double* out, int threads,
              ProgressRelay& relay, std::atomic<bool>& cancel) {
  const bool cheap = relative_cost(s.model, s.flat, s.max_k) == 1.0;
  const NdfKind ndf = s.ndf;
  const double alpha = s.alpha;
  const int max_k = s.max_k;
  const auto stride = static_cast<std::size_t>(per_k);
  auto run = [&](auto&& f) { for_pairs(n, threads, wi, wo, cheap, relay, cancel, f); };
  if (s.model == BrdfModel::vgroove_nonsymmetric || s.model == BrdfModel::walter || s.fresnel) {
    // Eq. 21-23 (independent partner law of Eq. 20, or B = A; anisotropic with alpha_y), Walter's
    // BSDF, and the symmetric models with Fresnel: analytic::evaluate_brdf, as the command line
    // calls it.
    analytic::BrdfEvalOptions opt = s.options();
    opt.per_k = per_k;
    const BrdfModel model = s.model;
    return run([&](std::size_t j, const analytic::Dir3& i, const analytic::Dir3& o, const double*, const double*) {
      const analytic::BrdfValue v = analytic::evaluate_brdf(model, i, o, opt);
      if (per_k > 0)
        std::copy(v.by_k.begin(), v.by_k.end(), out + j * stride);
      else
        out[j] = v.value;
    });
  }
  if (s.flat) {
    if (s.model == BrdfModel::cook_torrance)
      return run([&](std::size_t j, const analytic::Dir3&, const analytic::Dir3&, const double* a, const double* b) {
        out[j] = analytic::flatland_brdf_single(ndf, alpha, flat_angle(a), flat_angle(b));
      });
    if (per_k > 0)
      return run([&](std::size_t j, const analytic::Dir3&, const analytic::Dir3&, const double* a, const double* b) {
        const double ti = flat_angle(a), to = flat_angle(b);
        for (int k = 1; k <= per_k; ++k)
          out[j * stride + static_cast<std::size_t>(k - 1)] = analytic::flatland_brdf_k(ndf, alpha, ti, to, k);
      });
    return run([&](std::size_t j, const analytic::Dir3&, const analytic::Dir3&, const double* a, const double* b) {
      out[j] = analytic::flatland_brdf(ndf, alpha, flat_angle(a), flat_angle(b), max_k);
    });
  }
  if (s.model == BrdfModel::cook_torrance)
    return run([&](std::size_t j, const analytic::Dir3& i, const analytic::Dir3& o, const double*, const double*) {
      out[j] = analytic::cook_torrance(i, o, ndf, alpha);
    });
  if (per_k > 0)
    return run([&](std::size_t j, const analytic::Dir3& i, const analytic::Dir3& o, const double*, const double*) {
      for (int k = 1; k <= per_k; ++k)
        out[j * stride + static_cast<std::size_t>(k - 1)] = analytic::vgroove_brdf_k(i, o, k, ndf, alpha);
    });
  run([&](std::size_t j, const analytic::Dir3& i, const analytic::Dir3& o, const double*, const double*) {
    out[j] = analytic::vgroove_brdf(i, o, ndf, alpha, max_k);
  });
}

// The settings as vgroove.BRDF keeps them: the canonical names and the orders resolved.
py::dict settings_dict(const std::string& model, const std::string& ndf, double alpha, const std::string& dim,
                       const py::object& max_k, const py::object& alpha_y, const py::object& partner,
                       const py::object& eta, const py::object& masking) {
  const BrdfSettings s = brdf_settings(model, ndf, alpha, dim, max_k, alpha_y, partner, eta, masking);
  py::dict d;
  d["model"] = analytic::brdf_model_name(s.model);
  d["ndf"] = ndf_name(s.ndf);
  d["dim"] = s.flat ? "flatland" : "3d";
  d["max_k"] = s.max_k;
  if (s.model == BrdfModel::walter) d["eta"] = s.dielectric_eta, d["masking"] = analytic::masking_flag_name(s.masking);
  return d;
}

// per_k: 0 (the sums) or the orders k = 1..per_k, each on its own (per_k <= max_k; Cook-Torrance:
// its value as k = 1). wi and wo: one row or n rows each.
py::array_t<double> brdf(const std::string& model_name, const std::string& ndf_name, double alpha, DoubleArray wi,
                         DoubleArray wo, const py::object& per_k_obj, const py::object& max_k,
                         const std::string& dim_name, int threads, const py::object& alpha_y, const py::object& partner,
                         const py::object& eta, const py::object& masking, const py::object& progress) {
  const BrdfSettings s = brdf_settings(model_name, ndf_name, alpha, dim_name, max_k, alpha_y, partner, eta, masking);
  validation::check_threads(threads, "threads");
  ProgressRelay relay(progress);
  if (wi.ndim() != 2 || wi.shape(1) != 3 || wo.ndim() != 2 || wo.shape(1) != 3)
    throw support::UserError("wi and wo must be arrays of shape (n, 3)");
  const std::size_t n = static_cast<std::size_t>(std::max(wi.shape(0), wo.shape(0)));
  const Rows a = rows_of(wi, "wi", n, s.flat), b = rows_of(wo, "wo", n, s.flat);
  if (s.model == BrdfModel::walter) check_light_above(a, n);
  // Cook-Torrance and Walter per k: the value as the only column, k = 1.
  const bool ct = s.model == BrdfModel::cook_torrance || s.model == BrdfModel::walter;
  int per_k = static_cast<int>(to_count(per_k_obj, "per_k", 0, ct ? std::numeric_limits<int>::max() : s.max_k));
  if (ct) per_k = std::min(per_k, 1);
  if (per_k > 0 && static_cast<double>(n) * per_k > 1e9)
    throw support::UserError("per_k with " + std::to_string(per_k) + " orders over " + std::to_string(n) +
                             " directions needs more than 10^9 values");
  py::array_t<double> out = per_k > 0
                                ? new_array<double>({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(per_k)})
                                : new_array<double>({static_cast<py::ssize_t>(n)});
  double* po = out.mutable_data();
  if (ct) per_k = 0;  // the value fills the column
  run_interruptible(
      [&](std::atomic<bool>& cancel) {
        evaluate(s, per_k, a, b, n, po, threads, relay, cancel);
        return 0;
      },
      static_cast<double>(n) * relative_cost(s.model, s.flat, s.max_k) < 2048.0, &relay);
  return out;
}

validation::CheckBrdfOptions check_options(const std::string& name, const std::string& ndf, double alpha,
                                           const std::vector<double>& theta_i_deg, const py::object& rays,
                                           const std::string& dim, const py::object& grooves, const py::object& seed,
                                           int theta_bins, int phi_bins, int flatland_bins, double sigmas,
                                           double model_tolerance, int quadrature_order, int threads,
                                           const std::string& surface, const py::object& field_size,
                                           double correlation_length, const py::object& fields) {
  validation::CheckBrdfOptions o;
  if (surface != "vgroove" && surface != "heightfield")
    throw support::UserError("surface = \"" + surface + "\" is not one of \"vgroove\", \"heightfield\"");
  o.surface = surface == "heightfield" ? validation::CheckSurface::heightfield : validation::CheckSurface::vgroove;
  o.field_size = static_cast<int>(to_count(field_size, "field_size", 16, 65536));
  o.correlation_length = correlation_length;
  o.fields = static_cast<int>(to_count(fields, "fields", 2, 1000));
  o.name = name;
  o.ndf = parse_ndf(ndf);
  o.alpha = alpha;
  o.theta_i_deg = theta_i_deg;
  o.rays = static_cast<long>(to_count(rays, "rays", 1, validation::kMaxRays));
  o.dim = parse_dim(dim);
  o.grooves = static_cast<int>(to_count(grooves, "grooves", 1, validation::kMaxGrooves));
  o.seed = static_cast<std::uint64_t>(to_seed(seed, "seed"));
  o.theta_bins = theta_bins, o.phi_bins = phi_bins, o.flatland_bins = flatland_bins;
  o.sigmas = sigmas, o.model_tolerance = model_tolerance, o.quadrature_order = quadrature_order;
  o.threads = threads;
  validation::check_options(o);
  return o;
}

// f: a Python callable f(wi, wo) -> values, wi and wo float arrays of shape (n, 3); or the name
// of a built-in model (brdf_settings), evaluated in C++ one direction at a time. Progress: the
// check reports its start (0 of 1) and its end (1 of 1).
py::object check_brdf(const py::object& f, const py::object& max_k, const std::string& name, const std::string& ndf,
                      double alpha, const std::vector<double>& theta_i_deg, const py::object& rays,
                      const std::string& dim, const py::object& grooves, const py::object& seed, int theta_bins,
                      int phi_bins, int flatland_bins, double sigmas, double model_tolerance, int quadrature_order,
                      int threads, const py::object& progress, const std::string& surface, const py::object& field_size,
                      double correlation_length, const py::object& fields, const py::object& eta,
                      const std::string& side) {
  // eta and side first: a BSDF's options are refused, one line each, before the conductor's check_options.
  if (side != "above" && side != "below")
    throw support::UserError("side = \"" + side + "\" is not one of \"above\", \"below\"");
  validation::CheckBrdfOptions bsdf;
  // None: the conductor check (C++'s eta 0); a given 0 is out of range like any other eta <= 0.
  bsdf.eta = eta.is_none() ? 0.0 : eta.cast<double>();
  if (!eta.is_none() && bsdf.eta == 0.0)
    throw support::UserError("eta = 0 is out of range [0.1, 10], not 1 (None: the conductor check)");
  bsdf.side = side == "below" ? sim::Medium::below : sim::Medium::above;
  bsdf.surface = surface == "heightfield" ? validation::CheckSurface::heightfield : validation::CheckSurface::vgroove;
  validation::check_bsdf_options(bsdf);
  validation::CheckBrdfOptions o = check_options(name, ndf, alpha, theta_i_deg, rays, dim, grooves, seed, theta_bins,
                                                 phi_bins, flatland_bins, sigmas, model_tolerance, quadrature_order,
                                                 threads, surface, field_size, correlation_length, fields);
  o.eta = bsdf.eta, o.side = bsdf.side;
  ProgressRelay relay(progress);
  relay.set(0, 1);
  relay.flush();
  if (py::isinstance<py::str>(f)) {
    const BrdfSettings s =
        brdf_settings(f.cast<std::string>(), ndf, alpha, dim, max_k, py::none(), py::none(), py::none(), py::none());
    if (s.model == BrdfModel::walter)
      throw support::UserError(
          "f = \"walter\": check_brdf holds reflection BRDFs with F = 1 against the traced "
          "conductor surface; Walter's is a dielectric BSDF");
    const analytic::BrdfEvalOptions eval = s.options();
    const BrdfModel model = s.model;
    const validation::BrdfFn fn = [=](const analytic::Dir3& i, const analytic::Dir3& w) {
      return analytic::evaluate_brdf(model, i, w, eval).value;
    };
    const validation::CheckBrdfResult r = run_interruptible(
        [&](std::atomic<bool>& cancel) {
          o.cancel = &cancel;
          validation::CheckBrdfResult res = validation::check_brdf(fn, o);
          relay.set(1, 1);
          return res;
        },
        false, &relay);
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
  const validation::CheckBrdfResult r = run_interruptible(
      [&](std::atomic<bool>& cancel) {
        stop = &cancel;
        o.cancel = &cancel;
        validation::CheckBrdfResult res = validation::check_brdf(batch, o);
        relay.set(1, 1);
        return res;
      },
      false, &relay);
  if (error) std::rethrow_exception(error);
  return to_python(r.to_json());
}

// The kaleidoscopic dielectric model's binned lobe (analytic/kaleidoscope_dielectric_lobe.h), checked
// as `vgroove brdf --model vgroove-dielectric` checks its flags (the same ranges, named as the
// arguments): reflected and transmitted flux per bin, per interaction count k (rows k = 0..orders and
// one for every k > orders) when orders > 0, and the albedos.
py::dict dielectric_lobe(const std::string& ndf_name, double alpha, double eta, double theta_i_deg,
                         const std::string& dim_name, int orders, int flatland_bins, int theta_bins, int phi_bins,
                         const py::object& progress) {
  const NdfKind ndf = parse_ndf(ndf_name);
  const bool flat = parse_dim(dim_name) == SurfaceDim::flatland;
  check_alpha(alpha);
  auto check = [](double v, double lo, bool lo_closed, double hi, bool hi_closed, const std::string& what) {
    if (!(std::isfinite(v) && (lo_closed ? v >= lo : v > lo) && (hi_closed ? v <= hi : v < hi)))
      throw support::UserError(what + " = " + support::number_text(v) + " is out of range " +
                               support::interval_text(lo, lo_closed, hi, hi_closed));
  };
  check(eta, 0, false, validation::kMaxFresnelEta, true, "eta");
  check(theta_i_deg, flat ? -90 : 0, !flat, 90, false, "theta_i_deg");
  if (orders < 0 || orders > validation::kMaxPrintedK)
    throw support::UserError("per_k = " + std::to_string(orders) + " is out of range [0, " +
                             std::to_string(validation::kMaxPrintedK) + "] (0: none)");
  auto count = [](int v, int hi, const char* what) {
    if (v < 1 || v > hi)
      throw support::UserError(std::string(what) + " = " + std::to_string(v) + " is out of range [1, " +
                               std::to_string(hi) + "]");
  };
  if (flat) {
    count(flatland_bins, validation::kMaxFlatlandBins, "flatland_bins");
  } else {
    count(theta_bins, validation::kMaxThetaBins, "theta_bins");
    count(phi_bins, validation::kMaxPhiBins, "phi_bins");
    if (phi_bins % 2 != 0)
      throw support::UserError("phi_bins = " + std::to_string(phi_bins) +
                               " must be even (bins centred on phi = 0 and on the light at phi = 180)");
  }
  const double ti = deg_to_rad(theta_i_deg);
  // The library takes no cancel flag: Ctrl-C is raised when the lobe is done. progress: 0 of 1, 1 of 1.
  ProgressRelay relay(progress);
  relay.set(0, 1);
  analytic::DielectricLobe L = run_interruptible(
      [&](std::atomic<bool>&) {
        analytic::DielectricLobe r =
            flat ? analytic::kaleidoscope_dielectric_lobe_flatland(ndf, alpha, eta, ti, flatland_bins, orders)
                 : analytic::kaleidoscope_dielectric_lobe_3d(ndf, alpha, eta, ti, theta_bins, phi_bins, orders);
        relay.set(1, 1);
        return r;
      },
      false, &relay);
  std::vector<py::ssize_t> shape =
      flat ? std::vector<py::ssize_t>{flatland_bins} : std::vector<py::ssize_t>{theta_bins, phi_bins};
  py::dict d;
  d["reflected"] = array_from(std::move(L.reflected), shape);
  d["transmitted"] = array_from(std::move(L.transmitted), shape);
  if (orders > 0) {
    auto by_k = [&](std::vector<std::vector<double>>& rows_k) {
      std::vector<double> all;
      for (const auto& r : rows_k) all.insert(all.end(), r.begin(), r.end());
      std::vector<py::ssize_t> s = shape;
      s.insert(s.begin(), static_cast<py::ssize_t>(rows_k.size()));
      return array_from(std::move(all), s);
    };
    d["reflected_by_k"] = by_k(L.reflected_by_k);
    d["transmitted_by_k"] = by_k(L.transmitted_by_k);
  }
  d["albedo_r"] = L.albedo_r, d["albedo_t"] = L.albedo_t, d["shadow_or_unknown"] = L.shadow_or_unknown;
  d["upward"] = L.upward, d["unresolved"] = L.unresolved, d["error_estimate"] = L.error_estimate;
  return d;
}

// The kaleidoscopic dielectric model's BSDF at n points (analytic/kaleidoscope_dielectric_point.h),
// `vgroove brdf --model vgroove-dielectric --theta-o-deg` over rows (theta_i_deg, phi_i_deg,
// theta_o_deg, phi_o_deg) of `angles`, checked as the command line checks its directions (the same
// ranges, the arguments' names, "[j]" for row j of several) and evaluated as it evaluates them
// (app/cmd_brdf.cpp, dielectric_point: the same calls, so the same bits): f, pdf = f |cos theta_o|
// and with orders > 0 the rows k = 0..orders and one for every k > orders.
py::dict dielectric_bsdf(const std::string& ndf_name, double alpha, double eta, DoubleArray angles,
                         const std::string& dim_name, int orders, int threads, const py::object& progress) {
  const NdfKind ndf = parse_ndf(ndf_name);
  const bool flat = parse_dim(dim_name) == SurfaceDim::flatland;
  check_alpha(alpha);
  validation::check_threads(threads, "threads");
  if (!(std::isfinite(eta) && eta > 0 && eta <= validation::kMaxFresnelEta))
    throw support::UserError("eta = " + support::number_text(eta) + " is out of range " +
                             support::interval_text(0, false, validation::kMaxFresnelEta, true));
  if (orders < 0 || orders > validation::kMaxPrintedK)
    throw support::UserError("per_k = " + std::to_string(orders) + " is out of range [0, " +
                             std::to_string(validation::kMaxPrintedK) + "] (0: none)");
  if (angles.ndim() != 2 || angles.shape(1) != 4) throw support::UserError("angles must be an array of shape (n, 4)");
  const auto n = static_cast<std::size_t>(angles.shape(0));
  const double* ang = angles.data();
  for (std::size_t j = 0; j < n; ++j) {
    const std::string at = n > 1 ? "[" + std::to_string(j) + "]" : "";
    auto check = [&](double v, double lo, bool lo_closed, double hi, bool hi_closed, const char* what) {
      if (!(std::isfinite(v) && (lo_closed ? v >= lo : v > lo) && (hi_closed ? v <= hi : v < hi)))
        throw support::UserError(what + at + " = " + support::number_text(v) + " is out of range " +
                                 support::interval_text(lo, lo_closed, hi, hi_closed));
    };
    const double* a = ang + 4 * j;
    check(a[0], flat ? -90 : 0, !flat, 90, false, "theta_i_deg");
    check(a[2], flat ? -180 : 0, true, 180, true, "theta_o_deg");
    if (!flat) check(a[1], -360, true, 360, true, "phi_i_deg"), check(a[3], -360, true, 360, true, "phi_o_deg");
    if (std::abs(a[2]) == 90.0)
      throw support::UserError("theta_o_deg" + at + " = " + support::number_text(a[2]) + " is out of range " +
                               (flat ? "[-180, -90) or (-90, 90) or (90, 180]" : "[0, 90) or (90, 180]") +
                               " with model vgroove-dielectric (on the horizon f = density / |cos theta_o| is not "
                               "defined)");
  }
  const auto rows = static_cast<std::size_t>(orders) + 2;
  if (orders > 0 && static_cast<double>(n) * static_cast<double>(rows) > 1e9)
    throw support::UserError("per_k with " + std::to_string(orders) + " orders over " + std::to_string(n) +
                             " directions needs more than 10^9 values");
  py::array_t<double> f = new_array<double>({static_cast<py::ssize_t>(n)});
  py::array_t<double> pdf = new_array<double>({static_cast<py::ssize_t>(n)});
  py::array_t<double> by_k = new_array<double>(
      {static_cast<py::ssize_t>(orders > 0 ? n : 0), static_cast<py::ssize_t>(orders > 0 ? rows : 0)});
  double *pf = f.mutable_data(), *pp = pdf.mutable_data(), *pk = by_k.mutable_data();
  ProgressRelay relay(progress);
  // The command line's dielectric_point (app/cmd_brdf.cpp), one row: pdf the library's to the bit.
  auto one = [&](std::size_t j) {
    const double* a = ang + 4 * j;
    analytic::DielectricPointValue v;
    double pd = 0.0;
    if (flat) {
      const bool reflected = std::abs(a[2]) < 90.0;
      const double ti = deg_to_rad(a[0]);
      const double to = deg_to_rad(reflected ? a[2] : a[2] - std::copysign(180.0, a[2]));
      v = analytic::kaleidoscope_dielectric_bsdf_flatland(ndf, alpha, eta, ti, to, reflected, orders);
      pd = orders == 0 ? v.f * std::cos(to)
                       : analytic::kaleidoscope_dielectric_pdf_flatland(ndf, alpha, eta, ti, to, reflected);
    } else {
      const analytic::Dir3 i = analytic::dir3(deg_to_rad(a[0]), deg_to_rad(a[1]));
      const analytic::Dir3 o = analytic::dir3(deg_to_rad(a[2]), deg_to_rad(a[3]));
      v = analytic::kaleidoscope_dielectric_bsdf_3d(ndf, alpha, eta, i, o, orders);
      pd = orders == 0 ? v.f * std::abs(o.z) : analytic::kaleidoscope_dielectric_pdf_3d(ndf, alpha, eta, i, o);
    }
    pf[j] = v.f, pp[j] = pd;
    if (orders > 0) std::copy(v.by_k.begin(), v.by_k.end(), pk + j * rows);
  };
  // About 0.06 ms a point: chunks of 64, the cancel flag read between them.
  constexpr std::size_t chunk = 64;
  run_interruptible(
      [&](std::atomic<bool>& cancel) {
        support::parallel_for((n + chunk - 1) / chunk, support::resolve_threads(threads),
                              [&](std::size_t c) {
                                for (std::size_t j = c * chunk; j < std::min(n, (c + 1) * chunk); ++j) one(j);
                              },
                              relay.fn(chunk, n), &cancel, 1);
        return 0;
      },
      n <= chunk, &relay);
  py::dict d;
  d["value"] = f;
  d["pdf"] = pdf;
  if (orders > 0) d["by_k"] = by_k;
  return d;
}

}  // namespace

void bind_brdfs(py::module_& m) {
  m.def("dielectric_lobe", &dielectric_lobe, py::arg("ndf"), py::arg("alpha"), py::arg("eta"), py::arg("theta_i_deg"),
        py::arg("dim"), py::arg("orders"), py::arg("flatland_bins"), py::arg("theta_bins"), py::arg("phi_bins"),
        py::arg("progress") = py::none());
  m.def("dielectric_bsdf", &dielectric_bsdf, py::arg("ndf"), py::arg("alpha"), py::arg("eta"), py::arg("angles"),
        py::arg("dim"), py::arg("orders"), py::arg("threads"), py::arg("progress") = py::none());
  m.def("brdf_settings", &settings_dict, py::arg("model"), py::arg("ndf"), py::arg("alpha"), py::arg("dim"),
        py::arg("max_k"), py::arg("alpha_y"), py::arg("partner"), py::arg("eta"), py::arg("masking") = py::none());
  m.def("brdf", &brdf, py::arg("model"), py::arg("ndf"), py::arg("alpha"), py::arg("wi"), py::arg("wo"),
        py::arg("per_k"), py::arg("max_k"), py::arg("dim"), py::arg("threads"), py::arg("alpha_y") = py::none(),
        py::arg("partner") = py::none(), py::arg("eta") = py::none(), py::arg("masking") = py::none(),
        py::arg("progress") = py::none());
  m.def("check_brdf", &check_brdf, py::arg("f"), py::arg("max_k"), py::arg("name"), py::arg("ndf"), py::arg("alpha"),
        py::arg("theta_i_deg"), py::arg("rays"), py::arg("dim"), py::arg("grooves"), py::arg("seed"),
        py::arg("theta_bins"), py::arg("phi_bins"), py::arg("flatland_bins"), py::arg("sigmas"),
        py::arg("model_tolerance"), py::arg("quadrature_order"), py::arg("threads"), py::arg("progress") = py::none(),
        py::arg("surface") = "vgroove", py::arg("field_size") = 256, py::arg("correlation_length") = 8.0,
        py::arg("fields") = 4, py::arg("eta") = py::none(), py::arg("side") = "above");
  // The orders each model sums when max_k is not given (analytic/brdf_model.h: the one table of
  // every face).
  py::dict defaults;
  for (BrdfModel model :
       {BrdfModel::vgroove, BrdfModel::vgroove_nonsymmetric, BrdfModel::cook_torrance, BrdfModel::walter})
    for (bool flat : {false, true})
      defaults[py::make_tuple(analytic::brdf_model_name(model), flat ? "flatland" : "3d")] =
          analytic::default_max_k(model, flat);
  m.attr("BRDF_MAX_K") = defaults;
}

}  // namespace vgroove::python
