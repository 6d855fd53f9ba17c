// vgroove sim: procedural microsurfaces of nonsymmetric V-grooves (flatland and 3D, isotropic or
// anisotropic), and the light they scatter, traced exactly. Lee et al. 2018 ("Practical Multiple
// Scattering for Rough Surfaces", ACM TOG 37(6)), Sec. 5.2 (Eq. 18-20), Fig. 7-8; derived here
// independently of analytic/ (never included). Each groove: one facet's tilt from the NDF's tilt
// law q, the other's from r = q tan / E_q[tan] (Eq. 20), independently, on a side chosen with
// probability 1/2 (3D: the azimuth); anisotropic Beckmann and GGX by scaled slopes, the partner at
// alpha(phi). Partner::symmetric draws B = A. Traced as sim/microsurface.h (flatland) and
// sim/microsurface3d.h (3D) into the same tallies; bit-identical for any chunk split.
// Holds: every facet's normal follows D in projected area and its partner's tilt Eq. (20)
// independently; every ray leaves and is counted; chunk order does not matter.
// Tests: tests/sim/microsurface_nonsymmetric_test.cpp
// (NonsymmetricPopulation.FacetFollowsTheNdfAndItsPartnerEq20Independently,
// NonsymmetricPopulation.AnisotropicSlopesAndPartners, NonsymmetricMicrosurface.EveryRayLeavesAndIsCounted,
// NonsymmetricMicrosurface.ChunkOrderDoesNotMatter), tests/sim/partner_sampling_test.cpp.
// Derivation: docs/derivations/nonsymmetric.md.
#pragma once

#include "vgroove/sim/microsurface.h"
#include "vgroove/sim/microsurface3d.h"

#include <cstdint>
#include <vector>

namespace vgroove::sim {

enum class Partner : unsigned char {
  independent,  // the second facet's tilt from Eq. (20), independently
  symmetric,    // the second facet's tilt equal to the first's
};

struct NonsymmetricSurfaceOptions {
  NdfKind ndf = NdfKind::beckmann;
  double alpha_x = 0.5;       // flatland and isotropic surfaces: alpha_x == alpha_y
  double alpha_y = 0.5;       // Phong: isotropic only; independent Phong partners need alpha < sqrt(2)
  double axes_azimuth = 0.0;  // 3D: azimuth of the alpha_x axis in the tally's frame
  Partner partner = Partner::independent;
  int grooves = 10000;
  std::uint64_t seed = 0;
  bool isotropic() const { return alpha_x == alpha_y; }
};

// The roughness along the azimuth phi of the roughness axes' frame: 1/alpha^2 = cos^2/ax^2 + sin^2/ay^2.
double alpha_along(double alpha_x, double alpha_y, double phi);

struct NonsymmetricMicrosurface {
  NonsymmetricSurfaceOptions options;
  std::vector<double> theta_l, theta_r;  // theta_l in (-pi/2, 0], theta_r in [0, pi/2)
  std::vector<Groove> grooves;           // make_nonsymmetric_groove(theta_l, theta_r)
};

struct NonsymmetricMicrosurface3d {
  NonsymmetricSurfaceOptions options;
  std::vector<double> theta_l, theta_r;  // in each groove's cross-section (a, n)
  std::vector<double> phi_a;             // azimuth of a in the tally's frame, [0, 2 pi)
  std::vector<GrooveFrame3d> frames;
  std::vector<Groove> grooves;
};

inline constexpr std::uint64_t kNonsymGrooveStream = 0x6e736772ULL;        // "nsgr"
inline constexpr std::uint64_t kNonsymGroove3dStream = 0x6e7367723364ULL;  // "nsgr3d"
inline constexpr std::uint64_t kNonsymRay3dStream = 0x6e737233ULL;         // "nsr3"

NonsymmetricMicrosurface make_nonsymmetric_microsurface(const NonsymmetricSurfaceOptions& opt);
NonsymmetricMicrosurface3d make_nonsymmetric_microsurface3d(const NonsymmetricSurfaceOptions& opt);
// Appends one groove (tests and hand-made surfaces): facet angles in the cross-section, azimuth of a.
void add_nonsymmetric_groove3d(NonsymmetricMicrosurface3d& m, double theta_l, double theta_r, double phi_a);

// Flatland: the rays of chunk c (for_each_landing over the grooves), and all chunks merged in order.
MicrosurfaceTally trace_nonsymmetric_microsurface_chunk(const NonsymmetricMicrosurface& surface,
                                                        const MicrosurfaceTraceOptions& opt, std::int64_t chunk);
MicrosurfaceTally trace_nonsymmetric_microsurface(const NonsymmetricMicrosurface& surface,
                                                  const MicrosurfaceTraceOptions& opt);

// 3D: the rays of chunk c (a groove uniformly, a point across its opening uniformly), and all chunks.
Microsurface3dTally trace_nonsymmetric_microsurface3d_chunk(const NonsymmetricMicrosurface3d& surface,
                                                            const Microsurface3dTraceOptions& opt, std::int64_t chunk);
Microsurface3dTally trace_nonsymmetric_microsurface3d(const NonsymmetricMicrosurface3d& surface,
                                                      const Microsurface3dTraceOptions& opt);

}  // namespace vgroove::sim
