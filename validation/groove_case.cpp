#include "vgroove/validation/groove_case.h"

#include "vgroove/sim/tally.h"
#include "vgroove/sim/zones.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

namespace vgroove::validation {

namespace {

// A facet whose projected width is below this fraction of its length receives a beam too thin
// to place rays in (positions round at 1e-16): it is treated as not lit, by model and tracer alike.
constexpr double kMinProjectedWidth = 1e-12;
// Reflections traced between two reads of the cancellation flag, at most (a few milliseconds).
constexpr double kBouncesPerPoll = 4e6;

}  // namespace

sim::Groove make_groove(const GrooveParams& p) {
  return p.symmetric ? sim::make_symmetric_groove(p.theta_v) : sim::make_nonsymmetric_groove(p.theta_l, p.theta_r);
}

ModelShares model_shares(const GrooveParams& p, double theta_i, sim::Side side, analytic::Eq6Form form) {
  ModelShares m;
  if (p.symmetric) {
    const auto pred = analytic::G_kaleidoscopic(theta_i, p.theta_v, side, form);
    m.lit = pred.lit, m.k = pred.k, m.f_a = pred.f_a, m.shadow = pred.shadow;
    m.share[0] = pred.fewer, m.share[1] = pred.more, m.shares = 2;
  } else {
    const auto pred = analytic::G_nonsymmetric(theta_i, p.theta_l, p.theta_r, side);
    m.lit = pred.lit, m.k = pred.k_b, m.f_a = pred.f_a, m.shadow = pred.shadow;
    for (int z = 0; z < 4; ++z) m.share[z] = pred.share[z];
    m.shares = 4;
  }
  return m;
}

double entering_width(const ModelShares (&shares)[2]) {
  double width = 0.0;
  for (const ModelShares& m : shares) {
    if (!m.lit) continue;
    double entering = 0.0;
    for (int z = 0; z < m.shares; ++z) entering += m.share[z].G;
    width += m.f_a * entering;
  }
  return width;
}

double model_exit_angle(const GrooveParams& p, double theta_i, int n, sim::Side side) {
  return p.symmetric ? analytic::exit_angle(theta_i, p.theta_v, n, side)
                     : analytic::exit_angle_nonsymmetric(theta_i, p.theta_l, p.theta_r, n, side);
}

namespace {

FacetOutcome run_facet(const GrooveParams& params, const sim::Groove& g, double theta_i, sim::Side side,
                       const CaseOptions& opt, std::uint64_t stream, const std::atomic<bool>* cancel) {
  FacetOutcome out;
  const ModelShares pred = model_shares(params, theta_i, side, opt.form);
  // The model's f_a is in units of the longer facet, the tracer's too (unit facets or the longer
  // one of unit length), so one threshold serves both kinds.
  if (!pred.lit || pred.f_a < kMinProjectedWidth) return out;
  out.compared = true;
  out.k = pred.k;

  const sim::Interval aim = sim::aimed_at(g, theta_i, side);
  const sim::Vec2 dir = sim::beam_direction(theta_i);
  sim::Rng rng(opt.seed, stream, static_cast<std::uint64_t>(side));
  const sim::TraceOptions topt{opt.max_bounces};
  // One beam, one direction: BeamTracer computes once what depends on the direction only and
  // traces each ray exactly as sim::trace does (bit for bit), a block of rays at a time.
  const sim::BeamTracer beam(g, dir, topt);
  // Every traced ray is tallied (its exit direction is checked); the fractions come from the
  // counts, or with breakpoints from the zones' measures.
  sim::Tally tally;
  const int f = static_cast<int>(side), o = 1 - f;
  double blocked = 0.0, lost = 0.0;  // fractions: shadowed; no bin in the model (vertex, limit, other facet)
  std::map<int, double> traced;      // fractions per k on this facet (sparse: k reaches 10^8 in narrow grooves)
  if (opt.sampling == sim::Sampling::breakpoints) {
    const sim::ZoneSearch zs =
        sim::find_zones(beam, aim, opt.rays, [&](double, const sim::TraceResult& r) { tally.add(r); });
    const double width = aim.width();
    for (const sim::Zone& z : zs.zones) {
      const double share = z.width() / width;
      const sim::TraceResult& r = z.ray;
      if (r.how == sim::Termination::blocked)
        blocked += share;
      else if (r.how != sim::Termination::escaped || static_cast<int>(r.first) != f)
        lost += share;
      else
        traced[r.bounces] += share;
    }
    // Zones of distinct outcome; a vertex hit between two zones of one outcome (a point, or a few
    // ulps where the rounded s equals a facet's end) does not split it.
    const sim::TraceResult* last = nullptr;
    for (const sim::Zone& z : zs.zones) {
      if (z.ray.how == sim::Termination::vertex_hit) continue;
      if (last == nullptr || !sim::same_outcome(*last, z.ray)) ++out.zones;
      last = &z.ray;
    }
    out.grid = zs.grid;
    out.uncertified_cells = zs.uncertified_cells;
    out.missed_bound = zs.missed_bound() / width;
    out.narrowest_zone = zs.narrowest() / width;
  } else {
    // Blocks of rays small enough that the cancellation flag is read every few million reflections
    // (a ray in a groove of aperture theta_v makes at most ceil(pi / theta_v) of them).
    const double per_ray = std::ceil(std::numbers::pi / g.theta_v) + 1.0;
    const int block = static_cast<int>(std::clamp(kBouncesPerPoll / per_ray, 1.0, double{sim::BeamTracer::kBlock}));
    sim::trace_beam(
        beam, opt.sampling, aim, opt.rays, rng, [&](long, const sim::TraceResult& r) { tally.add(r); }, cancel, block);
    const double n = static_cast<double>(opt.rays);
    blocked = static_cast<double>(tally.blocked) / n;
    std::int64_t other = 0;
    for (const auto& e : tally.bins[o]) other += e.bin.count;
    lost = static_cast<double>(tally.vertex_hits + tally.bounce_limit + other) / n;
    for (const auto& e : tally.bins[f]) traced[e.k] += static_cast<double>(e.bin.count) / n;
  }
  out.rays = tally.rays;
  out.bounces = tally.bounces;
  out.vertex_hits = tally.vertex_hits;
  out.bounce_limit = tally.bounce_limit;
  for (const auto& e : tally.bins[o]) out.wrong_first += e.bin.count;

  // L1 over every bin either side has, in ascending k (the traced bins and the model's shares;
  // every other k adds |0 - 0|).
  double l1 = std::abs(blocked - pred.shadow) + lost;
  std::vector<int> ks;
  for (const auto& [k, fraction] : traced) ks.push_back(k);
  // Shares of the model outside the traced bins (a count below 0 or past the last bin) count too.
  for (int z = 0; z < pred.shares; ++z) {
    if (pred.share[z].n < 0)
      l1 += std::abs(pred.share[z].G);
    else
      ks.push_back(pred.share[z].n);
  }
  std::sort(ks.begin(), ks.end());
  ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
  for (int k : ks) {
    const auto it = traced.find(k);
    const double fraction = it == traced.end() ? 0.0 : it->second;
    double model = 0.0;
    for (int z = 0; z < pred.shares; ++z)
      if (pred.share[z].n == k) model += pred.share[z].G;
    l1 += std::abs(fraction - model);
  }
  // Eq. (5) and (8) hold for any bounce count, so every traced bin is checked, predicted or not.
  for (const auto& e : tally.bins[f]) {
    if (e.bin.count == 0) continue;
    const double theta_o = model_exit_angle(params, theta_i, e.k, side);
    const double err = std::abs(sim::angle_between(sim::direction_at(theta_o), e.bin.exit_dir)) + e.bin.spread();
    out.theta_o_error = std::max(out.theta_o_error, err);
  }
  out.l1 = l1;
  out.non_finite = !std::isfinite(out.l1) || !std::isfinite(out.theta_o_error);
  for (const auto& side_bins : tally.bins)
    for (const auto& e : side_bins)
      if (e.bin.count > 0 && !e.bin.exit_dir.allFinite()) out.non_finite = true;

  if (opt.probe_vertices) {
    // The line through the apex, the facet's own rim, and both rims of the opening.
    const sim::Interval open = sim::opening(g);
    for (double x : {aim.lo, aim.hi, open.lo, open.hi}) {
      const sim::TraceResult r = sim::trace(g, sim::beam_ray(g, dir, x), topt);
      ++out.probe_rays;
      switch (r.how) {
        case sim::Termination::escaped:
          ++out.probe_escaped;
          if (!r.exit_dir.allFinite()) out.non_finite = true;
          break;
        case sim::Termination::vertex_hit:
          ++out.probe_vertex_hits;
          break;
        case sim::Termination::blocked:
          ++out.probe_blocked;
          break;
        case sim::Termination::bounce_limit:
          ++out.probe_bounce_limit;
          break;
      }
    }
  }
  return out;
}

}  // namespace

CaseOutcome run_case(const GrooveParams& groove, double theta_i, const CaseOptions& opt, std::uint64_t stream,
                     const std::atomic<bool>* cancel) {
  CaseOutcome c;
  c.groove = groove;
  c.theta_i = theta_i;
  if (groove.degenerate()) return c;
  const sim::Groove g = make_groove(groove);
  for (sim::Side s : {sim::Side::left, sim::Side::right}) {
    FacetOutcome& f = c.facet[static_cast<int>(s)];
    f = run_facet(groove, g, theta_i, s, opt, stream, cancel);
    if (!f.compared) continue;
    c.l1 = std::max(c.l1, f.l1);
    c.rays += f.rays;
    c.bounces += f.bounces;
    c.theta_o_error = std::max(c.theta_o_error, f.theta_o_error);
    c.non_finite = c.non_finite || f.non_finite;
  }
  return c;
}

}  // namespace vgroove::validation
