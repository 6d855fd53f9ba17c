#include "vgroove/sim/heightfield_grooves.h"

#include "vgroove/sim/rng.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace vgroove::sim {
namespace {

bool power_of_two(int n) { return n >= 2 && (n & (n - 1)) == 0; }

struct Seed {
  double x, y;
  int groove;
};

}  // namespace

double groove_slope(NdfKind ndf, double alpha, double u) {
  // P(tan theta <= t) under D cos(theta) d omega: Beckmann 1 - e^{-t^2/alpha^2}, GGX t^2 / (alpha^2
  // + t^2); inverted.
  if (ndf == NdfKind::beckmann) return alpha * std::sqrt(-std::log1p(-u));
  if (ndf == NdfKind::ggx) return alpha * std::sqrt(u / (1.0 - u));
  throw std::invalid_argument("groove field ndf must be beckmann or ggx");
}

std::vector<FiniteGroove> random_finite_grooves(const GrooveFieldOptions& opt) {
  if (!power_of_two(opt.n) || opt.n < 8 || opt.n > 4096)
    throw std::invalid_argument("groove field n = " + std::to_string(opt.n) + " is not a power of two in [8, 4096]");
  if (!(opt.alpha > 0.0)) throw std::invalid_argument("groove field alpha must be > 0");
  if (!(opt.groove_length >= 0.0 && opt.groove_length <= opt.n / 4.0))
    throw std::invalid_argument("groove field groove_length = " + std::to_string(opt.groove_length) +
                                " is out of range [0, n/4]");
  if (!(opt.groove_spacing >= 4.0 && opt.groove_spacing <= opt.n / 4.0))
    throw std::invalid_argument("groove field groove_spacing = " + std::to_string(opt.groove_spacing) +
                                " is out of range [4, n/4]");
  const double area = static_cast<double>(opt.n) * opt.n;
  const auto count = static_cast<int>(std::lround(area / (opt.groove_spacing * opt.groove_spacing)));
  std::vector<FiniteGroove> g(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k) {
    Rng rng(opt.seed, kGrooveFieldStream, static_cast<std::uint64_t>(k));
    FiniteGroove& f = g[static_cast<std::size_t>(k)];
    f.x = opt.n * rng.uniform();
    f.y = opt.n * rng.uniform();
    f.phi = std::numbers::pi * rng.uniform();  // an axis: phi and phi + pi are the same groove
    f.length = opt.groove_length;
    f.slope = groove_slope(opt.ndf, opt.alpha, rng.uniform());
  }
  return g;
}

Heightfield make_finite_groove_field(int n, const std::vector<FiniteGroove>& grooves, double seed_step,
                                     GrooveFieldLabels* labels) {
  if (!power_of_two(n)) throw std::invalid_argument("groove field n = " + std::to_string(n) + " is not a power of two");
  if (grooves.size() < 2) throw std::invalid_argument("groove field: at least 2 grooves");
  if (!(seed_step > 0.0)) throw std::invalid_argument("groove field seed_step must be > 0");
  std::vector<Seed> seeds;
  std::vector<int> first(grooves.size() + 1, 0);
  for (std::size_t g = 0; g < grooves.size(); ++g) {
    const FiniteGroove& f = grooves[g];
    if (!(f.slope >= 0.0) || !std::isfinite(f.slope) || !(f.length >= 0.0))
      throw std::invalid_argument("groove field: groove slopes and lengths must be finite and >= 0");
    const int m = static_cast<int>(std::floor(f.length / seed_step + 1e-9)) + 1;
    const double c = std::cos(f.phi), s = std::sin(f.phi);
    first[g] = static_cast<int>(seeds.size());
    for (int k = 0; k < m; ++k) {
      const double t = m == 1 ? 0.0 : f.length * (static_cast<double>(k) / (m - 1) - 0.5);
      seeds.push_back({f.x + t * c, f.y + t * s, static_cast<int>(g)});
    }
  }
  first[grooves.size()] = static_cast<int>(seeds.size());
  const auto K = static_cast<std::int64_t>(seeds.size());
  Heightfield hf;
  hf.n = n;
  hf.h.assign(static_cast<std::size_t>(n) * n, 0.0);
  if (labels) {
    labels->groove.assign(hf.h.size(), -1);
    labels->facet.assign(hf.h.size(), -1);
  }
  // Seeds in buckets of B x B cells (nb per side, a power of two), searched in square rings
  // around the vertex's bucket: after rings 0..R every unvisited seed is at least R B away.
  int nb = 1;
  while (nb * 2 <= n / 8 && static_cast<double>(nb) * nb * 2 <= static_cast<double>(seeds.size())) nb *= 2;
  const int B = n / nb;
  const double period = n;
  auto wrap = [&](double d) { return d - period * std::floor(d / period + 0.5); };  // into [-n/2, n/2)
  std::vector<std::vector<int>> bucket(static_cast<std::size_t>(nb) * nb);
  for (std::size_t q = 0; q < seeds.size(); ++q) {
    const double x = seeds[q].x - period * std::floor(seeds[q].x / period);
    const double y = seeds[q].y - period * std::floor(seeds[q].y / period);
    const int bx = std::min(nb - 1, static_cast<int>(x / B)), by = std::min(nb - 1, static_cast<int>(y / B));
    bucket[static_cast<std::size_t>(by) * nb + bx].push_back(static_cast<int>(q));
  }
  struct Rel {
    double x, y, r2, r1;
    int q;
  };
  std::vector<Rel> cand, own;
  std::vector<std::int64_t> stamp(bucket.size(), -1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int64_t vertex = static_cast<std::int64_t>(j) * n + i;
      // Seeds relative to the vertex at their nearest periodic image (the grooves' reach is below
      // n/2 by the options' ranges).
      auto rel = [&](int q) {
        const double x = wrap(seeds[static_cast<std::size_t>(q)].x - i),
                     y = wrap(seeds[static_cast<std::size_t>(q)].y - j);
        const double r2 = x * x + y * y;
        return Rel{x, y, r2, std::sqrt(r2), q};
      };
      cand.clear();
      const int bi = i / B, bj = j / B;
      int R = -1, G = -1;
      double best = -std::numeric_limits<double>::infinity();
      std::int64_t facet = -1;
      for (;;) {
        ++R;
        const bool all = 2 * R + 1 >= nb;  // the rings cover every bucket
        for (int dj = -R; dj <= R; ++dj)
          for (int di = -R; di <= R; ++di) {
            if (std::max(std::abs(di), std::abs(dj)) != R) continue;
            const auto k = static_cast<std::size_t>(((bj + dj) & (nb - 1)) * nb + ((bi + di) & (nb - 1)));
            if (stamp[k] == vertex) continue;  // a ring wider than the period visits it again
            stamp[k] = vertex;
            for (int q : bucket[k]) cand.push_back(rel(q));
          }
        const double reach = all ? std::numeric_limits<double>::infinity() : static_cast<double>(R) * B;
        if (cand.empty()) continue;
        const Rel* nearest = &cand[0];
        for (const Rel& c : cand)
          if (c.r2 < nearest->r2) nearest = &c;
        if (nearest->r1 > reach) continue;  // a nearer seed may sit in the next ring
        G = seeds[static_cast<std::size_t>(nearest->q)].groove;
        // max over the groove's seeds of the distance to the nearest bisector with another
        // groove's seed: (|b|^2 - |a|^2) / (2 |b - a|), a and b relative to the vertex.
        own.clear();
        for (int q = first[static_cast<std::size_t>(G)]; q < first[static_cast<std::size_t>(G) + 1]; ++q)
          own.push_back(rel(q));
        best = -std::numeric_limits<double>::infinity();
        bool settled = true;
        for (const Rel& a : own) {
          double d_min = std::numeric_limits<double>::infinity();
          std::int64_t arg = -1;
          for (const Rel& c : cand) {
            // (|b| - |a|) / 2 bounds the bisector distance from below: no closer bisector there.
            if (0.5 * (c.r1 - a.r1) >= d_min || seeds[static_cast<std::size_t>(c.q)].groove == G) continue;
            const double d = (c.r2 - a.r2) / (2.0 * std::hypot(c.x - a.x, c.y - a.y));
            if (d < d_min) d_min = d, arg = c.q;
          }
          // An unvisited seed (at least `reach` away) could still set a's distance.
          if (0.5 * (reach - a.r1) < d_min) settled = false;
          if (d_min > best) best = d_min, facet = static_cast<std::int64_t>(a.q) * K + arg;
        }
        if (settled || all) break;
      }
      const std::size_t v = static_cast<std::size_t>(j) * n + i;
      hf.h[v] = -grooves[static_cast<std::size_t>(G)].slope * best;
      if (labels) labels->groove[v] = G, labels->facet[v] = facet;
    }
  return hf;
}

Heightfield make_random_groove_field(const GrooveFieldOptions& opt, GrooveFieldLabels* labels) {
  const std::vector<FiniteGroove> g = random_finite_grooves(opt);
  double step = opt.seed_step;
  if (opt.groove_length > 0.0 && !(step >= 1.0 && step <= opt.groove_length))
    throw std::invalid_argument("groove field seed_step = " + std::to_string(step) +
                                " is out of range [1, groove_length]");
  if (!(step > 0.0)) step = 1.0;
  return make_finite_groove_field(opt.n, g, step, labels);
}

}  // namespace vgroove::sim
