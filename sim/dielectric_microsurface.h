// vgroove sim: exact 2D tracing of light across a procedural V-groove surface (sim/microsurface.h)
// that separates two dielectrics.
//
// The surface. The microsurface's G symmetric grooves side by side, each one groove width wide,
// peaks on the line y = 0, repeated periodically along x (groove n is groove n mod G). Groove j,
// built with unit facets (make_symmetric_groove), is scaled by c_j = 1 / (2 rim_x) to unit width:
// a point (x, y) of its own frame lies at (j + 1/2 + c_j x, c_j (y - rim_height)) on the surface.
// Scaling and shifting turn no direction, so directions are the same in both frames.
//
// Medium 1 (n1) lies above the surface, medium 2 (n2) below; eta = n2 / n1. Hits as in
// sim/dielectric_groove.h (exact Fresnel at the local angle, Snell, total internal reflection;
// split or random branching). In medium 1 a path stays inside its groove (all peaks on one line)
// and goes from facet to facet by sim::trace's arithmetic in the groove's own frame, so in the
// conductor limit every ray is sim::trace's in that groove, bit for bit, and the tallies are those
// of trace_microsurface_chunk_reference. In medium 2 a path runs below the surface across any
// number of grooves: the grooves along its way are tested in order (each groove's facets lie over
// its own width, so the first groove hit holds the nearest hit), until it meets a facet's
// underside or runs downward below the deepest apex, where it has left into medium 2.
//
// Light from above lands in a groove as for sim::trace_microsurface (sim::for_each_landing gives
// the groove and the ray in its frame). Light from below is given by where its line crosses the
// line y = -depth_max() (no facet lies below it), at x in groove widths.
#pragma once

#include "vgroove/sim/dielectric_groove.h"
#include "vgroove/sim/microsurface.h"

#include <vector>

namespace vgroove::sim {

class DielectricSurfaceTracer {
 public:
  // Throws std::invalid_argument naming the field and its range (as DielectricGrooveTracer).
  // The surface is referenced, not copied: it must outlive the tracer.
  DielectricSurfaceTracer(const Microsurface& surface, const DielectricOptions& opt);

  const DielectricOptions& options() const { return opt_; }
  int grooves() const { return static_cast<int>(surface_.grooves.size()); }
  // The deepest apex below the peaks' line, in groove widths.
  double depth_max() const { return depth_max_; }

  // Light from above landing in groove `groove` (0 <= groove < grooves()), the ray in that
  // groove's frame crossing its rim line inside the opening (for_each_landing's rays), dir.y < 0.
  // Exits' `first` is the facet of that groove hit first.
  DielectricResult& trace_from_above(int groove, const Ray2& ray, Rng& rng, DielectricResult& out) const;

  // Light from below whose line crosses y = -depth_max() at x (groove widths; any x, taken
  // periodically), travelling along dir (dir.y > 0).
  DielectricResult& trace_from_below(double x, const Vec2& dir, Rng& rng, DielectricResult& out) const;

 private:
  struct Hit {
    int groove;
    Side side;
    double s;
  };
  // The first facet a path in medium 2 meets from the surface point p (groove widths, in the frame
  // where groove n0 spans [n0, n0 + 1]) along d, the facet (exclude_groove, exclude_side) left out
  // (exclude_groove -1: none). False when it meets none (it has left into medium 2), or, with
  // `unresolved` set, when rounding lets an upward path pass a whole period without a hit.
  bool march(const Vec2& p, long n0, const Vec2& d, int exclude_groove, Side exclude_side, Hit& hit,
             bool& unresolved) const;
  DielectricResult& run(const Hit& first, const Vec2& d, Medium from, Rng& rng, DielectricResult& out) const;

  const Microsurface& surface_;
  DielectricOptions opt_;
  std::vector<double> scale_;  // c_j
  double depth_max_ = 0.0;
};

}  // namespace vgroove::sim
