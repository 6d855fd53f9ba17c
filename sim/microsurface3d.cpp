#include "vgroove/sim/microsurface3d.h"

#include "vgroove/common/simd.h"
#include "vgroove/sim/exit_bins.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace vgroove::sim {

double theta_m_pdf_3d(NdfKind kind, double alpha, double theta_m) {
  if (!(theta_m >= 0.0 && theta_m < 0.5 * std::numbers::pi)) return 0.0;
  const double c = std::cos(theta_m), s = std::sin(theta_m), a2 = alpha * alpha;
  switch (kind) {
    case NdfKind::ggx: {
      // 2 a^2 sin / (cos^3 (a^2 + tan^2)^2) with the cos^4 of tan^4 moved into the bracket:
      // finite up to pi/2.
      const double q = a2 * c * c + s * s;
      return 2.0 * a2 * s * c / (q * q);
    }
    case NdfKind::beckmann: {
      if (c == 0.0) return 0.0;  // exp(-tan^2/a^2) wins over 1/cos^3
      const double t = s / c;
      return 2.0 * std::exp(-t * t / a2) * s / (a2 * c * c * c);
    }
    case NdfKind::phong:  // (p + 2) cos^(p+1) sin, p + 2 = 2/a^2
      return (2.0 / a2) * std::pow(c, 2.0 / a2 - 1.0) * s;
    case NdfKind::student_t: {
      // dP/dtheta = 2 (gamma - 1) tan / (k2 cos^2) (1 + tan^2/k2)^-gamma, with 1 + tan^2/k2 =
      // (k2 c^2 + s^2) / (k2 c^2): 2 (gamma - 1) s / (k2 c^3) (k2 c^2 / (k2 c^2 + s^2))^gamma.
      const double g = kind.gamma, k2 = (g - 1.0) * a2, k2c2 = k2 * c * c;
      return 2.0 * (g - 1.0) * s / (k2 * c * c * c) * std::pow(k2c2 / (k2c2 + s * s), g);
    }
  }
  return 0.0;
}

double theta_m_cdf_3d(NdfKind kind, double alpha, double theta_m) {
  if (!(theta_m > 0.0)) return 0.0;
  if (theta_m >= 0.5 * std::numbers::pi) return 1.0;
  const double c = std::cos(theta_m), s = std::sin(theta_m), a2 = alpha * alpha;
  switch (kind) {
    case NdfKind::ggx:
      return s * s / (a2 * c * c + s * s);  // tan^2 / (a^2 + tan^2)
    case NdfKind::beckmann: {
      const double t = s / c;
      return -std::expm1(-t * t / a2);
    }
    case NdfKind::phong:
      return -std::expm1((2.0 / a2) * std::log(c));  // 1 - cos^(p+2)
    case NdfKind::student_t: {
      const double g = kind.gamma, t = s / c;
      return -std::expm1((1.0 - g) * std::log1p(t * t / ((g - 1.0) * a2)));
    }
  }
  return 0.0;
}

double sample_theta_m_3d(NdfKind kind, double alpha, double u) {
  assert(u > 0.0 && u < 1.0 && alpha > 0.0);
  switch (kind) {
    case NdfKind::ggx:
      return std::atan(alpha * std::sqrt(u / (1.0 - u)));
    case NdfKind::beckmann:
      return std::atan(alpha * std::sqrt(-std::log1p(-u)));
    case NdfKind::phong: {
      // cos theta = (1 - u)^(a^2/2); 1 - cos theta = 2 sin^2(theta/2) keeps small angles exact.
      const double w = -std::expm1(0.5 * alpha * alpha * std::log1p(-u));
      return 2.0 * std::asin(std::sqrt(0.5 * w));
    }
    case NdfKind::student_t: {
      // (1 + tan^2/k2)^(1 - gamma) = 1 - u: tan^2 = k2 ((1 - u)^(-1/(gamma - 1)) - 1).
      const double g = kind.gamma;
      return std::atan(std::sqrt((g - 1.0) * alpha * alpha * std::expm1(std::log1p(-u) / (1.0 - g))));
    }
  }
  return 0.0;
}

void add_groove3d(Microsurface3d& m, double theta_m, double phi_a) {
  // The steepest facet that still leaves an opening (as in make_microsurface): an angle that
  // rounds to pi/2 would close the groove.
  const double t = std::min(std::nextafter(0.5 * std::numbers::pi, 0.0), theta_m);
  m.theta_m.push_back(t);
  m.phi_a.push_back(phi_a);
  m.frames.push_back(GrooveFrame3d{std::cos(phi_a), std::sin(phi_a)});
  // make_symmetric_groove's facet normals are at -t (left, leaning towards +a) and +t: the 2D
  // images of s = dir(t, phi_a) and s' = dir(t, phi_a + pi).
  m.grooves.push_back(make_symmetric_groove(std::numbers::pi - 2.0 * t));
  m.data.push_back(symmetric_groove_data(m.grooves.back()));
}

Microsurface3d make_microsurface3d(const Microsurface3dOptions& opt) {
  assert(opt.alpha > 0.0 && opt.grooves > 0);
  Microsurface3d m;
  m.options = opt;
  const auto n = static_cast<std::size_t>(opt.grooves);
  m.theta_m.reserve(n);
  m.phi_a.reserve(n);
  m.frames.reserve(n);
  m.grooves.reserve(n);
  m.data.reserve(n);
  for (int j = 0; j < opt.grooves; ++j) {
    Rng rng(opt.seed, kGroove3dStream, static_cast<std::uint64_t>(j));
    const double t = sample_theta_m_3d(opt.ndf, opt.alpha, uniform_open(rng));
    const double phi = std::numbers::pi * uniform_open(rng);
    add_groove3d(m, t, phi);
  }
  return m;
}

Trace3dResult trace_groove3d(const Groove& g, const GrooveFrame3d& frame, const Vec3& i, double f,
                             const TraceOptions& opt) {
  const double ia = i.x() * frame.cos_phi_a + i.y() * frame.sin_phi_a;
  const double iu = -i.x() * frame.sin_phi_a + i.y() * frame.cos_phi_a;
  const double in = i.z();
  // |(i.a, i.n)| = sqrt(1 - (i.u)^2) for a unit i; > 0 since i.n > 0.
  const double r = std::sqrt(ia * ia + in * in);
  // The ray travels along -i: in the cross-section along -(i.a, i.n) / r.
  const Vec2 d(-ia / r, -in / r);
  const double xl = g.rim_x(Side::left), xr = g.rim_x(Side::right);
  Trace3dResult out;
  out.trace = trace(g, beam_ray(g, d, xl + f * (xr - xl)), opt);
  if (out.trace.how == Termination::escaped) {
    const Vec2& e = out.trace.exit_dir;
    // o = r (e_x a + e_y n) - (i.u) u.
    const double oa = r * e.x();
    out.o = Vec3(oa * frame.cos_phi_a + iu * frame.sin_phi_a, oa * frame.sin_phi_a - iu * frame.cos_phi_a, r * e.y());
  }
  return out;
}

Microsurface3dTally::Microsurface3dTally(int theta_bins_, int phi_bins_, int max_k_)
    : theta_bins(theta_bins_),
      phi_bins(phi_bins_),
      max_k(max_k_),
      by_k(static_cast<std::size_t>(max_k_) + 2, 0),
      hist(static_cast<std::size_t>(theta_bins_) * static_cast<std::size_t>(phi_bins_), 0),
      hist_by_k((static_cast<std::size_t>(max_k_) + 2) * static_cast<std::size_t>(theta_bins_) *
                    static_cast<std::size_t>(phi_bins_),
                0) {
  assert(theta_bins_ > 0 && phi_bins_ > 0 && phi_bins_ % 2 == 0 && max_k_ >= 0);
}

int Microsurface3dTally::theta_bin_of(double theta_o) const {
  // theta_o is in [0, pi/2) here; the clamp only absorbs rounding of the division.
  return std::clamp(static_cast<int>(std::floor(theta_o / theta_width())), 0, theta_bins - 1);
}

int Microsurface3dTally::phi_bin_of(double phi_o) const {
  // Bin p covers [(p - 1/2) d, (p + 1/2) d), taken modulo 2 pi: phi in (-pi, -pi + d/2) wraps to
  // the bin centred on pi.
  int p = static_cast<int>(std::floor(phi_o / phi_width() + 0.5));
  p %= phi_bins;
  return p < 0 ? p + phi_bins : p;
}

void Microsurface3dTally::add(const Trace3dResult& r) {
  const int k = r.trace.bounces;
  if (!count(r.trace.how, k, r.o.z() > 0.0)) return;
  const int row = row_of(k);
  // acos is exact enough here: bins are far wider than its error near o.z = 1 (~1e-8 rad).
  const int t = theta_bin_of(std::acos(std::min(1.0, r.o.z())));
  const int p = phi_bin_of(std::atan2(r.o.y(), r.o.x()));
  ++by_k[static_cast<std::size_t>(row)];
  ++hist[static_cast<std::size_t>(t) * phi_bins + p];
  ++hist_by_k[index(row, t, p)];
}

void Microsurface3dTally::add_binned(Termination how, int k, bool upward, int t, int p) {
  if (!count(how, k, upward)) return;
  const int row = row_of(k);
  p = p < 0 ? p + phi_bins : (p >= phi_bins ? p - phi_bins : p);
  ++by_k[static_cast<std::size_t>(row)];
  ++hist[static_cast<std::size_t>(t) * phi_bins + p];
  ++hist_by_k[index(row, t, p)];
}

void Microsurface3dTally::add_binned_block(const Termination* how, const int* k, const double* o_z, const double* t,
                                           const double* p, int n) {
  std::int64_t up = 0, sum_k = 0;
  int k_max = 0;
  // The arrays' addresses and sizes in registers (a count written through a pointer could
  // otherwise be any of them).
  std::int64_t* const rows = by_k.data();
  std::int64_t* const cells = hist.data();
  std::int64_t* const row_cells = hist_by_k.data();
  const int nphi = phi_bins, last_row = max_k + 1;
  const std::ptrdiff_t per_row = static_cast<std::ptrdiff_t>(theta_bins) * nphi;
  for (int q = 0; q < n; ++q) {
    const int kq = k[q];
    if (how[q] != Termination::escaped || !(o_z[q] > 0.0)) [[unlikely]] {
      count(how[q], kq, o_z[q] > 0.0);  // a lost ray: counted, not binned
      continue;
    }
    ++up, sum_k += kq, k_max = std::max(k_max, kq);
    const int row = std::min(kq, last_row);  // row_of(kq)
    // p in [-nphi, 2 nphi) wrapped by masks: half the rays of a block come with p < 0 (the chunks
    // centre the bins on phi = 0), so a branch would be mispredicted on every other ray.
    int pb = static_cast<int>(p[q]);
    pb += nphi & -static_cast<int>(pb < 0);
    pb -= nphi & -static_cast<int>(pb >= nphi);
    const std::ptrdiff_t cell = static_cast<std::ptrdiff_t>(static_cast<int>(t[q]) * nphi + pb);
    ++rows[row];
    ++cells[cell];
    ++row_cells[row * per_row + cell];
  }
  add_escaped(up, sum_k, k_max);
}

void Microsurface3dTally::merge(const Microsurface3dTally& o) {
  assert(o.theta_bins == theta_bins && o.phi_bins == phi_bins && o.max_k == max_k);
  merge_fates(o);
  for (std::size_t i = 0; i < by_k.size(); ++i) by_k[i] += o.by_k[i];
  for (std::size_t i = 0; i < hist.size(); ++i) hist[i] += o.hist[i];
  for (std::size_t i = 0; i < hist_by_k.size(); ++i) hist_by_k[i] += o.hist_by_k[i];
}

std::int64_t chunk_count(const Microsurface3dTraceOptions& opt) {
  return (opt.rays + kRaysPerChunk - 1) / kRaysPerChunk;
}

VGROOVE_TARGET_CLONES
void trace_microsurface3d_chunk(const Microsurface3d& surface, const Microsurface3dTraceOptions& opt,
                                std::int64_t chunk, Microsurface3dTally& tally) {
  assert(opt.theta_i >= 0.0 && opt.theta_i < 0.5 * std::numbers::pi && opt.rays >= 0);
  assert(tally.theta_bins == opt.theta_bins && tally.phi_bins == opt.phi_bins && tally.max_k == opt.max_k);
  if (surface.data.size() != surface.grooves.size() || opt.trace.max_bounces < 1) {
    tally.merge(trace_microsurface3d_chunk_reference(surface, opt, chunk));
    return;
  }
  const std::int64_t begin = chunk * kRaysPerChunk;
  const std::int64_t end = std::min(opt.rays, begin + kRaysPerChunk);
  if (begin >= end || surface.grooves.empty()) return;
  Rng rng(opt.seed, kRay3dStream, static_cast<std::uint64_t>(chunk));
  const Vec3 i(-std::sin(opt.theta_i), 0.0, std::cos(opt.theta_i));  // as the reference
  const double g_count = static_cast<double>(surface.grooves.size());
  const int last = static_cast<int>(surface.grooves.size()) - 1;
  const double dphi = 2.0 * std::numbers::pi / opt.phi_bins;
  const AngleEdges theta_edges(0.0, 0.5 * std::numbers::pi / opt.theta_bins, opt.theta_bins);
  const AngleEdges phi_edges(-std::numbers::pi - 0.5 * dphi, dphi, opt.phi_bins + 1);
  SymmetricBlock in;
  SymmetricHits hits;
  double iu_of[kSymmetricBlock], r_of[kSymmetricBlock], ca_of[kSymmetricBlock], sa_of[kSymmetricBlock];
  double ex[kSymmetricBlock], ey[kSymmetricBlock], oz[kSymmetricBlock], t_of[kSymmetricBlock], p_of[kSymmetricBlock];
  double ox_of[kSymmetricBlock], oy_of[kSymmetricBlock], rho_of[kSymmetricBlock], gt_of[kSymmetricBlock],
      gp_of[kSymmetricBlock];
  Termination how[kSymmetricBlock];
  int k_of[kSymmetricBlock];
  double u_of[2 * kSymmetricBlock];
  std::uint64_t bits[2 * kSymmetricBlock];
  for (std::int64_t j0 = begin; j0 < end; j0 += kSymmetricBlock) {
    const int m = static_cast<int>(std::min<std::int64_t>(kSymmetricBlock, end - j0));
    // The stream's next 2m numbers, two per ray in the reference's order.
    rng.next_u64s(bits, 2 * m);
    uniform_open_of(bits, u_of, 2 * m);
    for (int q = 0; q < m; ++q) {
      // Equal macro areas: the groove uniformly; then the landing point uniformly across it.
      const int g = std::min(last, static_cast<int>(u_of[2 * q] * g_count));
      const double f = u_of[2 * q + 1];
      const auto gi = static_cast<std::size_t>(g);
      const SymmetricGrooveData& d = surface.data[gi];
      in.left_x[q] = d.left_x;
      in.right_x[q] = d.right_x;
      in.rim_height[q] = d.rim_height;
      in.x[q] = d.left_x + f * (d.right_x - d.left_x);
      ca_of[q] = surface.frames[gi].cos_phi_a;
      sa_of[q] = surface.frames[gi].sin_phi_a;
    }
    // trace_groove3d's cross-section, operation for operation (a loop apart from the draws and
    // the grooves' scattered reads, which the compiler vectorizes).
    for (int q = 0; q < m; ++q) {
      const double ia = i.x() * ca_of[q] + i.y() * sa_of[q];
      const double iu = -i.x() * sa_of[q] + i.y() * ca_of[q];
      const double in_ = i.z();
      const double r = std::sqrt(ia * ia + in_ * in_);
      in.dx[q] = -ia / r;
      in.dy[q] = -in_ / r;
      iu_of[q] = iu;
      r_of[q] = r;
    }
    block_reflections(in, m, opt.trace.max_bounces, kBlockRounds, hits);
    // Every lane as the block settled it; then the lanes it did not settle, one by one.
    for (int q = 0; q < m; ++q) {
      how[q] = Termination::escaped, k_of[q] = static_cast<int>(hits.k[q]), ex[q] = hits.d1x[q], ey[q] = hits.d1y[q];
    }
    for (int q = 0; q < m; ++q) {
      if (hits.path[q] == 0) [[likely]]
        continue;
      const TraceResult tr = finish_lane(in, hits, q, opt.trace);
      how[q] = tr.how, k_of[q] = tr.bounces, ex[q] = tr.exit_dir.x(), ey[q] = tr.exit_dir.y();
    }
    // Lift and bin, every lane (o = r (e_x a + e_y n) - (i.u) u, as trace_groove3d): the bins
    // from the guesses where they are far from every edge (vectorized: no memory read but the
    // lanes'), the edge tests for the rest (within 2e-7 rad of an edge: about 1 lane in 4 x 10^4
    // at 1 deg bins; and exits past the theta range).
    for (int q = 0; q < m; ++q) {
      const double oa = r_of[q] * ex[q], iu = iu_of[q];
      const double ox = oa * ca_of[q] + iu * sa_of[q], oy = oa * sa_of[q] - iu * ca_of[q];
      oz[q] = r_of[q] * ey[q];
      ox_of[q] = ox, oy_of[q] = oy;
      rho_of[q] = std::sqrt(ox * ox + oy * oy);
      gt_of[q] = atan2_guess(rho_of[q], oz[q]);
      gp_of[q] = atan2_guess(oy, ox);
      t_of[q] = theta_edges.bin_if_far(gt_of[q]);
      p_of[q] = phi_edges.bin_if_far(gp_of[q]);
    }
    for (int q = 0; q < m; ++q) {
      if (t_of[q] < 0.0) [[unlikely]]
        t_of[q] = theta_edges.bin_branchless(oz[q], rho_of[q], gt_of[q]);
      if (p_of[q] < 0.0) [[unlikely]]
        p_of[q] = phi_edges.bin_branchless(ox_of[q], oy_of[q], gp_of[q]);
      p_of[q] -= static_cast<double>(opt.phi_bins / 2);
    }
    tally.add_binned_block(how, k_of, oz, t_of, p_of, m);
  }
}

Microsurface3dTally trace_microsurface3d_chunk(const Microsurface3d& surface, const Microsurface3dTraceOptions& opt,
                                               std::int64_t chunk) {
  Microsurface3dTally tally(opt.theta_bins, opt.phi_bins, opt.max_k);
  trace_microsurface3d_chunk(surface, opt, chunk, tally);
  return tally;
}

Microsurface3dTally trace_microsurface3d_chunk_reference(const Microsurface3d& surface,
                                                         const Microsurface3dTraceOptions& opt, std::int64_t chunk) {
  assert(opt.theta_i >= 0.0 && opt.theta_i < 0.5 * std::numbers::pi && opt.rays >= 0);
  Microsurface3dTally tally(opt.theta_bins, opt.phi_bins, opt.max_k);
  const std::int64_t begin = chunk * kRaysPerChunk;
  const std::int64_t end = std::min(opt.rays, begin + kRaysPerChunk);
  if (begin >= end || surface.grooves.empty()) return tally;
  Rng rng(opt.seed, kRay3dStream, static_cast<std::uint64_t>(chunk));
  // dir(theta_i, pi), with its y written as the exact 0 (sin pi rounds to 1.2e-16).
  const Vec3 i(-std::sin(opt.theta_i), 0.0, std::cos(opt.theta_i));
  const double g_count = static_cast<double>(surface.grooves.size());
  const int last = static_cast<int>(surface.grooves.size()) - 1;
  for (std::int64_t j = begin; j < end; ++j) {
    // Equal macro areas: the groove uniformly; then the landing point uniformly across it.
    const int g = std::min(last, static_cast<int>(uniform_open(rng) * g_count));
    const double f = uniform_open(rng);
    const auto gi = static_cast<std::size_t>(g);
    tally.add(trace_groove3d(surface.grooves[gi], surface.frames[gi], i, f, opt.trace));
  }
  return tally;
}

Microsurface3dTally trace_microsurface3d(const Microsurface3d& surface, const Microsurface3dTraceOptions& opt) {
  Microsurface3dTally total(opt.theta_bins, opt.phi_bins, opt.max_k);
  const std::int64_t n = chunk_count(opt);
  for (std::int64_t c = 0; c < n; ++c) trace_microsurface3d_chunk(surface, opt, c, total);
  return total;
}

}  // namespace vgroove::sim
