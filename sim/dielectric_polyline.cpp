#include "vgroove/sim/dielectric_polyline.h"

#include "vgroove/sim/dielectric_interaction.h"
#include "vgroove/sim/polyline_tracer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace vgroove::sim {

namespace {

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

DielectricPolylineTracer::DielectricPolylineTracer(const Polyline& p, const DielectricOptions& opt) : p_(p), opt_(opt) {
  detail::check_dielectric_options(opt);
}

DielectricResult& DielectricPolylineTracer::trace(double x, const Vec2& dir, Medium from, Rng& rng,
                                                  DielectricResult& out) const {
  out.clear();
  detail::check_light_direction(dir, from);
  if (!(x >= p_.x.front() && x < p_.x.back()))
    throw std::invalid_argument("x = " + number_text(x) + " is out of range [" + number_text(p_.x.front()) + ", " +
                                number_text(p_.x.back()) + ") (one period of the profile)");
  const PolylineHit first =
      from == Medium::above ? first_hit_from_top(p_, x, dir) : first_hit_from_bottom(p_, lows_, x, dir);
  if (first.kind != PolylineHit::Kind::segment) {
    // A vertex; a ray that crosses its entry line always meets the profile, so `escaped` is
    // rounding too: never dropped.
    out.vertex = 1.0;
    return out;
  }
  const Part first_part =
      p_.normal[static_cast<std::size_t>(first.segment)].x() > 0.0 ? Part::left_facet : Part::right_facet;
  const detail::FlatlandLaw law{opt_.eta, 1.0 / opt_.eta, &opt_};
  const bool split = opt_.branching == Branching::split;
  std::vector<detail::PendingHit>& pending = out.pending;
  pending.push_back(detail::PendingHit{dir, first.s, 1.0, 0, 0, first_part, from, first.segment});
  while (!pending.empty()) {
    const detail::PendingHit h = pending.back();
    pending.pop_back();
    if (h.k == opt_.max_interactions) {
      out.bounce_limit += h.w;
      out.max_k = std::max(out.max_k, h.k);
      continue;
    }
    const Vec2& n = p_.normal[static_cast<std::size_t>(h.groove)];
    const double dn = h.d.dot(n);
    // The path crossed the segment from its own side (d.n < 0 from above, > 0 from below) but for
    // rounding when it runs along the segment: the hit is then undefined, as at a vertex
    // (trace_polyline's rule).
    if (h.in == Medium::above ? !(dn < 0.0) : !(dn > 0.0)) [[unlikely]] {
      out.vertex += h.w;
      out.max_k = std::max(out.max_k, h.k);
      continue;
    }
    ++out.interactions;
    Vec2 t_dir = Vec2::Zero();
    const double F = law(h.d, n, h.in, t_dir);
    double w_branch[2];
    detail::branch_weights(split, F, h.w, rng, w_branch);
    for (int b = 0; b < 2; ++b) {
      const double w = w_branch[b];
      if (!(w > 0.0)) continue;
      const int k = h.k + 1;
      out.max_k = std::max(out.max_k, k);
      if (w < opt_.min_weight) {
        out.cut += w;
        ++out.paths_cut;
        continue;
      }
      // trace_polyline's reflection, operation for operation.
      Vec2 d = h.d;
      if (b == 0)
        d -= (2.0 * dn) * n;
      else
        d = t_dir;
      const Medium medium = b == 0 ? h.in : detail::other_medium(h.in);
      const std::uint64_t path = detail::branch_path(h.path, h.k, b);
      const PolylineHit next = medium == Medium::above ? first_hit_from(p_, h.groove, h.pos, d)
                                                       : first_hit_from_below(p_, lows_, h.groove, h.pos, d);
      if (next.kind == PolylineHit::Kind::segment) {
        pending.push_back(detail::PendingHit{d, next.s, w, path, k, h.on, medium, next.segment});
        continue;
      }
      if (next.kind == PolylineHit::Kind::vertex) {
        out.vertex += w;
        continue;
      }
      out.add_exit(DielectricExit{d, w, path, k, medium, first_part});
    }
  }
  return out;
}

}  // namespace vgroove::sim
