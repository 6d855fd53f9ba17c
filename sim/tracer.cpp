#include "vgroove/sim/tracer.h"

namespace vgroove::sim {

const char* termination_name(Termination t) {
  switch (t) {
    case Termination::escaped:
      return "escaped";
    case Termination::blocked:
      return "blocked";
    case Termination::vertex_hit:
      return "vertex_hit";
    case Termination::bounce_limit:
      return "bounce_limit";
  }
  return "?";
}

bool BeamTracer::first_hit_both(double x_rim, double sn, bool away_l, bool away_r, int& f, double& s) const {
  // Both answer only near the apex, and then the nearer one, by t = tn / den, is taken.
  const double tn_l = x_rim * g_.facet[0].edge.y() - h_ex_[0];
  const double tn_r = x_rim * g_.facet[1].edge.y() - h_ex_[1];
  const bool miss_l = away_l || den_[0] == 0.0 || tn_l * den_[0] < 0.0 || std::abs(sn) > limit_[0];
  const bool miss_r = away_r || den_[1] == 0.0 || tn_r * den_[1] < 0.0 || std::abs(sn) > limit_[1];
  if (miss_l && miss_r) return false;
  if (!miss_l && !miss_r) {
    const double s_l = sn / den_[0], s_r = sn / den_[1];
    if (s_l >= 0.0 && (s_r < 0.0 || tn_l / den_[0] <= tn_r / den_[1]))
      f = 0, s = s_l;
    else
      f = 1, s = s_r;
  } else {
    f = miss_l ? 1 : 0;
    s = sn / den_[f];
  }
  return true;
}

BeamTracer::BeamTracer(const Groove& g, const Vec2& dir, const TraceOptions& opt)
    : g_(g), dir_(dir), opt_(opt), h_dx_(g.rim_height * dir.x()) {
  // The same products, in the same order, as sim::trace forms per ray.
  const int n_max = opt.max_bounces >= 0 && opt.max_bounces < kMaxTable ? opt.max_bounces : kMaxTable;
  for (int first = 0; first < 2; ++first) {
    const Facet& f0 = g.facet[first];
    den_[first] = cross(f0.edge, dir);
    h_ex_[first] = g.rim_height * f0.edge.x();
    limit_[first] = f0.length * std::abs(den_[first]);
    std::vector<Reflection>& tab = table_[first];
    Vec2 d = dir;
    for (int k = 0; k < n_max; ++k) {
      const Facet& f = g.facet[first ^ (k & 1)];
      const Facet& o = g.facet[first ^ (~k & 1)];
      Reflection e;
      d = f.reflect(d);
      e.d_out = d;
      const double den = cross(o.edge, d);
      const double c = cross(f.edge, d);
      e.leaves = !(den * f.turn_to_other > 0.0) || c * den < 0.0;
      e.abs_c = std::abs(c);
      e.limit = o.length * std::abs(den);
      e.ratio = c / den;
      tab.push_back(e);
      if (e.leaves) break;
    }
  }
}

}  // namespace vgroove::sim
