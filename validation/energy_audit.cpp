// vgroove validation: the energy audit's suite, work and cells (energy_audit.h); its figures,
// report and table are in energy_audit_report.cpp.
#include "vgroove/validation/energy_audit.h"

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/albedo_vgroove.h"
#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/sim/heightfield.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/detail/part_fields.h"
#include "vgroove/validation/heightfield_lobe.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

namespace vgroove::validation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::uint64_t kAuditWalkStream = 0x6175646974ULL;  // "audit"
// The heightfield reference's streams: fields (per ndf, alpha, field), rays (per cell, chunk).
constexpr std::uint64_t kAuditFieldStream = 0x6175646668ULL, kAuditRayStream = 0x6175647268ULL;
constexpr double kEnergyUnit = 4294967296.0;  // 2^32 units per path of energy 1

std::vector<std::string> metal_symbols() {
  std::vector<std::string> s;
  for (const ReferenceMetal& m : reference_metals()) s.push_back(m.symbol);
  return s;
}

}  // namespace

EnergyAuditCell EnergyAuditSuite::cell_at(std::size_t c) const {
  EnergyAuditCell out;
  const std::size_t nm = mus.size(), na = alphas.size();
  out.mu_index = c % nm;
  out.alpha_index = (c / nm) % na;
  out.mu = mus[out.mu_index];
  out.alpha = alphas[out.alpha_index];
  out.ndf = ndfs[c / (nm * na)];
  return out;
}

EnergyAuditSuite parse_energy_audit(const nlohmann::json& j, const std::string& file) {
  support::JsonObject root(j, file, "");
  EnergyAuditSuite s;
  s.file = file;
  s.name = root.string("name");
  s.description = root.string_or("description", "");
  root.one_of("kind", {"energy_audit"});
  for (const std::string& n : read_names(root, "ndf", {"ggx", "beckmann"}))
    s.ndfs.push_back(n == "ggx" ? NdfKind::ggx : NdfKind::beckmann);
  s.alphas = read_numbers(root, "alpha", kMinAlpha, true, kMaxAlpha, true);
  s.mus = read_numbers(root, "mu", kMinMu, true, 1.0, true);
  s.walk_paths = root.integer("walk_paths", 1, kMaxAuditPaths);
  s.seed = static_cast<std::uint64_t>(root.integer_or("seed", 1, 0, std::numeric_limits<long long>::max()));
  s.max_k = static_cast<int>(root.integer("max_k", 1, kMaxAuditK));
  s.grey_F0 = read_numbers(root, "grey_F0", 0.0, true, 1.0, true);
  // The white furnace and the metalness mixes' dielectric are always there.
  for (double F0 : {1.0, 0.04})
    if (std::find(s.grey_F0.begin(), s.grey_F0.end(), F0) == s.grey_F0.end()) s.grey_F0.push_back(F0);
  std::sort(s.grey_F0.begin(), s.grey_F0.end());
  s.grey_F0.erase(std::unique(s.grey_F0.begin(), s.grey_F0.end()), s.grey_F0.end());
  s.metals = read_names(root, "metals", metal_symbols());
  s.metalness = read_numbers(root, "metalness", 0.0, true, 1.0, true);
  {
    support::JsonObject r = root.object("regions");
    s.rough_alpha = r.number("rough_alpha", kMinAlpha, true, kMaxAlpha, true);
    s.grazing_mu = r.number("grazing_mu", kMinMu, true, 1.0, true);
    r.finish();
  }
  s.cycles_table = root.boolean_or("cycles_table", true);
  if (root.has("references")) {
    const std::vector<std::string> refs =
        read_names(root, "references", {kAuditReferences[0], kAuditReferences[1], kAuditReferences[2]});
    for (const char* must : {kAuditReferences[0], kAuditReferences[1]})
      if (std::find(refs.begin(), refs.end(), must) == refs.end())
        root.fail("references", std::string("lacks \"") + must +
                                    "\": the V-groove model and the Smith walk are always audited (\"heightfield\" is "
                                    "the optional one)");
    s.heightfield = std::find(refs.begin(), refs.end(), kAuditReferences[2]) != refs.end();
  }
  if (s.heightfield) {
    support::JsonObject h = root.object("heightfield");
    s.hf_fields = static_cast<int>(h.integer("fields", 1, kAuditMaxFields));
    s.hf_rays_per_field = h.integer("rays_per_field", 1, kMaxAuditPaths);
    s.hf_field_size = static_cast<int>(h.integer("field_size", 16, 4096));
    if ((s.hf_field_size & (s.hf_field_size - 1)) != 0)
      h.fail("field_size", "= " + std::to_string(s.hf_field_size) + " is not a power of two in [16, 4096]");
    s.hf_correlation_length = h.number("correlation_length", 2.0, true, s.hf_field_size / 8.0, true);
    h.finish();
  } else if (root.has("heightfield")) {
    root.fail("heightfield", "is given but /references has no \"heightfield\"");
  }
  {
    support::JsonObject t = root.object("thresholds");
    s.sigmas = t.number("sigmas", 0.0, false, kMaxSigmas, true);
    s.vgroove_furnace = t.number("vgroove_furnace", 1e-15, true, 0.1, true);
    t.finish();
  }
  root.finish();
  return s;
}

nlohmann::json energy_audit_json(const EnergyAuditSuite& s) {
  nlohmann::json ndfs = nlohmann::json::array();
  for (NdfKind n : s.ndfs) ndfs.push_back(ndf_name(n));
  nlohmann::json j = {{"name", s.name},
                      {"kind", "energy_audit"},
                      {"description", s.description},
                      {"ndf", ndfs},
                      {"alpha", exact_json(s.alphas)},
                      {"mu", exact_json(s.mus)},
                      {"walk_paths", s.walk_paths},
                      {"seed", s.seed},
                      {"max_k", s.max_k},
                      {"grey_F0", exact_json(s.grey_F0)},
                      {"metals", s.metals},
                      {"metalness", exact_json(s.metalness)},
                      {"regions", {{"rough_alpha", s.rough_alpha}, {"grazing_mu", s.grazing_mu}}},
                      {"thresholds", {{"sigmas", s.sigmas}, {"vgroove_furnace", s.vgroove_furnace}}}};
  j["cycles_table"] = s.cycles_table;
  if (s.heightfield) {  // only then: the default audit's spec is what it was
    j["references"] = {kAuditReferences[0], kAuditReferences[1], kAuditReferences[2]};
    j["heightfield"] = {{"fields", s.hf_fields},
                        {"rays_per_field", s.hf_rays_per_field},
                        {"field_size", s.hf_field_size},
                        {"correlation_length", exact_json(s.hf_correlation_length)}};
  }
  return j;
}

// The fields of one (ndf, alpha), each made once on first use by whichever thread needs it (every mu
// of it traces the same fields: audit_heightfield_field).
struct AuditFields {
  struct Slot {
    std::once_flag made;
    sim::HeightfieldSurface surface;
  };
  std::vector<std::unique_ptr<Slot>> slots;
};

// The fields some context holds now, by (ndf, alpha) index (weakly), and the group prepared last
// (strongly: the next cell, usually of the same group, finds them after its predecessor's context
// is gone). Memory: the contexts' fields and one group's more.
struct AuditFieldShare {
  std::mutex mutex;
  std::map<std::size_t, std::weak_ptr<AuditFields>> held;
  std::shared_ptr<AuditFields> last;
};

std::shared_ptr<const EnergyAuditWork::Context> EnergyAuditWork::prepare(std::size_t cell) const {
  auto ctx = std::make_shared<Context>();
  if (!suite.heightfield) return ctx;
  const std::size_t group = cell / suite.mus.size();
  std::unique_lock<std::mutex> lock;
  if (field_share) {
    lock = std::unique_lock<std::mutex>(field_share->mutex);
    ctx->fields = field_share->held[group].lock();
    if (ctx->fields) {
      field_share->last = ctx->fields;
      return ctx;
    }
  }
  ctx->fields = std::make_shared<AuditFields>();
  for (int f = 0; f < suite.hf_fields; ++f) ctx->fields->slots.push_back(std::make_unique<AuditFields::Slot>());
  if (field_share) field_share->held[group] = field_share->last = ctx->fields;
  return ctx;
}

sim::HeightfieldSurface audit_heightfield_field(const EnergyAuditSuite& s, std::size_t cell, int field) {
  const EnergyAuditCell c = s.cell_at(cell);
  const HeightfieldFieldSpec spec{
      c.ndf, c.alpha, s.hf_field_size, s.hf_correlation_length, HeightfieldSurfaceKind::gaussian, 1.0};
  // One surface per (ndf, alpha) measured at every mu: the key drops the mu index.
  const std::uint64_t key = static_cast<std::uint64_t>(cell / s.mus.size()) * 65536 + static_cast<std::uint64_t>(field);
  return make_field_surface(spec, sim::Rng(s.seed, kAuditFieldStream, key).next_u64());
}

int audit_heightfield_field_of(const EnergyAuditSuite& s, std::int64_t chunk) {
  return static_cast<int>((chunk - s.walk_chunks()) / s.hf_chunks_per_field());
}

void audit_heightfield_rays(const EnergyAuditSuite& s, const sim::HeightfieldSurface& f, std::size_t cell,
                            std::int64_t chunk, std::vector<Eigen::Vector3d>& origins, Eigen::Vector3d& dir) {
  const EnergyAuditCell c = s.cell_at(cell);
  const std::int64_t q = (chunk - s.walk_chunks()) % s.hf_chunks_per_field();
  const std::int64_t first = q * kAuditRaysPerChunk,
                     last = std::min<std::int64_t>(s.hf_rays_per_field, first + kAuditRaysPerChunk);
  sim::Rng rng(sim::splitmix64(s.seed ^ kAuditRayStream), cell, static_cast<std::uint64_t>(chunk));
  const double n = static_cast<double>(f.field.n), z0 = f.hierarchy.root().hi + 1.0;
  origins.clear();
  for (std::int64_t r = first; r < last; ++r) {
    const double x = n * rng.uniform(), y = n * rng.uniform();
    origins.emplace_back(x, y, z0);
  }
  dir = Eigen::Vector3d(-std::sqrt((1.0 - c.mu) * (1.0 + c.mu)), 0.0, -c.mu);
}

namespace {

// The heightfield reference's chunk: each ray traced once with its bounce cosines, its weight per
// channel prod_j F_c(cos_j) in bounce order (sim/heightfield_tracer.h: the throughput of a trace
// with fresnel = F_c), in units of 2^-32 per ray.
void run_heightfield_chunk(const EnergyAuditWork& w, const EnergyAuditWork::Context& ctx, std::size_t cell,
                           std::int64_t chunk, AuditTally& t) {
  const EnergyAuditSuite& s = w.suite;
  const int C = w.channels->size(), R = s.max_k + 2;
  const int field = audit_heightfield_field_of(s, chunk);
  AuditFields::Slot& slot = *ctx.fields->slots[static_cast<std::size_t>(field)];
  std::call_once(slot.made, [&] { slot.surface = audit_heightfield_field(s, cell, field); });
  std::vector<Eigen::Vector3d> origins;
  Eigen::Vector3d dir;
  audit_heightfield_rays(s, slot.surface, cell, chunk, origins, dir);
  std::vector<double> cosines, prod(static_cast<std::size_t>(C)), f(static_cast<std::size_t>(C));
  sim::HeightfieldRayOptions opt;
  opt.max_bounces = kHeightfieldMaxBounces;
  opt.cosines = &cosines;
  for (const Eigen::Vector3d& o : origins) {
    const sim::HeightfieldRayResult r = sim::trace_heightfield_ray(slot.surface, o, dir, opt);
    ++t.hf_rays;
    if (r.how == sim::HeightfieldFate::lost) {
      ++t.hf_lost;
      continue;
    }
    if (r.how == sim::HeightfieldFate::bounce_limit) {
      ++t.hf_bounce_limit;
      continue;
    }
    std::fill(prod.begin(), prod.end(), 1.0);
    for (double cj : cosines) {
      w.channels->evaluate(cj, f.data());
      for (int c = 0; c < C; ++c) prod[static_cast<std::size_t>(c)] *= f[static_cast<std::size_t>(c)];
    }
    const std::size_t row = static_cast<std::size_t>(std::min(r.bounces, s.max_k + 1));
    ++t.hf_by_k[row];
    ++t.hf_field_by_k[static_cast<std::size_t>(field) * R + row];
    for (int c = 0; c < C; ++c) {
      const std::int64_t units = std::llround(prod[static_cast<std::size_t>(c)] * kEnergyUnit);
      t.hf_energy[row * C + static_cast<std::size_t>(c)] += units;
      t.hf_field_energy[static_cast<std::size_t>(field) * C + static_cast<std::size_t>(c)] += units;
    }
  }
}

}  // namespace

EnergyAuditWork::Tally EnergyAuditWork::run_chunks(const Context& ctx, std::size_t cell, std::int64_t begin,
                                                   std::int64_t end) const {
  const EnergyAuditCell c = suite.cell_at(cell);
  const int C = channels->size(), R = suite.max_k + 2;
  Tally t;
  t.by_k.assign(static_cast<std::size_t>(R), 0);
  t.energy.assign(static_cast<std::size_t>(R) * C, 0);
  if (suite.heightfield) {
    t.hf_by_k.assign(static_cast<std::size_t>(R), 0);
    t.hf_energy.assign(static_cast<std::size_t>(R) * C, 0);
    t.hf_field_by_k.assign(static_cast<std::size_t>(suite.hf_fields) * R, 0);
    t.hf_field_energy.assign(static_cast<std::size_t>(suite.hf_fields) * C, 0);
  }
  const analytic::Dir3 i{std::sqrt((1.0 - c.mu) * (1.0 + c.mu)), 0.0, c.mu};
  std::vector<double> prod(C), f(C);
  for (std::int64_t chunk = begin; chunk < end; ++chunk) {
    if (chunk >= suite.walk_chunks()) {
      run_heightfield_chunk(*this, ctx, cell, chunk, t);
      continue;
    }
    sim::Rng rng(sim::splitmix64(suite.seed ^ kAuditWalkStream), cell, static_cast<std::uint64_t>(chunk));
    auto uniform = [&rng] { return sim::uniform_open(rng); };
    const std::int64_t first = chunk * kAuditPathsPerChunk,
                       last = std::min<std::int64_t>(suite.walk_paths, first + kAuditPathsPerChunk);
    for (std::int64_t p = first; p < last; ++p) {
      std::fill(prod.begin(), prod.end(), 1.0);
      const analytic::Walk3d w = analytic::smith_walk_3d(
          c.ndf, c.alpha, i, uniform,
          [&](double cos_vm) {
            channels->evaluate(cos_vm, f.data());
            for (int ch = 0; ch < C; ++ch) prod[ch] *= f[ch];
          },
          kWalkMaxBounces);
      ++t.paths;
      if (!w.left) {
        ++t.lost;
        continue;
      }
      const std::size_t row = static_cast<std::size_t>(std::min(w.k, suite.max_k + 1));
      ++t.by_k[row];
      for (int ch = 0; ch < C; ++ch) t.energy[row * C + ch] += std::llround(prod[ch] * kEnergyUnit);
    }
  }
  return t;
}

void EnergyAuditWork::merge(Tally& into, const Tally& from) {
  into.paths += from.paths, into.lost += from.lost;
  for (std::size_t r = 0; r < into.by_k.size(); ++r) into.by_k[r] += from.by_k[r];
  for (std::size_t r = 0; r < into.energy.size(); ++r) into.energy[r] += from.energy[r];
  into.hf_rays += from.hf_rays, into.hf_lost += from.hf_lost, into.hf_bounce_limit += from.hf_bounce_limit;
  auto add = [](std::vector<std::int64_t>& a, const std::vector<std::int64_t>& b) {
    for (std::size_t r = 0; r < a.size(); ++r) a[r] += b[r];
  };
  add(into.hf_by_k, from.hf_by_k), add(into.hf_energy, from.hf_energy);
  add(into.hf_field_by_k, from.hf_field_by_k), add(into.hf_field_energy, from.hf_field_energy);
}

EnergyAuditWork::Fixed EnergyAuditWork::run_fixed(std::size_t cell) const {
  const auto t0 = std::chrono::steady_clock::now();
  const EnergyAuditCell c = suite.cell_at(cell);
  const int C = channels->size();
  Fixed f;
  f.filament_dfg_y = f.cycles_E = f.cycles_E_avg = kNaN;
  const analytic::VgrooveAlbedo v =
      analytic::vgroove_albedo(c.ndf, c.alpha, c.mu, C, channels->reflectance(), suite.max_k);
  f.vgroove_rows = v.by_k;
  analytic::AlbedoOptions opt;
  opt.tol = 1e-10;
  auto single = [&](const analytic::MicrofacetModel& m, SingleScattering& s, std::vector<double>& E_F,
                    bool with_E_avg = true) {
    s.E = analytic::albedo_single(m, c.alpha, c.mu, opt).value;
    const analytic::SplitSum ss = analytic::dfg_split_sum(m, c.alpha, c.mu, opt);
    s.scale = ss.scale.value, s.bias = ss.bias.value;
    s.E_avg = kNaN;
    if (with_E_avg && c.mu_index == 0) {
      analytic::AlbedoOptions avg;
      avg.tol = 1e-9;
      s.E_avg = analytic::albedo_average(m, c.alpha, avg).value;
    }
    E_F.resize(static_cast<std::size_t>(C));
    for (int ch = 0; ch < C; ++ch) {
      const Channel& k = channels->channels()[static_cast<std::size_t>(ch)];
      E_F[static_cast<std::size_t>(ch)] = k.kind == ChannelKind::schlick
                                              ? k.F0 * s.scale + s.bias
                                              : analytic::albedo_single_fresnel(
                                                    m, c.alpha, c.mu, [&k](double x) { return k.F(x); }, opt)
                                                    .value;
    }
  };
  single({c.ndf, analytic::MaskingKind::smith_height_correlated}, f.smith, f.smith_E_F);
  single({c.ndf, analytic::MaskingKind::vcavity}, f.vcavity, f.vcavity_E_F);
  single({c.ndf, analytic::MaskingKind::smith_separable}, f.separable, f.separable_E_F, false);
  if (c.ndf == NdfKind::ggx) {
    f.filament_dfg_y = filament_dfg_y(c.alpha, c.mu);
    if (cycles) f.cycles_E = cycles_E(*cycles, c.alpha, c.mu), f.cycles_E_avg = cycles_E_avg(*cycles, c.alpha);
  }
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return f;
}

nlohmann::json EnergyAuditWork::tally_json(const Tally& t) {
  nlohmann::json j = {{"paths", t.paths}, {"lost", t.lost}, {"by_k", t.by_k}, {"energy", t.energy}};
  if (!t.hf_by_k.empty())
    j["heightfield"] = {{"rays", t.hf_rays},
                        {"lost", t.hf_lost},
                        {"bounce_limit", t.hf_bounce_limit},
                        {"by_k", t.hf_by_k},
                        {"energy", t.hf_energy},
                        {"field_by_k", t.hf_field_by_k},
                        {"field_energy", t.hf_field_energy}};
  return j;
}

EnergyAuditWork::Tally EnergyAuditWork::read_tally(support::JsonObject& j, std::size_t,
                                                   const std::vector<ChunkRun>& runs) const {
  Tally t;
  // The walk's chunks [0, walk_chunks) and the heightfield's after them.
  const std::int64_t W = suite.walk_chunks();
  std::vector<ChunkRun> walk_runs;
  std::int64_t hf_rays = 0;
  for (const ChunkRun& r : runs) {
    if (r.first < W) walk_runs.emplace_back(r.first, std::min(r.second, W));
    for (std::int64_t c = std::max(r.first, W); c < r.second; ++c) {
      const std::int64_t q = (c - W) % suite.hf_chunks_per_field();
      hf_rays += std::min<std::int64_t>(suite.hf_rays_per_field, (q + 1) * kAuditRaysPerChunk) - q * kAuditRaysPerChunk;
    }
  }
  const std::int64_t paths = rays_in_chunks(walk_runs, suite.walk_paths, kAuditPathsPerChunk);
  t.paths = j.integer("paths", paths, paths);
  t.lost = j.integer("lost", 0, paths);
  const std::size_t R = static_cast<std::size_t>(suite.max_k) + 2, C = static_cast<std::size_t>(channels->size());
  t.by_k = read_counts(j, "by_k", R, paths);
  check_sum(j, "by_k", t.by_k, paths - t.lost, "the paths that left (paths - lost)");
  t.energy = read_counts(j, "energy", R * C, std::numeric_limits<std::int64_t>::max());
  for (std::size_t r = 0; r < R; ++r)
    for (std::size_t c = 0; c < C; ++c)
      if (static_cast<double>(t.energy[r * C + c]) > static_cast<double>(t.by_k[r]) * kEnergyUnit)
        j.fail_at("energy", r * C + c,
                  "= " + std::to_string(t.energy[r * C + c]) + " exceeds its row's paths (" +
                      std::to_string(t.by_k[r]) + ") times 2^32: a path keeps at most all its energy");
  if (suite.heightfield) {
    support::JsonObject h = j.object("heightfield");
    t.hf_rays = h.integer("rays", hf_rays, hf_rays);
    t.hf_lost = h.integer("lost", 0, hf_rays);
    t.hf_bounce_limit = h.integer("bounce_limit", 0, hf_rays - t.hf_lost);
    t.hf_by_k = read_counts(h, "by_k", R, hf_rays);
    check_sum(h, "by_k", t.hf_by_k, hf_rays - t.hf_lost - t.hf_bounce_limit,
              "the rays that left (rays - lost - bounce_limit)");
    t.hf_energy = read_counts(h, "energy", R * C, std::numeric_limits<std::int64_t>::max());
    for (std::size_t r = 0; r < R; ++r)
      for (std::size_t c = 0; c < C; ++c)
        if (static_cast<double>(t.hf_energy[r * C + c]) > static_cast<double>(t.hf_by_k[r]) * kEnergyUnit)
          h.fail_at("energy", r * C + c, "exceeds its row's rays times 2^32: a ray keeps at most all its energy");
    const std::size_t F = static_cast<std::size_t>(suite.hf_fields);
    t.hf_field_by_k = read_counts(h, "field_by_k", F * R, hf_rays);
    t.hf_field_energy = read_counts(h, "field_energy", F * C, std::numeric_limits<std::int64_t>::max());
    // The per-field arrays add up to the rows' totals.
    for (std::size_t r = 0; r < R; ++r) {
      std::int64_t n = 0;
      for (std::size_t f = 0; f < F; ++f) n += t.hf_field_by_k[f * R + r];
      if (n != t.hf_by_k[r]) h.fail("field_by_k", "does not add up over the fields to /by_k");
    }
    for (std::size_t c = 0; c < C; ++c) {
      std::int64_t rows = 0, fields = 0;
      for (std::size_t r = 0; r < R; ++r) rows += t.hf_energy[r * C + c];
      for (std::size_t f = 0; f < F; ++f) fields += t.hf_field_energy[f * C + c];
      if (rows != fields) h.fail("field_energy", "does not add up over the fields to /energy's channel total");
    }
    h.finish();
  }
  return t;
}

nlohmann::json EnergyAuditWork::fixed_json(const Fixed& f) {
  auto ss = [](const SingleScattering& s) {
    return nlohmann::json{{"E", exact_json(s.E)},
                          {"scale", exact_json(s.scale)},
                          {"bias", exact_json(s.bias)},
                          {"E_avg", exact_json(s.E_avg)}};
  };
  return {{"vgroove_rows", exact_json(f.vgroove_rows)},
          {"smith", ss(f.smith)},
          {"vcavity", ss(f.vcavity)},
          {"smith_E_F", exact_json(f.smith_E_F)},
          {"vcavity_E_F", exact_json(f.vcavity_E_F)},
          {"separable", ss(f.separable)},
          {"separable_E_F", exact_json(f.separable_E_F)},
          {"filament_dfg_y", exact_json(f.filament_dfg_y)},
          {"cycles_E", exact_json(f.cycles_E)},
          {"cycles_E_avg", exact_json(f.cycles_E_avg)},
          {"model_s", f.seconds}};
}

EnergyAuditWork::Fixed EnergyAuditWork::read_fixed(support::JsonObject& j, std::size_t cell) const {
  // Albedos are fractions of the incident flux; what the cell recomputes at no cost (Schlick's
  // channels from the split sum, Cycles' table) must be that value bit for bit, and what it does
  // not have (E_avg but at mu index 0, the engines' values but for GGX) NaN.
  const EnergyAuditCell c = suite.cell_at(cell);
  Fixed f;
  const std::size_t R = static_cast<std::size_t>(suite.max_k) + 2, C = static_cast<std::size_t>(channels->size());
  // The V-groove rows' total is 1 with F = 1 to the suite's furnace tolerance (the audit's check of
  // it), never above 1 by more.
  const double furnace = std::max(kModelExcess, suite.vgroove_furnace);
  f.vgroove_rows = read_fractions(j, "vgroove_rows", R * C, furnace);
  for (std::size_t ch = 0; ch < C; ++ch) {
    double total = 0.0;
    for (std::size_t r = 0; r < R; ++r) total += f.vgroove_rows[r * C + ch];
    if (!(total <= 1.0 + furnace))
      j.fail("vgroove_rows", "adds up to an albedo of " + support::format("%.17g", total) + " in channel " +
                                 std::to_string(ch) + ", more than 1 + vgroove_furnace");
  }
  auto nan_or = [&](support::JsonObject& o, const std::string& key, bool present) {
    const double x = read_exact_double(o, key);
    if (present && !(x >= -kModelExcess && x <= 1.0 + kModelExcess))
      o.fail(key, "= " + support::value_text(o.raw(key)) + " is out of range [0, 1] (an albedo)");
    if (!present && !std::isnan(x))
      o.fail(key, "= " + support::value_text(o.raw(key)) + " must be \"nan\" (not computed for this cell)");
    return x;
  };
  auto ss = [&](const std::string& key, SingleScattering& s, bool with_E_avg = true) {
    support::JsonObject o = j.object(key);
    s.E = read_fraction(o, "E");
    s.scale = read_fraction(o, "scale");
    s.bias = read_fraction(o, "bias");
    s.E_avg = nan_or(o, "E_avg", with_E_avg && c.mu_index == 0);
    o.finish();
  };
  ss("smith", f.smith);
  ss("vcavity", f.vcavity);
  ss("separable", f.separable, false);
  auto E_F = [&](const std::string& key, const SingleScattering& s) {
    std::vector<double> v = read_fractions(j, key, C);
    for (std::size_t ch = 0; ch < C; ++ch) {
      const Channel& k = channels->channels()[ch];
      if (k.kind == ChannelKind::schlick && v[ch] != k.F0 * s.scale + s.bias)
        j.fail_at(key, ch,
                  "= " + support::value_text(j.raw(key)[ch]) + " is not F0 scale + bias = " +
                      support::format("%.17g", k.F0 * s.scale + s.bias) + " (Schlick's channel)");
    }
    return v;
  };
  f.smith_E_F = E_F("smith_E_F", f.smith);
  f.vcavity_E_F = E_F("vcavity_E_F", f.vcavity);
  f.separable_E_F = E_F("separable_E_F", f.separable);
  const bool ggx = c.ndf == NdfKind::ggx;
  f.filament_dfg_y = nan_or(j, "filament_dfg_y", ggx);
  f.cycles_E = read_exact_double(j, "cycles_E");
  f.cycles_E_avg = read_exact_double(j, "cycles_E_avg");
  auto same = [&](const std::string& key, double x, double want) {
    if (!(x == want || (std::isnan(x) && std::isnan(want))))
      j.fail(key, "= " + support::value_text(j.raw(key)) + " is not the table's " + support::format("%.17g", want));
  };
  same("cycles_E", f.cycles_E, ggx && cycles ? cycles_E(*cycles, c.alpha, c.mu) : kNaN);
  same("cycles_E_avg", f.cycles_E_avg, ggx && cycles ? cycles_E_avg(*cycles, c.alpha) : kNaN);
  f.seconds = j.number("model_s", 0.0, true, 1e9, true);
  return f;
}

nlohmann::json energy_audit_command_suite(const std::vector<std::string>& ndfs, const std::vector<double>& alphas,
                                          const std::vector<double>& mus, long long paths, long long seed, int max_k,
                                          bool heightfield) {
  nlohmann::json suite = {{"name", "energy_audit_cli"},
                          {"kind", "energy_audit"},
                          {"description", "vgroove energy --audit"},
                          {"ndf", ndfs},
                          {"alpha", alphas},
                          {"mu", mus},
                          {"walk_paths", paths},
                          {"seed", seed},
                          {"max_k", max_k},
                          {"grey_F0", {0.02, 0.04, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0}},
                          {"metals", {"Au", "Ag", "Cu", "Al"}},
                          {"metalness", {0.0, 0.25, 0.5, 0.75, 1.0}},
                          {"regions", {{"rough_alpha", 0.5}, {"grazing_mu", 0.25}}},
                          {"cycles_table", true},
                          {"thresholds", {{"sigmas", 5}, {"vgroove_furnace", 1e-7}}}};
  if (heightfield) {
    suite["references"] = {"vgroove", "smith_walk", "heightfield"};
    suite["heightfield"] = {{"fields", 4},
                            {"rays_per_field", std::max<long long>(1, paths / 4)},
                            {"field_size", 256},
                            {"correlation_length", 8}};
  }
  return suite;
}

double energy_audit_memory_bytes(const EnergyAuditSuite& s, int threads) {
  // Per cell its tally and fixed part (rows x channels, ~50 channels) and the report's arrays.
  double bytes = static_cast<double>(s.cells()) * (s.max_k + 2) * 64.0 * 8.0 * 12.0;
  if (s.heightfield)  // two cells' fields per worker and the group prepared last (AuditFieldShare)
    bytes += (2.0 * support::resolve_threads(threads) + 1.0) * s.hf_fields * sim::heightfield_bytes(s.hf_field_size);
  return bytes;
}

Job<EnergyAuditWork> energy_audit_job(const EnergyAuditSuite& s, nlohmann::json descriptor) {
  EnergyAuditWork w{s, std::make_shared<const ChannelSet>(s.grey_F0, s.metals), nullptr, nullptr};
  if (s.heightfield) w.field_share = std::make_shared<AuditFieldShare>();
  if (s.cycles_table) w.cycles = std::make_shared<const CyclesTables>(published_cycles_tables());
  std::vector<support::WorkUnit> units(s.cells());
  // A worker holds its cell's fields (at most two cells' at once per worker), the share one group more.
  if (s.heightfield)
    check_field_fits(s.hf_field_size, (2.0 * support::resolve_threads(0) + 1.0) * s.hf_fields,
                     s.file + ": /heightfield/field_size", 16);
  for (std::size_t c = 0; c < units.size(); ++c) {
    // Estimates (ns of one core; they only balance the shards): ~1.5 us a path, ~0.3 s the fixed part
    // (three times that where E_avg is computed); a heightfield chunk about a walk chunk.
    units[c].chunks = s.chunks();
    units[c].chunk_cost = 1500 * std::min<std::int64_t>(s.walk_paths, kAuditPathsPerChunk);
    units[c].has_fixed = true;
    units[c].fixed_cost = s.cell_at(c).mu_index == 0 ? 900'000'000 : 300'000'000;
  }
  return make_job(std::move(w), std::move(units), std::move(descriptor));
}

}  // namespace vgroove::validation
