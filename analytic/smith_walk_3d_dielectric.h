// vgroove analytic: the Smith multiple-scattering random walk of Heitz, Hanika, d'Eon, Dachsbacher
// (ACM TOG 35(4), 2016; its dielectric microsurface) in 3D: medium 1 above, medium 2 below, eta =
// n2 / n1, light from either side, Beckmann and GGX. The 3D conductor walk (analytic/smith_walk_3d.h)
// in the frame of the medium the ray is in, as the flatland dielectric walk does
// (analytic/smith_walk_flatland_dielectric.h): medium 2 sees the microsurface flipped (z -> -z,
// log C1 -> log(1 - C1)); at each intersection the ray reflects with probability F (dielectric
// Fresnel at the local angle, 1 under TIR), else refracts (Snell, optics/snell.h). A pure function
// of its caller's uniform numbers. Holds: F = 1 is the conductor walk bit for bit; eta = 1 goes
// straight through; its k = 1 energies are Walter's with Smith's height-correlated G2
// (analytic/albedo_glass.h), from either side; the transmitted averages are reciprocal.
// Tests: tests/analytic/smith_walk_3d_dielectric_test.cpp (SmithWalk3dDielectric.ConductorLimitIsTheConductorWalk,
// SmithWalk3dDielectric.EtaOnePassesStraightThrough,
// SmithWalk3dDielectric.SingleScatteringIsWaltersWithTheHeightCorrelatedG2,
// SmithWalk3dDielectric.TransmittedAveragesAreReciprocal, SmithWalk3dDielectric.EveryWalkLeavesAndHardCasesStayFinite).
// Derivation: docs/derivations/smith_walk_dielectric.md ("In 3D").
#pragma once

#include "vgroove/analytic/smith_walk_3d.h"
#include "vgroove/analytic/smith_walk_flatland_dielectric.h"
#include "vgroove/optics/snell.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace vgroove::analytic {

struct DielectricWalk3d {
  int k = 0;                            // interactions (reflections and refractions)
  Dir3 o{};                             // exit direction in the world frame (o.z > 0 above, < 0 below)
  std::uint64_t path = 0;               // bit j set: interaction j refracted (the first 64)
  WalkMedium side = WalkMedium::above;  // the medium it left into
  bool left = false;                    // false: still inside after max_k interactions
};

// The walk of light arriving from `from` along -i, i the unit direction towards the light in the
// world frame (i.z > 0 from above, i.z < 0 from below). uniform() returns numbers in (0, 1): one
// per free path, two per intersection (the facet normal, as smith_walk_3d), and one per
// intersection with F < 1 (the choice), in that order. law(cos_i, eta_rel) gives F where Snell's
// law transmits (DielectricFresnelLaw).
template <class Uniform, class Law = DielectricFresnelLaw>
DielectricWalk3d smith_walk_3d_dielectric(NdfKind ndf, double alpha, const Dir3& i, WalkMedium from,
                                          const DielectricWalkOptions& opt, Uniform&& uniform, const Law& law = Law{}) {
  DielectricWalk3d w;
  WalkMedium medium = from;
  // The frame of the medium the ray travels in: medium 1's is the world's, medium 2's the world's
  // mirrored in the mean plane (z -> -z), where the flipped microsurface lies below the medium.
  const double s = from == WalkMedium::above ? 1.0 : -1.0;
  Dir3 d{-i.x, -i.y, -s * i.z};  // travelling along -i
  double lc = 0.0;
  for (;;) {
    const double next = walk_free_path(ndf, alpha, lc, polar_angle(d), uniform());
    if (std::isinf(next)) {
      w.o = medium == WalkMedium::above ? d : Dir3{d.x, d.y, -d.z};
      w.side = medium;
      w.left = true;
      return w;
    }
    if (w.k == opt.max_k) return w;
    lc = next;
    const int j = w.k++;
    const Dir3 v{-d.x, -d.y, -d.z};
    const double u0 = uniform(), u1 = uniform();
    const Dir3 m = sample_visible_normal_3d(ndf, alpha, v, u0, u1);
    // <v, m> > 0 for every visible normal; the clamp only absorbs rounding.
    const double c = std::max(0.0, v.x * m.x + v.y * m.y + v.z * m.z);
    const double eta_rel = medium == WalkMedium::above ? opt.eta : 1.0 / opt.eta;
    const double cos_t = optics::snell_cos_transmitted(c, eta_rel);
    const double F = opt.conductor_limit || cos_t < 0.0 ? 1.0 : law(c, eta_rel);
    if (F >= 1.0 || uniform() < F) {
      d = {2.0 * c * m.x - v.x, 2.0 * c * m.y - v.y, 2.0 * c * m.z - v.z};
    } else {
      // Refraction (optics::refract's t = d / eta + (cos_i / eta - cos_t) m), then the other
      // medium's frame: z flips, and the height's log C1 becomes that of the flipped surface.
      Dir3 t = d;
      if (eta_rel != 1.0) {
        const double inv = 1.0 / eta_rel, a = inv * c - cos_t;
        t = {inv * d.x + a * m.x, inv * d.y + a * m.y, inv * d.z + a * m.z};
      }
      d = {t.x, t.y, -t.z};
      medium = medium == WalkMedium::above ? WalkMedium::below : WalkMedium::above;
      lc = log1m_exp(lc);
      if (j < 64) w.path |= std::uint64_t{1} << j;
    }
    // A unit vector to rounding; renormalized so that no drift accumulates over long walks.
    const double len = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    d = {d.x / len, d.y / len, d.z / len};
  }
}

}  // namespace vgroove::analytic
