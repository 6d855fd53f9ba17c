// vgroove sim: a 3D microsurface of infinitely long symmetric V-grooves whose facet normals follow
// a 3D NDF, traced exactly with the 2D tracer in each groove's cross-section and lifted back to 3D
// (DESIGN.md, "3D from 2D"). Lee et al. 2018 ("Practical Multiple Scattering for Rough Surfaces"),
// Sec. 3, 5.1 and 7.1 (Fig. 11). Derived independently of analytic/ (never included).
// Grooves: phi_a uniform on [0, pi), theta_m with the density 2 pi D cos sin (closed-form CDFs and
// inverses per NDF); exits lift as o = sqrt(1 - (i.u)^2) (e_x a + e_y n) - (i.u) u. The light is at
// i = dir(theta_i, pi). Deterministic: any split of chunks over threads gives the same bits.
// Holds: the groove law by chi-square; every ray leaves (albedo 1); the lift matches 3D
// reflections; chunk order does not matter.
// Tests: tests/sim/microsurface3d_test.cpp (Sampling3d.GroovesFollowThePdf,
// Sampling3d.SampleInvertsTheCdf, Microsurface3dLift.MatchesThreeDimensionalReflections,
// Microsurface3d.AlbedoIsOneAndEveryRayIsAccounted, Microsurface3d.DeterministicAcrossChunkOrders).
// Derivation: docs/derivations/microsurface.md.
#pragma once

#include "vgroove/sim/microsurface.h"

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace vgroove::sim {

using Vec3 = Eigen::Vector3d;

// The direction at polar angle theta and azimuth phi.
inline Vec3 direction3(double theta, double phi) {
  return Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// The groove polar angle theta_m in [0, pi/2): density 2 pi D cos sin (above), its distribution
// function, and its inverse (u in (0, 1) to theta_m, monotone). Matched pair: tests check them together.
double theta_m_pdf_3d(NdfKind kind, double alpha, double theta_m);
double theta_m_cdf_3d(NdfKind kind, double alpha, double theta_m);
double sample_theta_m_3d(NdfKind kind, double alpha, double u);

struct Microsurface3dOptions {
  NdfKind ndf = NdfKind::ggx;
  double alpha = 0.5;  // roughness, > 0 (Phong: alpha < sqrt(2), so that p > -1)
  int grooves = 10000;
  std::uint64_t seed = 0;
};

// One groove's frame: a across it, u along its axis.
struct GrooveFrame3d {
  double cos_phi_a = 1.0, sin_phi_a = 0.0;
  Vec3 a() const { return Vec3(cos_phi_a, sin_phi_a, 0.0); }
  Vec3 u() const { return Vec3(-sin_phi_a, cos_phi_a, 0.0); }  // n x a
};

struct Microsurface3d {
  Microsurface3dOptions options;
  std::vector<double> theta_m;        // [0, pi/2)
  std::vector<double> phi_a;          // [0, pi)
  std::vector<GrooveFrame3d> frames;  // from phi_a
  std::vector<Groove> grooves;        // cross-sections: aperture pi - 2 theta_m, unit facets
  // The cross-sections in 24 bytes each (symmetric_block.h), what the batch trace reads.
  std::vector<SymmetricGrooveData> data;
};

inline constexpr std::uint64_t kGroove3dStream = 0x67726f6f76653364ULL;  // "groove3d"
inline constexpr std::uint64_t kRay3dStream = 0x7261797333ULL;           // "rays3"

Microsurface3d make_microsurface3d(const Microsurface3dOptions& opt);
// Appends one groove (for tests and hand-made surfaces).
void add_groove3d(Microsurface3d& m, double theta_m, double phi_a);

// One ray in one groove: i towards the light (unit, i.z > 0), f in (0, 1) the landing point across
// the opening from the rim at -a to the rim at +a. o is valid when trace.how == escaped.
struct Trace3dResult {
  TraceResult trace;  // in the cross-section (exit_dir = (e_x, e_y))
  Vec3 o = Vec3::Zero();
};
Trace3dResult trace_groove3d(const Groove& g, const GrooveFrame3d& frame, const Vec3& i, double f,
                             const TraceOptions& opt = {});

struct Microsurface3dTraceOptions {
  double theta_i = 0.0;  // polar angle of the light, in [0, pi/2); its azimuth is pi
  std::int64_t rays = 100000;
  std::uint64_t seed = 0;
  int theta_bins = 90;  // equal bins over [0, pi/2)
  int phi_bins = 72;    // equal bins centred on phi = 0; even
  int max_k = 16;       // per-k histograms for k = 0..max_k; larger k share the last row
  TraceOptions trace;
};

// Histogram layout shared with analytic::Lobe3d (analytic/lobe_3d.h): theta_o in [0, pi/2) in
// theta_bins equal bins; phi_o in phi_bins equal bins centred on phi = 0, phi_bins even; the light
// at polar angle theta_i and azimuth pi; rows k = 0..max_k (+1 for k > max_k);
// index [(row * theta_bins + t) * phi_bins + p].
//
// Every ray is in exactly one of escaped, blocked, vertex_hits, bounce_limit, not_upward; every
// escaped ray in one k row and one (theta_o, phi_o) bin.
struct Microsurface3dTally : RayFates {
  int theta_bins = 0;
  int phi_bins = 0;
  int max_k = 0;
  std::vector<std::int64_t> by_k;       // [row]
  std::vector<std::int64_t> hist;       // [t * phi_bins + p], all escaped rays
  std::vector<std::int64_t> hist_by_k;  // [(row * theta_bins + t) * phi_bins + p]

  Microsurface3dTally() = default;
  Microsurface3dTally(int theta_bins_, int phi_bins_, int max_k_);

  double theta_width() const { return 0.5 * std::numbers::pi / theta_bins; }
  double phi_width() const { return 2.0 * std::numbers::pi / phi_bins; }
  int theta_bin_of(double theta_o) const;
  int phi_bin_of(double phi_o) const;  // phi_o in [-pi, pi]
  int row_of(int k) const { return k > max_k ? max_k + 1 : k; }
  std::size_t index(int row, int t, int p) const {
    return (static_cast<std::size_t>(row) * theta_bins + t) * phi_bins + p;
  }

  void add(const Trace3dResult& r);
  // A ray whose bins are known: theta bin t, phi bin p in [-phi_bins, 2 phi_bins) (taken modulo
  // phi_bins).
  void add_binned(Termination how, int k, bool upward, int t, int p);
  // add_binned for n rays (t[q], p[q] whole numbers; o_z[q] > 0: upward), the same counts: the
  // fates' totals kept in registers over the block instead of in memory ray by ray, p wrapped
  // without branches.
  void add_binned_block(const Termination* how, const int* k, const double* o_z, const double* t, const double* p,
                        int n);
  void merge(const Microsurface3dTally& other);  // same bins and max_k
};

std::int64_t chunk_count(const Microsurface3dTraceOptions& opt);

// The rays of chunk c (kRaysPerChunk of them; the last chunk holds the rest): the grooves and
// landing points in the order of the stream, traced in blocks (symmetric_block.h, bit for bit
// trace_groove3d's 2D trace), lifted and binned from arctangent guesses, by the edge tests where
// a guess lies near an edge (sim/exit_bins.h; the same bins).
Microsurface3dTally trace_microsurface3d_chunk(const Microsurface3d& surface, const Microsurface3dTraceOptions& opt,
                                               std::int64_t chunk);
// The same rays added to `tally` (bins and max_k of opt): a caller that sums chunks keeps one
// tally instead of clearing and merging one per chunk (the 3D per-k histograms are ~1 MB).
void trace_microsurface3d_chunk(const Microsurface3d& surface, const Microsurface3dTraceOptions& opt,
                                std::int64_t chunk, Microsurface3dTally& tally);
// The same one ray at a time with trace_groove3d on surface.grooves, binned by acos and atan2:
// the path before the blocks, kept for the tests and the benchmarks' side-by-side.
Microsurface3dTally trace_microsurface3d_chunk_reference(const Microsurface3d& surface,
                                                         const Microsurface3dTraceOptions& opt, std::int64_t chunk);

// All chunks, merged in order (one thread; a caller may run the chunks on several and merge).
Microsurface3dTally trace_microsurface3d(const Microsurface3d& surface, const Microsurface3dTraceOptions& opt);

}  // namespace vgroove::sim
