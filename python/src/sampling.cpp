// vgroove Python module: importance sampling of the symmetric V-groove BRDF (analytic/
// sampling_3d.h, analytic/sampling_flatland.h), of the nonsymmetric one (analytic/
// sampling_nonsymmetric.h; Lee et al. 2018, Sec. 6) and of Walter et al. 2007's rough dielectric
// BSDF (analytic/walter_sampling.h) and of the kaleidoscopic dielectric model
// (analytic/sampling_dielectric.h) over arrays, the density of the directions they produce, and
// the uniform numbers of vgroove's deterministic streams (sim/rng.h).
#include "common.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/facet_strategy.h"
#include "vgroove/analytic/kaleidoscope_dielectric_point.h"
#include "vgroove/analytic/sampling_3d.h"
#include "vgroove/analytic/sampling_dielectric.h"
#include "vgroove/analytic/sampling_flatland.h"
#include "vgroove/analytic/sampling_nonsymmetric.h"
#include "vgroove/analytic/walter_sampling.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/parallel.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/run_options.h"
#include "vgroove/validation/spec_lists.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::python {

namespace {

using validation::SurfaceDim;

// The NDF, with `vgroove sample`'s message (its list in that command's order).
NdfKind sampler_ndf(const std::string& name) {
  if (const auto k = ndf_from_name(name)) return *k;
  throw support::UserError("ndf = \"" + name + "\" is not one of \"ggx\", \"beckmann\", \"phong\"");
}

// The sampler's options, checked: the strategy exists for (ndf, dim), max_k in [1, 100000] (the
// command line's `vgroove sample` ranges).
analytic::SamplerOptions sampler_options(const std::string& strategy, NdfKind ndf, SurfaceDim dim, long long max_k) {
  const auto s = analytic::strategy_from_name(strategy);
  if (!s)
    throw support::UserError("strategy = \"" + strategy +
                             "\" is not one of \"printed\", \"vndf\", \"smith-vndf\", \"bounded-vndf\"");
  const bool flat = dim == SurfaceDim::flatland;
  if (!analytic::strategy_supports(*s, ndf, flat))
    throw support::UserError("strategy = \"" + strategy + "\" does not exist for ndf " + analytic::ndf_name(ndf) +
                             " dim " + (flat ? "flatland" : "3d") +
                             " (smith-vndf: ggx only; bounded-vndf: ggx in 3d only)");
  if (max_k < 1 || max_k > validation::kMaxSamplerK)
    throw support::UserError("max_k = " + std::to_string(max_k) + " is out of range [1, " +
                             std::to_string(validation::kMaxSamplerK) + "]");
  return {*s, static_cast<int>(max_k)};
}

// Rows of u in [0, 1)^m.
void check_uniforms(const double* u, std::size_t n, std::size_t m) {
  bool inside = true;  // a first pass without branches; the loop below names the first bad number
  for (std::size_t j = 0; j < m * n; ++j) inside &= (u[j] >= 0.0) & (u[j] < 1.0);
  if (inside) return;
  for (std::size_t j = 0; j < m * n; ++j)
    if (!(u[j] >= 0.0 && u[j] < 1.0))
      throw support::UserError("u[" + std::to_string(j / m) + "][" + std::to_string(j % m) +
                               "] = " + support::number_text(u[j]) + " is out of range [0, 1)");
}

// "vgroove" (symmetric grooves, four numbers per sample) or "vgroove-nonsymmetric" (Eq. 21-23 with
// the independent partner law of Eq. 20, five numbers), as `vgroove sample --model`; the message
// names the models python/vgroove/_sampling.py's sample() takes (walter and vgroove-dielectric have
// calls of their own), as the command line's.
bool parse_sampler_model(const std::string& m) {
  if (m == "vgroove") return false;
  if (m == "vgroove-nonsymmetric") return true;
  throw support::UserError(
      "model = \"" + m + "\" is not one of \"vgroove\", \"vgroove-nonsymmetric\", \"walter\", \"vgroove-dielectric\"");
}

// The nonsymmetric sampler (its partner table), or UserError where the partner law does not exist.
analytic::NonsymmetricSampler nonsymmetric_sampler(NdfKind ndf, double alpha, const analytic::SamplerOptions& opt,
                                                   bool flat, double tolerance) {
  if (!(tolerance >= validation::kMinPartnerTolerance && tolerance <= validation::kMaxPartnerTolerance))
    throw support::UserError(
        "tolerance = " + support::number_text(tolerance) + " is out of range " +
        support::interval_text(validation::kMinPartnerTolerance, true, validation::kMaxPartnerTolerance, true));
  if (ndf == NdfKind::phong && alpha > 1.0)
    throw support::UserError("alpha = " + support::number_text(alpha) +
                             " is out of range (0, 1] for model vgroove-nonsymmetric with ndf phong (the partner "
                             "law's table)");
  try {
    analytic::NonsymmetricSampler S = analytic::make_nonsymmetric_sampler(ndf, alpha, opt, flat);
    S.tolerance = tolerance;
    return S;
  } catch (const std::domain_error& e) {
    throw support::UserError(e.what());
  }
}

// The light: rows of wi (n x 3, or one row for all), or the angles theta_i_deg (n, or one for all)
// of the suites' convention (azimuth 180 deg: dir3(theta_i, pi) in 3D; in flatland the signed angle
// itself), as radians = deg * pi/180.
struct Light {
  const double* wi = nullptr;
  const double* theta_i_deg = nullptr;
  std::size_t step = 1;  // 0: one light for every row
  const double* w(std::size_t j) const { return wi + 3 * step * j; }
  double deg(std::size_t j) const { return theta_i_deg[step * j]; }
  double angle(std::size_t j) const { return wi ? flat_angle(w(j)) : deg(j) * kRadPerDeg; }
};

// Row j's light direction in 3D, read by one thread row after row: a run of equal angles (a scalar
// theta_i_deg broadcast to every row) gives its direction once, the same bits as each row's.
class LightCursor {
 public:
  explicit LightCursor(const Light& l) : l_(l) {}
  analytic::Dir3 dir(std::size_t j) {
    if (l_.wi) {
      const double* w = l_.w(j);
      return {w[0], w[1], w[2]};
    }
    const double t = l_.deg(j);
    if (!(t == t_)) t_ = t, d_ = analytic::dir3(t * kRadPerDeg, std::numbers::pi);
    return d_;
  }

 private:
  const Light& l_;
  double t_ = std::numeric_limits<double>::quiet_NaN();
  analytic::Dir3 d_;
};

// The light's range: `vgroove sample --theta-i-deg`'s [0, kMaxSurfaceThetaIDeg] (the brdf and
// furnace suites'), in flatland signed, [-89.9, 89.9] (the mirror image). A direction wi is held to
// it by its polar angle (flatland: its signed angle) rounded to 1e-9 deg as reports print angles,
// so that direction(89.9, 180) is taken. One row (or one angle) serves every row of the call.
Light light_of(const std::optional<DoubleArray>& wi, std::optional<Rows>& wi_unit,
               const std::optional<DoubleArray>& theta_i_deg, std::size_t n, bool flat) {
  Light l;
  if (wi.has_value() == theta_i_deg.has_value())
    throw support::UserError("give the light as either wi (unit vectors) or theta_i_deg, not both or neither");
  constexpr double hi = validation::kMaxSurfaceThetaIDeg;
  const double lo = flat ? -hi : 0.0;
  const std::string range = support::interval_text(lo, true, hi, true);
  if (wi) {
    if (wi->ndim() != 2 || wi->shape(1) != 3 || (wi->shape(0) != 1 && static_cast<std::size_t>(wi->shape(0)) != n))
      throw support::UserError("wi must be an array of shape (n, 3) with n = " + std::to_string(n));
    wi_unit = rows_of(*wi, "wi", n, flat);
    const std::size_t rows = static_cast<std::size_t>(wi->shape(0));
    const double* w = wi_unit->w.data();
    for (std::size_t j = 0; j < rows; ++j) {
      const double* d = w + 3 * j;
      const double t = validation::output_deg(flat ? flat_angle(d) : std::atan2(std::hypot(d[0], d[1]), d[2]));
      if (!(t >= lo && t <= hi))
        throw support::UserError("wi[" + std::to_string(j) + "] = (" + support::number_text(d[0]) + ", " +
                                 support::number_text(d[1]) + ", " + support::number_text(d[2]) + ") is " +
                                 support::number_text(t) + " deg from the normal, out of range " + range);
    }
    l.wi = w;
    l.step = rows == 1 ? 0 : 1;
  } else {
    const std::size_t rows = theta_i_deg->ndim() == 1 ? static_cast<std::size_t>(theta_i_deg->shape(0)) : 0;
    if (rows != 1 && rows != n)
      throw support::UserError("theta_i_deg must be an array of shape (n,) with n = " + std::to_string(n));
    for (std::size_t j = 0; j < rows; ++j) {
      const double t = theta_i_deg->data()[j];
      if (!(t >= lo && t <= hi))
        throw support::UserError("theta_i_deg[" + std::to_string(j) + "] = " + support::number_text(t) +
                                 " is out of range " + range);
    }
    l.theta_i_deg = theta_i_deg->data();
    l.step = rows == 1 ? 0 : 1;
  }
  return l;
}

// Runs row(j, cursor) for j < n in chunks of 4096 rows (16 where a row costs milliseconds: the
// nonsymmetric pdf) on `threads` threads, without the GIL (Ctrl-C stops it between chunks); each
// chunk reads the light with its own cursor. Progress counts rows.
template <class Row>
void for_rows(std::size_t n, int threads, const Light& light, ProgressRelay& relay, bool slow, Row&& row) {
  const std::size_t chunk = slow ? 16 : 4096;
  run_interruptible(
      [&](std::atomic<bool>& cancel) {
        support::parallel_for((n + chunk - 1) / chunk, support::resolve_threads(threads),
                              [&](std::size_t c) {
                                LightCursor cursor(light);
                                const std::size_t end = std::min(n, (c + 1) * chunk);
                                for (std::size_t j = c * chunk; j < end; ++j) row(j, cursor);
                              },
                              relay.fn(chunk, n), &cancel, 1);
        return 0;
      },
      n < (slow ? 2 : 2048), &relay);
}

py::dict sample(const std::string& model, const std::string& ndf_name, double alpha,
                const std::optional<DoubleArray>& wi, const std::optional<DoubleArray>& theta_i_deg, DoubleArray u,
                const std::string& strategy, long long max_k, double tolerance, const std::string& dim_name,
                int threads, const py::object& eta, const py::object& progress) {
  const bool nonsym = parse_sampler_model(model);
  const NdfKind ndf = sampler_ndf(ndf_name);
  check_alpha(alpha);
  const SurfaceDim dim = parse_dim(dim_name);
  const analytic::SamplerOptions opt = sampler_options(strategy, ndf, dim, max_k);
  validation::check_threads(threads, "threads");
  const py::ssize_t m = nonsym ? 5 : 4;
  if (u.ndim() != 2 || u.shape(1) != m)
    throw support::UserError("u must be an array of shape (n, " + std::to_string(m) + ")");
  const std::size_t n = static_cast<std::size_t>(u.shape(0));
  const bool flat = dim == SurfaceDim::flatland;
  std::optional<Rows> wi_unit;
  const Light light = light_of(wi, wi_unit, theta_i_deg, n, flat);
  check_uniforms(u.data(), n, static_cast<std::size_t>(m));
  // A conductor's Fresnel term in the weights (3D; the directions and pdf do not depend on it).
  analytic::FresnelFn F;
  if (!eta.is_none()) {
    if (flat) throw support::UserError("eta applies to dim 3d only (the flatland samplers have no Fresnel term)");
    F = conductor_of(eta).fn();
  }
  ProgressRelay relay(progress);
  const analytic::NonsymmetricSampler ns =
      nonsym ? nonsymmetric_sampler(ndf, alpha, opt, flat, tolerance) : analytic::NonsymmetricSampler{};
  const auto sn = static_cast<py::ssize_t>(n);
  auto wo = new_array<double>({sn, 3});
  auto k = new_array<std::int32_t>({sn});
  auto pdf = new_array<double>({sn});
  auto weight = new_array<double>({sn});
  auto beyond = new_array<bool>({sn});
  bool* pb = beyond.mutable_data();
  double* po = wo.mutable_data();
  std::int32_t* pk = k.mutable_data();
  double *pp = pdf.mutable_data(), *pw = weight.mutable_data();
  const double* pu = u.data();
  for_rows(n, threads, light, relay, nonsym, [&](std::size_t j, LightCursor& cursor) {
    if (nonsym) {
      const double* v = pu + 5 * j;
      const std::array<double, 5> uj{v[0], v[1], v[2], v[3], v[4]};
      if (flat) {
        const analytic::VgrooveSampleFlatland x = analytic::sample_nonsymmetric_flatland(ns, light.angle(j), uj);
        po[3 * j] = -std::sin(x.theta_o), po[3 * j + 1] = 0.0, po[3 * j + 2] = std::cos(x.theta_o);
        pk[j] = x.k, pp[j] = x.pdf, pw[j] = x.weight, pb[j] = x.beyond_max_k;
      } else {
        const analytic::VgrooveSample3d x = analytic::sample_nonsymmetric_3d(ns, cursor.dir(j), uj, F);
        po[3 * j] = x.o.x, po[3 * j + 1] = x.o.y, po[3 * j + 2] = x.o.z;
        pk[j] = x.k, pp[j] = x.pdf, pw[j] = x.weight, pb[j] = x.beyond_max_k;
      }
      return;
    }
    const std::array<double, 4> uj{pu[4 * j], pu[4 * j + 1], pu[4 * j + 2], pu[4 * j + 3]};
    if (flat) {
      const analytic::VgrooveSampleFlatland x = analytic::sample_vgroove_flatland(light.angle(j), uj, ndf, alpha, opt);
      po[3 * j] = -std::sin(x.theta_o), po[3 * j + 1] = 0.0, po[3 * j + 2] = std::cos(x.theta_o);
      pk[j] = x.k, pp[j] = x.pdf, pw[j] = x.weight, pb[j] = x.beyond_max_k;
    } else {
      const analytic::VgrooveSample3d x = analytic::sample_vgroove_3d(cursor.dir(j), uj, ndf, alpha, opt, F);
      po[3 * j] = x.o.x, po[3 * j + 1] = x.o.y, po[3 * j + 2] = x.o.z;
      pk[j] = x.k, pp[j] = x.pdf, pw[j] = x.weight, pb[j] = x.beyond_max_k;
    }
  });
  py::dict out;
  out["wo"] = wo;
  out["k"] = k;
  out["pdf"] = pdf;
  out["weight"] = weight;
  out["beyond_max_k"] = beyond;
  return out;
}

py::array_t<double> pdf(const std::string& model, const std::string& ndf_name, double alpha,
                        const std::optional<DoubleArray>& wi, const std::optional<DoubleArray>& theta_i_deg,
                        DoubleArray wo, const std::string& strategy, long long max_k, double tolerance,
                        const std::string& dim_name, int threads, const py::object& progress) {
  const bool nonsym = parse_sampler_model(model);
  const NdfKind ndf = sampler_ndf(ndf_name);
  check_alpha(alpha);
  const SurfaceDim dim = parse_dim(dim_name);
  const analytic::SamplerOptions opt = sampler_options(strategy, ndf, dim, max_k);
  validation::check_threads(threads, "threads");
  if (wo.ndim() != 2 || wo.shape(1) != 3) throw support::UserError("wo must be an array of shape (n, 3)");
  const std::size_t n = static_cast<std::size_t>(wo.shape(0));
  const bool flat = dim == SurfaceDim::flatland;
  std::optional<Rows> wi_unit;
  const Light light = light_of(wi, wi_unit, theta_i_deg, n, flat);
  wo = unit_directions(wo, "wo", flat);
  ProgressRelay relay(progress);
  const analytic::NonsymmetricSampler ns =
      nonsym ? nonsymmetric_sampler(ndf, alpha, opt, flat, tolerance) : analytic::NonsymmetricSampler{};
  auto out = new_array<double>({static_cast<py::ssize_t>(n)});
  double* po = out.mutable_data();
  const double* pw = wo.data();
  for_rows(n, threads, light, relay, nonsym, [&](std::size_t j, LightCursor& cursor) {
    const double* o = pw + 3 * j;
    if (nonsym) {
      po[j] = flat ? analytic::nonsymmetric_pdf_flatland(ns, light.angle(j), flat_angle(o))
                   : analytic::nonsymmetric_pdf_3d(ns, cursor.dir(j), analytic::Dir3{o[0], o[1], o[2]});
      return;
    }
    po[j] = flat ? analytic::vgroove_pdf_flatland(light.angle(j), flat_angle(o), ndf, alpha, opt)
                 : analytic::vgroove_pdf_3d(cursor.dir(j), analytic::Dir3{o[0], o[1], o[2]}, ndf, alpha, opt);
  });
  return out;
}

// Walter's sampler's settings, with `vgroove sample --model walter`'s checks and messages (the
// flags' names without their dashes): eta = n_far / n_near in (0, 1000], not 1; the G2 by its flag
// name (None: smith_separable); no strategy or max_k (the Python wrapper passes whether they were
// given); 3d only.
struct WalterSettings {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5, eta = 1.5;
  analytic::MaskingKind masking = analytic::MaskingKind::smith_separable;
};
WalterSettings walter_settings(const std::string& ndf_name, double alpha, double eta, const std::string& masking,
                               bool strategy_given, bool max_k_given, const std::string& dim_name) {
  WalterSettings w;
  w.ndf = sampler_ndf(ndf_name);
  check_alpha(alpha);
  w.alpha = alpha;
  if (strategy_given)
    throw support::UserError(
        "strategy applies to model vgroove and vgroove-nonsymmetric only (walter draws "
        "its facets from the Smith VNDF for ggx, from |m.n| D(m) for beckmann and phong)");
  if (max_k_given)
    throw support::UserError(
        "max_k applies to model vgroove and vgroove-nonsymmetric only (walter is single "
        "scattering)");
  parse_dim(dim_name);
  if (dim_name != "3d")
    throw support::UserError("dim = \"" + dim_name + "\" is not available with model walter (its sampler is 3d only)");
  if (!(eta > 0.0 && eta <= validation::kMaxFresnelEta && eta != 1.0))
    throw support::UserError("eta = " + support::number_text(eta) + " is out of range " +
                             support::interval_text(0, false, validation::kMaxFresnelEta, true) +
                             ", not 1, with model walter (at eta = 1 the light goes straight through: a delta, no "
                             "density to sample)");
  w.eta = eta;
  const auto g = analytic::masking_from_flag(masking);
  if (!g)
    throw support::UserError("masking = \"" + masking + "\" is not one of \"smith\", \"smith_separable\", \"vcavity\"");
  if (!analytic::masking_supported(*g, w.ndf))
    throw support::UserError("masking = \"" + masking +
                             "\" needs ndf ggx or beckmann (Smith's Lambda has no closed form for phong); "
                             "masking vcavity takes phong");
  w.masking = *g;
  return w;
}

py::dict walter_sample(const std::string& ndf_name, double alpha, const std::optional<DoubleArray>& wi,
                       const std::optional<DoubleArray>& theta_i_deg, DoubleArray u, double eta,
                       const std::string& masking, bool strategy_given, bool max_k_given, const std::string& dim_name,
                       int threads, const py::object& progress) {
  const WalterSettings w = walter_settings(ndf_name, alpha, eta, masking, strategy_given, max_k_given, dim_name);
  validation::check_threads(threads, "threads");
  if (u.ndim() != 2 || u.shape(1) != 3) throw support::UserError("u must be an array of shape (n, 3)");
  const std::size_t n = static_cast<std::size_t>(u.shape(0));
  std::optional<Rows> wi_unit;
  const Light light = light_of(wi, wi_unit, theta_i_deg, n, false);
  check_uniforms(u.data(), n, 3);
  ProgressRelay relay(progress);
  const auto sn = static_cast<py::ssize_t>(n);
  auto wo = new_array<double>({sn, 3});
  auto k = new_array<std::int32_t>({sn});
  auto pdf = new_array<double>({sn});
  auto weight = new_array<double>({sn});
  auto transmitted = new_array<bool>({sn});
  double *po = wo.mutable_data(), *pp = pdf.mutable_data(), *pw = weight.mutable_data();
  std::int32_t* pk = k.mutable_data();
  bool* pt = transmitted.mutable_data();
  const double* pu = u.data();
  for_rows(n, threads, light, relay, false, [&](std::size_t j, LightCursor& cursor) {
    const double* v = pu + 3 * j;
    const analytic::WalterSample x =
        analytic::sample_walter(w.ndf, w.alpha, w.eta, w.masking, cursor.dir(j), v[0], v[1], v[2]);
    // A draw that gives no direction: k 0, pdf and weight 0, wo the normal (its o means nothing).
    const analytic::Dir3 o = x.ok ? x.o : analytic::Dir3{0.0, 0.0, 1.0};
    po[3 * j] = o.x, po[3 * j + 1] = o.y, po[3 * j + 2] = o.z;
    pk[j] = x.ok ? 1 : 0, pp[j] = x.ok ? x.pdf : 0.0, pw[j] = x.ok ? x.weight : 0.0;
    pt[j] = x.ok && x.transmitted;
  });
  py::dict out;
  out["wo"] = wo;
  out["k"] = k;
  out["pdf"] = pdf;
  out["weight"] = weight;
  out["transmitted"] = transmitted;
  return out;
}

// The kaleidoscopic dielectric model's sampler (analytic/sampling_dielectric.h), as `vgroove sample
// --model vgroove-dielectric`: eta in (0, 1000], not 1; the light by theta_i_deg (3d: at azimuth
// 180 deg, [0, 89.9]; flatland signed); u of shape (n, 5) in 3d, (n, 4) in flatland; light_from
// "above" or "below". Returns wo (n x 3, z > 0 above the macrosurface; flatland in the (x, z) plane;
// the normal with no direction), k, weight (1, or 0 with no direction), reflected.
// The kaleidoscopic dielectric sampler's eta and light side, refused as `vgroove sample` refuses them.
void check_dielectric_eta(double eta) {
  if (!(eta > 0.0 && eta <= validation::kMaxFresnelEta && eta != 1.0))
    throw support::UserError("eta = " + support::number_text(eta) + " is out of range " +
                             support::interval_text(0, false, validation::kMaxFresnelEta, true) +
                             ", not 1, with model vgroove-dielectric (at eta = 1 every chain goes straight through: a "
                             "delta, no lobe to sample)");
}
analytic::DielectricLightFrom dielectric_light_from(const std::string& light_from) {
  if (light_from == "below") return analytic::DielectricLightFrom::below;
  if (light_from != "above")
    throw support::UserError("light_from = \"" + light_from + "\" is not one of \"above\", \"below\"");
  return analytic::DielectricLightFrom::above;
}

py::dict dielectric_sample(const std::string& ndf_name, double alpha, double eta,
                           const std::optional<DoubleArray>& theta_i_deg, DoubleArray u, const std::string& dim_name,
                           const std::string& light_from, int threads, const py::object& progress) {
  const NdfKind ndf = sampler_ndf(ndf_name);
  check_alpha(alpha);
  check_dielectric_eta(eta);
  const SurfaceDim dim = parse_dim(dim_name);
  const bool flat = dim == SurfaceDim::flatland;
  analytic::DielectricSamplerOptions opt;
  opt.from = dielectric_light_from(light_from);
  validation::check_threads(threads, "threads");
  const std::size_t m = flat ? 4 : 5;
  if (u.ndim() != 2 || static_cast<std::size_t>(u.shape(1)) != m)
    throw support::UserError(std::string("u must be an array of shape (n, ") + (flat ? "4" : "5") + ")");
  const std::size_t n = static_cast<std::size_t>(u.shape(0));
  std::optional<Rows> wi_unit;
  const Light light = light_of(std::nullopt, wi_unit, theta_i_deg, n, flat);
  check_uniforms(u.data(), n, m);
  ProgressRelay relay(progress);
  const auto sn = static_cast<py::ssize_t>(n);
  auto wo = new_array<double>({sn, 3});
  auto k = new_array<std::int32_t>({sn});
  auto weight = new_array<double>({sn});
  auto reflected = new_array<bool>({sn});
  double *po = wo.mutable_data(), *pw = weight.mutable_data();
  std::int32_t* pk = k.mutable_data();
  bool* pr = reflected.mutable_data();
  const double* pu = u.data();
  const bool below = opt.from == analytic::DielectricLightFrom::below;
  for_rows(n, threads, light, relay, false, [&](std::size_t j, LightCursor&) {
    const double* v = pu + m * j;
    const double ti = light.angle(j);
    if (flat) {
      const analytic::DielectricSampleFlatland x =
          analytic::sample_vgroove_dielectric_flatland(ti, {v[0], v[1], v[2], v[3]}, ndf, alpha, eta, opt);
      // The exit side: above when reflected with the light above, or transmitted with it below;
      // (-sin t, 0, cos t) above and (sin t, 0, -cos t) below (the lobe's angle from that side's normal).
      const double side = (x.reflected != below) ? 1.0 : -1.0;
      const bool ok = x.weight > 0.0;
      po[3 * j] = ok ? -side * std::sin(x.theta_o) : 0.0, po[3 * j + 1] = 0.0;
      po[3 * j + 2] = ok ? side * std::cos(x.theta_o) : 1.0;
      pk[j] = x.k, pw[j] = x.weight, pr[j] = x.weight > 0.0 && x.reflected;
    } else {
      const analytic::DielectricSample3d x =
          analytic::sample_vgroove_dielectric_3d(ti, {v[0], v[1], v[2], v[3], v[4]}, ndf, alpha, eta, opt);
      const analytic::Dir3 o = x.weight > 0.0 ? x.o : analytic::Dir3{0.0, 0.0, 1.0};
      po[3 * j] = o.x, po[3 * j + 1] = o.y, po[3 * j + 2] = o.z;
      pk[j] = x.k, pw[j] = x.weight, pr[j] = x.weight > 0.0 && x.reflected;
    }
  });
  py::dict out;
  out["wo"] = wo;
  out["k"] = k;
  out["weight"] = weight;
  out["reflected"] = reflected;
  return out;
}

// The density of dielectric_sample's directions at wo (analytic/kaleidoscope_dielectric_point.h):
// per steradian in 3D, per radian of theta_o in flatland (wo in the plane y = 0, its angle from the
// exit side's normal as the sampler encodes it); 0 on the horizon.
py::array_t<double> dielectric_pdf(const std::string& ndf_name, double alpha, double eta,
                                   const std::optional<DoubleArray>& theta_i_deg, DoubleArray wo,
                                   const std::string& dim_name, const std::string& light_from, int threads,
                                   const py::object& progress) {
  const NdfKind ndf = sampler_ndf(ndf_name);
  check_alpha(alpha);
  check_dielectric_eta(eta);
  const bool flat = parse_dim(dim_name) == SurfaceDim::flatland;
  analytic::DielectricPointOptions opt;
  opt.from = dielectric_light_from(light_from);
  const bool below = opt.from == analytic::DielectricLightFrom::below;
  validation::check_threads(threads, "threads");
  if (wo.ndim() != 2 || wo.shape(1) != 3) throw support::UserError("wo must be an array of shape (n, 3)");
  const std::size_t n = static_cast<std::size_t>(wo.shape(0));
  std::optional<Rows> wi_unit;
  const Light light = light_of(std::nullopt, wi_unit, theta_i_deg, n, flat);
  wo = unit_directions(wo, "wo", flat);
  ProgressRelay relay(progress);
  auto out = new_array<double>({static_cast<py::ssize_t>(n)});
  double* po = out.mutable_data();
  const double* pw = wo.data();
  for_rows(n, threads, light, relay, false, [&](std::size_t j, LightCursor&) {
    const double* o = pw + 3 * j;
    const double ti = light.angle(j);
    if (o[2] == 0.0) {
      po[j] = 0.0;
    } else if (flat) {
      // dielectric_sample's encoding: (-sin t, 0, cos t) above, (sin t, 0, -cos t) below.
      const bool above = o[2] > 0.0;
      const double t = above ? std::atan2(-o[0], o[2]) : std::atan2(o[0], -o[2]);
      po[j] = analytic::kaleidoscope_dielectric_pdf_flatland(ndf, alpha, eta, ti, t, above != below, opt);
    } else {
      analytic::Dir3 i = analytic::dir3(ti, std::numbers::pi);  // the sampler's light, mirrored from below
      if (below) i.z = -i.z;
      po[j] = analytic::kaleidoscope_dielectric_pdf_3d(ndf, alpha, eta, i, analytic::Dir3{o[0], o[1], o[2]}, opt);
    }
  });
  return out;
}

py::array_t<double> walter_pdf(const std::string& ndf_name, double alpha, const std::optional<DoubleArray>& wi,
                               const std::optional<DoubleArray>& theta_i_deg, DoubleArray wo, double eta,
                               const std::string& masking, bool strategy_given, bool max_k_given,
                               const std::string& dim_name, int threads, const py::object& progress) {
  const WalterSettings w = walter_settings(ndf_name, alpha, eta, masking, strategy_given, max_k_given, dim_name);
  validation::check_threads(threads, "threads");
  if (wo.ndim() != 2 || wo.shape(1) != 3) throw support::UserError("wo must be an array of shape (n, 3)");
  const std::size_t n = static_cast<std::size_t>(wo.shape(0));
  std::optional<Rows> wi_unit;
  const Light light = light_of(wi, wi_unit, theta_i_deg, n, false);
  wo = unit_directions(wo, "wo", false);
  ProgressRelay relay(progress);
  auto out = new_array<double>({static_cast<py::ssize_t>(n)});
  double* po = out.mutable_data();
  const double* pw = wo.data();
  for_rows(n, threads, light, relay, false, [&](std::size_t j, LightCursor& cursor) {
    const double* o = pw + 3 * j;
    po[j] = analytic::walter_pdf(w.ndf, w.alpha, w.eta, cursor.dir(j), analytic::Dir3{o[0], o[1], o[2]});
  });
  return out;
}

// n x dims uniform numbers in [0, 1), row after row, from the stream sim::Rng(seed, a, b): what
// vgroove's Monte Carlo draws (e.g. `vgroove sample`: a = 0x5a3d, b = 0 in 3D, 1 in flatland, four
// per sample).
py::array_t<double> uniforms(const py::object& n_obj, const py::object& seed_obj, const py::object& a_obj,
                             const py::object& b_obj, const py::object& dims_obj) {
  const auto n = static_cast<std::size_t>(to_count(n_obj, "n", 0, validation::kMaxRays));
  const auto dims = static_cast<std::size_t>(to_count(dims_obj, "dims", 1, 64));
  const auto seed = static_cast<std::uint64_t>(to_seed(seed_obj, "seed"));
  const auto a = static_cast<std::uint64_t>(to_seed(a_obj, "stream[0]"));
  const auto b = static_cast<std::uint64_t>(to_seed(b_obj, "stream[1]"));
  auto out = new_array<double>({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(dims)});
  double* p = out.mutable_data();
  run_interruptible(
      [&](std::atomic<bool>& cancel) {
        sim::Rng rng(seed, a, b);
        for (std::size_t j = 0; j < n * dims; ++j) {
          if ((j & 0xfffff) == 0 && cancel.load()) break;
          p[j] = rng.uniform();
        }
        return 0;
      },
      n * dims < 1'000'000);
  return out;
}

}  // namespace

void bind_sampling(py::module_& m) {
  m.def("sample", &sample, py::arg("model"), py::arg("ndf"), py::arg("alpha"), py::arg("wi"), py::arg("theta_i_deg"),
        py::arg("u"), py::arg("strategy"), py::arg("max_k"), py::arg("tolerance"), py::arg("dim"), py::arg("threads"),
        py::arg("eta") = py::none(), py::arg("progress") = py::none());
  m.def("pdf", &pdf, py::arg("model"), py::arg("ndf"), py::arg("alpha"), py::arg("wi"), py::arg("theta_i_deg"),
        py::arg("wo"), py::arg("strategy"), py::arg("max_k"), py::arg("tolerance"), py::arg("dim"), py::arg("threads"),
        py::arg("progress") = py::none());
  m.def("walter_sample", &walter_sample, py::arg("ndf"), py::arg("alpha"), py::arg("wi"), py::arg("theta_i_deg"),
        py::arg("u"), py::arg("eta"), py::arg("masking"), py::arg("strategy_given"), py::arg("max_k_given"),
        py::arg("dim"), py::arg("threads"), py::arg("progress") = py::none());
  m.def("walter_pdf", &walter_pdf, py::arg("ndf"), py::arg("alpha"), py::arg("wi"), py::arg("theta_i_deg"),
        py::arg("wo"), py::arg("eta"), py::arg("masking"), py::arg("strategy_given"), py::arg("max_k_given"),
        py::arg("dim"), py::arg("threads"), py::arg("progress") = py::none());
  m.def("dielectric_pdf", &dielectric_pdf, py::arg("ndf"), py::arg("alpha"), py::arg("eta"), py::arg("theta_i_deg"),
        py::arg("wo"), py::arg("dim"), py::arg("light_from") = "above", py::arg("threads") = 0,
        py::arg("progress") = py::none());
  m.def("dielectric_sample", &dielectric_sample, py::arg("ndf"), py::arg("alpha"), py::arg("eta"),
        py::arg("theta_i_deg"), py::arg("u"), py::arg("dim"), py::arg("light_from") = "above", py::arg("threads") = 0,
        py::arg("progress") = py::none());
  // The samplers' default max_k (analytic/sampling_3d.h, analytic/sampling_nonsymmetric.h).
  m.attr("SAMPLER_MAX_K") = analytic::kSamplerMaxK;
  m.attr("NONSYMMETRIC_SAMPLER_MAX_K") = analytic::kNonsymmetricSamplerMaxK;
  m.def("uniforms", &uniforms, py::arg("n"), py::arg("seed"), py::arg("a"), py::arg("b"), py::arg("dims"));
}

}  // namespace vgroove::python
