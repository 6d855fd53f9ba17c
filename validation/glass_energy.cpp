#include "vgroove/validation/glass_energy.h"

#include "vgroove/analytic/albedo_glass.h"
#include "vgroove/analytic/compensation.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/smith_walk_3d_dielectric.h"
#include "vgroove/analytic/smith_walk_flatland_dielectric.h"
#include "vgroove/common/angles.h"
#include "vgroove/sim/beam.h"
#include "vgroove/sim/dielectric_lifted.h"
#include "vgroove/sim/dielectric_microsurface.h"
#include "vgroove/sim/dielectric_vgroove_surface.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"
#include "vgroove/support/format.h"
#include "vgroove/support/seconds_since.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/detail/part_fields.h"
#include "vgroove/validation/energy_audit.h"
#include "vgroove/validation/ranges.h"
#include "vgroove/validation/report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <string>
#include <tuple>

namespace vgroove::validation {

namespace {

constexpr std::uint64_t kGlassSurfaceStream = 0x676c617373ULL;  // "glass"
constexpr std::uint64_t kGlassRayStream = 0x676c61737372ULL;    // "glassr"

const char* side_name(sim::Medium m) { return m == sim::Medium::above ? "above" : "below"; }

// The surface of (ndf, dim, alpha) (sim/dielectric_vgroove_surface.h); the seed set apart per (ndf,
// dim, alpha).
sim::Microsurface glass_surface(const GlassGrid& g, const GlassCell& c, std::size_t surface_index) {
  sim::MicrosurfaceOptions o;
  o.ndf = c.ndf;
  o.alpha = c.alpha;
  o.grooves = g.grooves;
  o.seed = sim::Rng(g.seed, kGlassSurfaceStream, surface_index).next_u64();
  return sim::make_dielectric_vgroove_surface(o, c.dim == SurfaceDim::three_d);
}

// Which surface a cell uses: its (ndf, dimension, alpha).
std::size_t surface_index(const GlassGrid& g, std::size_t cell) {
  const GlassCell c = g.cell_at(cell);
  const auto at = [](const auto& v, const auto& x) {
    return static_cast<std::size_t>(std::find(v.begin(), v.end(), x) - v.begin());
  };
  return (at(g.ndfs, c.ndf) * g.dims.size() + at(g.dims, c.dim)) * g.alphas.size() + at(g.alphas, c.alpha);
}

std::int64_t chunks_of(const GlassGrid& g) { return (g.rays + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk; }

void tally(const sim::DielectricResult& r, sim::Medium from, int max_k, GlassCounts& t) {
  t.rays += 1;
  t.interactions += r.interactions;
  if (!r.exits.empty()) {
    const sim::DielectricExit& e = r.exits.front();
    const std::size_t row = static_cast<std::size_t>(std::min(e.k, max_k + 1) - 1);
    (e.side == from ? t.reflected : t.transmitted)[row] += 1;
  } else if (r.bounce_limit > 0.0) {
    t.bounce_limit += 1;
  } else {
    t.vertex += 1;
  }
}

// A hemispherical cell's light angle, cosine-weighted (one number): 3D mu = sqrt(u) (density 2
// mu); flatland sin theta = u (density cos theta).
void draw_cosine_weighted(SurfaceDim dim, sim::Rng& rng, double& st, double& ct) {
  const double u = sim::uniform_open(rng);
  if (dim == SurfaceDim::three_d)
    ct = std::sqrt(u), st = std::sqrt(1.0 - u);
  else
    st = u, ct = std::sqrt((1.0 - u) * (1.0 + u));
}

// Rays [begin, end) of cell `cell` in chunks of sim::kRaysPerChunk, each chunk from its own stream.
void trace_unit(const GlassGrid& g, std::size_t cell, const sim::Microsurface& surface, std::int64_t chunk0,
                std::int64_t chunk1, GlassCounts& t, const std::atomic<bool>* cancel) {
  const GlassCell c = g.cell_at(cell);
  sim::DielectricOptions opt;
  opt.eta = c.eta;
  opt.branching = sim::Branching::random;
  opt.max_interactions = g.max_interactions;
  opt.conductor_limit = g.conductor_limit;
  const sim::DielectricSurfaceTracer tracer(surface, opt);
  const bool hemisphere = c.mu == kHemisphere;
  double st = std::sqrt((1.0 - c.mu) * (1.0 + c.mu)), ct = c.mu;
  const bool above = c.from == sim::Medium::above;
  sim::DielectricResult r;
  for (std::int64_t chunk = chunk0; chunk < chunk1; ++chunk) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    sim::Rng rng(g.seed, kGlassRayStream + cell, static_cast<std::uint64_t>(chunk));
    const std::int64_t n = std::min<std::int64_t>(sim::kRaysPerChunk, g.rays - chunk * sim::kRaysPerChunk);
    for (std::int64_t j = 0; j < n; ++j) {
      if (hemisphere) draw_cosine_weighted(c.dim, rng, st, ct);
      // Flatland: the light travels along (st, -ct) from above, (st, ct) from below. 3D: the light's
      // plane of incidence at azimuth 0, travelling along (-st, 0, -+ct).
      sim::trace_dielectric_vgroove_ray(tracer, surface, c.dim == SurfaceDim::three_d, c.from,
                                        sim::Vec2(st, above ? -ct : ct), sim::Vec3(-st, 0.0, above ? -ct : ct), opt,
                                        rng, r);
      tally(r, c.from, g.max_k, t);
    }
  }
}

// The same rays' cells from the dielectric Smith walk: per ray (cosine-weighted where the cell is
// hemispherical, as trace_unit) one walk from the light's side; a walk still inside after
// max_interactions counts in bounce_limit.
void walk_unit(const GlassGrid& g, std::size_t cell, std::int64_t chunk0, std::int64_t chunk1, GlassCounts& t,
               const std::atomic<bool>* cancel) {
  const GlassCell c = g.cell_at(cell);
  analytic::DielectricWalkOptions opt;
  opt.eta = c.eta;
  opt.conductor_limit = g.conductor_limit;
  opt.max_k = g.max_interactions;
  const bool hemisphere = c.mu == kHemisphere;
  double st = std::sqrt((1.0 - c.mu) * (1.0 + c.mu)), ct = c.mu;
  const analytic::WalkMedium from =
      c.from == sim::Medium::above ? analytic::WalkMedium::above : analytic::WalkMedium::below;
  for (std::int64_t chunk = chunk0; chunk < chunk1; ++chunk) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return;
    sim::Rng rng(g.seed, kGlassRayStream + cell, static_cast<std::uint64_t>(chunk));
    const auto uniform = [&rng] { return sim::uniform_open(rng); };
    const std::int64_t n = std::min<std::int64_t>(sim::kRaysPerChunk, g.rays - chunk * sim::kRaysPerChunk);
    for (std::int64_t j = 0; j < n; ++j) {
      if (hemisphere) draw_cosine_weighted(c.dim, rng, st, ct);
      int k = 0;
      bool left = false, same_side = false;
      if (c.dim == SurfaceDim::three_d) {
        const analytic::Dir3 i{st, 0.0, from == analytic::WalkMedium::above ? ct : -ct};
        const analytic::DielectricWalk3d w = analytic::smith_walk_3d_dielectric(c.ndf, c.alpha, i, from, opt, uniform);
        k = w.k, left = w.left, same_side = w.side == from;
      } else {
        const analytic::FlatlandDielectricWalk w =
            analytic::smith_walk_flatland_dielectric(c.ndf, c.alpha, std::atan2(st, ct), from, opt, uniform);
        k = w.k, left = w.left, same_side = w.side == from;
      }
      t.rays += 1;
      t.interactions += k;
      if (!left) {
        t.bounce_limit += 1;
        continue;
      }
      const std::size_t row = static_cast<std::size_t>(std::min(k, g.max_k + 1) - 1);
      (same_side ? t.reflected : t.transmitted)[row] += 1;
    }
  }
}

GlassCounts empty_counts(int max_k) {
  GlassCounts t;
  t.reflected.assign(static_cast<std::size_t>(max_k) + 1, 0);
  t.transmitted.assign(static_cast<std::size_t>(max_k) + 1, 0);
  return t;
}

double sum(const std::vector<long long>& v) {
  double s = 0.0;
  for (long long x : v) s += static_cast<double>(x);
  return s;
}

}  // namespace

GlassCell GlassGrid::cell_at(std::size_t c) const {
  GlassCell out;
  const bool average = c >= cells();
  const std::size_t nm = average ? 1 : mus.size(), na = alphas.size(), ne = etas.size(), ns = sides.size(),
                    nd = dims.size();
  if (average) c -= cells();
  out.mu = average ? kHemisphere : mus[c % nm];
  out.alpha = alphas[(c / nm) % na];
  out.eta = etas[(c / (nm * na)) % ne];
  out.from = sides[(c / (nm * na * ne)) % ns];
  out.dim = dims[(c / (nm * na * ne * ns)) % nd];
  out.ndf = ndfs[c / (nm * na * ne * ns * nd)];
  return out;
}

void set_glass_axes(GlassGrid& g, const std::vector<std::string>& ndfs, const std::vector<std::string>& dims,
                    const std::vector<std::string>& sides, const std::string& prefix) {
  g.ndfs.clear(), g.dims.clear(), g.sides.clear();
  for (const std::string& n : ndfs) {
    const auto k = ndf_from_name(n);
    if (!k || (*k != NdfKind::ggx && *k != NdfKind::beckmann))
      throw support::UserError(prefix + "ndf = \"" + n + "\" is not one of \"ggx\", \"beckmann\"" +
                               (prefix.empty() ? "" : " with --eta"));
    g.ndfs.push_back(*k);
  }
  for (const std::string& d : dims) {
    if (d != "flatland" && d != "3d")
      throw support::UserError(prefix + "dim = \"" + d + "\" is not one of \"flatland\", \"3d\"");
    g.dims.push_back(d == "flatland" ? SurfaceDim::flatland : SurfaceDim::three_d);
  }
  for (const std::string& s : sides) {
    if (s != "above" && s != "below")
      throw support::UserError(prefix + "side = \"" + s + "\" is not one of \"above\", \"below\"");
    g.sides.push_back(s == "above" ? sim::Medium::above : sim::Medium::below);
  }
}

void check_glass_grid(const GlassGrid& g, const std::string& prefix) {
  auto list = [&](const std::vector<double>& v, const std::string& flag, double lo, double hi, const std::string& why) {
    if (v.empty() || v.size() > kMaxGridPoints)
      throw support::UserError(flag + " has " + std::to_string(v.size()) + " values, out of range [1, " +
                               std::to_string(kMaxGridPoints) + "]");
    for (double x : v)
      if (!(x >= lo && x <= hi))
        throw support::UserError(flag + " = " + support::number_text(x) + " is out of range " +
                                 support::interval_text(lo, true, hi, true) + why);
  };
  list(g.mus, prefix + "mu", kMinMu, 1.0, " (mu = cos theta_i: theta_i <= 89.9 deg, the rough surfaces' range)");
  list(g.alphas, prefix + "alpha", kMinAlpha, kMaxAlpha, "");
  list(g.etas, prefix + "eta", kMinGlassEta, kMaxGlassEta, " (n2 / n1: below the surface over above it)");
  for (double e : g.etas)
    if (e == 1.0)
      throw support::UserError(prefix + "eta = 1 is no interface (light passes straight through): leave it out");
  for (NdfKind n : g.ndfs)
    if (n != NdfKind::ggx && n != NdfKind::beckmann)
      throw support::UserError(prefix + "ndf = \"" + ndf_name(n) + "\" is not one of \"ggx\", \"beckmann\" with glass");
  if (g.ndfs.empty() || g.dims.empty() || g.sides.empty())
    throw support::UserError(prefix + "ndf, " + prefix + "dim and " + prefix + "side each need a value");
  if (g.rays < 1 || g.rays > kMaxEnergyRays)
    throw support::UserError(prefix + "rays = " + std::to_string(g.rays) + " is out of range [1, " +
                             std::to_string(kMaxEnergyRays) + "]");
  if (g.max_k < 1 || g.max_k > kMaxEnergyK)
    throw support::UserError(prefix + (prefix.empty() ? "max_k = " : "max-k = ") + std::to_string(g.max_k) +
                             " is out of range [1, " + std::to_string(kMaxEnergyK) + "]");
  if (g.grooves < 1 || g.grooves > kMaxGlassGrooves)
    throw support::UserError(prefix + "grooves = " + std::to_string(g.grooves) + " is out of range [1, " +
                             std::to_string(kMaxGlassGrooves) + "]");
}

void GlassCounts::merge(const GlassCounts& o) {
  rays += o.rays;
  for (std::size_t k = 0; k < reflected.size(); ++k) reflected[k] += o.reflected[k], transmitted[k] += o.transmitted[k];
  bounce_limit += o.bounce_limit, vertex += o.vertex, interactions += o.interactions;
}

const char* glass_reference_name(GlassReference r) {
  return r == GlassReference::smith_walk ? "smith_walk" : "vgroove";
}

GlassReference glass_reference_from(const std::string& name, const std::string& prefix) {
  if (name == "vgroove") return GlassReference::vgroove;
  if (name == "smith_walk") return GlassReference::smith_walk;
  throw support::UserError(prefix + "reference = \"" + name + "\" is not one of \"vgroove\", \"smith_walk\"");
}

std::shared_ptr<const GlassWork::Context> GlassWork::prepare(std::size_t cell) const {
  if (grid.reference == GlassReference::smith_walk) return std::make_shared<const Context>();
  return std::make_shared<const Context>(Context{glass_surface(grid, grid.cell_at(cell), surface_index(grid, cell))});
}

GlassCounts GlassWork::run_chunks(const Context& ctx, std::size_t cell, std::int64_t begin, std::int64_t end) const {
  GlassCounts t = empty_counts(grid.max_k);
  if (grid.reference == GlassReference::smith_walk)
    walk_unit(grid, cell, begin, end, t, cancel);
  else
    trace_unit(grid, cell, ctx.surface, begin, end, t, cancel);
  return t;
}

nlohmann::json GlassWork::tally_json(const Tally& t) {
  return {{"rays", t.rays},
          {"reflected", t.reflected},
          {"transmitted", t.transmitted},
          {"bounce_limit", t.bounce_limit},
          {"vertex", t.vertex},
          {"interactions", t.interactions}};
}

GlassCounts GlassWork::read_tally(support::JsonObject& j, std::size_t, const std::vector<ChunkRun>& runs) const {
  const std::int64_t n = rays_in_chunks(runs, grid.rays, sim::kRaysPerChunk);
  GlassCounts t = empty_counts(grid.max_k);
  t.rays = j.integer("rays", n, n);
  const std::size_t rows = static_cast<std::size_t>(grid.max_k) + 1;
  const auto counts = [&](const std::string& key, std::vector<long long>& into) {
    const std::vector<std::int64_t> v = read_counts(j, key, rows, t.rays);
    into.assign(v.begin(), v.end());
  };
  counts("reflected", t.reflected);
  counts("transmitted", t.transmitted);
  t.bounce_limit = j.integer("bounce_limit", 0, t.rays);
  t.vertex = j.integer("vertex", 0, t.rays);
  // Each ray meets the surface at least once and at most max_interactions times.
  t.interactions = j.integer("interactions", t.rays, t.rays * static_cast<long long>(grid.max_interactions));
  const double ended = sum(t.reflected) + sum(t.transmitted) + static_cast<double>(t.bounce_limit + t.vertex);
  if (ended != static_cast<double>(t.rays))
    j.fail("rays", "= " + std::to_string(t.rays) + " but reflected, transmitted, bounce_limit and vertex hold " +
                       support::number_text(ended) + " (every ray ends in exactly one)");
  return t;
}

GlassWork::Fixed GlassWork::read_fixed(support::JsonObject& j, std::size_t) const {
  throw support::UserError(j.file() + ": " + j.pointer() + " is given: a glass cell has no fixed part");
}

nlohmann::json glass_grid_json(const GlassGrid& g) {
  nlohmann::json ndfs = nlohmann::json::array(), dims = nlohmann::json::array(), sides = nlohmann::json::array();
  for (NdfKind n : g.ndfs) ndfs.push_back(ndf_name(n));
  for (SurfaceDim d : g.dims) dims.push_back(surface_dim_name(d));
  for (sim::Medium m : g.sides) sides.push_back(side_name(m));
  return {{"ndf", ndfs},
          {"dimensions", dims},
          {"sides", sides},
          {"eta", exact_json(g.etas)},
          {"alpha", exact_json(g.alphas)},
          {"mu", exact_json(g.mus)},
          {"rays", g.rays},
          {"seed", g.seed},
          {"max_k", g.max_k},
          {"grooves", g.grooves},
          {"max_interactions", g.max_interactions},
          {"conductor_limit", g.conductor_limit},
          {"reference", glass_reference_name(g.reference)}};
}

GlassGrid glass_grid_from_json(const nlohmann::json& j, const std::string& where) {
  GlassGrid g;
  try {
    std::vector<std::string> ndfs, dims, sides;
    for (const auto& n : j.at("ndf")) ndfs.push_back(n.get<std::string>());
    for (const auto& d : j.at("dimensions")) dims.push_back(d.get<std::string>());
    for (const auto& s : j.at("sides")) sides.push_back(s.get<std::string>());
    set_glass_axes(g, ndfs, dims, sides, where + ": ");
    g.etas = exact_doubles(j.at("eta"));
    g.alphas = exact_doubles(j.at("alpha"));
    g.mus = exact_doubles(j.at("mu"));
    g.rays = j.at("rays").get<long long>();
    g.seed = j.at("seed").get<std::uint64_t>();
    g.max_k = j.at("max_k").get<int>();
    g.grooves = j.at("grooves").get<int>();
    g.max_interactions = j.at("max_interactions").get<int>();
    g.conductor_limit = j.at("conductor_limit").get<bool>();
    g.reference = glass_reference_from(j.at("reference").get<std::string>(), where + ": ");
  } catch (const nlohmann::json::exception& e) {
    throw support::UserError(where + ": not a glass table's grid (" + e.what() + ")");
  }
  check_glass_grid(g, where + ": ");
  return g;
}

Job<GlassWork> glass_job(const GlassGrid& g, const std::atomic<bool>* cancel) {
  check_glass_grid(g);
  std::vector<support::WorkUnit> units(g.cells() + g.average_cells());
  const std::int64_t chunks = chunks_of(g);
  for (std::size_t c = 0; c < units.size(); ++c) {
    units[c].chunks = chunks;
    // About a microsecond per ray (a few interactions each); rougher surfaces take more.
    units[c].chunk_cost = static_cast<std::int64_t>(1000.0 * (1.0 + g.cell_at(c).alpha)) *
                          std::min<std::int64_t>(g.rays, sim::kRaysPerChunk);
  }
  nlohmann::json d = {
      {"command", "energy --eta"}, {"kind", "glass_energy"},      {"input_file", ""},
      {"input_path", ""},          {"input", glass_grid_json(g)}, {"options", nlohmann::json::object()}};
  return make_job(GlassWork{g, cancel}, std::move(units), std::move(d));
}

GlassTable glass_table_from(const GlassGrid& g, std::vector<UnitResult<GlassWork>> results) {
  GlassTable t;
  t.grid = g;
  for (auto& r : results) t.cells.push_back(std::move(r.tally));
  return t;
}

std::optional<GlassTable> run_glass_table(const GlassGrid& g, int threads, const support::ProgressFn& progress,
                                          const std::atomic<bool>* cancel) {
  const auto t0 = std::chrono::steady_clock::now();
  auto results = run_job(glass_job(g, cancel), threads, progress, cancel);
  if (!results) return std::nullopt;
  GlassTable t = glass_table_from(g, std::move(*results));
  t.threads = support::resolve_threads(threads);
  t.wall_s = support::seconds_since(t0);
  return t;
}

std::vector<GlassReciprocity> glass_reciprocity(const GlassTable& t) {
  const GlassGrid& g = t.grid;
  std::vector<GlassReciprocity> out;
  const std::size_t base = g.cells();
  for (std::size_t c = 0; c < g.average_cells(); ++c) {
    const GlassCell x = g.cell_at(base + c);
    if (x.from != sim::Medium::above) continue;
    for (std::size_t d = 0; d < g.average_cells(); ++d) {
      const GlassCell y = g.cell_at(base + d);
      if (y.from != sim::Medium::below || y.ndf != x.ndf || y.dim != x.dim || y.eta != x.eta || y.alpha != x.alpha)
        continue;
      const GlassCounts &a = t.cells[base + c], &b = t.cells[base + d];
      const double pa = sum(a.transmitted) / static_cast<double>(a.rays);
      const double pb = sum(b.transmitted) / static_cast<double>(b.rays);
      const double scale = x.dim == SurfaceDim::three_d ? x.eta * x.eta : x.eta;
      GlassReciprocity r;
      r.cell = x;
      r.above = pa, r.below = pb, r.scaled_below = scale * pb;
      r.se = std::hypot(std::sqrt(pa * (1 - pa) / static_cast<double>(a.rays)),
                        scale * std::sqrt(pb * (1 - pb) / static_cast<double>(b.rays)));
      out.push_back(r);
    }
  }
  return out;
}

nlohmann::json glass_table_json(const GlassTable& t) { return glass_table_json(t, glass_compensation_audit(t)); }

nlohmann::json glass_table_json(const GlassTable& t, const std::vector<GlassCompensationRow>& audit) {
  const GlassGrid& g = t.grid;
  nlohmann::json j = provenance();
  j["kind"] = "glass_energy";
  j["seed"] = g.seed;
  j["threads"] = t.threads;
  j["wall_s"] = t.wall_s;
  nlohmann::json ndfs = nlohmann::json::array(), dims = nlohmann::json::array(), sides = nlohmann::json::array();
  for (NdfKind n : g.ndfs) ndfs.push_back(ndf_name(n));
  for (SurfaceDim d : g.dims) dims.push_back(surface_dim_name(d));
  for (sim::Medium m : g.sides) sides.push_back(side_name(m));
  j["grid"] = {{"ndf", ndfs},
               {"dimension", dims},
               {"side", sides},
               {"eta", g.etas},
               {"alpha", g.alphas},
               {"mu", g.mus},
               {"rays", g.rays},
               {"max_k", g.max_k},
               {"grooves", g.grooves},
               {"max_interactions", g.max_interactions},
               {"reference", glass_reference_name(g.reference)}};
  j["definitions"] = {
      {"axes",
       "arrays are indexed [ndf][dimension][side][eta][alpha][mu] (and [row] for the by-k arrays, rows k = "
       "1..max_k then k > max_k)"},
      {"side",
       "above: light arrives in medium 1 (index n1, above the surface); below: in medium 2 (n2) from far "
       "below"},
      {"eta", "n2 / n1 (the index below the surface over the index above it), whatever the side"},
      {"mu", "cos of the light's angle from the normal of the side it arrives from"},
      {"alpha", "the NDF's roughness (GGX, Beckmann) of the grooves' facets"},
      {"E_R", "the share of the light that leaves into the medium it came from"},
      {"E_T", "the share that leaves into the other medium"},
      {"se", "standard error sqrt(E (1 - E) / rays) of a share"},
      {"surface",
       g.reference == GlassReference::smith_walk
           ? "the Smith microsurface of the NDF as Heitz et al. 2016's dielectric random walk sees it (no "
             "grooves: the grooves value is not used)"
           : "V-grooves of equal width, facet angles from the NDF (3D: the projected-area law 2 pi D cos sin; "
             "flatland: 2 D2 cos), extruded along one axis; in 3D the grooves' azimuth is uniform per ray"}};
  const std::size_t nc = g.cells(), rows = static_cast<std::size_t>(g.max_k) + 1;
  std::vector<double> er(nc), et(nc), ser(nc), set(nc), lim(nc), vtx(nc), erk(nc * rows), etk(nc * rows);
  for (std::size_t c = 0; c < nc; ++c) {
    const GlassCounts& x = t.cells[c];
    const double N = static_cast<double>(x.rays);
    er[c] = sum(x.reflected) / N, et[c] = sum(x.transmitted) / N;
    ser[c] = std::sqrt(er[c] * (1 - er[c]) / N), set[c] = std::sqrt(et[c] * (1 - et[c]) / N);
    lim[c] = static_cast<double>(x.bounce_limit) / N, vtx[c] = static_cast<double>(x.vertex) / N;
    for (std::size_t k = 0; k < rows; ++k)
      erk[c * rows + k] = static_cast<double>(x.reflected[k]) / N, etk[c * rows + k] = x.transmitted[k] / N;
  }
  const std::vector<std::size_t> shape{g.ndfs.size(), g.dims.size(),   g.sides.size(),
                                       g.etas.size(), g.alphas.size(), g.mus.size()};
  std::vector<std::size_t> shape_k = shape;
  shape_k.push_back(rows);
  auto array = [](const std::vector<std::size_t>& s, const std::vector<double>& v) {
    return nlohmann::json{{"shape", s}, {"values", v}};
  };
  j["arrays"] = {{"E_R", array(shape, er)},         {"E_T", array(shape, et)},           {"se_R", array(shape, ser)},
                 {"se_T", array(shape, set)},       {"bounce_limit", array(shape, lim)}, {"vertex", array(shape, vtx)},
                 {"E_R_by_k", array(shape_k, erk)}, {"E_T_by_k", array(shape_k, etk)}};
  nlohmann::json averages = nlohmann::json::array(), pairs = nlohmann::json::array();
  for (std::size_t c = g.cells(); c < t.cells.size(); ++c) {
    const GlassCell x = g.cell_at(c);
    const GlassCounts& n = t.cells[c];
    const double N = static_cast<double>(n.rays), pr = sum(n.reflected) / N, pt = sum(n.transmitted) / N;
    averages.push_back({{"ndf", ndf_name(x.ndf)},
                        {"dimension", surface_dim_name(x.dim)},
                        {"side", side_name(x.from)},
                        {"eta", x.eta},
                        {"alpha", x.alpha},
                        {"R_avg", pr},
                        {"T_avg", pt},
                        {"se_R", std::sqrt(pr * (1 - pr) / N)},
                        {"se_T", std::sqrt(pt * (1 - pt) / N)},
                        {"rays", n.rays}});
  }
  for (const GlassReciprocity& r : glass_reciprocity(t))
    pairs.push_back({{"ndf", ndf_name(r.cell.ndf)},
                     {"dimension", surface_dim_name(r.cell.dim)},
                     {"eta", r.cell.eta},
                     {"alpha", r.cell.alpha},
                     {"T_avg_above", r.above},
                     {"T_avg_below", r.below},
                     {"scaled_T_avg_below", r.scaled_below},
                     {"difference", r.above - r.scaled_below},
                     {"se", r.se},
                     {"z", r.z()}});
  j["averages"] = {{"definition",
                    "the light's angle drawn cosine-weighted over its hemisphere (3D: density 2 mu; "
                    "flatland: cos theta): R_avg and T_avg are the hemispherical averages, without "
                    "quadrature error"},
                   {"cells", averages}};
  j["reciprocity"] = {{"holds",
                       "T_avg(above) = eta^p T_avg(below), p = 2 in 3D and 1 in flatland (reciprocity of "
                       "the exact surface, f_t(i, o) / n_o^p = f_t(o, i) / n_i^p)"},
                      {"pairs", pairs}};
  j["kulla_conty_glass"] = glass_compensation_audit_json(audit);
  if (!audit.empty())
    j["kulla_conty_glass"].update(
        glass_form_summary_json(t, audit, glass_forms(), glass_form_summary(audit, glass_forms())));
  return j;
}

void print_glass_table(std::ostream& os, const GlassTable& t) { print_glass_table(os, t, glass_compensation_audit(t)); }

void print_glass_table(std::ostream& os, const GlassTable& t, const std::vector<GlassCompensationRow>& rows) {
  const GlassGrid& g = t.grid;
  char line[256];
  if (g.reference == GlassReference::smith_walk)
    std::snprintf(line, sizeof line,
                  "glass energy (the Smith walk): %zu cells, %lld walks each; %.1f s on %d threads\n", g.cells(),
                  g.rays, t.wall_s, t.threads);
  else
    std::snprintf(line, sizeof line, "glass energy: %zu cells, %lld rays each, %d grooves; %.1f s on %d threads\n",
                  g.cells(), g.rays, g.grooves, t.wall_s, t.threads);
  os << line;
  os << "  ndf       dim       side   eta     alpha   mu        E_R        E_T        se     limit\n";
  const std::size_t most = 200;
  for (std::size_t c = 0; c < std::min(most, g.cells()); ++c) {
    const GlassCell x = g.cell_at(c);
    const GlassCounts& n = t.cells[c];
    const double N = static_cast<double>(n.rays), er = sum(n.reflected) / N, et = sum(n.transmitted) / N;
    std::snprintf(line, sizeof line, "  %-9s %-9s %-6s %-7.4g %-7.4g %-9.4g %-10.6f %-10.6f %-6.1e %.1e\n",
                  ndf_name(x.ndf), surface_dim_name(x.dim), side_name(x.from), x.eta, x.alpha, x.mu, er, et,
                  std::sqrt(std::max(er * (1 - er), et * (1 - et)) / N), static_cast<double>(n.bounce_limit) / N);
    os << line;
  }
  if (g.cells() > most) os << "  ... " << g.cells() - most << " more cells in the JSON\n";
  for (const GlassReciprocity& r : glass_reciprocity(t)) {
    std::snprintf(line, sizeof line,
                  "  reciprocity %s %s eta %g alpha %g: T_avg above %.6f, eta^%d T_avg below %.6f (%+.1f se)\n",
                  ndf_name(r.cell.ndf), surface_dim_name(r.cell.dim), r.cell.eta, r.cell.alpha, r.above,
                  r.cell.dim == SurfaceDim::three_d ? 2 : 1, r.scaled_below, r.z());
    os << line;
  }
  print_glass_compensation_audit(os, rows);
  if (!rows.empty()) print_glass_form_summary(os, glass_form_summary(rows, glass_forms()), g.reference);
}

namespace {

double audit_share(const std::vector<long long>& v, long long rays) {
  return static_cast<double>(std::accumulate(v.begin(), v.end(), 0LL)) / static_cast<double>(rays);
}

// Both sides' R_avg, T_avg (8-point rule in mu, each value to tol 1e-5).
struct SideAverages {
  double R_out = 0.0, T_out = 0.0, R_in = 0.0, T_in = 0.0;
};
SideAverages averages(const analytic::MicrofacetModel& m, double alpha, double N) {
  analytic::AlbedoOptions o;
  o.tol = 1e-5;
  const analytic::GaussLegendre g = analytic::gauss_legendre(8);
  SideAverages s;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const double mu = 0.5 + 0.5 * g.x[k];
    const analytic::GlassAlbedo a = analytic::albedo_glass(m, alpha, mu, N, o);
    const analytic::GlassAlbedo b = analytic::albedo_glass(m, alpha, mu, 1.0 / N, o);
    s.R_out += g.w[k] * mu * a.R.value, s.T_out += g.w[k] * mu * a.T.value;
    s.R_in += g.w[k] * mu * b.R.value, s.T_in += g.w[k] * mu * b.T.value;
  }
  return s;
}

}  // namespace

analytic::MicrofacetModel glass_single_scattering_model(GlassReference r, NdfKind ndf) {
  return {ndf, r == GlassReference::smith_walk ? analytic::MaskingKind::smith_height_correlated
                                               : analytic::MaskingKind::vcavity};
}

std::vector<GlassCompensationRow> glass_compensation_audit(const GlassTable& t) {
  const GlassGrid& g = t.grid;
  std::vector<GlassCompensationRow> rows;
  if (g.conductor_limit) return rows;
  std::map<std::tuple<std::string, double, double>, SideAverages> cache;
  analytic::AlbedoOptions o;
  o.tol = 1e-5;
  const std::size_t all = g.cells() + g.average_cells();
  for (std::size_t c = 0; c < all; ++c) {
    const GlassCell x = g.cell_at(c);
    if (x.dim != SurfaceDim::three_d) continue;
    const analytic::MicrofacetModel m = glass_single_scattering_model(g.reference, x.ndf);
    const double N = x.eta > 1.0 ? x.eta : 1.0 / x.eta;
    const double eta_rel = x.from == sim::Medium::above ? x.eta : 1.0 / x.eta;
    const auto key = std::make_tuple(std::string(ndf_name(x.ndf)), x.alpha, N);
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, averages(m, x.alpha, N)).first;
    const SideAverages& s = it->second;
    analytic::KullaContyGlassAverages a;
    a.N = N;
    a.E_avg_out = s.R_out + s.T_out, a.E_avg_in = s.R_in + s.T_in;
    analytic::AlbedoOptions f;
    f.tol = 1e-12;
    a.F_avg_out = analytic::dielectric_fresnel_average(N, f).value;
    a.F_avg_in = analytic::dielectric_fresnel_average(1.0 / N, f).value;
    GlassCompensationRow r;
    r.cell = x;
    r.eta_rel = eta_rel;
    r.averages = a;
    if (x.mu == kHemisphere) {
      r.E_R = eta_rel > 1.0 ? s.R_out : s.R_in;
      r.E_T = eta_rel > 1.0 ? s.T_out : s.T_in;
    } else {
      const analytic::GlassAlbedo e = analytic::albedo_glass(m, x.alpha, x.mu, eta_rel, o);
      r.E_R = e.R.value, r.E_T = e.T.value;
    }
    r.moonray = analytic::kulla_conty_glass_albedo(r.E_R, r.E_T, analytic::kulla_conty_glass_weights(eta_rel, a));
    r.scale_one = analytic::kulla_conty_glass_albedo(
        r.E_R, r.E_T, analytic::kulla_conty_glass_weights(eta_rel, a, analytic::KullaContyGlassForm::inside_scale_one));
    const double cycles_scale = analytic::cycles_glass_albedo_scaling(r.E_R + r.E_T, 1.0);  // clear glass: Fss 1
    r.cycles = {r.E_R * cycles_scale, r.E_T * cycles_scale};
    const GlassCounts& n = t.cells[c];
    const double rays = static_cast<double>(n.rays);
    r.rays = n.rays;
    r.left = std::accumulate(n.reflected.begin(), n.reflected.end(), 0LL) +
             std::accumulate(n.transmitted.begin(), n.transmitted.end(), 0LL);
    r.R = audit_share(n.reflected, n.rays), r.T = audit_share(n.transmitted, n.rays);
    r.se_R = std::sqrt(r.R * (1.0 - r.R) / rays), r.se_T = std::sqrt(r.T * (1.0 - r.T) / rays);
    rows.push_back(r);
  }
  return rows;
}

void print_glass_compensation_audit(std::ostream& os, const std::vector<GlassCompensationRow>& rows) {
  if (rows.empty()) return;
  os << "  Kulla-Conty glass (MoonRay; scale one: the inside transmitted weight unscaled), fed with the exact\n"
        "  single scattering E_ss; formula minus traced (se of the traced value):\n"
        "  ndf       side   eta     alpha   mu      E_ss R   E_ss T   MoonRay dR  dT        scale one dR  dT      se\n";
  char line[256];
  for (const GlassCompensationRow& r : rows) {
    char mu[16];
    if (r.cell.mu == kHemisphere)
      std::snprintf(mu, sizeof mu, "avg");
    else
      std::snprintf(mu, sizeof mu, "%.4g", r.cell.mu);
    std::snprintf(line, sizeof line,
                  "  %-9s %-6s %-7.4g %-7.4g %-7s %-8.5f %-8.5f %+-9.5f %+-9.5f %+-9.5f %+-9.5f %.1e\n",
                  ndf_name(r.cell.ndf), r.cell.from == sim::Medium::above ? "above" : "below", r.cell.eta, r.cell.alpha,
                  mu, r.E_R, r.E_T, r.moonray.R - r.R, r.moonray.T - r.T, r.scale_one.R - r.R, r.scale_one.T - r.T,
                  std::max(r.se_R, r.se_T));
    os << line;
  }
}

nlohmann::json glass_compensation_audit_json(const std::vector<GlassCompensationRow>& rows) {
  nlohmann::json cells = nlohmann::json::array();
  for (const GlassCompensationRow& r : rows)
    cells.push_back({{"ndf", ndf_name(r.cell.ndf)},
                     {"side", r.cell.from == sim::Medium::above ? "above" : "below"},
                     {"eta", r.cell.eta},
                     {"alpha", r.cell.alpha},
                     {"mu", r.cell.mu == kHemisphere ? nlohmann::json("average") : nlohmann::json(r.cell.mu)},
                     {"E_ss_R", r.E_R},
                     {"E_ss_T", r.E_T},
                     {"moonray_R", r.moonray.R},
                     {"moonray_T", r.moonray.T},
                     {"scale_one_R", r.scale_one.R},
                     {"scale_one_T", r.scale_one.T},
                     {"cycles_glass_R", r.cycles.R},
                     {"cycles_glass_T", r.cycles.T},
                     {"traced_R", r.R},
                     {"traced_T", r.T},
                     {"se_R", r.se_R},
                     {"se_T", r.se_T}});
  return {{"definition",
           "Kulla-Conty rough-glass compensation as MoonRay ships it (moonray) and with the inside transmitted "
           "weight unscaled (scale_one), Cycles' glass scaling of both lobes by 1 / E (cycles_glass), fed with the "
           "exact single scattering E_ss_R, E_ss_T of the reference's "
           "model (smith_walk: Walter with the height-correlated Smith G2; vgroove: Walter with the V-cavity G) "
           "and the exact dielectric F_avg, beside the traced totals; 3D cells; docs/derivations/"
           "energy_compensation.md"},
          {"cells", cells}};
}

// ---- The forms over the grid ----------------------------------------------------------------------

const std::vector<GlassForm>& glass_forms() {
  static const std::vector<GlassForm> forms = {
      {"moonray",
       "Kulla-Conty glass as MoonRay ships it: R' = E_R + w_R (1 - E), T' = E_T + w_T (1 - E), inside w_T "
       "carrying n^2 = 1 / eta^2",
       [](const GlassCompensationRow& r) { return r.moonray; }},
      {"scale_one", "the same with the inside transmitted weight unscaled (n^2 -> 1)",
       [](const GlassCompensationRow& r) { return r.scale_one; }},
      {"cycles_glass",
       "Cycles' glass (microfacet_ggx_glass_albedo_scaling, clear glass Fss = 1): R' = E_R / E, T' = E_T / E, "
       "E = E_R + E_T of the lit side",
       [](const GlassCompensationRow& r) { return r.cycles; }}};
  return forms;
}

GlassRegions glass_regions() {
  const EnergyAuditSuite s;
  return {s.rough_alpha, s.grazing_mu};
}

double glass_share_se(double p, long long n) {
  const double N = static_cast<double>(n);
  return n > 0 ? std::sqrt(std::max(p * (1.0 - p), 1.0 / N) / N) : 0.0;
}

double glass_noise_threshold(std::size_t m) {
  // m erfc(z / sqrt 2) = 0.01, by bisection (erfc falls monotonically).
  const double want = 0.01 / static_cast<double>(std::max<std::size_t>(m, 1));
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (std::erfc(mid / std::numbers::sqrt2) > want ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void GlassErrorStat::add(double e, double z, const std::string& where) {
  if (!std::isfinite(e)) return;
  ++n, sum_abs += std::abs(e), sum += e, sum_abs_z += std::abs(z);
  if (n == 1 || std::abs(e) > std::abs(worst)) worst = e, worst_z = z, at = where;
  if (n == 1 || std::abs(z) > std::abs(max_z)) max_z = z, z_at = where;
}
double GlassErrorStat::mean_abs() const { return n ? sum_abs / static_cast<double>(n) : std::nan(""); }
double GlassErrorStat::mean() const { return n ? sum / static_cast<double>(n) : std::nan(""); }
double GlassErrorStat::mean_abs_z() const { return n ? sum_abs_z / static_cast<double>(n) : std::nan(""); }

int GlassFormSummary::closest(int side, int region, int quantity, bool farthest) const {
  int best = -1;
  for (std::size_t f = 0; f < forms.size(); ++f) {
    const GlassErrorStat& st = at(f, side, region, quantity);
    if (st.n == 0) continue;
    const double m = st.mean_abs(),
                 b = best < 0 ? 0.0 : at(static_cast<std::size_t>(best), side, region, quantity).mean_abs();
    if (best < 0 || (farthest ? m > b : m < b)) best = static_cast<int>(f);
  }
  return best;
}

namespace {

std::string glass_cell_text(const GlassCell& c) {
  return support::format("%s %s eta %.4g alpha %.4g mu %.4g", ndf_name(c.ndf), side_name(c.from), c.eta, c.alpha, c.mu);
}

bool in_glass_region(int region, const GlassRegions& g, const GlassCell& c) {
  return region == 0 || (region == 1 && c.alpha >= g.rough_alpha) || (region == 2 && c.mu <= g.grazing_mu);
}

// A row's errors (formula - traced) and their z for R', T', R' + T'.
void row_errors(const GlassCompensationRow& r, const analytic::CompensatedGlass& f, double e[3], double z[3]) {
  const double S = static_cast<double>(r.left) / static_cast<double>(r.rays);
  e[0] = f.R - r.R, e[1] = f.T - r.T, e[2] = f.R + f.T - S;
  z[0] = e[0] / glass_share_se(r.R, r.rays), z[1] = e[1] / glass_share_se(r.T, r.rays);
  z[2] = e[2] / glass_share_se(S, r.rays);
}

}  // namespace

GlassFormSummary glass_form_summary(const std::vector<GlassCompensationRow>& rows, const std::vector<GlassForm>& forms,
                                    const GlassRegions& regions) {
  GlassFormSummary s;
  s.regions = regions;
  for (const GlassForm& f : forms) s.forms.push_back(f.id);
  s.stats.assign(forms.size() * 27, GlassErrorStat{});
  for (const GlassCompensationRow& r : rows) {
    if (r.cell.mu == kHemisphere || r.rays <= 0) continue;
    const std::string where = glass_cell_text(r.cell);
    for (std::size_t f = 0; f < forms.size(); ++f) {
      double e[3], z[3];
      row_errors(r, forms[f].of(r), e, z);
      for (int side : {0, r.cell.from == sim::Medium::above ? 1 : 2})
        for (int reg = 0; reg < 3; ++reg) {
          if (!in_glass_region(reg, regions, r.cell)) continue;
          for (int q = 0; q < 3; ++q) s.stats[((f * 3 + side) * 3 + reg) * 3 + q].add(e[q], z[q], where);
        }
    }
  }
  return s;
}

namespace {

// The forms whose mean |error| is the closest's (or the farthest's) within 1e-12: ties named together.
std::string tied_names(const GlassFormSummary& s, int side, int region, int quantity, bool farthest) {
  const int b = s.closest(side, region, quantity, farthest);
  if (b < 0) return "";
  const double spread =
      s.at(static_cast<std::size_t>(s.closest(side, region, quantity, true)), side, region, quantity).mean_abs() -
      s.at(static_cast<std::size_t>(s.closest(side, region, quantity)), side, region, quantity).mean_abs();
  if (farthest && spread <= 1e-12) return "none (all tied)";
  const double m = s.at(static_cast<std::size_t>(b), side, region, quantity).mean_abs();
  std::string out;
  for (std::size_t f = 0; f < s.forms.size(); ++f) {
    const GlassErrorStat& st = s.at(f, side, region, quantity);
    if (st.n > 0 && std::abs(st.mean_abs() - m) <= 1e-12) out += (out.empty() ? "" : " = ") + s.forms[f];
  }
  return out;
}

}  // namespace

void print_glass_form_summary(std::ostream& os, const GlassFormSummary& s, GlassReference reference) {
  const GlassErrorStat& any = s.at(0, 0, 0, 0);
  if (s.forms.empty() || any.n == 0) return;
  os << "  The forms over the grid against " << glass_reference_name(reference) << " (" << any.n
     << " cells): error = formula - traced, the worst (signed), its z = error / se, the mean |error|;\n"
        "  se = sqrt(max(p (1 - p), 1 / rays) / rays) of the traced share; * within noise: the largest |z| of the "
        "line's m cells\n  <= z_m, m erfc(z_m / sqrt 2) = 1 % (Bonferroni); rough: alpha >= "
     << support::number_text(s.regions.rough_alpha) << ", grazing: mu <= " << support::number_text(s.regions.grazing_mu)
     << " (the conductor audit's regions)\n";
  os << support::format("  %-13s %-5s %-7s %4s | %-27s | %-27s | %-27s | %s\n", "form", "side", "region", "n",
                        "R' worst (z)  mean|e|", "T' worst (z)  mean|e|", "R'+T' worst (z)  mean|e|",
                        "z_m, largest |z|");
  for (std::size_t f = 0; f < s.forms.size(); ++f)
    for (int side = 0; side < 3; ++side)
      for (int reg = 0; reg < 3; ++reg) {
        if (s.at(f, side, reg, 0).n == 0) continue;
        std::string line = support::format("  %-13s %-5s %-7s %4ld", s.forms[f].c_str(), kGlassSides[side],
                                           kGlassRegionNames[reg], s.at(f, side, reg, 0).n);
        for (int q = 0; q < 3; ++q) {
          const GlassErrorStat& st = s.at(f, side, reg, q);
          line += support::format(" | %+9.2e %7.1f%s %8.2e", st.worst, st.worst_z, st.within_noise() ? "*" : " ",
                                  st.mean_abs());
        }
        os << line
           << support::format(" | %.2f, %.1f / %.1f / %.1f\n", s.at(f, side, reg, 0).threshold(),
                              std::abs(s.at(f, side, reg, 0).max_z), std::abs(s.at(f, side, reg, 1).max_z),
                              std::abs(s.at(f, side, reg, 2).max_z));
      }
  for (int side = 0; side < 3; ++side)
    for (int reg = 0; reg < 3; ++reg)
      for (int q = 0; q < 3; ++q) {
        const int b = s.closest(side, reg, q), w = s.closest(side, reg, q, true);
        if (b < 0) continue;
        const GlassErrorStat &sb = s.at(static_cast<std::size_t>(b), side, reg, q),
                             &sw = s.at(static_cast<std::size_t>(w), side, reg, q);
        os << support::format(
            "  closest from %s, %s, %s': %s (mean |error| %.2e, worst %+.2e at %s, %s); farthest %s (%.2e)\n",
            kGlassSides[side], kGlassRegionNames[reg], kGlassQuantities[q], tied_names(s, side, reg, q, false).c_str(),
            sb.mean_abs(), sb.worst, sb.at.c_str(), sb.within_noise() ? "within noise" : "beyond noise",
            tied_names(s, side, reg, q, true).c_str(), sw.mean_abs());
      }
}

nlohmann::json glass_form_summary_json(const GlassTable& t, const std::vector<GlassCompensationRow>& rows,
                                       const std::vector<GlassForm>& forms, const GlassFormSummary& s) {
  const GlassGrid& g = t.grid;
  nlohmann::json fj = nlohmann::json::array();
  for (const GlassForm& f : forms) fj.push_back({{"id", f.id}, {"formula", f.formula}});
  nlohmann::json summary = nlohmann::json::array(), closest = nlohmann::json::array();
  const auto num = [](double x) { return exact_json(x); };
  for (std::size_t f = 0; f < s.forms.size(); ++f)
    for (int side = 0; side < 3; ++side)
      for (int reg = 0; reg < 3; ++reg)
        for (int q = 0; q < 3; ++q) {
          const GlassErrorStat& st = s.at(f, side, reg, q);
          if (st.n == 0) continue;
          summary.push_back({{"form", s.forms[f]},
                             {"side", kGlassSides[side]},
                             {"region", kGlassRegionNames[reg]},
                             {"quantity", kGlassQuantities[q]},
                             {"count", st.n},
                             {"worst", num(st.worst)},
                             {"worst_at", st.at},
                             {"mean_abs", num(st.mean_abs())},
                             {"mean", num(st.mean())},
                             {"worst_z", num(st.worst_z)},
                             {"max_z", num(st.max_z)},
                             {"max_z_at", st.z_at},
                             {"mean_abs_z", num(st.mean_abs_z())},
                             {"z_threshold", st.threshold()},
                             {"within_noise", st.within_noise()}});
        }
  for (int side = 0; side < 3; ++side)
    for (int reg = 0; reg < 3; ++reg)
      for (int q = 0; q < 3; ++q) {
        const int b = s.closest(side, reg, q), w = s.closest(side, reg, q, true);
        if (b < 0) continue;
        const GlassErrorStat &sb = s.at(static_cast<std::size_t>(b), side, reg, q),
                             &sw = s.at(static_cast<std::size_t>(w), side, reg, q);
        closest.push_back(
            {{"side", kGlassSides[side]},
             {"region", kGlassRegionNames[reg]},
             {"quantity", kGlassQuantities[q]},
             {"closest", s.forms[static_cast<std::size_t>(b)]},
             {"closest_tied", tied_names(s, side, reg, q, false)},
             {"mean_abs", num(sb.mean_abs())},
             {"worst", num(sb.worst)},
             {"within_noise", sb.within_noise()},
             {"farthest", s.forms[static_cast<std::size_t>(w)]},
             {"farthest_tied", tied_names(s, side, reg, q, true)},
             {"farthest_mean_abs", num(sw.mean_abs())},
             {"statement",
              support::format("from %s, %s, %s': closest %s (mean |error| %.2e, worst %+.2e at %s, %s); farthest %s "
                              "(mean |error| %.2e)",
                              kGlassSides[side], kGlassRegionNames[reg], kGlassQuantities[q],
                              tied_names(s, side, reg, q, false).c_str(), sb.mean_abs(), sb.worst, sb.at.c_str(),
                              sb.within_noise() ? "within noise" : "beyond noise",
                              tied_names(s, side, reg, q, true).c_str(), sw.mean_abs())}});
      }
  // The error maps: the grid's 3D cells, [ndf][side][eta][alpha][mu]; NaN (null) where no row.
  const std::vector<std::size_t> shape{g.ndfs.size(), g.sides.size(), g.etas.size(), g.alphas.size(), g.mus.size()};
  const std::size_t size = shape[0] * shape[1] * shape[2] * shape[3] * shape[4];
  const auto index = [&](const GlassCell& c) {
    const auto at = [](const auto& v, const auto& x) {
      return static_cast<std::size_t>(std::find(v.begin(), v.end(), x) - v.begin());
    };
    return (((at(g.ndfs, c.ndf) * shape[1] + at(g.sides, c.from)) * shape[2] + at(g.etas, c.eta)) * shape[3] +
            at(g.alphas, c.alpha)) *
               shape[4] +
           at(g.mus, c.mu);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  nlohmann::json maps = nlohmann::json::object();
  const char* keys[] = {"R", "T", "R+T"};
  for (std::size_t f = 0; f < forms.size(); ++f) {
    std::vector<double> e[3], z[3];
    for (int q = 0; q < 3; ++q) e[q].assign(size, nan), z[q].assign(size, nan);
    for (const GlassCompensationRow& r : rows) {
      if (r.cell.mu == kHemisphere || r.rays <= 0) continue;
      double ev[3], zv[3];
      row_errors(r, forms[f].of(r), ev, zv);
      const std::size_t i = index(r.cell);
      for (int q = 0; q < 3; ++q) e[q][i] = ev[q], z[q][i] = zv[q];
    }
    nlohmann::json m = nlohmann::json::object();
    for (int q = 0; q < 3; ++q) {
      nlohmann::json ej = nlohmann::json::array(), zj = nlohmann::json::array();
      for (std::size_t i = 0; i < size; ++i) ej.push_back(num(e[q][i])), zj.push_back(num(z[q][i]));
      m[keys[q]] = {{"error", ej}, {"z", zj}};
    }
    maps[forms[f].id] = m;
  }
  nlohmann::json ndfs = nlohmann::json::array(), sides = nlohmann::json::array();
  for (NdfKind n : g.ndfs) ndfs.push_back(ndf_name(n));
  for (sim::Medium m : g.sides) sides.push_back(side_name(m));
  return {{"forms", fj},
          {"regions",
           {{"rough", "alpha >= " + support::number_text(s.regions.rough_alpha)},
            {"grazing", "mu <= " + support::number_text(s.regions.grazing_mu)},
            {"source", "the conductor audit's regions (validation/energy_audit.h, EnergyAuditSuite)"}}},
          {"noise",
           {{"se", "sqrt(max(p (1 - p), 1 / rays) / rays) of the traced share p (R, T, or R + T: the rays that left)"},
            {"z", "error / se, error = formula - traced"},
            {"within_noise",
             "max |z| over the line's cells <= z_threshold, m erfc(z_threshold / sqrt 2) = 0.01 for its m cells "
             "(Bonferroni: a 1 % false alarm when the form is exact); the feed's quadrature (tol 1e-5) is not in se"}}},
          {"summary", summary},
          {"closest", closest},
          {"error_maps",
           {{"shape", shape},
            {"axes", {{"ndf", ndfs}, {"side", sides}, {"eta", g.etas}, {"alpha", g.alphas}, {"mu", g.mus}}},
            {"definition",
             "per form and quantity, error (formula - traced) and z at [ndf][side][eta][alpha][mu], flattened "
             "row-major; \"nan\" where no 3D cell"},
            {"forms", maps}}}};
}

}  // namespace vgroove::validation
