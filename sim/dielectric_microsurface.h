// vgroove sim: exact 2D tracing of light across a procedural V-groove surface (sim/microsurface.h)
// that separates two dielectrics (medium 1, index n1, above; medium 2, n2, below; eta = n2 / n1).
// Hits as in sim/dielectric_groove.h (exact Fresnel at the local angle, Snell, total internal
// reflection; split or random branching). In medium 1 a path stays in its groove and follows
// sim::trace's arithmetic in the groove's frame, so the conductor limit is
// trace_microsurface_chunk_reference's tally bit for bit; in medium 2 it runs below the surface
// across any number of grooves (tested in order) until it meets an underside or leaves downward.
// Holds: the conductor limit bit for bit; eta = 1 passes straight through; energy conserved and
// refracted light traced on; split and random branching agree in distribution.
// Tests: tests/sim/dielectric_microsurface_test.cpp (DielectricSurface.ConductorLimitIsTodaysMicrosurfaceTally,
// DielectricSurface.EtaOnePassesStraightThrough, DielectricSurface.EnergyIsConservedAndRefractedLightIsTracedOn,
// DielectricSurface.SplittingAndRandomBranchingAgreeInDistribution, DielectricSurface.BadInputIsRefused).
// Derivation: docs/derivations/dielectric_groove.md.
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

  // The two with another law of one hit (as DielectricGrooveTracer::trace_with; instantiated for
  // detail::FlatlandLaw and detail::LiftedLaw).
  template <class Law>
  DielectricResult& trace_from_above_with(int groove, const Ray2& ray, const Law& law, Rng& rng,
                                          DielectricResult& out) const;
  template <class Law>
  DielectricResult& trace_from_below_with(double x, const Vec2& dir, const Law& law, Rng& rng,
                                          DielectricResult& out) const;

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
  template <class Law>
  DielectricResult& run(const Hit& first, const Vec2& d, Medium from, const Law& law, Rng& rng,
                        DielectricResult& out) const;

  const Microsurface& surface_;
  DielectricOptions opt_;
  std::vector<double> scale_;  // c_j
  double depth_max_ = 0.0;
};

}  // namespace vgroove::sim
