#include "vgroove/validation/check_bsdf.h"

#include "vgroove/sim/beam.h"
#include "vgroove/sim/dielectric_lifted.h"
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/seconds_since.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/case_surface.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/lobe_comparison.h"
#include "vgroove/validation/ranges.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::validation {

namespace {

constexpr double kPi = std::numbers::pi;
// The rays' streams: apart from the conductor check's and the energy tables'.
constexpr std::uint64_t kCheckBsdfRays = 0x6362736466ULL;  // "cbsdf"

// The traced surface: the conductor check's grooves for the same seed (make_case_surface), as a
// flatland surface whose cross-sections the dielectric tracer reads (in 3D the 3D law's theta_m).
sim::Microsurface bsdf_surface(const CheckBrdfOptions& o) {
  CaseSurface cs = make_case_surface(o.dim, o.ndf, o.alpha, o.grooves, o.seed);
  if (o.dim == SurfaceDim::flatland) return std::move(cs.flat);
  sim::Microsurface m;
  m.options.ndf = o.ndf, m.options.alpha = o.alpha, m.options.grooves = o.grooves, m.options.seed = o.seed;
  m.theta_m = std::move(cs.three_d.theta_m);
  m.grooves = std::move(cs.three_d.grooves);
  m.data = std::move(cs.three_d.data);
  return m;
}

// Per-hemisphere bin layout (check_brdf's): its bin of an exit, or -1 outside every bin.
struct HemisphereBins {
  SurfaceDim dim;
  int theta_bins, phi_bins, flatland_bins;
  int bins() const { return dim == SurfaceDim::flatland ? flatland_bins : theta_bins * phi_bins; }
  // Flatland: the signed exit angle from the exit side's normal (sim::exit_angle).
  int flat_bin(double angle) const {
    const int b = static_cast<int>(std::floor((angle + 0.5 * kPi) / (kPi / flatland_bins)));
    return std::clamp(b, 0, flatland_bins - 1);
  }
  // 3D: theta from the exit side's normal, phi = atan2(y, x), bins centred on phi = 0.
  int bin3(const sim::Vec3& o) const {
    const double theta = std::atan2(std::hypot(o.x(), o.y()), std::abs(o.z()));
    const int t = std::min(theta_bins - 1, static_cast<int>(theta / (0.5 * kPi / theta_bins)));
    const double dp = 2.0 * kPi / phi_bins;
    int p = static_cast<int>(std::floor((std::atan2(o.y(), o.x()) + 0.5 * dp) / dp)) % phi_bins;
    if (p < 0) p += phi_bins;
    return t * phi_bins + p;
  }
};

// Rays [chunk * kRaysPerChunk, ...) of incidence c: counts per bin of both hemispheres.
void trace_chunk(const CheckBrdfOptions& o, const sim::Microsurface& surface,
                 const sim::DielectricSurfaceTracer& tracer, double theta_i, std::size_t c, std::int64_t chunk,
                 const HemisphereBins& hb, std::vector<std::int64_t>& counts, std::int64_t& rays) {
  const double st = std::sin(theta_i), ct = std::cos(theta_i);
  const bool above = o.side == sim::Medium::above;
  const double groove_count = static_cast<double>(surface.grooves.size());
  const int last = static_cast<int>(surface.grooves.size()) - 1;
  const std::size_t B = static_cast<std::size_t>(hb.bins());
  sim::Rng rng(o.seed, kCheckBsdfRays + c, static_cast<std::uint64_t>(chunk));
  const std::int64_t n = std::min<std::int64_t>(sim::kRaysPerChunk, o.rays - chunk * sim::kRaysPerChunk);
  sim::DielectricResult r;
  for (std::int64_t j = 0; j < n; ++j) {
    // The lit point: a groove and a place across its opening (above), or a place in the period (below).
    const double x = sim::uniform_open(rng) * groove_count;
    const int gi = std::min(last, static_cast<int>(x));
    const sim::Groove& groove = surface.grooves[static_cast<std::size_t>(gi)];
    const double xl = groove.rim_x(sim::Side::left), xr = groove.rim_x(sim::Side::right);
    const double x_open = xl + (x - gi) * (xr - xl);
    // The light travels along +x (it sits at azimuth pi), down from above or up from below.
    if (o.dim == SurfaceDim::flatland) {
      if (above)
        tracer.trace_from_above(gi, sim::beam_ray(groove, sim::Vec2(st, -ct), x_open), rng, r);
      else
        tracer.trace_from_below(x, sim::Vec2(st, ct), rng, r);
      if (!r.exits.empty()) {
        const sim::DielectricExit& e = r.exits.front();
        counts[(e.side == sim::Medium::above ? 0 : B) + static_cast<std::size_t>(hb.flat_bin(sim::exit_angle(e)))] += 1;
      }
    } else {
      const double phi_a = kPi * rng.uniform();  // the patch's grooves' azimuth
      const sim::GrooveFrame3d frame{std::cos(phi_a), std::sin(phi_a)};
      const sim::Vec3 d(st, 0.0, above ? -ct : ct);
      const sim::LiftedRay ray = sim::lift_ray(d, frame, o.side, tracer.options());
      if (above)
        tracer.trace_from_above_with(gi, sim::beam_ray(groove, ray.e, x_open), ray.law, rng, r);
      else
        tracer.trace_from_below_with(x, ray.e, ray.law, rng, r);
      if (!r.exits.empty()) {
        const sim::DielectricExit& e = r.exits.front();
        const sim::Vec3 out = sim::lift_exit(ray, frame, e.dir, e.side);
        counts[(e.side == sim::Medium::above ? 0 : B) + static_cast<std::size_t>(hb.bin3(out))] += 1;
      }
    }
    ++rays;
  }
}

// One lobe of albedo a (R or T): its flux fractions s_b of all N rays are multinomial over the
// rays and a mixture over the G grooves, as the conductor's (validation/histogram_metrics.h:
// variance p_b (1 - p_b) (1/N + 1/G)), and so is its albedo (binomial). Its normalized lobe
// q_b = s_b / a rests on the a N rays that left on its side: variance q (1 - q) / (a N) from the
// rays and at most q (1 - a q) / (a G) from the grooves (Var(s_b) / a^2 with p_b = a q_b), its
// L1 against the mean sum sqrt(2 v / pi) + sigmas sd, the tolerance scaled by 1 / a likewise.
CheckLobeSide side_of(const char* lobe, const std::vector<double>& sim, const std::vector<double>& model, double rays,
                      const CheckBrdfOptions& o, double tolerance, const HemisphereBins& hb) {
  const CheckBrdfCase c = check_lobes(sim, model, rays, o.grooves, o.sigmas, tolerance);
  CheckLobeSide s;
  s.lobe = lobe;
  s.albedo_sim = c.albedo_sim, s.albedo_model = c.albedo_model, s.albedo_threshold = c.albedo_threshold;
  const double a = std::clamp(c.albedo_model, 0.0, 1.0);
  s.albedo_sd = std::sqrt(a * (1.0 - a) * (1.0 / rays + 1.0 / o.grooves));
  s.l1_flux = c.l1_flux, s.l1_flux_expected = c.l1_flux_expected, s.l1_flux_threshold = c.l1_flux_threshold;
  s.l1 = c.l1;
  double mean = 0.0, var = 0.0;
  if (a > 0.0) {
    for (double q : normalized(model)) {
      q = std::clamp(q, 0.0, 1.0);
      const double v = q * (1.0 - q) / (a * rays) + q * (1.0 - a * q) / (a * o.grooves);
      mean += std::sqrt(2.0 * v / kPi), var += (1.0 - 2.0 / kPi) * v;
    }
  }
  s.l1_expected = mean;
  s.l1_threshold = mean + o.sigmas * std::sqrt(var) + (a > 0.0 ? tolerance / a : tolerance);
  s.worst = worst_bins(sim, model, hb.dim, hb.theta_bins, hb.phi_bins, hb.flatland_bins);
  for (WorstBin& w : s.worst) w.lobe = lobe;
  s.pass = !c.non_finite && std::isfinite(s.l1) && s.l1 <= s.l1_threshold && s.l1_flux <= s.l1_flux_threshold &&
           std::abs(s.albedo_sim - s.albedo_model) <= s.albedo_threshold;
  return s;
}

}  // namespace

void check_bsdf_options(const CheckBrdfOptions& o) {
  if (o.eta == 0.0) return;
  if (!(o.eta >= kMinGlassEta && o.eta <= kMaxGlassEta && o.eta != 1.0))
    throw support::UserError("eta = " + support::number_text(o.eta) + " is out of range " +
                             support::interval_text(kMinGlassEta, true, kMaxGlassEta, true) +
                             ", not 1 (0: the conductor check)");
  if (o.side != sim::Medium::above && o.side != sim::Medium::below)
    throw support::UserError("side = " + std::to_string(static_cast<int>(o.side)) + " is not above or below");
  if (o.surface != CheckSurface::vgroove)
    throw support::UserError(std::string("surface = ") + check_surface_name(o.surface) +
                             ": with eta the traced surface is the dielectric V-groove surface (surface vgroove)");
}

analytic::Dir3 bsdf_light(double theta_i, sim::Medium side) {
  analytic::Dir3 wi = analytic::dir3(theta_i, kPi);
  if (side == sim::Medium::below) wi.z = -wi.z;
  return wi;
}

std::vector<TracedLobe> trace_bsdf_lobes(const CheckBrdfOptions& o, const std::vector<double>& theta_i, int threads) {
  const sim::Microsurface surface = bsdf_surface(o);
  sim::DielectricOptions dopt;
  dopt.eta = o.eta;
  dopt.branching = sim::Branching::random;  // one exit per ray: the rays are multinomial over the bins
  const sim::DielectricSurfaceTracer tracer(surface, dopt);
  const HemisphereBins hb{o.dim, o.theta_bins, o.phi_bins, o.flatland_bins};
  const std::size_t bins = 2 * static_cast<std::size_t>(hb.bins());
  const std::int64_t chunks = (static_cast<std::int64_t>(o.rays) + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
  const std::size_t items = theta_i.size() * static_cast<std::size_t>(chunks);
  std::vector<std::vector<std::int64_t>> counts(items);
  std::vector<std::int64_t> rays(items, 0);
  std::vector<double> secs(items, 0.0);
  const bool complete = support::parallel_for(
      items, support::resolve_threads(threads),
      [&](std::size_t item) {
        const auto t0 = support::Clock::now();
        const std::size_t c = item / static_cast<std::size_t>(chunks);
        counts[item].assign(bins, 0);
        trace_chunk(o, surface, tracer, theta_i[c], c, static_cast<std::int64_t>(item % chunks), hb, counts[item],
                    rays[item]);
        secs[item] = support::seconds_since(t0);
      },
      {}, o.cancel, 1);
  if (!complete || support::cancelled(o.cancel)) return {};
  std::vector<TracedLobe> out(theta_i.size());
  for (std::size_t c = 0; c < theta_i.size(); ++c) {
    std::vector<std::int64_t> sum(bins, 0);
    for (std::int64_t k = 0; k < chunks; ++k) {
      const std::size_t item = c * static_cast<std::size_t>(chunks) + static_cast<std::size_t>(k);
      for (std::size_t b = 0; b < bins; ++b) sum[b] += counts[item][b];
      out[c].rays += rays[item];
      out[c].thread_s += secs[item];
    }
    out[c].flux = fractions(sum, static_cast<double>(out[c].rays));
  }
  return out;
}

CheckBrdfCase check_bsdf_lobes(const std::vector<double>& sim, const std::vector<double>& model, double rays,
                               const CheckBrdfOptions& o, double tolerance) {
  const HemisphereBins hb{o.dim, o.theta_bins, o.phi_bins, o.flatland_bins};
  const auto B = static_cast<std::ptrdiff_t>(hb.bins());
  const std::vector<double> sim_up(sim.begin(), sim.begin() + B), sim_down(sim.begin() + B, sim.end());
  const std::vector<double> model_up(model.begin(), model.begin() + B), model_down(model.begin() + B, model.end());
  const bool above = o.side == sim::Medium::above;
  // Both hemispheres as one lobe: the total albedo R + T and the shape over all 2 B bins.
  CheckBrdfCase c = check_lobes(sim, model, rays, o.grooves, o.sigmas, tolerance);
  c.lobes.push_back(
      side_of("reflected", above ? sim_up : sim_down, above ? model_up : model_down, rays, o, tolerance, hb));
  c.lobes.push_back(
      side_of("transmitted", above ? sim_down : sim_up, above ? model_down : model_up, rays, o, tolerance, hb));
  // The worst bins over both, each named by its lobe.
  for (const CheckLobeSide& s : c.lobes) c.worst.insert(c.worst.end(), s.worst.begin(), s.worst.end());
  std::stable_sort(c.worst.begin(), c.worst.end(), [](const WorstBin& a, const WorstBin& b) {
    return std::abs(a.sim - a.model) > std::abs(b.sim - b.model);
  });
  c.worst.resize(std::min<std::size_t>(c.worst.size(), 5));
  for (const CheckLobeSide& s : c.lobes) c.pass = c.pass && s.pass;
  return c;
}

}  // namespace vgroove::validation
