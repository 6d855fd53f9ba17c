#include "vgroove/validation/check_brdf.h"
#include "vgroove/support/seconds_since.h"
#include "vgroove/validation/check_bsdf.h"
#include "vgroove/validation/lobe_comparison.h"

#include "vgroove/analytic/quadrature.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/heightfield_lobe.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/traced_lobe.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <queue>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;

constexpr double kPi = std::numbers::pi;
constexpr int kWorstBins = 5;

void check_range(bool ok, const std::string& what, double v, const std::string& range) {
  if (!ok) throw support::UserError(what + " = " + support::number_text(v) + " is out of range " + range);
}

// The user's model integrated over the bins, globally adaptive: every bin starts as one cell; a
// cell's value is the Gauss-Legendre rule on its four quarters (two halves in flatland) and its
// error estimate the difference from the rule on the whole cell. The cell with the largest
// estimate is split until the estimates sum to at most `tolerance` or `max_evals` evaluations
// are spent. A model's discontinuities (the support of a bounce order ending) and integrable
// peaks (1/sin(theta_h) at the mirror direction) are resolved where they are, not everywhere.
struct Cell {
  std::size_t bin;
  double t0, t1, p0, p1;       // theta and phi ranges (flatland: the signed angle, p unused)
  std::array<double, 4> part;  // the rule on each quarter (half)
  double value, err;
  bool operator<(const Cell& o) const { return err < o.err; }
};

// A value of the model that is not a BRDF's (NaN, an infinity or below 0), thrown by the first
// rule that meets one: the check fails there, naming the directions and the value.
struct BadModelValue {
  std::string message;
};

std::string vector_text(const double* v) {
  return "(" + support::number_text(v[0]) + ", " + support::number_text(v[1]) + ", " + support::number_text(v[2]) + ")";
}

class BinIntegrator {
 public:
  // side_bins: the bins of the hemisphere above; a bin past them is below (check_bsdf.h: theta
  // from -n, wo.z < 0; flatland wo = (sin theta, 0, -cos theta), sim::exit_angle's), for a BSDF.
  BinIntegrator(const BrdfBatchFn& f, const analytic::Dir3& wi, bool flat, const analytic::GaussLegendre& g,
                double theta_i_deg, std::size_t side_bins, bool bsdf)
      : f_(f), wi_(wi), flat_(flat), g_(g), theta_i_deg_(theta_i_deg), side_bins_(side_bins), bsdf_(bsdf) {}

  // The rule on [t0, t1] x [p0, p1]: f(wi, wo) cos(theta) sin(theta) (3D) or f cos(theta) (flatland).
  // The nodes' values come from one batch call, then are summed in node order.
  double rule(double t0, double t1, double p0, double p1, bool below = false) {
    const double ht = 0.5 * (t1 - t0), hp = 0.5 * (p1 - p0);
    const std::size_t m = g_.size(), nodes = flat_ ? m : m * m;
    wis_.resize(3 * nodes), wos_.resize(3 * nodes), vals_.resize(nodes);
    for (std::size_t a = 0, j = 0; a < m; ++a) {
      const double theta = t0 + ht * (1.0 + g_.x[a]);
      for (std::size_t b = 0; b < (flat_ ? 1 : m); ++b, ++j) {
        analytic::Dir3 wo = flat_ ? analytic::Dir3{-std::sin(theta), 0.0, std::cos(theta)}
                                  : analytic::dir3(theta, p0 + hp * (1.0 + g_.x[b]));
        if (below) wo.z = -wo.z, wo.x = flat_ ? -wo.x : wo.x;
        wis_[3 * j] = wi_.x, wis_[3 * j + 1] = wi_.y, wis_[3 * j + 2] = wi_.z;
        wos_[3 * j] = wo.x, wos_[3 * j + 1] = wo.y, wos_[3 * j + 2] = wo.z;
      }
    }
    f_(wis_.data(), wos_.data(), nodes, vals_.data());
    evals += static_cast<std::int64_t>(nodes);
    // A BRDF is a density of reflected radiance: finite and non-negative (-0 included). Anything
    // else fails the check here, before the bins are integrated or the surface traced.
    for (std::size_t j = 0; j < nodes; ++j)
      if (!(vals_[j] >= 0.0 && vals_[j] <= std::numeric_limits<double>::max()))
        throw BadModelValue{"f(wi, wo) = " + support::number_text(vals_[j]) + " at wi = " + vector_text(&wis_[3 * j]) +
                            ", wo = " + vector_text(&wos_[3 * j]) + " (theta_i_deg " +
                            support::number_text(theta_i_deg_) + (bsdf_ ? "): a BSDF's" : "): a BRDF's") +
                            " values must be finite and >= 0"};
    double s = 0.0;
    for (std::size_t a = 0, j = 0; a < m; ++a) {
      const double theta = t0 + ht * (1.0 + g_.x[a]);
      if (flat_) {
        s += g_.w[a] * vals_[j++] * std::cos(theta);
        continue;
      }
      double row = 0.0;
      for (std::size_t b = 0; b < m; ++b) row += g_.w[b] * vals_[j++];
      s += g_.w[a] * row * std::cos(theta) * std::sin(theta);
    }
    return flat_ ? s * ht : s * ht * hp;
  }

  Cell make(std::size_t bin, double t0, double t1, double p0, double p1, double coarse) {
    Cell c{bin, t0, t1, p0, p1, {}, 0.0, 0.0};
    const double tm = 0.5 * (t0 + t1), pm = 0.5 * (p0 + p1);
    const bool d = bin >= side_bins_;
    if (flat_) {
      c.part = {rule(t0, tm, p0, p1, d), rule(tm, t1, p0, p1, d), 0.0, 0.0};
    } else {
      c.part = {rule(t0, tm, p0, pm, d), rule(tm, t1, p0, pm, d), rule(t0, tm, pm, p1, d), rule(tm, t1, pm, p1, d)};
    }
    c.value = c.part[0] + c.part[1] + c.part[2] + c.part[3];
    c.err = std::abs(c.value - coarse);
    if (!std::isfinite(c.err)) c.err = std::numeric_limits<double>::max();  // refine what is not finite
    return c;
  }

  void split(const Cell& c, std::vector<Cell>& out) {
    const double tm = 0.5 * (c.t0 + c.t1), pm = 0.5 * (c.p0 + c.p1);
    if (flat_) {
      out.push_back(make(c.bin, c.t0, tm, c.p0, c.p1, c.part[0]));
      out.push_back(make(c.bin, tm, c.t1, c.p0, c.p1, c.part[1]));
      return;
    }
    out.push_back(make(c.bin, c.t0, tm, c.p0, pm, c.part[0]));
    out.push_back(make(c.bin, tm, c.t1, c.p0, pm, c.part[1]));
    out.push_back(make(c.bin, c.t0, tm, pm, c.p1, c.part[2]));
    out.push_back(make(c.bin, tm, c.t1, pm, c.p1, c.part[3]));
  }

  std::int64_t evals = 0;

 private:
  const BrdfBatchFn& f_;
  analytic::Dir3 wi_;
  bool flat_;
  const analytic::GaussLegendre& g_;
  double theta_i_deg_;
  std::size_t side_bins_;
  bool bsdf_;
  std::vector<double> wis_, wos_, vals_;
};

// Whether a case's integration stops early: Ctrl-C, or an earlier case (in the options' order)
// met a value that is not a BRDF's (its error is the one reported, whatever the thread count).
struct CaseStop {
  const std::atomic<bool>* cancel;
  const std::atomic<std::size_t>* first_bad;
  std::size_t c;
  bool operator()() const { return support::cancelled(cancel) || first_bad->load(std::memory_order_relaxed) < c; }
};

ModelLobe model_bins(const BrdfBatchFn& f, double theta_i_deg, const CheckBrdfOptions& o,
                     const analytic::GaussLegendre& g, const CaseStop& stop) {
  const bool flat = o.dim == SurfaceDim::flatland;
  const std::size_t side_bins = flat ? static_cast<std::size_t>(o.flatland_bins)
                                     : static_cast<std::size_t>(o.theta_bins) * static_cast<std::size_t>(o.phi_bins);
  const bool bsdf = o.eta != 0.0;  // both hemispheres' bins, the light on o.side (check_bsdf.h)
  BinIntegrator in(f, bsdf_light(deg_to_rad(theta_i_deg), bsdf ? o.side : sim::Medium::above), flat, g, theta_i_deg,
                   side_bins, bsdf);
  std::priority_queue<Cell> cells;
  double err = 0.0;
  // The first pass calls f five times per bin (three in flatland; up to 5 x 10^6 calls, a Python
  // callback each, or 70 ms of a flatland sum at max_k 1024): the stop is read before each bin.
  for (std::size_t h = 0; h < (bsdf ? 2u : 1u); ++h) {
    const std::size_t first = h * side_bins;
    const bool below = h == 1;
    if (flat) {
      const double w = kPi / o.flatland_bins;
      for (int b = 0; b < o.flatland_bins; ++b) {
        if (stop()) break;
        const double t0 = -0.5 * kPi + b * w, t1 = t0 + w;
        cells.push(in.make(first + static_cast<std::size_t>(b), t0, t1, 0.0, 0.0, in.rule(t0, t1, 0.0, 0.0, below)));
      }
    } else {
      const double dt = 0.5 * kPi / o.theta_bins, dp = 2.0 * kPi / o.phi_bins;
      for (int t = 0; t < o.theta_bins; ++t)
        for (int p = 0; p < o.phi_bins; ++p) {
          if (stop()) break;
          const double t0 = t * dt, t1 = t0 + dt, p0 = p * dp - 0.5 * dp, p1 = p0 + dp;
          cells.push(in.make(first + static_cast<std::size_t>(t) * o.phi_bins + p, t0, t1, p0, p1,
                             in.rule(t0, t1, p0, p1, below)));
        }
    }
  }
  std::vector<Cell> children;
  double total = 0.0;  // the running sum of the estimates (summed afresh at the end)
  for (auto q = cells; !q.empty(); q.pop()) total += q.top().err;
  while (total > o.model_tolerance && in.evals < o.max_model_evals) {
    if (stop()) break;
    const Cell c = cells.top();
    cells.pop();
    total -= c.err;
    children.clear();
    in.split(c, children);
    for (Cell& ch : children) {
      total += ch.err;
      cells.push(std::move(ch));
    }
  }
  ModelLobe out;
  out.flux.assign(bsdf ? 2 * side_bins : side_bins, 0.0);
  while (!cells.empty()) {
    out.flux[cells.top().bin] += cells.top().value;
    err += cells.top().err;
    cells.pop();
  }
  out.error = err;
  out.evals = in.evals;
  return out;
}

// The heightfields' lobes at every incidence: field by field (one in memory at a time), each
// field's rays cut into chunks traced as items (incidence, chunk) on the threads; the counts per
// field pooled by pool_fields. The same lobes for any thread count; empty when *cancel was set.
std::vector<TracedLobe> trace_heightfield_lobes(const CheckBrdfOptions& o, const std::vector<double>& theta_i,
                                                int threads, std::vector<FieldLobe>& pooled) {
  const std::size_t cases = theta_i.size();
  const std::size_t bins = static_cast<std::size_t>(o.theta_bins) * static_cast<std::size_t>(o.phi_bins);
  std::vector<TracedLobe> out(cases);
  // Per case, per field: its counts per bin and its rays.
  std::vector<std::vector<std::vector<std::int64_t>>> counts(cases);
  std::vector<std::vector<std::int64_t>> rays(cases);
  for (int r = 0; r < o.fields; ++r) {
    const sim::HeightfieldSurface s = check_field(o, r);
    std::vector<sim::HeightfieldTraceOptions> to(cases);
    for (std::size_t c = 0; c < cases; ++c) to[c] = check_field_trace(o, theta_i[c], c, r);
    const std::int64_t chunks = sim::heightfield_chunk_count(to[0]);
    const std::size_t items = cases * static_cast<std::size_t>(chunks);
    std::vector<sim::HeightfieldTally> tallies(items);
    std::vector<double> secs(items, 0.0);
    const bool complete = support::parallel_for(
        items, threads,
        [&](std::size_t item) {
          const auto t0 = Clock::now();
          const std::size_t c = item / static_cast<std::size_t>(chunks);
          tallies[item] = sim::trace_heightfield_chunk(s, to[c], static_cast<std::int64_t>(item % chunks));
          secs[item] = seconds_since(t0);
        },
        {}, o.cancel, 1);
    if (!complete || support::cancelled(o.cancel)) return {};
    for (std::size_t c = 0; c < cases; ++c) counts[c].emplace_back(bins, 0), rays[c].push_back(0);
    for (std::size_t item = 0; item < items; ++item) {
      const std::size_t c = item / static_cast<std::size_t>(chunks);
      rays[c].back() += add_field_counts(tallies[item], counts[c].back());
      out[c].thread_s += secs[item];
    }
  }
  pooled.clear();
  for (std::size_t c = 0; c < cases; ++c) {
    pooled.push_back(pool_fields(counts[c], rays[c]));
    out[c].flux = pooled.back().flux, out[c].rays = pooled.back().rays;
  }
  return out;
}

}  // namespace

void check_options(const CheckBrdfOptions& o) {
  // Each range from validation/ranges.h, the one table every face reads.
  const auto within = [](double v, double lo, bool lo_closed, double hi, bool hi_closed, const char* what) {
    const bool ok = (lo_closed ? v >= lo : v > lo) && (hi_closed ? v <= hi : v < hi);
    check_range(ok, what, v, support::interval_text(lo, lo_closed, hi, hi_closed));
  };
  within(o.alpha, kMinAlpha, true, kMaxAlpha, true, "alpha");
  if (o.theta_i_deg.empty()) throw support::UserError("theta_i_deg: give at least one incident angle");
  for (double t : o.theta_i_deg) within(t, 0.0, true, kMaxSurfaceThetaIDeg, true, "theta_i_deg");
  within(static_cast<double>(o.rays), 1, true, static_cast<double>(kMaxRays), true, "rays");
  within(o.grooves, 1, true, kMaxGrooves, true, "grooves");
  within(o.theta_bins, 1, true, kMaxCheckBrdfThetaBins, true, "theta_bins");
  check_range(o.phi_bins >= 2 && o.phi_bins <= kMaxCheckBrdfPhiBins && o.phi_bins % 2 == 0, "phi_bins", o.phi_bins,
              support::interval_text(2, true, kMaxCheckBrdfPhiBins, true) + ", even");
  within(o.flatland_bins, 1, true, kMaxFlatlandBins, true, "flatland_bins");
  within(o.sigmas, 0.0, false, kMaxSigmas, true, "sigmas");
  within(o.model_tolerance, 0.0, true, 1.0, true, "model_tolerance");
  within(o.quadrature_order, 1, true, kMaxGaussLegendreOrder, true, "quadrature_order");
  check_range(o.max_model_evals >= 1, "max_model_evals", static_cast<double>(o.max_model_evals), "[1, 2^63)");
  within(o.threads, 0, true, kMaxThreads, true, "threads");
  if (o.surface == CheckSurface::heightfield) {
    if (o.dim != SurfaceDim::three_d)
      throw support::UserError("dim = flatland: surface heightfield is a 3D surface (dim 3d)");
    if (o.ndf != NdfKind::beckmann && o.ndf != NdfKind::ggx)
      throw support::UserError(std::string("ndf = ") + ndf_name(o.ndf) +
                               ": surface heightfield takes beckmann or ggx (the fields' slope laws)");
    check_range(o.field_size >= 16 && o.field_size <= 65536 && (o.field_size & (o.field_size - 1)) == 0, "field_size",
                o.field_size, "[16, 65536], a power of two");
    within(o.correlation_length, 2.0, true, o.field_size / 8.0, true, "correlation_length");
    within(o.fields, 2, true, std::min<double>(1000.0, static_cast<double>(o.rays)), true, "fields");
    // One field in memory at a time, traced by every thread.
    check_field_fits(o.field_size, 1.0, "field_size", 16);
  }
  check_bsdf_options(o);
}

ModelLobe integrate_model_lobe(const BrdfBatchFn& f, double theta_i_deg, const CheckBrdfOptions& opt) {
  check_options(opt);
  const std::atomic<std::size_t> first_bad{1};
  try {
    ModelLobe m = model_bins(f, theta_i_deg, opt, analytic::gauss_legendre(opt.quadrature_order),
                             CaseStop{opt.cancel, &first_bad, 0});
    return support::cancelled(opt.cancel) ? ModelLobe{} : m;
  } catch (const BadModelValue& e) {
    throw support::UserError(e.message);
  }
}

CheckBrdfCase check_lobes(const std::vector<double>& sim, const std::vector<double>& model, double rays, double grooves,
                          double sigmas, double model_tolerance) {
  CheckBrdfCase c;
  c.albedo_sim = sum(sim);
  c.albedo_model = sum(model);
  c.non_finite = !all_finite(model) || std::any_of(model.begin(), model.end(), [](double v) { return v < 0.0; });
  const LobeComparison lc =
      compare_lobes(sim, model, static_cast<int>(sim.size()), rays, grooves, sigmas, model_tolerance);
  c.l1 = lc.shape.l1, c.l1_expected = lc.shape.expected, c.l1_threshold = lc.shape.threshold;
  c.l1_flux = lc.joint.l1, c.l1_flux_expected = lc.joint.expected, c.l1_flux_threshold = lc.joint.threshold;
  c.albedo_threshold = albedo_threshold(c.albedo_model, rays, grooves, sigmas, model_tolerance);
  c.pass = !c.non_finite && std::isfinite(c.l1) && lc.shape.holds() && lc.joint.holds() &&
           std::abs(c.albedo_sim - c.albedo_model) <= c.albedo_threshold;
  return c;
}

// Field r's and its rays' seeds: streams of opt.seed apart from the V-groove surface's.
constexpr std::uint64_t kCheckFieldSeeds = 0x63626866ULL, kCheckRaySeeds = 0x63627261ULL;

sim::HeightfieldSurface check_field(const CheckBrdfOptions& o, int r) {
  const HeightfieldFieldSpec spec{o.ndf, o.alpha, o.field_size, o.correlation_length};
  return make_field_surface(spec, sim::Rng(o.seed, kCheckFieldSeeds, static_cast<std::uint64_t>(r)).next_u64());
}

sim::HeightfieldTraceOptions check_field_trace(const CheckBrdfOptions& o, double theta_i, std::size_t c, int r) {
  sim::HeightfieldTraceOptions to;
  to.theta_i = theta_i, to.phi_i = kPi, to.rays = o.rays / o.fields + (r < o.rays % o.fields ? 1 : 0);
  to.seed = sim::Rng(o.seed, kCheckRaySeeds, static_cast<std::uint64_t>(r) * 65536 + c).next_u64();
  to.theta_bins = o.theta_bins, to.phi_bins = o.phi_bins, to.max_k = 0;
  return to;
}

std::int64_t add_field_counts(const sim::HeightfieldTally& t, std::vector<std::int64_t>& counts) {
  // Rows k = 0 (none: every ray meets the field) and k >= 1, summed per bin.
  for (std::size_t q = 0; q < t.hist_by_k.size(); ++q) counts[q % counts.size()] += t.hist_by_k[q];
  return t.rays;
}

FieldLobe pool_fields(const std::vector<std::vector<std::int64_t>>& counts, const std::vector<std::int64_t>& rays) {
  FieldLobe out;
  const std::size_t F = counts.size(), bins = counts.front().size();
  std::vector<std::int64_t> total(bins, 0);
  std::vector<std::vector<double>> per_field;
  for (std::size_t r = 0; r < F; ++r) {
    for (std::size_t b = 0; b < bins; ++b) total[b] += counts[r][b];
    out.rays += rays[r];
    per_field.push_back(fractions(counts[r], static_cast<double>(rays[r])));
  }
  const double N = static_cast<double>(out.rays);
  out.flux = fractions(total, N);
  std::vector<double> albedos;
  for (const auto& f : per_field) albedos.push_back(sum(f));
  const auto spread = [F](const auto& value_of) {
    double m = 0.0, v = 0.0;
    for (std::size_t r = 0; r < F; ++r) m += value_of(r);
    m /= static_cast<double>(F);
    for (std::size_t r = 0; r < F; ++r) v += (value_of(r) - m) * (value_of(r) - m);
    return v / (static_cast<double>(F) - 1.0) / static_cast<double>(F);
  };
  out.var.assign(bins, 0.0);
  for (std::size_t b = 0; b < bins; ++b) {
    const double p = std::clamp(out.flux[b], 0.0, 1.0);
    out.var[b] = std::max(spread([&](std::size_t r) { return per_field[r][b]; }), p * (1.0 - p) / N);
  }
  const double a = std::clamp(sum(out.flux), 0.0, 1.0);
  out.albedo_var = std::max(spread([&](std::size_t r) { return albedos[r]; }), a * (1.0 - a) / N);
  return out;
}

CheckBrdfCase check_lobes_with_variance(const std::vector<double>& sim, const std::vector<double>& model,
                                        const std::vector<double>& var, double albedo_var, double rays, double sigmas,
                                        double tolerance) {
  CheckBrdfCase c;
  c.albedo_sim = sum(sim);
  c.albedo_model = sum(model);
  c.non_finite = !all_finite(model) || std::any_of(model.begin(), model.end(), [](double v) { return v < 0.0; });
  const auto expected = [&](double scale, double& mean, double& thr) {
    double m = 0.0, v2 = 0.0;
    for (double v : var) m += std::sqrt(2.0 * v * scale / kPi), v2 += (1.0 - 2.0 / kPi) * v * scale;
    mean = m, thr = m + sigmas * std::sqrt(v2) + tolerance;
  };
  c.l1_flux = l1(sim, model);
  expected(1.0, c.l1_flux_expected, c.l1_flux_threshold);
  c.l1 = l1(normalized(sim), normalized(model));
  expected(c.albedo_sim > 0.0 ? 1.0 / (c.albedo_sim * c.albedo_sim) : 1.0, c.l1_expected, c.l1_threshold);
  c.albedo_threshold = sigmas * std::sqrt(albedo_var) + 1.0 / rays + tolerance;
  c.pass = !c.non_finite && std::isfinite(c.l1) && c.l1 <= c.l1_threshold && c.l1_flux <= c.l1_flux_threshold &&
           std::abs(c.albedo_sim - c.albedo_model) <= c.albedo_threshold;
  return c;
}

BrdfBatchFn batch_of(const BrdfFn& f) {
  return [&f](const double* wi, const double* wo, std::size_t n, double* out) {
    for (std::size_t j = 0; j < n; ++j)
      out[j] = f({wi[3 * j], wi[3 * j + 1], wi[3 * j + 2]}, {wo[3 * j], wo[3 * j + 1], wo[3 * j + 2]});
  };
}

CheckBrdfResult check_brdf(const BrdfFn& f, const CheckBrdfOptions& opt) { return check_brdf(batch_of(f), opt); }

CheckBrdfResult check_brdf(const BrdfBatchFn& f, const CheckBrdfOptions& opt) {
  check_options(opt);
  CheckBrdfResult res;
  res.options = opt;
  res.threads = support::resolve_threads(opt.threads);
  const auto t0 = Clock::now();
  const std::size_t cases = opt.theta_i_deg.size();
  std::vector<double> theta_i;
  for (double d : opt.theta_i_deg) theta_i.push_back(deg_to_rad(d));

  // The model's bins, one work item per incidence, then the traced lobes. A value that is not a
  // BRDF's stops its case and the cases after it at once; the first such case in the options'
  // order is reported (the cases before it run on), so the error does not depend on the threads.
  std::vector<ModelLobe> model(cases);
  std::vector<double> model_s(cases, 0.0);
  std::vector<std::string> bad(cases);
  std::atomic<std::size_t> first_bad{cases};
  const analytic::GaussLegendre rule = analytic::gauss_legendre(opt.quadrature_order);
  const bool integrated = support::parallel_for(
      cases, res.threads,
      [&](std::size_t c) {
        const auto ti = Clock::now();
        try {
          model[c] = model_bins(f, opt.theta_i_deg[c], opt, rule, CaseStop{opt.cancel, &first_bad, c});
        } catch (const BadModelValue& e) {
          bad[c] = e.message;
          for (std::size_t b = first_bad.load(); c < b && !first_bad.compare_exchange_weak(b, c);) {
          }
        }
        model_s[c] = seconds_since(ti);
      },
      {}, opt.cancel, 1);
  if (first_bad.load() < cases && !support::cancelled(opt.cancel)) throw support::UserError(bad[first_bad.load()]);
  LobeSetup setup;
  setup.ndf = opt.ndf, setup.alpha = opt.alpha, setup.dim = opt.dim, setup.rays = opt.rays;
  setup.grooves = opt.grooves, setup.seed = opt.seed;
  setup.theta_bins = opt.theta_bins, setup.phi_bins = opt.phi_bins, setup.flatland_bins = opt.flatland_bins;
  const bool field = opt.surface == CheckSurface::heightfield, bsdf = opt.eta != 0.0;
  std::vector<FieldLobe> pooled;
  const std::vector<TracedLobe> traced = !integrated ? std::vector<TracedLobe>{}
                                         : field     ? trace_heightfield_lobes(opt, theta_i, res.threads, pooled)
                                         : bsdf      ? trace_bsdf_lobes(opt, theta_i, res.threads)
                                                     : trace_lobes(setup, theta_i, res.threads, opt.cancel);
  res.wall_s = seconds_since(t0);
  if (traced.size() != cases || (opt.cancel && opt.cancel->load())) {
    res.interrupted = true;
    return res;
  }
  res.pass = true;
  for (std::size_t c = 0; c < cases; ++c) {
    const std::vector<double>& sim = traced[c].flux;
    const std::vector<double>& m = model[c].flux;
    const double N = static_cast<double>(traced[c].rays);
    // The model's side is known to within its integration error: it widens each threshold.
    const double tol = opt.model_tolerance + model[c].error;
    // The V-groove surface: the bound from N rays over G grooves; heightfields: their fields' spread.
    // With eta, both hemispheres and each lobe apart (check_bsdf.h).
    CheckBrdfCase out = field
                            ? check_lobes_with_variance(sim, m, pooled[c].var, pooled[c].albedo_var, N, opt.sigmas, tol)
                        : bsdf ? check_bsdf_lobes(sim, m, N, opt, tol)
                               : check_lobes(sim, m, N, opt.grooves, opt.sigmas, tol);
    out.model_error = model[c].error;
    out.model_evals = model[c].evals;
    out.theta_i_deg = opt.theta_i_deg[c];
    out.rays = traced[c].rays;
    out.sim_wall_s = traced[c].thread_s;
    out.model_wall_s = model_s[c];
    if (!bsdf) out.worst = worst_bins(sim, m, opt.dim, opt.theta_bins, opt.phi_bins, opt.flatland_bins);
    res.pass = res.pass && out.pass;
    res.cases.push_back(std::move(out));
  }
  return res;
}

std::vector<WorstBin> worst_bins(const std::vector<double>& sim, const std::vector<double>& model, SurfaceDim dim,
                                 int theta_bins, int phi_bins, int flatland_bins) {
  std::vector<std::size_t> order(sim.size());
  std::iota(order.begin(), order.end(), 0);
  const std::size_t shown = std::min<std::size_t>(kWorstBins, order.size());
  std::partial_sort(
      order.begin(), order.begin() + static_cast<std::ptrdiff_t>(shown), order.end(),
      [&](std::size_t a, std::size_t b) { return std::abs(sim[a] - model[a]) > std::abs(sim[b] - model[b]); });
  std::vector<WorstBin> out;
  for (std::size_t n = 0; n < shown; ++n) {
    WorstBin w;
    const std::size_t i = order[n];
    if (dim == SurfaceDim::flatland) {
      w.theta_o_deg = output_deg(-0.5 * kPi + (static_cast<double>(i) + 0.5) * kPi / flatland_bins);
    } else {
      const std::size_t t = i / static_cast<std::size_t>(phi_bins), p = i % static_cast<std::size_t>(phi_bins);
      w.theta_o_deg = output_deg((static_cast<double>(t) + 0.5) * 0.5 * kPi / theta_bins);
      double phi = static_cast<double>(p) * 2.0 * kPi / phi_bins;
      if (phi > kPi) phi -= 2.0 * kPi;
      w.phi_o_deg = output_deg(phi);
    }
    w.sim = sim[i], w.model = model[i];
    out.push_back(w);
  }
  return out;
}

nlohmann::json CheckBrdfResult::to_json() const {
  nlohmann::json j = provenance();
  j["kind"] = "check_brdf";
  j["name"] = options.name;
  j["seed"] = options.seed;
  j["threads"] = threads;
  j["wall_s"] = wall_s;
  j["inputs"] = {{"ndf", ndf_name(options.ndf)},
                 {"alpha", options.alpha},
                 {"dimension", surface_dim_name(options.dim)},
                 {"theta_i_deg", options.theta_i_deg},
                 {"rays", options.rays},
                 {"grooves", options.grooves},
                 {"surface", check_surface_name(options.surface)},
                 {"theta_bins", options.theta_bins},
                 {"phi_bins", options.phi_bins},
                 {"flatland_bins", options.flatland_bins},
                 {"sigmas", options.sigmas},
                 {"model_tolerance", options.model_tolerance},
                 {"quadrature_order", options.quadrature_order},
                 {"max_model_evals", options.max_model_evals}};
  nlohmann::json cs = nlohmann::json::array();
  const auto worst_json = [](const std::vector<WorstBin>& bins) {
    nlohmann::json worst = nlohmann::json::array();
    for (const WorstBin& w : bins) {
      worst.push_back({{"theta_o_deg", w.theta_o_deg}, {"phi_o_deg", w.phi_o_deg}, {"sim", w.sim}, {"model", w.model}});
      if (!w.lobe.empty()) worst.back()["lobe"] = w.lobe;
    }
    return worst;
  };
  for (const CheckBrdfCase& c : cases) {
    const nlohmann::json worst = worst_json(c.worst);
    cs.push_back({{"theta_i_deg", c.theta_i_deg},
                  {"rays", c.rays},
                  {"albedo_sim", c.albedo_sim},
                  {"albedo_model", c.albedo_model},
                  {"albedo_threshold", c.albedo_threshold},
                  {"l1", c.l1},
                  {"l1_expected", c.l1_expected},
                  {"l1_threshold", c.l1_threshold},
                  {"l1_flux", c.l1_flux},
                  {"l1_flux_expected", c.l1_flux_expected},
                  {"l1_flux_threshold", c.l1_flux_threshold},
                  {"worst_bins", worst},
                  {"sim_wall_s", c.sim_wall_s},
                  {"model_integration_error", c.model_error},
                  {"model_evaluations", c.model_evals},
                  {"model_wall_s", c.model_wall_s},
                  {"non_finite", c.non_finite},
                  {"pass", c.pass}});
    if (options.eta == 0.0) continue;
    nlohmann::json lobes = nlohmann::json::array();
    for (const CheckLobeSide& s : c.lobes)
      lobes.push_back({{"lobe", s.lobe},
                       {"albedo_sim", s.albedo_sim},
                       {"albedo_model", s.albedo_model},
                       {"albedo_sd", s.albedo_sd},
                       {"albedo_threshold", s.albedo_threshold},
                       {"l1", s.l1},
                       {"l1_expected", s.l1_expected},
                       {"l1_threshold", s.l1_threshold},
                       {"l1_flux", s.l1_flux},
                       {"l1_flux_expected", s.l1_flux_expected},
                       {"l1_flux_threshold", s.l1_flux_threshold},
                       {"worst_bins", worst_json(s.worst)},
                       {"pass", s.pass}});
    cs.back()["lobes"] = lobes;
  }
  if (options.eta != 0.0) j["inputs"]["eta"] = options.eta, j["inputs"]["side"] = sim::medium_name(options.side);
  if (options.surface == CheckSurface::heightfield)
    j["inputs"]["heightfield"] = {{"field_size", options.field_size},
                                  {"correlation_length", options.correlation_length},
                                  {"fields", options.fields},
                                  {"field_bytes", sim::heightfield_bytes(options.field_size)}};
  j["cases"] = cs;
  j["interrupted"] = interrupted;
  j["pass"] = pass;
  return j;
}

}  // namespace vgroove::validation
