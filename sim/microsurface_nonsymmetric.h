// vgroove sim: procedural microsurfaces of nonsymmetric V-grooves (flatland and 3D, isotropic or
// anisotropic), and the light they scatter, traced exactly.
//
// Lee, Jarabo, Jeon, Gutierrez, Kim. "Practical Multiple Scattering for Rough Surfaces". ACM TOG
// 37(6), 2018: Sec. 5.2 (nonsymmetric grooves, Eq. 18-20: the second facet's tilt independent of
// the first, drawn from P(theta_r)), Fig. 7 (anisotropic Beckmann), Fig. 8 (symmetric against
// nonsymmetric). Derived here independently of analytic/ (never included).
//
// The grooves. Each groove has two facets whose normals lie in its cross-section: the one whose
// normal leans towards +a (the "left" facet of sim/groove.h, normal angle theta_l = -A) and the
// one leaning towards -a (right, theta_r = +B). Both rims lie on the macrosurface (all peaks on
// one plane: light never leaves its groove), every groove spans the same macro width (flatland)
// or area (3D), and its facet lengths follow from the equal rim heights (make_nonsymmetric_groove).
//
// Which (A, B). Lee et al.'s construction (Eq. 18-19; tests/sim/partner_sampling_test.cpp checks
// it) gives each groove a first facet of fixed projected width, its tilt a from the NDF's tilt law
// q, and a second facet of tilt b from Eq. (20), r = q tan / E_q[tan], whose width tan a / tan b
// follows. Its grooves cover the macrosurface with the shape density (per macro area)
//   q(a) r(b) (1 + tan a / tan b) / 2 = (q(a) r(b) + r(a) q(b)) / 2,
// since q(a) tan a r(b) / tan b = r(a) q(b) E_q[tan] / E_q[tan] (r / tan = q / E_q[tan]). So the same
// surface, with every groove of equal width, is drawn as: one facet's tilt from q, the other's
// from r, independently, on a side chosen with probability 1/2. In 3D the side is the azimuth:
// the facet from q leans towards a = (cos phi_a, sin phi_a, 0) with phi_a uniform on [0, 2 pi),
// which covers both assignments (the groove at phi_a + pi with its facets swapped is the same
// groove). In flatland a fair coin picks it. Every facet of the surface then has its normal
// distributed by the NDF in projected area, and the tilt of its partner by r, independently of
// its own: the population of Lee et al.'s Eq. (21).
//
// Anisotropy (3D, Beckmann and GGX: elliptical slope laws P22(m) = P(|(m_x / alpha_x, m_y /
// alpha_y)|) / (alpha_x alpha_y)). The facet from q is the facet of a slope m drawn from P22: a
// unit-roughness isotropic slope scaled by (alpha_x, alpha_y); its normal's azimuth is that of
// -m, its tilt atan |m|. Along an azimuth phi the elliptical law is the isotropic one of roughness
// alpha(phi), 1/alpha(phi)^2 = cos^2(phi)/alpha_x^2 + sin^2(phi)/alpha_y^2, up to a constant, so
// the azimuths have the density ~ alpha(phi)^2, the tilt given phi is q at alpha(phi), and the
// partner's tilt is drawn from r at alpha(phi) (Sec. 5.2: "P(theta_r | phi_v)"). The roughness
// axes sit at the azimuth `axes_azimuth` of the tally's frame (the light at azimuth pi): a light at
// azimuth phi_i over the roughness axes is axes_azimuth = pi - phi_i.
//
// Partner::symmetric draws B = A: symmetric grooves with the same azimuth law (the symmetric model
// of anisotropic surfaces; isotropic, the law of sim/microsurface.h and sim/microsurface3d.h).
//
// Tracing and tallies: as sim/microsurface.h (flatland: the beam lands uniformly on the
// macrosurface, for_each_landing) and sim/microsurface3d.h (3D: a groove uniformly, a point across
// its opening uniformly, trace_groove3d in its cross-section, lifted back), into the same tallies.
//
// Determinism. Groove j's angles come from Rng(seed, stream, j) (its own stream whatever it
// draws); the rays are cut into chunks of kRaysPerChunk, chunk c drawing from Rng(ray seed,
// stream, c). Tallies hold integer counts, so any split of the chunks over threads, merged in any
// order, gives bit-identical results.
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
