#include "vgroove/validation/energy_table.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/validation/detail/part_fields.h"

#include "vgroove/analytic/brdf_flatland.h"
#include "vgroove/analytic/lobe_3d.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/support/format.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>

namespace vgroove::validation {

namespace {

// Cost estimates (ns of one core, measured on the project machine; they only balance the work):
// per ray a set-up (drawing the groove: Beckmann and Phong flatland slopes by Newton iteration)
// plus a cost per reflection; the model per cell.
std::int64_t ray_cost_ns(const EnergyCell& c, double mean_bounces) {
  const double setup = c.dim == SurfaceDim::three_d ? 200.0 : (c.ndf == NdfKind::ggx ? 90.0 : 600.0);
  return static_cast<std::int64_t>(setup + 8.0 * mean_bounces);
}
std::int64_t model_cost_ns(const EnergyCell& c) { return c.dim == SurfaceDim::three_d ? 250'000'000 : 2'000'000; }

// Mean reflections per ray of a cell, from a short trace of its own (another stream of the seed).
double pilot_bounces(const EnergyWork& w, std::size_t cell) {
  sim::NdfGrooveOptions o = w.options(cell);
  o.rays = 256;
  o.seed ^= 0x70696c6f74ULL;  // "pilot"
  o.trace.max_bounces = 10000;
  const sim::BounceCounts b = sim::trace_ndf_grooves_chunk(o, 0);
  return static_cast<double>(b.bounces + b.bounce_limit * o.trace.max_bounces) / static_cast<double>(b.rays);
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

EnergyCell EnergyGrid::cell_at(std::size_t c) const {
  EnergyCell out;
  const std::size_t nm = mus.size(), na = alphas.size(), nd = dims.size();
  out.mu = mus[c % nm];
  out.alpha = alphas[(c / nm) % na];
  out.dim = dims[(c / (nm * na)) % nd];
  out.ndf = ndfs[c / (nm * na * nd)];
  return out;
}

std::vector<double> midpoints(int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back((i + 0.5) / n);
  return v;
}

void check_energy_grid(const EnergyGrid& g) {
  auto list = [](const std::vector<double>& v, const std::string& flag, double lo, bool lo_closed, double hi,
                 const std::string& why) {
    if (v.empty() || v.size() > kMaxGridPoints)
      throw support::UserError(flag + " has " + std::to_string(v.size()) + " values, out of range [1, " +
                               std::to_string(kMaxGridPoints) + "]");
    for (double x : v)
      if (!((lo_closed ? x >= lo : x > lo) && x <= hi))
        throw support::UserError(flag + " = " + support::number_text(x) + " is out of range " +
                                 support::interval_text(lo, lo_closed, hi, true) + why);
  };
  list(g.mus, "--mu", kMinMu, true, 1.0, " (mu = cos theta_i: theta_i <= 89.9 deg, the rough surfaces' range)");
  list(g.alphas, "--alpha", kMinAlpha, true, kMaxAlpha, "");
  if (g.rays < 1 || g.rays > kMaxEnergyRays)
    throw support::UserError("--rays = " + std::to_string(g.rays) + " is out of range [1, " +
                             std::to_string(kMaxEnergyRays) + "]");
  if (g.max_k < 1 || g.max_k > kMaxEnergyK)
    throw support::UserError("--max-k = " + std::to_string(g.max_k) + " is out of range [1, " +
                             std::to_string(kMaxEnergyK) + "]");
}

EnergyModel energy_model(const EnergyCell& c, int max_k) {
  EnergyModel m;
  const double theta_i = std::acos(c.mu);
  if (c.dim == SurfaceDim::three_d) {
    const analytic::Lobe3d lobe = analytic::vgroove_lobe_3d(c.ndf, c.alpha, theta_i, 1, 2, max_k);
    m.by_k = lobe.by_k;
    m.albedo = lobe.albedo;
    m.cook_torrance = analytic::cook_torrance_lobe_3d(c.ndf, c.alpha, theta_i, 1, 2).albedo;
  } else {
    const analytic::FlatlandLobe lobe = analytic::flatland_lobe(c.ndf, c.alpha, theta_i, 1, max_k);
    m.by_k = lobe.by_k;
    m.albedo = lobe.albedo;
    m.cook_torrance = analytic::flatland_single_lobe(c.ndf, c.alpha, theta_i, 1).albedo;
  }
  return m;
}

sim::NdfGrooveOptions EnergyWork::options(std::size_t cell) const {
  const EnergyCell c = grid.cell_at(cell);
  sim::NdfGrooveOptions o;
  o.ndf = c.ndf;
  o.alpha = c.alpha;
  o.theta_i = std::acos(c.mu);
  o.three_d = c.dim == SurfaceDim::three_d;
  o.rays = grid.rays;
  o.seed = grid.seed;
  o.stream = cell;
  o.max_k = grid.max_k;
  return o;
}

EnergyWork::Tally EnergyWork::run_chunks(const Context&, std::size_t cell, std::int64_t begin, std::int64_t end) const {
  const sim::NdfGrooveOptions o = options(cell);
  Tally t(grid.max_k);
  for (std::int64_t c = begin; c < end; ++c) t.merge(sim::trace_ndf_grooves_chunk(o, c));
  return t;
}

nlohmann::json EnergyWork::tally_json(const Tally& t) {
  nlohmann::json j = fates_json(t);
  j["max_k"] = t.max_k, j["by_k"] = t.by_k;
  return j;
}

EnergyWork::Tally EnergyWork::read_tally(support::JsonObject& j, std::size_t cell,
                                         const std::vector<ChunkRun>& runs) const {
  j.integer("max_k", grid.max_k, grid.max_k);
  const sim::NdfGrooveOptions o = options(cell);
  return read_bounce_counts(j, grid.max_k, rays_in_chunks(runs, o.rays, sim::kRaysPerChunk), o.trace.max_bounces);
}

nlohmann::json EnergyWork::fixed_json(const Fixed& f) {
  return {
      {"by_k", exact_json(f.by_k)}, {"albedo", exact_json(f.albedo)}, {"cook_torrance", exact_json(f.cook_torrance)}};
}

EnergyWork::Fixed EnergyWork::read_fixed(support::JsonObject& j, std::size_t) const {
  // Fractions of the incident flux, the rows adding up to the albedo (energy_model).
  Fixed f;
  f.by_k = read_fractions(j, "by_k", static_cast<std::size_t>(grid.max_k) + 2);
  f.albedo = read_fraction(j, "albedo");
  f.cook_torrance = read_fraction(j, "cook_torrance");
  check_model_sum(j, "by_k", f.by_k, f.albedo, "albedo");
  return f;
}

nlohmann::json energy_grid_json(const EnergyGrid& g) {
  nlohmann::json ndfs = nlohmann::json::array(), dims = nlohmann::json::array();
  for (auto n : g.ndfs) ndfs.push_back(ndf_name(n));
  for (auto d : g.dims) dims.push_back(surface_dim_name(d));
  return {{"ndf", ndfs},
          {"dimensions", dims},
          {"alpha", exact_json(g.alphas)},
          {"mu", exact_json(g.mus)},
          {"rays", g.rays},
          {"seed", g.seed},
          {"max_k", g.max_k}};
}

EnergyGrid energy_grid_from_json(const nlohmann::json& j, const std::string& where) {
  EnergyGrid g;
  try {
    g.ndfs.clear(), g.dims.clear();
    for (const auto& n : j.at("ndf")) {
      const auto k = ndf_from_name(n.get<std::string>());
      if (!k) throw support::UserError(where + ": unknown NDF " + n.dump());
      g.ndfs.push_back(*k);
    }
    for (const auto& d : j.at("dimensions"))
      g.dims.push_back(d.get<std::string>() == "flatland" ? SurfaceDim::flatland : SurfaceDim::three_d);
    g.alphas = exact_doubles(j.at("alpha"));
    g.mus = exact_doubles(j.at("mu"));
    g.rays = j.at("rays").get<long long>();
    g.seed = j.at("seed").get<std::uint64_t>();
    g.max_k = j.at("max_k").get<int>();
  } catch (const nlohmann::json::exception& e) {
    throw support::UserError(where + ": not an energy table's grid (" + e.what() + ")");
  }
  check_energy_grid(g);
  return g;
}

Job<EnergyWork> energy_job(const EnergyGrid& g) {
  EnergyWork w{g};
  std::vector<support::WorkUnit> units(g.cells());
  const std::int64_t chunks = (g.rays + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
  for (std::size_t c = 0; c < units.size(); ++c) {
    const EnergyCell cell = g.cell_at(c);
    units[c].chunks = chunks;
    units[c].chunk_cost = ray_cost_ns(cell, pilot_bounces(w, c)) * std::min<std::int64_t>(g.rays, sim::kRaysPerChunk);
    units[c].has_fixed = true;
    units[c].fixed_cost = model_cost_ns(cell);
  }
  nlohmann::json d = {{"command", "energy"},
                      {"kind", "energy"},
                      {"input_file", ""},
                      {"input_path", ""},
                      {"input", energy_grid_json(g)},
                      {"options", nlohmann::json::object()}};
  return make_job(std::move(w), std::move(units), std::move(d));
}

EnergyTable energy_table_from(const EnergyGrid& g, std::vector<UnitResult<EnergyWork>> results) {
  EnergyTable t;
  t.grid = g;
  for (std::size_t c = 0; c < results.size(); ++c)
    t.cells.push_back({g.cell_at(c), std::move(results[c].tally), std::move(*results[c].fixed)});
  return t;
}

std::optional<EnergyTable> run_energy_table(const EnergyGrid& g, int threads, const support::ProgressFn& progress,
                                            const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  const Job<EnergyWork> job = energy_job(g);
  auto results = run_job(job, threads, progress, cancel);
  if (!results) return std::nullopt;
  EnergyTable t = energy_table_from(g, std::move(*results));
  t.threads = support::resolve_threads(threads);
  t.wall_s = support::seconds_since(t0);
  return t;
}

std::vector<EnergyArray> energy_arrays(const EnergyTable& t) {
  const EnergyGrid& g = t.grid;
  const std::size_t R = static_cast<std::size_t>(g.max_k) + 1;
  const std::vector<std::size_t> cell_shape = {g.ndfs.size(), g.dims.size(), g.alphas.size(), g.mus.size()};
  std::vector<std::size_t> row_shape = cell_shape;
  row_shape.push_back(R);
  std::vector<EnergyArray> a = {{"E_sim", row_shape, {}},
                                {"E_sim_se", row_shape, {}},
                                {"E_model", row_shape, {}},
                                {"E_total_sim", cell_shape, {}},
                                {"E_total_sim_se", cell_shape, {}},
                                {"E_total_model", cell_shape, {}},
                                {"E_multiple_sim", cell_shape, {}},
                                {"E_multiple_sim_se", cell_shape, {}},
                                {"E_multiple_model", cell_shape, {}},
                                {"E_cook_torrance", cell_shape, {}},
                                {"lost_fraction", cell_shape, {}}};
  auto se = [](double p, double n) { return std::sqrt(std::max(0.0, p * (1.0 - p)) / n); };
  for (const EnergyCellResult& c : t.cells) {
    const double N = static_cast<double>(c.counts.rays);
    for (std::size_t r = 0; r < R; ++r) {
      const double p = static_cast<double>(c.counts.by_k[r + 1]) / N;
      a[0].values.push_back(p);
      a[1].values.push_back(se(p, N));
      a[2].values.push_back(c.model.by_k[r + 1]);
    }
    const double total = static_cast<double>(c.counts.escaped) / N;
    const double multiple = static_cast<double>(c.counts.escaped - c.counts.by_k[1]) / N;
    a[3].values.push_back(total);
    a[4].values.push_back(se(total, N));
    a[5].values.push_back(c.model.albedo);
    a[6].values.push_back(multiple);
    a[7].values.push_back(se(multiple, N));
    a[8].values.push_back(c.model.albedo - c.model.by_k[1]);
    a[9].values.push_back(c.model.cook_torrance);
    a[10].values.push_back(static_cast<double>(c.counts.lost()) / N);
  }
  return a;
}

namespace {
// The largest |sim - model| in standard errors (floored at one ray's worth, 1/N) over the cells
// and rows, and where it is.
struct Agreement {
  double max_z = 0.0;
  std::size_t cell = 0;
  int k = 0;
  double max_model_albedo_error = 0.0, max_single_vs_k1 = 0.0;
  std::int64_t rays = 0, lost = 0, zero_bounce = 0;
};
Agreement agreement(const EnergyTable& t) {
  Agreement a;
  for (std::size_t n = 0; n < t.cells.size(); ++n) {
    const EnergyCellResult& c = t.cells[n];
    const double N = static_cast<double>(c.counts.rays);
    a.rays += c.counts.rays, a.lost += c.counts.lost(), a.zero_bounce += c.counts.by_k[0];
    for (std::size_t r = 1; r < c.counts.by_k.size(); ++r) {
      const double p = static_cast<double>(c.counts.by_k[r]) / N, m = c.model.by_k[r];
      const double z = std::abs(p - m) / std::max(std::sqrt(std::max(m, 1.0 / N) * (1.0 - m) / N), 1.0 / N);
      if (z > a.max_z || std::isnan(z)) a.max_z = z, a.cell = n, a.k = static_cast<int>(r);
    }
    a.max_model_albedo_error = std::max(a.max_model_albedo_error, std::abs(c.model.albedo - 1.0));
    a.max_single_vs_k1 = std::max(a.max_single_vs_k1, std::abs(c.model.cook_torrance - c.model.by_k[1]));
  }
  return a;
}

nlohmann::json nested(const EnergyArray& a) {
  // Row-major values into nested lists of the array's shape.
  std::function<nlohmann::json(std::size_t, std::size_t)> build = [&](std::size_t dim, std::size_t offset) {
    nlohmann::json out = nlohmann::json::array();
    std::size_t stride = 1;
    for (std::size_t d = dim + 1; d < a.shape.size(); ++d) stride *= a.shape[d];
    for (std::size_t i = 0; i < a.shape[dim]; ++i) {
      if (dim + 1 == a.shape.size())
        out.push_back(exact_json(a.values[offset + i]));
      else
        out.push_back(build(dim + 1, offset + i * stride));
    }
    return out;
  };
  return build(0, 0);
}
}  // namespace

nlohmann::json energy_table_json(const EnergyTable& t, const std::vector<std::string>& npy_files) {
  const EnergyGrid& g = t.grid;
  nlohmann::json j = provenance();
  j["command"] = "energy";
  j["threads"] = t.threads;
  j["wall_s"] = t.wall_s;
  j["grid"] = energy_grid_json(g);
  nlohmann::json theta = nlohmann::json::array();
  for (double m : g.mus) theta.push_back(output_deg(std::acos(m)));
  j["grid"]["theta_i_deg"] = theta;
  j["definitions"] = {
      {"E_k",
       "fraction of the incident light leaving after exactly k reflections (F = 1): the directional albedo "
       "of bounce order k"},
      {"sim",
       "exact tracing, every ray in a V-groove of its own drawn from the NDF (the infinite surface); "
       "standard error sqrt(E (1 - E) / N)"},
      {"model", "Lee et al. 2018 (3D: Eq. 16-17; flatland: the flatland lobe) integrated by quadrature"},
      {"cook_torrance", "albedo of Cook-Torrance with the V-cavity G (Eq. 1-3): the model's k = 1 term"},
      {"E_multiple", "sum over k >= 2 of E_k: the energy single scattering loses"},
      {"layout",
       "arrays indexed [ndf][dimension][alpha][mu], and [k - 1] last for E_sim, E_sim_se, E_model "
       "(k = 1..max_k; the last row holds every k > max_k); row-major"}};
  nlohmann::json arrays;
  const std::vector<EnergyArray> a = energy_arrays(t);
  for (std::size_t n = 0; n < a.size(); ++n) {
    if (!npy_files.empty())
      arrays[a[n].name] = {{"npy", npy_files[n]}, {"shape", a[n].shape}, {"dtype", "<f8"}};
    else
      arrays[a[n].name] = nested(a[n]);
  }
  const Agreement ag = agreement(t);
  const EnergyCell w = t.cells.empty() ? EnergyCell{} : t.cells[ag.cell].cell;
  j["summary"] = {{"cells", t.cells.size()},
                  {"rays", ag.rays},
                  {"lost_rays", ag.lost},
                  {"rays_with_zero_reflections", ag.zero_bounce},
                  {"largest_sim_model_difference_in_se", exact_json(ag.max_z)},
                  {"at",
                   {{"ndf", ndf_name(w.ndf)},
                    {"dimension", surface_dim_name(w.dim)},
                    {"alpha", w.alpha},
                    {"mu", w.mu},
                    {"k", ag.k}}},
                  {"largest_model_albedo_error", exact_json(ag.max_model_albedo_error)},
                  {"largest_cook_torrance_vs_model_k1", exact_json(ag.max_single_vs_k1)},
                  {"wall_s", t.wall_s}};
  j["arrays"] = std::move(arrays);
  return j;
}

void print_energy_table(std::ostream& os, const EnergyTable& t) {
  const EnergyGrid& g = t.grid;
  os << "energy: E(mu, alpha) per bounce order, " << g.rays << " rays per cell, seed " << g.seed << ", vgroove "
     << version_string() << " (git " << git_revision() << "), " << t.threads << " threads\n";
  os << "  cell: E_1 sim / model; E_>=2 sim (model); Cook-Torrance albedo = model E_1\n";
  std::size_t n = 0;
  for (auto ndf : g.ndfs)
    for (auto dim : g.dims) {
      os << "  " << ndf_name(ndf) << " " << surface_dim_name(dim) << "\n    alpha \\ mu";
      for (double m : g.mus) os << fmt(" %22.4g", m);
      os << "\n";
      for (double alpha : g.alphas) {
        os << fmt("    %9.4g", alpha);
        for (std::size_t m = 0; m < g.mus.size(); ++m, ++n) {
          const EnergyCellResult& c = t.cells[n];
          const double N = static_cast<double>(c.counts.rays);
          const double e1 = static_cast<double>(c.counts.by_k[1]) / N;
          const double ems = static_cast<double>(c.counts.escaped - c.counts.by_k[1]) / N;
          os << support::format(" %6.4f/%6.4f %.4f(%.4f)", e1, c.model.by_k[1], ems, c.model.albedo - c.model.by_k[1]);
        }
        os << "\n";
      }
    }
  const Agreement ag = agreement(t);
  os << "  largest |sim - model| " << fmt("%.2f", ag.max_z) << " standard errors (" << t.cells.size() << " cells x "
     << g.max_k + 1 << " orders); model albedo within " << fmt("%.1e", ag.max_model_albedo_error) << " of 1; lost rays "
     << ag.lost << " of " << ag.rays << "; wall " << fmt("%.2f", t.wall_s) << " s\n";
}

}  // namespace vgroove::validation
