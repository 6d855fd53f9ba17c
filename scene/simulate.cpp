#include "vgroove/scene/simulate.h"
#include "vgroove/support/printable.h"
#include "vgroove/support/seconds_since.h"

#include "vgroove/support/format.h"
#include "vgroove/validation/detail/part_fields.h"

#include "vgroove/analytic/kaleidoscope_fresnel.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/sim/effects.h"
#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/tracer.h"
#include "vgroove/support/parallel.h"
#include "vgroove/support/user_error.h"
#include "vgroove/validation/groove_case.h"
#include "vgroove/validation/partial_report.h"
#include "vgroove/validation/report.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <set>
#include <type_traits>

namespace vgroove::scene {

using namespace validation;

namespace {

// C reflectances along one path: the local cosine once per bounce, then C products (Eq. (11)).
template <class Reflectance>
struct ChannelsObserver {
  std::array<Reflectance, kMaxChannels> reflectance{};
  std::array<double, kMaxChannels> throughput{};
  int channels = 0;

  void reset() { std::fill_n(throughput.begin(), channels, 1.0); }
  void on_bounce(sim::Side, const sim::Vec2& dir_in, const sim::Facet& f) {
    const double c = std::abs(dir_in.dot(f.normal));
    for (int i = 0; i < channels; ++i)
      throughput[static_cast<std::size_t>(i)] *= reflectance[static_cast<std::size_t>(i)](c);
  }
};

sim::ConductorReflectance reflectance_of(const FresnelChannel& c, sim::ConductorReflectance*) {
  return {c.eta, c.kappa};
}
sim::SchlickReflectance reflectance_of(const FresnelChannel& c, sim::SchlickReflectance*) { return {c.F0}; }

// What every chunk shares: the scene and its grooves (one, or the microsurface's).
struct Setup {
  const Scene* scene = nullptr;
  std::vector<sim::Groove> grooves;
  int channels = 0;
  const std::atomic<bool>* cancel = nullptr;  // read before each ray: a chunk of narrow-groove rays is long
};

template <class Observer>
Observer make_observer(const Setup& s) {
  if constexpr (std::is_same_v<Observer, sim::NoBounceObserver>) {
    return {};
  } else {
    Observer obs;
    obs.channels = s.channels;
    using R = typename std::remove_reference_t<decltype(obs.reflectance[0])>;
    for (int c = 0; c < s.channels; ++c)
      obs.reflectance[static_cast<std::size_t>(c)] =
          reflectance_of(s.scene->channels[static_cast<std::size_t>(c)], static_cast<R*>(nullptr));
    return obs;
  }
}

ThetaTally empty_tally(const Scene& s) {
  ThetaTally t;
  const std::size_t C = s.channels.size();
  t.energy.assign(C, 0.0);
  const auto bins = static_cast<std::size_t>(s.record.theta_o_bins);
  if (bins > 0) {
    t.theta_o.assign(bins, 0);
    t.theta_o_by_k.assign((static_cast<std::size_t>(s.record.histogram_max_k) + 2) * bins, 0);
  }
  return t;
}

// The rays of chunk `chunk` at theta_i: the hot loop, one instantiation per effect combination.
template <class Observer, bool kHistograms, bool kEnergyPerK>
ThetaTally run_chunk(const Setup& s, double theta_i, std::int64_t chunk) {
  constexpr bool kEnergy = !std::is_same_v<Observer, sim::NoBounceObserver>;
  static_assert(kEnergy || !kEnergyPerK, "energy per k needs a Fresnel observer");
  const Scene& scene = *s.scene;
  ThetaTally t = empty_tally(scene);
  const sim::TraceOptions opt{scene.max_bounces};
  const std::size_t C = static_cast<std::size_t>(s.channels);
  const int bins = scene.record.theta_o_bins;
  const int max_k = scene.record.histogram_max_k;
  Observer obs = make_observer<Observer>(s);
  sim::for_each_landing(
      s.grooves, theta_i, scene.light.sampling, scene.light.rays, scene.light.seed, chunk,
      [&](const sim::Groove& groove, const sim::Ray2& ray) {
        if (support::cancelled(s.cancel)) return;  // the rest of the chunk is skipped; the run reports it
        if constexpr (kEnergy) obs.reset();
        const sim::TraceResult r = sim::trace(groove, ray, opt, obs);
        if (!t.count(r.how, r.bounces, r.exit_dir.y() > 0.0)) return;
        const auto k = static_cast<std::size_t>(std::min(r.bounces, kMaxKRow + 1));
        if (k >= t.by_k.size()) t.by_k.resize(k + 1, 0);
        ++t.by_k[k];
        if constexpr (kEnergy)
          for (std::size_t c = 0; c < C; ++c) t.energy[c] += obs.throughput[c];
        if constexpr (kEnergyPerK) {
          if ((k + 1) * C > t.energy_by_k.size()) t.energy_by_k.resize((k + 1) * C, 0.0);
          for (std::size_t c = 0; c < C; ++c) t.energy_by_k[k * C + c] += obs.throughput[c];
        }
        if constexpr (kHistograms) {
          const double w = std::numbers::pi / bins;
          // theta_o is inside (-pi/2, pi/2) here; the clamp only absorbs rounding of the division.
          const int bin = std::clamp(
              static_cast<int>(std::floor((sim::angle_from_normal(r.exit_dir) + 0.5 * std::numbers::pi) / w)), 0,
              bins - 1);
          const int row = r.bounces > max_k ? max_k + 1 : r.bounces;
          ++t.theta_o[static_cast<std::size_t>(bin)];
          ++t.theta_o_by_k[static_cast<std::size_t>(row) * static_cast<std::size_t>(bins) +
                           static_cast<std::size_t>(bin)];
        }
      });
  return t;
}

using ChunkFn = ThetaTally (*)(const Setup&, double, std::int64_t);

template <class Observer>
ChunkFn pick_record(const SceneRecord& rec) {
  const bool h = rec.theta_o_bins > 0;
  if constexpr (std::is_same_v<Observer, sim::NoBounceObserver>) {
    return h ? &run_chunk<Observer, true, false> : &run_chunk<Observer, false, false>;
  } else {
    if (rec.energy_per_k) return h ? &run_chunk<Observer, true, true> : &run_chunk<Observer, false, true>;
    return h ? &run_chunk<Observer, true, false> : &run_chunk<Observer, false, false>;
  }
}

// The loop for the scene's effects, chosen once per run.
ChunkFn pick_chunk_fn(const Scene& s) {
  switch (s.fresnel) {
    case FresnelKind::none:
      return pick_record<sim::NoBounceObserver>(s.record);
    case FresnelKind::conductor:
      return pick_record<ChannelsObserver<sim::ConductorReflectance>>(s.record);
    case FresnelKind::schlick:
      return pick_record<ChannelsObserver<sim::SchlickReflectance>>(s.record);
  }
  return nullptr;
}

// Reflectance of channel c as a function of cos theta, for the model.
double channel_F(const Scene& s, std::size_t c, double cos_theta) {
  const FresnelChannel& ch = s.channels[c];
  return s.fresnel == FresnelKind::conductor ? optics::fresnel_conductor(cos_theta, ch.eta, ch.kappa)
                                             : optics::fresnel_schlick(cos_theta, ch.F0);
}

std::string geometry_text(const Scene& s) {
  if (s.geometry.kind == GeometryKind::groove) return groove_text(s.geometry.groove);
  char buf[160];
  std::snprintf(buf, sizeof buf, "microsurface %s alpha %g, %d grooves (seed %llu)", sim::ndf_name(s.geometry.ndf),
                s.geometry.alpha, s.geometry.grooves, static_cast<unsigned long long>(s.geometry.surface_seed));
  return buf;
}

// The JSON key of row k: "k", or ">4096" for the shared last row.
std::string k_key(std::size_t k) {
  if (k <= static_cast<std::size_t>(kMaxKRow)) return std::to_string(k);
  std::string key(">");
  key += std::to_string(kMaxKRow);
  return key;
}

}  // namespace

void ThetaTally::merge(const ThetaTally& o) {
  merge_fates(o);
  if (o.by_k.size() > by_k.size()) by_k.resize(o.by_k.size(), 0);
  for (std::size_t k = 0; k < o.by_k.size(); ++k) by_k[k] += o.by_k[k];
  for (std::size_t c = 0; c < o.energy.size(); ++c) energy[c] += o.energy[c];
  if (o.energy_by_k.size() > energy_by_k.size()) energy_by_k.resize(o.energy_by_k.size(), 0.0);
  for (std::size_t i = 0; i < o.energy_by_k.size(); ++i) energy_by_k[i] += o.energy_by_k[i];
  for (std::size_t i = 0; i < o.theta_o.size(); ++i) theta_o[i] += o.theta_o[i];
  for (std::size_t i = 0; i < o.theta_o_by_k.size(); ++i) theta_o_by_k[i] += o.theta_o_by_k[i];
}

ModelFigures model_figures(const Scene& s, double theta_i) {
  ModelFigures m;
  if (s.geometry.kind != GeometryKind::groove) return m;
  const GrooveParams& p = s.geometry.groove;
  m.available = true;
  m.energy.assign(s.channels.size(), 0.0);
  // G is normalized by each facet's projected width f_a; the beam entering the opening is as wide
  // as the lit facets' unshadowed parts together (as in `vgroove analytic`).
  ModelShares shares[2];
  for (sim::Side side : {sim::Side::left, sim::Side::right})
    shares[static_cast<int>(side)] = model_shares(p, theta_i, side, analytic::Eq6Form::corrected);
  const double width = entering_width(shares);
  for (sim::Side side : {sim::Side::left, sim::Side::right}) {
    const ModelShares& sh = shares[static_cast<int>(side)];
    if (!sh.lit) continue;
    for (int z = 0; z < sh.shares; ++z) {
      const analytic::BounceShare& b = sh.share[z];
      const double w = b.G * sh.f_a / width;  // fraction of the entering beam with b.n reflections
      if (w == 0.0) continue;
      m.mean_k += w * b.n;
      for (std::size_t c = 0; c < s.channels.size(); ++c) {
        const auto F = [&](double cos_theta) { return channel_F(s, c, cos_theta); };
        // Lee et al. 2018, Eq. (11) (Eq. (23)'s R for nonsymmetric grooves): the product of F at
        // the local angles the kaleidoscope predicts.
        const double e = p.symmetric
                             ? analytic::fresnel_energy(theta_i, p.theta_v, b.n, side, F)
                             : analytic::fresnel_energy_nonsymmetric(theta_i, p.theta_l, p.theta_r, b.n, side, F);
        m.energy[c] += w * e;
      }
    }
  }
  return m;
}

double simulate_memory_bytes(const Scene& scene, int threads, bool result) {
  constexpr double kNumberBytes = 64;  // a count in the result JSON: its node, vector slot and text
  constexpr double kVectorBytes = 64;  // a vector's header and its allocation's overhead
  const double C = static_cast<double>(scene.channels.size());
  const double rows = std::min<double>(kMaxKRow, scene.max_bounces) + 2.0;
  const double cells = scene.record.theta_o_bins * (1.0 + scene.record.histogram_max_k + 2.0);
  const double counts = 8.0 * (rows + cells) + 3 * kVectorBytes;
  // Each chunk's energies are kept apart until its theta_i is complete (added in chunk order).
  const double chunk_energy = 8.0 * C * (1.0 + (scene.record.energy_per_k ? rows : 0.0)) + 3 * kVectorBytes;
  const double chunks = std::ceil(static_cast<double>(scene.light.rays) / sim::kRaysPerChunk);
  const double T = static_cast<double>(scene.light.theta_i.size());
  const double P = support::resolve_threads(threads);
  // Per theta_i: the merged counts and every chunk's energies, held twice while the parts are
  // merged; per thread an item's tally in flight and a context (the surface's grooves).
  const double unit = counts + chunks * chunk_energy;
  const double grooves = scene.geometry.kind == GeometryKind::groove ? 1.0 : 2.0 * scene.geometry.grooves;
  const double json = result ? T * kNumberBytes * (cells + rows * (1.0 + C)) : 0.0;
  return 2.0 * T * unit + P * (counts + 64.0 * chunk_energy) + std::min(P, T) * grooves * (sizeof(sim::Groove) + 8.0) +
         json;
}

struct SimulateWork::Context {
  Setup setup;
  ChunkFn fn = nullptr;
};

std::shared_ptr<const SimulateWork::Context> SimulateWork::prepare(std::size_t) const {
  auto ctx = std::make_shared<Context>();
  Setup& s = ctx->setup;
  s.scene = &scene;
  s.channels = static_cast<int>(scene.channels.size());
  s.cancel = cancel;  // the work's flag: a chunk of narrow-groove rays is long
  if (scene.geometry.kind == GeometryKind::groove) {
    s.grooves.push_back(make_groove(scene.geometry.groove));
  } else {
    sim::MicrosurfaceOptions mo;
    mo.ndf = scene.geometry.ndf;
    mo.alpha = scene.geometry.alpha;
    mo.grooves = scene.geometry.grooves;
    mo.seed = scene.geometry.surface_seed;
    s.grooves = sim::make_microsurface(mo).grooves;
  }
  ctx->fn = pick_chunk_fn(scene);
  return ctx;
}

SimTally SimulateWork::run_chunks(const Context& ctx, std::size_t unit, std::int64_t begin, std::int64_t end) const {
  SimTally out;
  out.counts = empty_tally(scene);
  for (std::int64_t c = begin; c < end; ++c) {
    ThetaTally t = ctx.fn(ctx.setup, scene.light.theta_i[unit], c);
    out.energies.push_back({c, std::move(t.energy), std::move(t.energy_by_k)});
    t.energy.assign(scene.channels.size(), 0.0);
    out.counts.merge(t);
  }
  return out;
}

void SimulateWork::merge(Tally& into, const Tally& from) {
  into.counts.merge(from.counts);
  into.energies.insert(into.energies.end(), from.energies.begin(), from.energies.end());
}

nlohmann::json SimulateWork::tally_json(const Tally& t) {
  nlohmann::json j = fates_json(t.counts);
  j["by_k"] = t.counts.by_k, j["theta_o"] = t.counts.theta_o, j["theta_o_by_k"] = t.counts.theta_o_by_k;
  nlohmann::json e = nlohmann::json::array();
  for (const ChunkEnergy& c : t.energies)
    e.push_back({{"chunk", c.chunk}, {"energy", exact_json(c.energy)}, {"energy_by_k", exact_json(c.energy_by_k)}});
  j["energies"] = std::move(e);
  return j;
}

SimTally SimulateWork::read_tally(support::JsonObject& j, std::size_t,
                                  const std::vector<validation::ChunkRun>& runs) const {
  using validation::read_counts;
  SimTally t;
  ThetaTally& c = t.counts;
  validation::read_fates(j, c, validation::rays_in_chunks(runs, scene.light.rays, sim::kRaysPerChunk),
                         scene.max_bounces);
  // Rows k = 0 .. the largest k seen (k > kMaxKRow share the last): none when no ray escaped.
  const std::size_t rows = c.escaped > 0 ? static_cast<std::size_t>(std::min(c.max_k_seen, kMaxKRow + 1)) + 1 : 0;
  c.by_k = read_counts(j, "by_k", rows, c.escaped);
  validation::check_sum(j, "by_k", c.by_k, c.escaped, "escaped rays");
  if (rows > 0 && c.by_k.back() == 0) j.fail("by_k", "ends in 0: its last row must hold the rays of max_k_seen");
  const ThetaTally shape = empty_tally(scene);
  c.theta_o = read_counts(j, "theta_o", shape.theta_o.size(), c.escaped);
  c.theta_o_by_k = read_counts(j, "theta_o_by_k", shape.theta_o_by_k.size(), c.escaped);
  if (!shape.theta_o.empty()) {
    validation::check_sum(j, "theta_o", c.theta_o, c.escaped, "escaped rays");
    std::vector<std::int64_t> rows_of(static_cast<std::size_t>(scene.record.histogram_max_k) + 2, 0);
    for (std::size_t k = 0; k < c.by_k.size(); ++k) rows_of[std::min<std::size_t>(k, rows_of.size() - 1)] += c.by_k[k];
    validation::check_margins(j, "theta_o_by_k", c.theta_o_by_k, rows_of, "by_k (rows above histogram_max_k summed)",
                              c.theta_o, "theta_o");
  }
  // Each chunk's energies, once per chunk the part ran, each channel at most the chunk's rays.
  const std::size_t C = scene.channels.size();
  const nlohmann::json& energies = j.raw("energies");
  if (!energies.is_array()) j.fail("energies", "must be an array");
  std::set<std::int64_t> expected;
  for (const validation::ChunkRun& r : runs)
    for (std::int64_t k = r.first; k < r.second; ++k) expected.insert(k);
  if (energies.size() != expected.size())
    j.fail("energies", "has " + std::to_string(energies.size()) + " chunks, not the " +
                           std::to_string(expected.size()) + " the part ran");
  for (std::size_t n = 0; n < energies.size(); ++n) {
    support::JsonObject e(energies[n], j.file(), j.path("energies") + "/" + std::to_string(n));
    const std::int64_t chunk = e.integer("chunk", 0, std::numeric_limits<long long>::max());
    if (expected.erase(chunk) == 0)
      e.fail("chunk", "= " + std::to_string(chunk) + " is not a chunk the part ran, or is given twice");
    const double most =
        static_cast<double>(validation::rays_in_chunks({{chunk, chunk + 1}}, scene.light.rays, sim::kRaysPerChunk));
    ChunkEnergy ce{chunk, validation::read_exact_doubles(e, "energy", C), {}};
    const nlohmann::json& by_k = e.raw("energy_by_k");
    if (!by_k.is_array() || by_k.size() % std::max<std::size_t>(C, 1) != 0 || by_k.size() > (kMaxKRow + 2) * C)
      e.fail("energy_by_k", "must be an array of whole rows of " + std::to_string(C) + " channels");
    if (!scene.record.energy_per_k ? !by_k.empty() : by_k.size() > c.by_k.size() * C)
      e.fail("energy_by_k", "has " + std::to_string(by_k.size()) + " values; the scene records " +
                                (scene.record.energy_per_k ? "at most its rows k times its channels" : "none"));
    ce.energy_by_k = validation::read_exact_doubles(e, "energy_by_k", by_k.size());
    for (const std::vector<double>* v : {&ce.energy, &ce.energy_by_k})
      for (std::size_t i = 0; i < v->size(); ++i)
        if (!((*v)[i] >= 0.0 && (*v)[i] <= most))
          e.fail_at(v == &ce.energy ? "energy" : "energy_by_k", i,
                    "= " + support::format("%.17g", (*v)[i]) + " is out of range [0, " +
                        support::format("%.17g", most) + "] (the chunk's rays)");
    // The rows k of a channel hold the same throughputs as its total, summed in another order.
    if (scene.record.energy_per_k)
      for (std::size_t ch = 0; ch < C; ++ch) {
        double sum = 0.0;
        for (std::size_t i = ch; i < ce.energy_by_k.size(); i += C) sum += ce.energy_by_k[i];
        if (!(std::abs(sum - ce.energy[ch]) <= 1e-9 * ce.energy[ch] + 1e-300))
          e.fail("energy_by_k", "sums to " + support::format("%.17g", sum) + " in channel " + std::to_string(ch) +
                                    ", not to its energy " + support::format("%.17g", ce.energy[ch]));
      }
    e.finish();
    t.energies.push_back(std::move(ce));
  }
  return t;
}

std::string lost_rays_problem(const SimulationResult& r) {
  for (std::size_t t = 0; t < r.tallies.size(); ++t) {
    const ThetaTally& ta = r.tallies[t];
    const std::int64_t lost = ta.vertex_hits + ta.blocked + ta.not_upward;
    if (ta.rays > 0 && static_cast<double>(lost) > kMaxLostShare * static_cast<double>(ta.rays))
      return support::format(
          "theta_i %g deg: %lld of %lld rays (%.2f %%) lost (%lld vertex hits, %lld blocked, %lld "
          "not upward), more than the %g %% a run may lose: no result written",
          validation::output_deg(r.theta_i[t]), static_cast<long long>(lost), static_cast<long long>(ta.rays),
          100.0 * static_cast<double>(lost) / ta.rays, static_cast<long long>(ta.vertex_hits),
          static_cast<long long>(ta.blocked), static_cast<long long>(ta.not_upward), 100.0 * kMaxLostShare);
  }
  return "";
}

validation::Job<SimulateWork> simulate_job(const Scene& scene, nlohmann::json descriptor) {
  // Cost: about 10 ns per reflection plus a ray's set-up; Fresnel conductors ~30 ns per bounce
  // and channel. Without a model of the scene's bounce counts: a flat estimate per ray.
  const std::int64_t per_ray = scene.fresnel == FresnelKind::conductor ? 200 : 40;
  std::vector<support::WorkUnit> units(scene.light.theta_i.size());
  for (auto& u : units) {
    u.chunks = (scene.light.rays + sim::kRaysPerChunk - 1) / sim::kRaysPerChunk;
    u.chunk_cost = per_ray * std::min<std::int64_t>(scene.light.rays, sim::kRaysPerChunk);
  }
  return validation::make_job(SimulateWork{scene}, std::move(units), std::move(descriptor));
}

SimulationResult simulation_from(const Scene& scene, const std::vector<validation::UnitResult<SimulateWork>>& results) {
  SimulationResult r;
  r.theta_i = scene.light.theta_i;
  for (std::size_t t = 0; t < results.size(); ++t) {
    ThetaTally total = results[t].tally.counts;
    std::vector<ChunkEnergy> energies = results[t].tally.energies;
    std::sort(energies.begin(), energies.end(),
              [](const ChunkEnergy& a, const ChunkEnergy& b) { return a.chunk < b.chunk; });
    // The energies as simulate() has always added them: from zero, chunk after chunk.
    ThetaTally sum = empty_tally(scene);
    for (ChunkEnergy& e : energies) {
      ThetaTally chunk = empty_tally(scene);
      chunk.energy = std::move(e.energy), chunk.energy_by_k = std::move(e.energy_by_k);
      chunk.theta_o.assign(sum.theta_o.size(), 0), chunk.theta_o_by_k.assign(sum.theta_o_by_k.size(), 0);
      sum.merge(chunk);
    }
    total.energy = std::move(sum.energy), total.energy_by_k = std::move(sum.energy_by_k);
    r.rays += total.rays;
    r.bounces += total.bounces;
    r.tallies.push_back(std::move(total));
    r.model.push_back(model_figures(scene, r.theta_i[t]));
  }
  return r;
}

SimulationResult simulate(const Scene& scene, int threads, const std::atomic<bool>* cancel) {
  const auto start = std::chrono::steady_clock::now();
  auto job = simulate_job(scene, {});
  job.work.cancel = cancel;
  const auto results = validation::run_job(job, threads, {}, cancel);
  SimulationResult r;
  if (results) {
    r = simulation_from(scene, *results);
  } else {
    r.theta_i = scene.light.theta_i;
    r.interrupted = true;
  }
  r.threads = support::resolve_threads(threads);
  r.wall_s = support::seconds_since(start);
  return r;
}

nlohmann::json result_json(const Scene& scene, const SimulationResult& r) {
  using nlohmann::json;
  json j = provenance();
  j["scene"] = scene.name;
  j["scene_file"] = scene.file;
  if (!scene.note.empty()) j["note"] = scene.note;
  j["seed"] = scene.light.seed;
  j["threads"] = r.threads;
  j["wall_s"] = r.wall_s;
  j["rays"] = r.rays;
  j["bounces"] = r.bounces;
  // The inputs as read (degrees), so a result can be rerun and diffed without its scene file.
  json geometry;
  if (scene.geometry.kind == GeometryKind::groove) {
    geometry = groove_json(scene.geometry.groove);
    geometry["kind"] = "groove";
  } else {
    geometry = {{"kind", "microsurface"},
                {"ndf", sim::ndf_name(scene.geometry.ndf)},
                {"alpha", scene.geometry.alpha},
                {"grooves", scene.geometry.grooves},
                {"seed", scene.geometry.surface_seed}};
  }
  json theta_deg = json::array();
  for (double t : scene.light.theta_i) theta_deg.push_back(output_deg(t));
  json channels = json::array();
  for (const FresnelChannel& c : scene.channels) {
    json cj = {{"name", c.name}};
    if (scene.fresnel == FresnelKind::schlick) {
      cj["F0"] = c.F0;
    } else {
      if (c.lambda_nm > 0.0) cj["lambda_nm"] = c.lambda_nm;
      cj["eta"] = c.eta, cj["kappa"] = c.kappa;
    }
    channels.push_back(cj);
  }
  json record = {{"counts_per_k", true}, {"energy_per_k", scene.record.energy_per_k}};
  if (scene.record.theta_o_bins > 0)
    record["theta_o_histograms"] = {{"bins", scene.record.theta_o_bins}, {"max_k", scene.record.histogram_max_k}};
  j["inputs"] = {{"geometry", geometry},
                 {"light",
                  {{"theta_i_deg", theta_deg},
                   {"rays", scene.light.rays},
                   {"sampling", sim::sampling_name(scene.light.sampling)},
                   {"seed", scene.light.seed}}},
                 {"effects",
                  {{"fresnel", {{"kind", fresnel_kind_name(scene.fresnel)}, {"channels", channels}}},
                   {"record", record},
                   {"max_bounces", scene.max_bounces}}}};
  const std::size_t C = scene.channels.size();
  json results = json::array();
  for (std::size_t t = 0; t < r.tallies.size(); ++t) {
    const ThetaTally& ta = r.tallies[t];
    const double n = ta.rays > 0 ? static_cast<double>(ta.rays) : 1.0;
    json row = {{"theta_i_deg", output_deg(r.theta_i[t])},
                {"rays", ta.rays},
                {"escaped", ta.escaped},
                {"blocked", ta.blocked},
                {"vertex_hit", ta.vertex_hits},
                {"bounce_limit", ta.bounce_limit},
                {"not_upward", ta.not_upward},
                {"escaped_fraction", static_cast<double>(ta.escaped) / n},
                {"mean_k", ta.mean_k()}};
    json counts = json::object();  // sparse: only the k that occur
    for (std::size_t k = 0; k < ta.by_k.size(); ++k)
      if (ta.by_k[k] > 0) counts[k_key(k)] = ta.by_k[k];
    row["counts_per_k"] = counts;
    if (C > 0) {
      json energy = json::object();
      for (std::size_t c = 0; c < C; ++c) energy[scene.channels[c].name] = ta.energy[c] / n;
      row["energy"] = energy;  // fraction of the incident rays' energy that leaves
    }
    if (scene.record.energy_per_k) {
      json per = json::object();
      for (std::size_t c = 0; c < C; ++c) {
        json ks = json::object();
        for (std::size_t k = 0; k * C + c < ta.energy_by_k.size(); ++k)
          if (k < ta.by_k.size() && ta.by_k[k] > 0) ks[k_key(k)] = ta.energy_by_k[k * C + c] / n;
        per[scene.channels[c].name] = ks;
      }
      row["energy_per_k"] = per;
    }
    if (r.model[t].available) {
      json m = {{"mean_k", r.model[t].mean_k}};
      if (C > 0) {
        json energy = json::object();
        for (std::size_t c = 0; c < C; ++c) energy[scene.channels[c].name] = r.model[t].energy[c];
        m["energy"] = energy;
      }
      row["model"] = m;
    }
    if (scene.record.theta_o_bins > 0) {
      const auto bins = static_cast<std::size_t>(scene.record.theta_o_bins);
      const int max_k = scene.record.histogram_max_k;
      json per_k = json::object();
      for (int k = 0; k <= max_k + 1; ++k) {
        const auto first = ta.theta_o_by_k.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(k) * bins);
        std::vector<std::int64_t> h(first, first + static_cast<std::ptrdiff_t>(bins));
        if (std::all_of(h.begin(), h.end(), [](std::int64_t v) { return v == 0; })) continue;
        std::string key = k <= max_k ? std::string() : std::string(">");
        key += std::to_string(k <= max_k ? k : max_k);  // the last row: k > max_k
        per_k[key] = h;
      }
      row["theta_o_histograms"] = {
          {"bins", scene.record.theta_o_bins}, {"range_deg", {-90, 90}}, {"all", ta.theta_o}, {"per_k", per_k}};
    }
    results.push_back(row);
  }
  j["results"] = results;
  return j;
}

void print_result_table(std::ostream& os, const Scene& scene, const SimulationResult& r) {
  char buf[256];
  std::string fresnel = fresnel_kind_name(scene.fresnel);
  if (!scene.channels.empty()) fresnel += " over " + std::to_string(scene.channels.size()) + " channel(s)";
  std::snprintf(buf, sizeof buf, "simulate %s: %s; fresnel %s; %lld rays per theta_i (%s, seed %llu)\n",
                support::printable(scene.name).c_str(), geometry_text(scene).c_str(), fresnel.c_str(),
                static_cast<long long>(scene.light.rays), sim::sampling_name(scene.light.sampling),
                static_cast<unsigned long long>(scene.light.seed));
  os << buf;
  const bool model = scene.geometry.kind == GeometryKind::groove;
  os << "  theta_i       rays   escaped   mean k";
  if (model) os << "  model k";
  for (const FresnelChannel& c : scene.channels) {
    std::snprintf(buf, sizeof buf, " %10s", ("E " + support::printable(c.name)).substr(0, 10).c_str());
    os << buf;
    if (model) {
      std::snprintf(buf, sizeof buf, " %10s", ("model " + support::printable(c.name)).substr(0, 10).c_str());
      os << buf;
    }
  }
  os << "\n";
  for (std::size_t t = 0; t < r.tallies.size(); ++t) {
    const ThetaTally& ta = r.tallies[t];
    const double n = ta.rays > 0 ? static_cast<double>(ta.rays) : 1.0;
    std::snprintf(buf, sizeof buf, "  %7.6g %10lld %9.6f %8.4f", output_deg(r.theta_i[t]),
                  static_cast<long long>(ta.rays), static_cast<double>(ta.escaped) / n, ta.mean_k());
    os << buf;
    if (model) {
      std::snprintf(buf, sizeof buf, " %8.4f", r.model[t].mean_k);
      os << buf;
    }
    for (std::size_t c = 0; c < scene.channels.size(); ++c) {
      std::snprintf(buf, sizeof buf, " %10.6f", ta.energy[c] / n);
      os << buf;
      if (model) {
        std::snprintf(buf, sizeof buf, " %10.6f", r.model[t].energy[c]);
        os << buf;
      }
    }
    os << "\n";
  }
  sim::RayFates all;
  for (const ThetaTally& ta : r.tallies) all.merge_fates(ta);
  // The reflections are those of the escaped rays (a lost ray's are not counted), so with every
  // ray at the bounce limit they are 0: the line says whose they are and why rays were lost.
  os << support::format(
      "  %lld rays, %lld reflections of the escaped ones; %lld lost (%lld at the bounce limit of %d, "
      "%lld vertex hits, %lld blocked, %lld not upward); %d threads, %.3f s\n",
      static_cast<long long>(r.rays), static_cast<long long>(r.bounces), static_cast<long long>(all.lost()),
      static_cast<long long>(all.bounce_limit), scene.max_bounces, static_cast<long long>(all.vertex_hits),
      static_cast<long long>(all.blocked), static_cast<long long>(all.not_upward), r.threads, r.wall_s);
}

}  // namespace vgroove::scene
