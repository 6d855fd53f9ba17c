#include "vgroove/sim/dielectric_microsurface.h"

#include "vgroove/sim/dielectric_interaction.h"
#include "vgroove/sim/dielectric_lifted_law.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vgroove::sim {

DielectricSurfaceTracer::DielectricSurfaceTracer(const Microsurface& surface, const DielectricOptions& opt)
    : surface_(surface), opt_(opt) {
  detail::check_dielectric_options(opt);
  scale_.reserve(surface.grooves.size());
  for (const Groove& g : surface.grooves) {
    const double c = 0.5 / g.rim_x(Side::right);
    scale_.push_back(c);
    depth_max_ = std::max(depth_max_, c * g.rim_height);
  }
}

bool DielectricSurfaceTracer::march(const Vec2& p, long n0, const Vec2& d, int exclude_groove, Side exclude_side,
                                    Hit& hit, bool& unresolved) const {
  const long G = static_cast<long>(surface_.grooves.size());
  const int step = d.x() > 0.0 ? 1 : (d.x() < 0.0 ? -1 : 0);
  for (long n = n0;; n += step) {
    if (step != 0 && (n - n0) * step > G + 1 && d.y() >= 0.0) {
      unresolved = true;  // rounding only: an upward path meets the deepest groove within a period
      return false;
    }
    // Past the deepest apex and going down (or level): nothing below is ever met.
    if (d.y() <= 0.0 && n != n0) {
      const double x_near = step > 0 ? static_cast<double>(n) : static_cast<double>(n + 1);
      const double y_near = p.y() + (x_near - p.x()) / d.x() * d.y();
      if (y_near < -depth_max_) return false;
    }
    const int j = static_cast<int>(((n % G) + G) % G);
    const Groove& g = surface_.grooves[static_cast<std::size_t>(j)];
    const double c = scale_[static_cast<std::size_t>(j)];
    const Vec2 apex(static_cast<double>(n) + 0.5, -c * g.rim_height);
    const Vec2 q = p - apex;
    double best_t = std::numeric_limits<double>::infinity();
    bool found = false;
    for (Side side : {Side::left, Side::right}) {
      if (n == n0 && j == exclude_groove && side == exclude_side) continue;
      const Facet& f = g[side];
      const double den = cross(f.edge, d);
      if (den == 0.0) continue;
      const double t = cross(q, f.edge) / den;
      if (!(t > 0.0 && t < best_t)) continue;
      const double s = cross(q, d) / den / c;
      if (!(s >= 0.0 && s <= f.length)) continue;
      best_t = t;
      found = true;
      hit = Hit{j, side, s};
    }
    if (found) return true;
    if (step == 0) return false;
  }
}

DielectricResult& DielectricSurfaceTracer::trace_from_above(int groove, const Ray2& ray, Rng& rng,
                                                            DielectricResult& out) const {
  return trace_from_above_with(groove, ray, detail::FlatlandLaw{opt_.eta, 1.0 / opt_.eta, &opt_}, rng, out);
}

DielectricResult& DielectricSurfaceTracer::trace_from_below(double x, const Vec2& dir, Rng& rng,
                                                            DielectricResult& out) const {
  return trace_from_below_with(x, dir, detail::FlatlandLaw{opt_.eta, 1.0 / opt_.eta, &opt_}, rng, out);
}

template <class Law>
DielectricResult& DielectricSurfaceTracer::trace_from_above_with(int groove, const Ray2& ray, const Law& law, Rng& rng,
                                                                 DielectricResult& out) const {
  out.clear();
  detail::check_light_direction(ray.dir, Medium::above);
  const Groove& g = surface_.grooves.at(static_cast<std::size_t>(groove));
  Hit first{groove, Side::left, -1.0};
  const double x = ray.origin.x();
  if (!(x > g.rim_x(Side::left) && x < g.rim_x(Side::right)) || !detail::first_facet_hit(g, ray, first.side, first.s)) {
    out.vertex = 1.0;  // on a peak exactly, or met no facet (a vertex by rounding, as sim::trace)
    return out;
  }
  return run(first, ray.dir, Medium::above, law, rng, out);
}

template <class Law>
DielectricResult& DielectricSurfaceTracer::trace_from_below_with(double x, const Vec2& dir, const Law& law, Rng& rng,
                                                                 DielectricResult& out) const {
  out.clear();
  detail::check_light_direction(dir, Medium::below);
  if (!std::isfinite(x)) {
    out.vertex = 1.0;  // no number: never dropped
    return out;
  }
  const double G = static_cast<double>(surface_.grooves.size());
  const double xw = x - std::floor(x / G) * G;  // into [0, G] (G itself by rounding: groove G is groove 0)
  const long n0 = static_cast<long>(std::floor(xw));
  Hit first{};
  bool unresolved = false;
  if (!march(Vec2(xw, -depth_max_), n0, dir, -1, Side::left, first, unresolved)) {
    out.vertex = 1.0;  // met nothing: a vertex by rounding (or no number), never dropped
    return out;
  }
  return run(first, dir, Medium::below, law, rng, out);
}

template <class Law>
DielectricResult& DielectricSurfaceTracer::run(const Hit& first, const Vec2& d0, Medium from, const Law& law, Rng& rng,
                                               DielectricResult& out) const {
  std::vector<detail::PendingHit>& pending = out.pending;
  pending.push_back(detail::PendingHit{d0, first.s, 1.0, 0, 0, static_cast<Part>(first.side), from, first.groove});
  const bool split = opt_.branching == Branching::split;
  const Part first_part = static_cast<Part>(first.side);
  while (!pending.empty()) {
    const detail::PendingHit h = pending.back();
    pending.pop_back();
    const Groove& g = surface_.grooves[static_cast<std::size_t>(h.groove)];
    const Side side = static_cast<Side>(h.on);
    const Facet& fa = g[side];
    if (h.pos == 0.0 || h.pos == fa.length) {
      out.vertex += h.w;  // exactly on an apex or a peak
      out.max_k = std::max(out.max_k, h.k);
      continue;
    }
    if (h.k == opt_.max_interactions) {
      out.bounce_limit += h.w;
      out.max_k = std::max(out.max_k, h.k);
      continue;
    }
    ++out.interactions;
    Vec2 t_dir = Vec2::Zero();
    const double F = law(h.d, fa.normal, h.in, t_dir);
    double w_branch[2];
    detail::branch_weights(split, F, h.w, rng, w_branch);
    for (int b = 0; b < 2; ++b) {
      const double w = w_branch[b];
      if (!(w > 0.0)) continue;
      const int k = h.k + 1;
      if (w < opt_.min_weight) {
        out.cut += w;
        ++out.paths_cut;
        out.max_k = std::max(out.max_k, k);
        continue;
      }
      const Vec2 d = b == 0 ? fa.reflect(h.d) : t_dir;
      const Medium medium = b == 0 ? h.in : detail::other_medium(h.in);
      const std::uint64_t path = detail::branch_path(h.path, h.k, b);
      if (medium == Medium::above) {
        double s_next;
        if (detail::step_to_other_facet(g, side, h.pos, d, s_next)) {
          pending.push_back(
              detail::PendingHit{d, s_next, w, path, k, static_cast<Part>(other(side)), medium, h.groove});
          continue;
        }
      } else {
        const double c = scale_[static_cast<std::size_t>(h.groove)];
        const Vec2 p(h.groove + 0.5 + c * h.pos * fa.edge.x(), c * (h.pos * fa.edge.y() - g.rim_height));
        Hit next{};
        bool unresolved = false;
        if (march(p, h.groove, d, h.groove, side, next, unresolved)) {
          pending.push_back(
              detail::PendingHit{d, next.s, w, path, k, static_cast<Part>(next.side), medium, next.groove});
          continue;
        }
        if (unresolved) {
          out.vertex += w;
          out.max_k = std::max(out.max_k, k);
          continue;
        }
      }
      out.add_exit(DielectricExit{d, w, path, k, medium, first_part});
    }
  }
  return out;
}

template DielectricResult& DielectricSurfaceTracer::trace_from_above_with(int, const Ray2&, const detail::FlatlandLaw&,
                                                                          Rng&, DielectricResult&) const;
template DielectricResult& DielectricSurfaceTracer::trace_from_above_with(int, const Ray2&, const detail::LiftedLaw&,
                                                                          Rng&, DielectricResult&) const;
template DielectricResult& DielectricSurfaceTracer::trace_from_below_with(double, const Vec2&,
                                                                          const detail::FlatlandLaw&, Rng&,
                                                                          DielectricResult&) const;
template DielectricResult& DielectricSurfaceTracer::trace_from_below_with(double, const Vec2&, const detail::LiftedLaw&,
                                                                          Rng&, DielectricResult&) const;

}  // namespace vgroove::sim
