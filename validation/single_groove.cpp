#include "vgroove/validation/single_groove.h"

#include "vgroove/common/angles.h"
#include "vgroove/validation/report.h"

#include <algorithm>
#include <map>

namespace vgroove::validation {

nlohmann::json rows_json(const std::vector<BounceRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const BounceRow& r : rows)
    out.push_back({{"first_facet", sim::side_name(r.first)},
                   {"k", r.k},
                   {"fraction", r.fraction},
                   {"theta_o_deg", output_deg(r.theta_o)}});
  return out;
}

ModelTable model_table(const GrooveParams& groove, double theta_i, analytic::Eq6Form form) {
  ModelTable t;
  ModelShares m[2];
  for (sim::Side side : {sim::Side::left, sim::Side::right})
    m[static_cast<int>(side)] = model_shares(groove, theta_i, side, form);
  const double width = entering_width(m);
  for (sim::Side side : {sim::Side::left, sim::Side::right}) {
    const ModelShares& p = m[static_cast<int>(side)];
    ModelFacet& f = t.facet[static_cast<int>(side)];
    if (!p.lit) continue;
    std::map<int, std::pair<double, double>> by_n;  // n -> (G, theta_o)
    for (int z = 0; z < p.shares; ++z) {
      auto& e = by_n[p.share[z].n];
      e.first += p.share[z].G;
      e.second = p.share[z].theta_o;
    }
    f.lit = true, f.k = p.k, f.f_a = p.f_a, f.shadow = p.shadow;
    for (const auto& [n, e] : by_n) {
      f.G.emplace_back(n, e.first);
      if (e.first != 0.0) t.rows.push_back({side, n, e.first * p.f_a / width, e.second});
    }
  }
  return t;
}

nlohmann::json analytic_json(const GrooveParams& groove, double theta_i_deg, analytic::Eq6Form form) {
  const ModelTable t = model_table(groove, theta_i_deg * kRadPerDeg, form);
  nlohmann::json facets = nlohmann::json::object();
  for (sim::Side side : {sim::Side::left, sim::Side::right}) {
    const ModelFacet& f = t.facet[static_cast<int>(side)];
    const char* name = sim::side_name(side);
    if (!f.lit) {
      facets[name] = nullptr;
      continue;
    }
    nlohmann::json G = nlohmann::json::object();
    for (const auto& [n, g] : f.G) G[std::to_string(n)] = g;
    facets[name] = {{"k", f.k}, {"f_a", f.f_a}, {"G", G}, {"shadow", f.shadow}};
  }
  nlohmann::json j = provenance();
  j["inputs"] = groove_json(groove);
  j["inputs"].update(
      {{"theta_i_deg", theta_i_deg}, {"eq6_form", form == analytic::Eq6Form::corrected ? "corrected" : "printed"}});
  j["bounces"] = rows_json(t.rows);
  j["facets"] = facets;
  return j;
}

bool trace_beam_rays(const GrooveParams& groove, double theta_i, long rays, sim::Sampling sampling, std::uint64_t seed,
                     int max_bounces, const RayBlockFn& fn, const std::atomic<bool>* cancel) {
  const sim::Groove g = make_groove(groove);
  const sim::Interval open = sim::opening(g);
  const sim::BeamTracer beam(g, sim::beam_direction(theta_i), sim::TraceOptions{max_bounces});
  sim::Rng rng(seed, 0, 0);
  double x[sim::BeamTracer::kBlock];
  sim::TraceResult traced[sim::BeamTracer::kBlock];
  for (long j0 = 0; j0 < rays; j0 += sim::BeamTracer::kBlock) {
    if (cancel && cancel->load(std::memory_order_relaxed)) return false;
    const int m = static_cast<int>(std::min<long>(sim::BeamTracer::kBlock, rays - j0));
    sim::sample_positions(sampling, open, j0, m, rays, rng, x);
    beam.trace(x, m, traced);
    fn(j0, m, x, traced);
  }
  return true;
}

std::vector<BounceRow> tally_rows(const sim::Tally& tally, long rays, double* max_spread) {
  std::vector<BounceRow> rows;
  double spread = 0.0;
  for (sim::Side side : {sim::Side::left, sim::Side::right}) {
    for (const auto& [k, b] : tally.bins[static_cast<int>(side)]) {
      if (b.count == 0) continue;
      rows.push_back({side, k, static_cast<double>(b.count) / static_cast<double>(rays), b.theta_o()});
      spread = std::max(spread, b.spread());
    }
  }
  if (max_spread) *max_spread = spread;
  return rows;
}

nlohmann::json trace_json(const GrooveParams& groove, double theta_i_deg, long rays, sim::Sampling sampling,
                          long long seed, int max_bounces, const sim::Tally& tally) {
  double max_spread = 0.0;
  const std::vector<BounceRow> rows = tally_rows(tally, rays, &max_spread);
  nlohmann::json j = provenance();
  j["inputs"] = groove_json(groove);
  j["inputs"].update({{"theta_i_deg", theta_i_deg},
                      {"rays", rays},
                      {"sampling", sim::sampling_name(sampling)},
                      {"seed", seed},
                      {"max_bounces", max_bounces}});
  j["bounces"] = rows_json(rows);
  j["rays"] = tally.rays;
  j["buckets"] = {{"escaped", tally.escaped},
                  {"blocked", tally.blocked},
                  {"vertex_hit", tally.vertex_hits},
                  {"bounce_limit", tally.bounce_limit}};
  j["max_exit_spread_rad"] = max_spread;
  return j;
}

}  // namespace vgroove::validation
