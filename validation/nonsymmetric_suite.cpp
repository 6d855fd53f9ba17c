#include "vgroove/validation/nonsymmetric_suite.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/support/format.h"
#include "vgroove/support/printable.h"
#include "vgroove/validation/lobe_bins.h"
#include "vgroove/validation/lobe_comparison.h"
#include "vgroove/validation/plane_cut.h"

#include "vgroove/analytic/brdf_nonsymmetric.h"
#include "vgroove/analytic/lobe_nonsymmetric.h"
#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface_nonsymmetric.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/validation/histogram_metrics.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"
#include "vgroove/validation/table_frame.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>

namespace vgroove::validation {

namespace {

using support::Clock;
using support::seconds_since;
constexpr double kPi = std::numbers::pi;
constexpr double kReciprocityTolerance = 1e-8;

analytic::NonsymmetricModel model_of(const NonsymmetricCase& c, bool symmetric) {
  analytic::NonsymmetricModel m;
  m.roughness = analytic::Roughness{c.ndf, c.alpha_x, c.alpha_y};
  m.partner = symmetric ? analytic::PartnerLaw::symmetric : analytic::PartnerLaw::independent;
  return m;
}

const char* partner_name(bool symmetric) { return symmetric ? "symmetric" : "independent"; }

// The traced joint (row, bin) fractions against the model's (compare_lobes), and the shape of the
// other partner law's model against the same trace.
void compare(NonsymmetricOutcome& out, const NonsymmetricSuite& suite, const std::vector<double>& sim_joint,
             const std::vector<double>& model_joint, const std::vector<double>& other_joint, int bins,
             double tolerance) {
  const double N = static_cast<double>(out.rays), G = static_cast<double>(suite.grooves);
  const LobeComparison c = compare_lobes(sim_joint, model_joint, bins, N, G, suite.sigmas, tolerance);
  const bool holds = take_comparison(out, c, N, G, suite.sigmas, tolerance);
  out.l1_other = l1(c.sim_shape, normalized(bin_totals(other_joint, bins)));
  out.other_rejected = out.l1_other > out.l1_threshold;
  out.non_finite = !(std::isfinite(out.l1) && std::isfinite(out.l1_k) && std::isfinite(out.albedo_model) &&
                     all_finite(model_joint) && all_finite(other_joint));
  out.pass = !out.non_finite && holds;
}

// All chunks of rays merged in order, as sim's trace_nonsymmetric_microsurface(3d) do (the same
// tally), with the cancellation flag read before each chunk.
template <class Tally, class Surface, class Options, class ChunkFn>
Tally trace_chunks(const Surface& surface, const Options& to, Tally total, ChunkFn&& chunk,
                   support::CancelFlag cancel) {
  const std::int64_t n = sim::chunk_count(to);
  for (std::int64_t c = 0; c < n && !support::cancelled(cancel); ++c) total.merge(chunk(surface, to, c));
  return total;
}

sim::NonsymmetricSurfaceOptions surface_options(const NonsymmetricSuite& suite, const NonsymmetricCase& c) {
  sim::NonsymmetricSurfaceOptions o;
  o.ndf = c.ndf;
  o.alpha_x = c.alpha_x;
  o.alpha_y = c.alpha_y;
  // The tally's frame has the light at azimuth pi: the alpha_x axis sits at pi - phi_i.
  o.axes_azimuth = kPi - c.phi_i;
  o.partner = c.symmetric ? sim::Partner::symmetric : sim::Partner::independent;
  o.grooves = suite.grooves;
  o.seed = suite.seed;
  return o;
}

// What the flatland and 3D cases differ in: the surface, its trace and tally, the model's lobe and
// where each keeps its histograms, the tolerance and the plane of incidence.
struct Flatland {
  static sim::NonsymmetricMicrosurface surface(const sim::NonsymmetricSurfaceOptions& o) {
    return sim::make_nonsymmetric_microsurface(o);
  }
  static sim::MicrosurfaceTally trace(const sim::NonsymmetricMicrosurface& surface, const NonsymmetricSuite& suite,
                                      const NonsymmetricCase& c, long rays, support::CancelFlag cancel) {
    sim::MicrosurfaceTraceOptions to;
    to.theta_i = c.theta_i;
    to.rays = rays;
    to.sampling = sim::Sampling::random;
    to.seed = suite.seed;
    to.theta_o_bins = suite.flatland_bins;
    to.max_k = suite.max_k;
    return trace_chunks(surface, to, sim::MicrosurfaceTally(to.theta_o_bins, to.max_k),
                        sim::trace_nonsymmetric_microsurface_chunk, cancel);
  }
  static analytic::FlatlandLobe lobe(const NonsymmetricSuite& suite, const NonsymmetricCase& c, bool symmetric,
                                     support::CancelFlag cancel) {
    analytic::NonsymmetricLobeOptions lo = analytic::flatland_options();
    lo.cancel = cancel;
    return analytic::flatland_nonsymmetric_lobe(model_of(c, symmetric), c.theta_i, suite.flatland_bins, suite.max_k,
                                                lo);
  }
  static const auto& hist(const sim::MicrosurfaceTally& t) { return t.theta_o; }
  static const auto& hist_by_k(const sim::MicrosurfaceTally& t) { return t.theta_o_by_k; }
  static const auto& hist(const analytic::FlatlandLobe& l) { return l.theta_o; }
  static const auto& hist_by_k(const analytic::FlatlandLobe& l) { return l.theta_o_by_k; }
  static double tolerance(const NonsymmetricSuite& suite) { return suite.model_tolerance_flatland; }
  static PlaneCut plane(const NonsymmetricSuite& suite) { return PlaneCut::flatland(suite.flatland_bins); }
};

struct ThreeD {
  static sim::NonsymmetricMicrosurface3d surface(const sim::NonsymmetricSurfaceOptions& o) {
    return sim::make_nonsymmetric_microsurface3d(o);
  }
  static sim::Microsurface3dTally trace(const sim::NonsymmetricMicrosurface3d& surface, const NonsymmetricSuite& suite,
                                        const NonsymmetricCase& c, long rays, support::CancelFlag cancel) {
    sim::Microsurface3dTraceOptions to;
    to.theta_i = c.theta_i;
    to.rays = rays;
    to.seed = suite.seed;
    to.theta_bins = suite.theta_bins;
    to.phi_bins = suite.phi_bins;
    to.max_k = suite.max_k;
    return trace_chunks(surface, to, sim::Microsurface3dTally(to.theta_bins, to.phi_bins, to.max_k),
                        sim::trace_nonsymmetric_microsurface3d_chunk, cancel);
  }
  static analytic::Lobe3d lobe(const NonsymmetricSuite& suite, const NonsymmetricCase& c, bool symmetric,
                               support::CancelFlag cancel) {
    analytic::NonsymmetricLobeOptions lo;
    lo.cancel = cancel;
    return analytic::nonsymmetric_lobe_3d(model_of(c, symmetric), c.theta_i, kPi - c.phi_i, suite.theta_bins,
                                          suite.phi_bins, suite.max_k, lo);
  }
  static const auto& hist(const sim::Microsurface3dTally& t) { return t.hist; }
  static const auto& hist_by_k(const sim::Microsurface3dTally& t) { return t.hist_by_k; }
  static const auto& hist(const analytic::Lobe3d& l) { return l.hist; }
  static const auto& hist_by_k(const analytic::Lobe3d& l) { return l.hist_by_k; }
  static double tolerance(const NonsymmetricSuite& suite) { return suite.model_tolerance_3d; }
  static PlaneCut plane(const NonsymmetricSuite& suite) { return PlaneCut::three_d(suite.theta_bins, suite.phi_bins); }
};

// One case: the surface traced, both partner laws' lobes, the comparison and the plane of incidence.
template <class Dim>
NonsymmetricOutcome run_case(const NonsymmetricSuite& suite, const NonsymmetricCase& c, long rays,
                             support::CancelFlag cancel) {
  NonsymmetricOutcome out;
  out.c = c;
  const auto t0 = Clock::now();
  const auto t = Dim::trace(Dim::surface(surface_options(suite, c)), suite, c, rays, cancel);
  out.sim_wall_s = seconds_since(t0);
  if (support::cancelled(cancel)) return out;
  take_counts(out, t);
  const auto t1 = Clock::now();
  const auto lobe = Dim::lobe(suite, c, c.symmetric, cancel);
  const auto other = Dim::lobe(suite, c, !c.symmetric, cancel);
  out.model_wall_s = seconds_since(t1);
  if (support::cancelled(cancel)) return out;
  out.albedo_model = lobe.albedo;
  const double N = static_cast<double>(t.rays);
  out.by_k_sim = fractions(t.by_k, N);
  out.by_k_model = lobe.by_k;
  out.by_k_other = other.by_k;
  const PlaneCut plane = Dim::plane(suite);
  const int bins = plane.bins();
  compare(out, suite, fractions(Dim::hist_by_k(t), N), Dim::hist_by_k(lobe), Dim::hist_by_k(other), bins,
          Dim::tolerance(suite));
  out.plane_theta_deg = plane.angles_deg();
  out.plane_sim = plane.cut([&](std::size_t n) { return static_cast<double>(Dim::hist(t)[n]) / N; });
  out.plane_model = plane.cut([&](std::size_t n) { return Dim::hist(lobe)[n]; });
  out.plane_other = plane.cut([&](std::size_t n) { return Dim::hist(other)[n]; });
  for (int k = 1; k <= std::min(suite.plane_k, suite.max_k); ++k) {
    const std::size_t row = static_cast<std::size_t>(k) * bins;
    out.plane_sim_k.push_back(
        plane.cut([&](std::size_t n) { return static_cast<double>(Dim::hist_by_k(t)[row + n]) / N; }));
    out.plane_model_k.push_back(plane.cut([&](std::size_t n) { return Dim::hist_by_k(lobe)[row + n]; }));
    out.plane_other_k.push_back(plane.cut([&](std::size_t n) { return Dim::hist_by_k(other)[row + n]; }));
  }
  return out;
}

// The rows of the reciprocity check: every (ndf, alpha, dimension) of the grid, every anisotropic
// roughness of the block (3D).
std::vector<ReciprocityRow> reciprocity_rows(const NonsymmetricSuite& s) {
  std::vector<ReciprocityRow> rows;
  for (SurfaceDim d : s.dims)
    for (auto ndf : s.ndfs)
      for (double a : s.alphas) rows.push_back({ndf, a, a, d, s.reciprocity_pairs, 0, 0.0, false});
  for (auto ndf : s.aniso_ndfs)
    for (double ax : s.alpha_x)
      for (double ay : s.alpha_y)
        rows.push_back({ndf, ax, ay, SurfaceDim::three_d, s.reciprocity_pairs, 0, 0.0, false});
  return rows;
}

void run_reciprocity(ReciprocityRow& row, std::uint64_t seed, std::size_t index, support::CancelFlag cancel) {
  std::mt19937_64 g(seed * 0x9e3779b97f4a7c15ULL + index);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  analytic::NonsymmetricModel m;
  m.roughness = analytic::Roughness{row.ndf, row.alpha_x, row.alpha_y};
  for (int n = 0; n < row.pairs; ++n) {
    if (support::cancelled(cancel)) return;
    for (int k = 1; k <= 4; ++k) {
      double a = 0.0, b = 0.0;
      if (row.dim == SurfaceDim::three_d) {
        const analytic::Dir3 i = analytic::dir3(std::acos(U(g)), 2.0 * kPi * U(g));
        const analytic::Dir3 o = analytic::dir3(std::acos(U(g)), 2.0 * kPi * U(g));
        a = analytic::nonsymmetric_brdf_k(i, o, k, m);
        b = analytic::nonsymmetric_brdf_k(o, i, k, m);
      } else {
        const double ti = (U(g) - 0.5) * kPi, to = (U(g) - 0.5) * kPi;
        a = analytic::flatland_nonsymmetric_brdf_k(ti, to, k, m);
        b = analytic::flatland_nonsymmetric_brdf_k(to, ti, k, m);
      }
      const double big = std::max(a, b);
      if (!(big > 1e-300)) continue;
      ++row.evaluated;
      row.worst = std::max(row.worst, std::abs(a - b) / big);
    }
  }
  row.pass = std::isfinite(row.worst) && row.worst <= kReciprocityTolerance;
}

std::vector<bool> read_partners(support::JsonObject& o) {
  std::vector<bool> out;
  for (const auto& p : read_names(o, "partners", {"independent", "symmetric"})) out.push_back(p == "symmetric");
  return out;
}

// Phong's independent partner law exists for alpha < sqrt(2) only (analytic/partner_distribution.h).
void check_partner_laws(support::JsonObject& o, const std::vector<analytic::NdfKind>& ndfs,
                        const std::vector<double>& alphas, const std::string& key) {
  for (auto ndf : ndfs)
    for (double a : alphas)
      if (!analytic::partner_law_exists(ndf, a))
        o.fail(key, "= " + support::number_text(a) + " has no partner law for " + analytic::ndf_name(ndf) +
                        " (Eq. 20 needs alpha < sqrt(2) for Phong)");
}

nlohmann::json case_json(const NonsymmetricOutcome& o) {
  nlohmann::json c = lobe_case_json(o, o.c.dim == SurfaceDim::flatland);
  c["ndf"] = analytic::ndf_name(o.c.ndf);
  c["alpha_x"] = o.c.alpha_x;
  c["alpha_y"] = o.c.alpha_y;
  c["theta_i_deg"] = output_deg(o.c.theta_i);
  c["phi_i_deg"] = output_deg(o.c.phi_i);
  c["dimension"] = surface_dim_name(o.c.dim);
  c["partner"] = partner_name(o.c.symmetric);
  c["anisotropic_block"] = o.c.anisotropic;
  c["other_partner"] = partner_name(!o.c.symmetric);
  c["l1_other_model"] = o.l1_other;
  c["other_model_rejected"] = o.other_rejected;
  c["by_k_other_model"] = o.by_k_other;
  c["plane"]["other_model"] = o.plane_other;
  c["plane"]["other_model_by_k"] = o.plane_other_k;
  return c;
}

}  // namespace

std::vector<NonsymmetricCase> NonsymmetricSuite::cases() const {
  std::vector<NonsymmetricCase> out;
  for (SurfaceDim d : dims)
    for (auto ndf : ndfs)
      for (double a : alphas)
        for (double t : theta_i) out.push_back({ndf, a, a, t, 0.0, d, false, false});
  for (bool sym : partners_symmetric)
    for (auto ndf : aniso_ndfs)
      for (double ax : alpha_x)
        for (double ay : alpha_y)
          for (double p : phi_i)
            for (double t : aniso_theta_i) out.push_back({ndf, ax, ay, t, p, SurfaceDim::three_d, sym, true});
  return out;
}

NonsymmetricSuite parse_nonsymmetric_suite(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  NonsymmetricSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"nonsymmetric_brdf"});
  s.ndfs = read_ndfs(root);
  s.alphas = read_numbers(root, "alpha", kMinAlpha, true, kMaxAlpha, true);
  check_partner_laws(root, s.ndfs, s.alphas, "alpha");
  for (double d : read_numbers(root, "theta_i_deg", 0.0, true, kMaxSurfaceThetaIDeg, true))
    s.theta_i.push_back(d * kRadPerDeg);
  for (const auto& d : read_names(root, "dimensions", {"flatland", "3d"}))
    s.dims.push_back(d == "flatland" ? SurfaceDim::flatland : SurfaceDim::three_d);
  if (root.has("anisotropic")) {
    support::JsonObject a = root.object("anisotropic");
    for (const auto& n : read_names(a, "ndf", {"beckmann", "ggx"})) s.aniso_ndfs.push_back(*ndf_from_name(n));
    s.alpha_x = read_numbers(a, "alpha_x", kMinAlpha, true, kMaxAlpha, true);
    s.alpha_y = read_numbers(a, "alpha_y", kMinAlpha, true, kMaxAlpha, true);
    for (double d : read_numbers(a, "theta_i_deg", 0.0, true, kMaxSurfaceThetaIDeg, true))
      s.aniso_theta_i.push_back(d * kRadPerDeg);
    for (double d : read_numbers(a, "phi_i_deg", -360.0, true, 360.0, true)) s.phi_i.push_back(d * kRadPerDeg);
    s.partners_symmetric = read_partners(a);
    a.finish();
  }
  s.rays = static_cast<long>(root.integer("rays", 1, kMaxRays));
  s.grooves = static_cast<int>(root.integer("grooves", 1, kMaxGrooves));
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, kMaxSeed));
  {
    const bool flat = std::find(s.dims.begin(), s.dims.end(), SurfaceDim::flatland) != s.dims.end();
    const bool three =
        !s.aniso_ndfs.empty() || std::find(s.dims.begin(), s.dims.end(), SurfaceDim::three_d) != s.dims.end();
    const LobeBins bins = read_lobe_bins(root, {s.flatland_bins, s.theta_bins, s.phi_bins, s.max_k}, flat, three);
    s.flatland_bins = bins.flatland_bins, s.theta_bins = bins.theta_bins, s.phi_bins = bins.phi_bins;
    s.max_k = bins.max_k;
  }
  s.plane_k = static_cast<int>(root.integer_or("plane_k", s.plane_k, 0, 64));
  s.reciprocity_pairs = static_cast<int>(root.integer_or("reciprocity_pairs", s.reciprocity_pairs, 0, 100000));
  {
    support::JsonObject t = root.object("thresholds");
    s.sigmas = t.number("sigmas", 0.0, false, 100.0, true);
    support::JsonObject m = t.object("model_tolerance");
    s.model_tolerance_flatland = m.number("flatland", 0.0, true, 2.0, true);
    s.model_tolerance_3d = m.number("3d", 0.0, true, 2.0, true);
    m.finish();
    t.finish();
  }
  root.finish();
  return s;
}

NonsymmetricOutcome run_nonsymmetric_case(const NonsymmetricSuite& suite, const NonsymmetricCase& c, long rays,
                                          const std::atomic<bool>* cancel) {
  return c.dim == SurfaceDim::flatland ? run_case<Flatland>(suite, c, rays, cancel)
                                       : run_case<ThreeD>(suite, c, rays, cancel);
}

double nonsymmetric_run_memory_bytes(const NonsymmetricSuite& suite, int threads, bool report) {
  constexpr double kNumberBytes = 64;  // a double in the report: its JSON node, vector slot and text
  const std::vector<NonsymmetricCase> cases = suite.cases();
  const double rows = suite.max_k + 2.0;
  double cells = 0.0, groove = 0.0, plane = 0.0;
  for (const NonsymmetricCase& c : cases) {
    const bool flat = c.dim == SurfaceDim::flatland;
    cells =
        std::max(cells, rows * (flat ? suite.flatland_bins : static_cast<double>(suite.theta_bins) * suite.phi_bins));
    groove = std::max(groove, sizeof(sim::Groove) + 16.0 + (flat ? 0.0 : 8.0 + sizeof(sim::GrooveFrame3d)));
    plane = std::max(plane, (flat ? suite.flatland_bins : 2.0 * suite.theta_bins) * (4.0 + 3.0 * suite.plane_k));
  }
  const double n = static_cast<double>(cases.size());
  const double workers = std::min<double>(support::resolve_threads(threads), n);
  // Per worker: the surface; the case's tally and a chunk's; the two models' lobes (this partner
  // law and the other) and the comparison's fractions and normalized copies: about twelve arrays of
  // the joint cells. Per case: its outcome (bounce rows and the plane of incidence), held twice
  // while parts are merged, and with `report` its JSON.
  const double per_worker = suite.grooves * groove + 12.0 * cells * 8.0;
  const double per_case = sizeof(NonsymmetricOutcome) + 2.0 * (3.0 * rows + plane) * 8.0 +
                          (report ? (3.0 * rows + plane) * kNumberBytes : 0.0);
  return workers * per_worker + n * per_case;
}

Job<NonsymmetricWork> nonsymmetric_job(const NonsymmetricSuite& suite, long rays, nlohmann::json descriptor,
                                       const std::atomic<bool>* cancel) {
  const std::vector<NonsymmetricCase> cases = suite.cases();
  const std::vector<ReciprocityRow> rows = reciprocity_rows(suite);
  const long n_rays = rays > 0 ? rays : suite.rays;
  const std::size_t n = cases.size();
  return item_job<NonsymmetricItem>(
      n + rows.size(),
      [suite, cases, rows, n_rays, cancel](std::size_t k) {
        NonsymmetricItem item;
        if (k < cases.size()) {
          item.outcome = run_nonsymmetric_case(suite, cases[k], n_rays, cancel);
        } else {
          item.reciprocity = rows[k - cases.size()];
          run_reciprocity(*item.reciprocity, suite.seed, k - cases.size(), cancel);
        }
        return item;
      },
      [cases, rows](support::JsonObject& o, std::size_t k, NonsymmetricItem& item) {
        const bool is_case = k < cases.size();
        if (item.outcome.has_value() == item.reciprocity.has_value() || item.outcome.has_value() != is_case)
          o.fail("outcome", std::string("must hold exactly the item's ") + (is_case ? "case" : "reciprocity row"));
        if (item.reciprocity) {
          const ReciprocityRow read = *item.reciprocity;
          item.reciprocity = rows[k - cases.size()];
          item.reciprocity->evaluated = read.evaluated, item.reciprocity->worst = read.worst;
          item.reciprocity->pass = read.pass;
          return;
        }
        NonsymmetricOutcome& c = *item.outcome;
        c.c = cases[k];
        const std::size_t plane = c.plane_theta_deg.size(), by_k = c.by_k_sim.size();
        const auto same = [](const std::vector<std::vector<double>>& v, std::size_t rows_, std::size_t cols) {
          return v.size() == rows_ && std::all_of(v.begin(), v.end(), [&](const auto& r) { return r.size() == cols; });
        };
        if (c.plane_sim.size() != plane || c.plane_model.size() != plane || c.plane_other.size() != plane ||
            c.by_k_model.size() != by_k || c.by_k_other.size() != by_k ||
            !same(c.plane_model_k, c.plane_sim_k.size(), plane) ||
            !same(c.plane_other_k, c.plane_sim_k.size(), plane) || !same(c.plane_sim_k, c.plane_sim_k.size(), plane))
          o.fail("outcome", "/case: the plane and bounce arrays differ in length");
      },
      std::move(descriptor));
}

NonsymmetricRun nonsymmetric_run_from(const NonsymmetricSuite&,
                                      const std::vector<UnitResult<NonsymmetricWork>>& results) {
  NonsymmetricRun run;
  for (const auto& r : results) {
    if (r.tally.outcome) run.cases.push_back(*r.tally.outcome);
    if (r.tally.reciprocity) run.reciprocity.push_back(*r.tally.reciprocity);
  }
  const auto all_pass = [](const auto& v) {
    return std::all_of(v.begin(), v.end(), [](const auto& o) { return o.pass; });
  };
  run.pass = all_pass(run.cases) && all_pass(run.reciprocity);
  return run;
}

NonsymmetricRun run_nonsymmetric_suite(const NonsymmetricSuite& suite, long rays, int threads,
                                       const support::ProgressFn& progress, const std::atomic<bool>* cancel) {
  const auto t0 = Clock::now();
  const auto results = run_job(nonsymmetric_job(suite, rays, {}, cancel), threads, progress, cancel);
  NonsymmetricRun run;
  if (results) run = nonsymmetric_run_from(suite, *results);
  run.threads = support::resolve_threads(threads);
  run.wall_s = seconds_since(t0);
  run.interrupted = !results;
  run.pass = run.pass && !run.interrupted;
  return run;
}

nlohmann::json nonsymmetric_report_json(const NonsymmetricSuite& suite, const NonsymmetricRun& run) {
  nlohmann::json j = report_header({suite.name, suite.file, "nonsymmetric_brdf", suite.description, suite.seed},
                                   run.threads, run.wall_s);
  nlohmann::json ti = nlohmann::json::array(), ati = nlohmann::json::array(), phi = nlohmann::json::array();
  for (double t : suite.theta_i) ti.push_back(output_deg(t));
  for (double t : suite.aniso_theta_i) ati.push_back(output_deg(t));
  for (double p : suite.phi_i) phi.push_back(output_deg(p));
  j["inputs"] = {{"theta_i_deg", ti},
                 {"alpha", suite.alphas},
                 {"anisotropic",
                  {{"alpha_x", suite.alpha_x}, {"alpha_y", suite.alpha_y}, {"theta_i_deg", ati}, {"phi_i_deg", phi}}},
                 {"grooves", suite.grooves},
                 {"flatland_bins", suite.flatland_bins},
                 {"theta_bins", suite.theta_bins},
                 {"phi_bins", suite.phi_bins},
                 {"max_k", suite.max_k},
                 {"sigmas", suite.sigmas},
                 {"model_tolerance", {{"flatland", suite.model_tolerance_flatland}, {"3d", suite.model_tolerance_3d}}}};
  nlohmann::json cases = nlohmann::json::array();
  std::int64_t rays = 0, bounces = 0;
  double worst_ratio = 0.0, worst_albedo = 0.0;
  std::size_t passed = 0, rejected = 0;
  for (const NonsymmetricOutcome& o : run.cases) {
    rays += o.rays, bounces += o.bounces;
    passed += o.pass;
    rejected += o.other_rejected;
    worst_ratio = std::max({worst_ratio, o.l1 / o.l1_threshold, o.l1_k / o.l1_k_threshold});
    worst_albedo = std::max(worst_albedo, std::abs(o.albedo_sim - o.albedo_model));
    cases.push_back(case_json(o));
  }
  j["cases"] = std::move(cases);
  nlohmann::json recip = nlohmann::json::array();
  double worst_recip = 0.0;
  for (const ReciprocityRow& r : run.reciprocity) {
    worst_recip = std::max(worst_recip, r.worst);
    recip.push_back({{"ndf", analytic::ndf_name(r.ndf)},
                     {"alpha_x", r.alpha_x},
                     {"alpha_y", r.alpha_y},
                     {"dimension", surface_dim_name(r.dim)},
                     {"pairs", r.pairs},
                     {"values_compared", r.evaluated},
                     {"worst_relative_asymmetry", r.worst},
                     {"pass", r.pass}});
  }
  j["reciprocity"] = {{"rule", "|rho_k(i, o) - rho_k(o, i)| / max over random pairs, k = 1..4; passes below 1e-8"},
                      {"rows", recip},
                      {"worst_relative_asymmetry", worst_recip}};
  j["summary"] = {{"cases", run.cases.size()},
                  {"passed", passed},
                  {"other_model_rejected", rejected},
                  {"rays", rays},
                  {"bounces", bounces},
                  {"worst_error_over_threshold", worst_ratio},
                  {"largest_albedo_difference", worst_albedo},
                  {"worst_relative_asymmetry", worst_recip},
                  {"wall_s", run.wall_s}};
  j["thresholds"] = {{"rule", "expected L1 + sigmas x its standard deviation + model tolerance (per case)"},
                     {"sigmas", suite.sigmas}};
  j["pass"] = run.pass;
  return j;
}

void print_nonsymmetric_table(std::ostream& os, const NonsymmetricSuite& suite, const NonsymmetricRun& run) {
  print_table_title(
      os, suite.name, "nonsymmetric_brdf",
      support::format("%zu cases, %ld rays x %d grooves each", run.cases.size(), suite.rays, suite.grooves),
      run.threads);
  os << support::format("  %-8s %-8s %5s %5s %7s %6s %-11s %8s %8s %8s %8s %8s %-8s %8s %5s\n", "dim", "ndf", "ax",
                        "ay", "theta_i", "phi_i", "partner", "L1", "L1 thr", "L1 by k", "thr", "other L1", "other",
                        "wall s", "pass");
  for (const NonsymmetricOutcome& o : run.cases) {
    os << support::format(
        "  %-8s %-8s %5.2f %5.2f %7.2f %6.1f %-11s %8.5f %8.5f %8.5f %8.5f %8.5f %-8s %8.3f %5s\n",
        surface_dim_name(o.c.dim), analytic::ndf_name(o.c.ndf), o.c.alpha_x, o.c.alpha_y, output_deg(o.c.theta_i),
        output_deg(o.c.phi_i), partner_name(o.c.symmetric), o.l1, o.l1_threshold, o.l1_k, o.l1_k_threshold, o.l1_other,
        o.other_rejected ? "rejected" : "accepted", o.sim_wall_s + o.model_wall_s, o.pass ? "yes" : "NO");
  }
  double worst = 0.0;
  std::size_t recip_pass = 0;
  for (const ReciprocityRow& r : run.reciprocity) {
    worst = std::max(worst, r.worst);
    recip_pass += r.pass;
  }
  std::size_t passed = 0, rejected = 0;
  for (const auto& o : run.cases) {
    passed += o.pass;
    rejected += o.other_rejected;
  }
  os << support::format("  reciprocity: %zu/%zu rows below 1e-8, worst relative asymmetry %.2e\n", recip_pass,
                        run.reciprocity.size(), worst);
  print_table_close(os, passed, run.cases.size(), run.wall_s,
                    support::format("cases pass; the other partner law's model rejected in %zu", rejected));
}

}  // namespace vgroove::validation
