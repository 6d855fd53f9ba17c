// vgroove validation: the energy audit's suite, work and cells (energy_audit.h); its figures,
// report and table are in energy_audit_report.cpp.
#include "vgroove/validation/energy_audit.h"

#include "vgroove/analytic/albedo_single.h"
#include "vgroove/analytic/albedo_vgroove.h"
#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/rng.h"
#include "vgroove/support/format.h"
#include "vgroove/support/json_reader.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/detail/part_fields.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/spec_lists.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace vgroove::validation {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::uint64_t kAuditWalkStream = 0x6175646974ULL;  // "audit"
constexpr double kEnergyUnit = 4294967296.0;                 // 2^32 units per path of energy 1

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
  return j;
}

EnergyAuditWork::Tally EnergyAuditWork::run_chunks(const Context&, std::size_t cell, std::int64_t begin,
                                                   std::int64_t end) const {
  const EnergyAuditCell c = suite.cell_at(cell);
  const int C = channels->size(), R = suite.max_k + 2;
  Tally t;
  t.by_k.assign(static_cast<std::size_t>(R), 0);
  t.energy.assign(static_cast<std::size_t>(R) * C, 0);
  const analytic::Dir3 i{std::sqrt((1.0 - c.mu) * (1.0 + c.mu)), 0.0, c.mu};
  std::vector<double> prod(C), f(C);
  for (std::int64_t chunk = begin; chunk < end; ++chunk) {
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
  auto single = [&](const analytic::MicrofacetModel& m, SingleScattering& s, std::vector<double>& E_F) {
    s.E = analytic::albedo_single(m, c.alpha, c.mu, opt).value;
    const analytic::SplitSum ss = analytic::dfg_split_sum(m, c.alpha, c.mu, opt);
    s.scale = ss.scale.value, s.bias = ss.bias.value;
    s.E_avg = kNaN;
    if (c.mu_index == 0) {
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
  if (c.ndf == NdfKind::ggx) {
    f.filament_dfg_y = filament_dfg_y(c.alpha, c.mu);
    if (cycles) f.cycles_E = cycles_E(*cycles, c.alpha, c.mu), f.cycles_E_avg = cycles_E_avg(*cycles, c.alpha);
  }
  f.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return f;
}

nlohmann::json EnergyAuditWork::tally_json(const Tally& t) {
  return {{"paths", t.paths}, {"lost", t.lost}, {"by_k", t.by_k}, {"energy", t.energy}};
}

EnergyAuditWork::Tally EnergyAuditWork::read_tally(support::JsonObject& j, std::size_t,
                                                   const std::vector<ChunkRun>& runs) const {
  Tally t;
  const std::int64_t paths = rays_in_chunks(runs, suite.walk_paths, kAuditPathsPerChunk);
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
  auto ss = [&](const std::string& key, SingleScattering& s) {
    support::JsonObject o = j.object(key);
    s.E = read_fraction(o, "E");
    s.scale = read_fraction(o, "scale");
    s.bias = read_fraction(o, "bias");
    s.E_avg = nan_or(o, "E_avg", c.mu_index == 0);
    o.finish();
  };
  ss("smith", f.smith);
  ss("vcavity", f.vcavity);
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

Job<EnergyAuditWork> energy_audit_job(const EnergyAuditSuite& s, nlohmann::json descriptor) {
  EnergyAuditWork w{s, std::make_shared<const ChannelSet>(s.grey_F0, s.metals), nullptr};
  if (s.cycles_table) w.cycles = std::make_shared<const CyclesTables>(published_cycles_tables());
  std::vector<support::WorkUnit> units(s.cells());
  const std::int64_t chunks = (s.walk_paths + kAuditPathsPerChunk - 1) / kAuditPathsPerChunk;
  for (std::size_t c = 0; c < units.size(); ++c) {
    // Estimates (ns of one core; they only balance the shards): ~1.5 us a path, ~0.3 s the fixed part
    // (three times that where E_avg is computed).
    units[c].chunks = chunks;
    units[c].chunk_cost = 1500 * std::min<std::int64_t>(s.walk_paths, kAuditPathsPerChunk);
    units[c].has_fixed = true;
    units[c].fixed_cost = s.cell_at(c).mu_index == 0 ? 900'000'000 : 300'000'000;
  }
  return make_job(std::move(w), std::move(units), std::move(descriptor));
}

}  // namespace vgroove::validation
