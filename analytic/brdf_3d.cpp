#include "vgroove/analytic/brdf_3d.h"

#include "vgroove/analytic/detail/atan_pair.h"
#include "vgroove/analytic/detail/brdf_3d_passes.h"
#include "vgroove/analytic/detail/ndf_visit.h"
#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/kaleidoscope_solutions.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <type_traits>

namespace vgroove::analytic {

Dir3 dir3(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

namespace {

double dot(const Dir3& a, const Dir3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// Directions that run nearly along the groove: i.u = -o.u close to +-1, the projections' length
// c small (then both directions graze the horizon: c >= i.n, o.n). There i.a = (i_xy . H_xy) / |H_xy|
// and o.a, products of numbers of order 1 whose sum is of order c, carry ~1e-16 absolute from
// the inputs alone (a unit vector in double is unit to ~1e-16), so c_i and c_o, equal for unit
// vectors, differ by ~1e-16 / c relative, and the projected angles t_i, t_o disagree with h by
// as much: below c ~ 1e-7 the k = 1 term would be 100 times Cook-Torrance near the mirror direction.
// Below kAlongTheGroove the two projections are formed as unit vectors have them:
// i.a + o.a = |H_xy| and i.a - o.a = (|i_xy|^2 - |o_xy|^2) / |H_xy| = (o.z^2 - i.z^2) / |H_xy|
// (|d_xy|^2 = 1 - d.z^2), both accurate to a few ulp of c, and i.h + o.h = |H|. Above it the
// dot products keep their bits (their error, 1e-16 / c^2 relative, is below 1e-12 there).
constexpr double kAlongTheGroove = 1e-2;

// i nearly opposite to o (|i + o| small: both near the horizon, azimuths opposite). For unit
// vectors i.h = o.h = |i + o| / 2; from the inputs' dot products each carries the inputs' 1e-16 as
// 1e-16 / |i + o|^2 relative, and i.h - o.h = (|i|^2 - |o|^2) / |i + o| is all rounding (k = 1 was
// 1.3e-8 off Cook-Torrance at |i + o| = 8e-5). Below kNearlyOpposite both take |i + o| / 2.
constexpr double kNearlyOpposite = 1e-2;

bool along_the_groove(double c_i, double c_o) { return std::max(c_i, c_o) < kAlongTheGroove; }

// i.a and o.a as unit vectors have them (above), a = H_xy / |H_xy|; swapped bitwise with (i, o).
void projections_along_the_groove(const Dir3& i, const Dir3& o, double& ia, double& oa) {
  const double r = std::hypot(i.x + o.x, i.y + o.y);
  const double q = (o.z - i.z) * (o.z + i.z) / r;
  ia = 0.5 * (r + q);
  oa = 0.5 * (r - q);
}

}  // namespace

// h = (i + o)/|i + o|, a = the horizontal direction of h, so that t_h = -theta_h <= 0 and the
// facet with normal h is the "left" one (2D angle -theta_m). Every field is computed symmetrically
// in (i, o) or swaps with them bitwise (t_i <-> t_o, ...), so that the evaluation below is
// reciprocal to the last bit (see beam_width). The library's hypot and atan2, and each field from
// the normalized h: the reference passes' frame (groove_frame_fast below rounds differently).
bool groove_frame(const Dir3& i, const Dir3& o, GrooveFrame& p) {
  Dir3 h{i.x + o.x, i.y + o.y, i.z + o.z};
  const double len = std::sqrt(dot(h, h));
  h = {h.x / len, h.y / len, h.z / len};
  const double rho = std::hypot(h.x, h.y);
  // The averages make c and i.h bitwise symmetric in (i, o) (they are equal mathematically).
  p.cos_d = len < kNearlyOpposite ? 0.5 * len : 0.5 * (dot(i, h) + dot(o, h));
  p.sin_h = rho;
  // h = n: no cross-section; the plane (x, z) stands in for it (a = x).
  const bool through_h = rho > 0.0;
  const Dir3 a = through_h ? Dir3{h.x / rho, h.y / rho, 0.0} : Dir3{1.0, 0.0, 0.0};
  p.ax = a.x;
  p.ay = a.y;
  double ia = dot(i, a), oa = dot(o, a);
  double c_i = std::sqrt(ia * ia + i.z * i.z), c_o = std::sqrt(oa * oa + o.z * o.z);
  if (along_the_groove(c_i, c_o)) {
    projections_along_the_groove(i, o, ia, oa);
    c_i = std::sqrt(ia * ia + i.z * i.z);
    c_o = std::sqrt(oa * oa + o.z * o.z);
    p.cos_d = 0.5 * len;
  }
  p.x.t_i = std::atan2(-ia, i.z);
  p.x.t_o = std::atan2(-oa, o.z);
  p.c = 0.5 * (c_i + c_o);
  p.x.sin_ti = -ia / c_i;
  p.x.cos_ti = i.z / c_i;
  p.x.sin_to = -oa / c_o;
  p.x.cos_to = o.z / c_o;
  // cos((t_i + t_o)/2) = cos(t_h) = h.n and cos((t_i - t_o)/2) = (i.h)/c (h bisects i_perp and o_perp).
  p.x.cos_half_sum = h.z;
  p.x.sin_half_sum = rho;
  p.x.single_from_h = h.z < kGrazingHalfVector || len < kNearlyOpposite;
  p.x.cos_half_diff = p.cos_d / p.c;
  return through_h;
}

namespace brdf_passes {

// groove_frame's fields for the batched GGX and Beckmann passes, rounded differently: from
// H = i + o = 2 (i.h) h without normalizing it first (a = H_xy / |H_xy|, i.a = (i_x H_x + i_y H_y) / |H_xy|,
// i.h = |H| / 2), the two angles from atan2_pair (at once, within 3 ulp), the quotients as
// products by reciprocals. groove_frame costs about one Cook-Torrance evaluation, mostly in its
// chain hypot -> a -> i.a -> atan2 (what each frame costs: docs/performance.md, "The BRDF's cost
// against Cook-Torrance"). Symmetric in (i, o) as groove_frame is.
// Only where both are well conditioned; elsewhere groove_frame, bit for bit:
//  - h within 1e-100 of n: sqrt(H_x^2 + H_y^2) would lose the precision hypot keeps;
//  - i.z + o.z <= 1e-2: i.h = (i.H + o.H) / (2 |H|) in the library's frame loses 2 eps / |H|
//    relative to cancellation as i -> -o, and the outcome tests (Eq. 4) decide at the horizon
//    on the last bits of the angles.
// Phong takes groove_frame (brdf_range): its D multiplies the angles' last bits by up to p
// (~2 10^4 at alpha = 0.01), beyond the 1e-12 the passes agree to. Beckmann's (by
// 2 tan^2 theta_m / alpha^2 / (sin cos)) is bounded pair by pair: the batched pass takes this
// frame where the bound holds and groove_frame elsewhere (brdf_3d_batch.cpp).
bool groove_frame_fast(const Dir3& i, const Dir3& o, GrooveFrame& p) {
  const Dir3 H{i.x + o.x, i.y + o.y, i.z + o.z};
  const double rho2 = H.x * H.x + H.y * H.y;
  if (!(rho2 > 1e-200 && H.z > 1e-2)) return groove_frame(i, o, p);
  const double len = std::sqrt(dot(H, H)), inv_len = 1.0 / len;
  const double rho = std::sqrt(rho2), inv_rho = 1.0 / rho;
  p.sin_h = rho * inv_len;
  p.cos_d = 0.5 * len;
  p.ax = H.x * inv_rho;
  p.ay = H.y * inv_rho;
  const Double2 a_dot = Double2{i.x * H.x + i.y * H.y, o.x * H.x + o.y * H.y} * inv_rho;  // i.a, o.a
  const Double2 z = {i.z, o.z};
  const Double2 t = atan2_pair(-a_dot, z);
  p.x.t_i = t[0];
  p.x.t_o = t[1];
  const Double2 c2 = a_dot * a_dot + z * z;
  const Double2 c = {std::sqrt(c2[0]), std::sqrt(c2[1])};  // c_i, c_o
  const Double2 inv_c = 1.0 / c;
  p.c = 0.5 * (c[0] + c[1]);
  const Double2 sin_t = -a_dot * inv_c, cos_t = z * inv_c;
  p.x.sin_ti = sin_t[0];
  p.x.cos_ti = cos_t[0];
  p.x.sin_to = sin_t[1];
  p.x.cos_to = cos_t[1];
  p.x.cos_half_sum = H.z * inv_len;
  p.x.sin_half_sum = p.sin_h;
  p.x.single_from_h = false;  // h.z > 5e-3 and |H| > 1e-2 here (above)
  p.x.cos_half_diff = p.cos_d / p.c;
  return true;
}

}  // namespace brdf_passes

namespace {

// The term of Eq. (16) of one solution of Eq. (5).
double solution_term(const GrooveFrame& p, const Solution& q, double cos_i, double cos_o, NdfKind ndf, double alpha,
                     const FresnelFn& F) {
  const double theta_m = 0.5 * (std::numbers::pi - q.theta_v);
  const double i_dot_s = p.c * q.W;  // |i.s| G = c G f_a: f_a is the 2D cosine of incidence
  // k = 1: s = h, so sin(theta_s)/sin(theta_h) = 1 exactly (Eq. 25); computing it would
  // divide two rounding errors next to the mirror direction.
  const double ratio = q.k == 1 ? 1.0 : q.C / (q.k * p.sin_h);
  // Lee et al. 2018, Eq. (16) with the Jacobian of Eq. (13).
  return ratio * fresnel_along_path(F, p.x.t_i, theta_m, q.first, q.k, p.c) * i_dot_s * D_cs(ndf, q.S, q.C, alpha) /
         (4.0 * p.cos_d * (cos_i * cos_o));
}

double ct_at(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const FresnelFn& F) {
  const double cos_i = i.z, cos_o = o.z;
  if (!(cos_i > 0.0 && cos_o > 0.0)) return 0.0;
  Dir3 h{i.x + o.x, i.y + o.y, i.z + o.z};
  const double len = std::sqrt(dot(h, h));
  h = {h.x / len, h.y / len, h.z / len};
  double ih = dot(i, h), oh = dot(o, h);
  if (len < kNearlyOpposite) ih = oh = 0.5 * len;  // (groove_frame)
  // Directions along a groove (i.u close to +-1): i.h and o.h from the projections unit vectors
  // have, as groove_frame takes them (i.h = (i.a) sin(theta_h) + (i.n) cos(theta_h)).
  if (const double rho = std::hypot(h.x, h.y); rho > 0.0) {
    const double ax = h.x / rho, ay = h.y / rho;
    double ia = i.x * ax + i.y * ay, oa = o.x * ax + o.y * ay;
    if (along_the_groove(std::sqrt(ia * ia + i.z * i.z), std::sqrt(oa * oa + o.z * o.z))) {
      projections_along_the_groove(i, o, ia, oa);
      ih = ia * rho + i.z * h.z;
      oh = oa * rho + o.z * h.z;
    }
  }
  // Lee et al. 2018, Eq. (3) with the V-cavity G1 of Eq. (2).
  const double G = std::min(G1_vcavity(ih, cos_i, h.z), G1_vcavity(oh, cos_o, h.z));
  const double Fr = F ? F(ih) : 1.0;
  // Lee et al. 2018, Eq. (1). D from cos(theta_h) = h.z and sin(theta_h) themselves: the angle
  // theta_h would round cos(theta_h) to ~1e-16 absolute, all of it when h grazes the horizon.
  return Fr * D_cs(ndf, h.z, std::hypot(h.x, h.y), alpha) * G / (4.0 * cos_i * cos_o);
}

// Which pass sums the solutions: the batched one (brdf_3d_batch.cpp, vgroove_brdf's), each
// solution on its own (for_each_solution), or every j of every k (for_each_solution_every_j).
enum class Pass { batched, per_solution, every_j };

// Where the batched pass is not run (brdf_3d_batch.cpp), but the per-solution pass:
//  - a projected cosine cos(t_i) or cos(t_o) below 1e-5: the batched pass chooses the width's ends
//    by comparing offsets of order 1 that carry ~1e-15, while the widths of a direction this close
//    to the cross-section's horizon are below 2 cos(t) (its lit share): from 1e-6 down its choice
//    went wrong (1.6e-4 relative at 1e-6, every value at 1e-7; Brdf3d.GrazingPairs*). The
//    per-solution pass decides them from the widths (beam_width).
//  - h within 0.29 deg of the cross-section's horizon (cos(t_h) < kGrazingHalfVector), or i nearly
//    opposite to o (|i + o| < kNearlyOpposite): the per-solution pass's k = 1 term takes S and C
//    from h (CrossSection::single_from_h), the batched one from theta_v, whose rounding there was
//    1e-8 off Cook-Torrance at h.z ~ 1e-4, and 1.8e-9 at |i + o| = 4e-6, where the groove's azimuth
//    (from the horizontal part of i + o, 7.6e-10) moved t_i by 5e-10.
constexpr double kBatchedMinProjectedCos = 1e-5;

bool batched_pass_holds(const GrooveFrame& p) {
  return std::min(p.x.cos_ti, p.x.cos_to) >= kBatchedMinProjectedCos && !p.x.single_from_h;
}

double brdf_range(const Dir3& i, const Dir3& o, int k_lo, int k_hi, NdfKind ndf, double alpha, const FresnelFn& F,
                  Pass pass = Pass::batched) {
  const double cos_i = i.z, cos_o = o.z;
  // Below or at the horizon: no flux (a set of measure zero; see the header).
  if (!(cos_i > 0.0 && cos_o > 0.0)) return 0.0;
  GrooveFrame p;
  // The frame's projected cosines are at least the 3D ones (cos t = n.d / c, c <= 1) and h.z is at
  // least (i.z + o.z) / 2 (h.z = (i.z + o.z) / |i + o|): a pair above both bounds needs no frame here.
  if (pass == Pass::batched &&
      (std::min(cos_i, cos_o) < kBatchedMinProjectedCos || cos_i + cos_o < 2.0 * kGrazingHalfVector)) {
    if (groove_frame(i, o, p) && !batched_pass_holds(p))
      return brdf_passes::brdf_per_solution(p, cos_i, cos_o, std::max(1, k_lo), k_hi, ndf, alpha, F);
  }
  // The batched Beckmann pass first in groove_frame_fast with every term vectorized: it declines
  // (NaN) a pair whose terms' weighted amplification exceeds its bound (brdf_3d_batch.cpp), and
  // is not tried where the k = 1 term alone exceeds it (y = tan theta_h / (alpha^2 cos^2 theta_h)
  // = sin_h / (alpha^2 cos^3 theta_h) > 64: the lobe's far tail, where it mostly would decline).
  if (pass == Pass::batched && ndf == NdfKind::beckmann && !F && brdf_passes::groove_frame_fast(i, o, p)) {
    const double ch = p.x.cos_half_sum;
    if (p.sin_h <= brdf_passes::kBeckmannMeanAmplification * (alpha * alpha) * (ch * ch * ch)) {
      const double v = brdf_passes::brdf_batched(p, cos_i, cos_o, std::max(1, k_lo), k_hi, ndf, alpha, F,
                                                 brdf_passes::BeckmannTails::vector);
      if (!std::isnan(v)) return v;
    }
  }
  // The batched GGX pass in groove_frame_fast (which says where and why), the others in groove_frame.
  if (!(pass == Pass::batched && ndf == NdfKind::ggx ? brdf_passes::groove_frame_fast(i, o, p)
                                                     : groove_frame(i, o, p))) {
    // h = n: the limit of Eq. (16) is Cook-Torrance with G = 1 for k = 1 (sin theta_s / sin theta_h
    // -> 1) and diverges like 1 / sin(theta_h) for k >= 2.
    if (k_hi >= 2) return std::numeric_limits<double>::infinity();
    return k_lo <= 1 ? ct_at(i, o, ndf, alpha, F) : 0.0;
  }
  if (pass == Pass::batched) return brdf_passes::brdf_batched(p, cos_i, cos_o, std::max(1, k_lo), k_hi, ndf, alpha, F);
  if (pass == Pass::per_solution) {
    return brdf_passes::brdf_per_solution(p, cos_i, cos_o, std::max(1, k_lo), k_hi, ndf, alpha, F);
  }
  double sum = 0.0;
  auto add = [&](const Solution& q) { sum += solution_term(p, q, cos_i, cos_o, ndf, alpha, F); };
  for (int k = std::max(1, k_lo); k <= k_hi; ++k) for_each_solution_every_j(p.x, k, add);
  return sum;
}

}  // namespace

// One pass over the solutions Eq. (4) allows (kaleidoscope_solutions.h), whatever k_hi is, each
// solution's term on its own: the evaluation before the batched pass, kept beside it as
// vgroove_brdf_per_solution_reference and run by the batched pass where both directions graze.
double brdf_passes::brdf_per_solution(const GrooveFrame& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf,
                                      double alpha, const FresnelFn& F) {
  double sum = 0.0;
  for_each_solution(p.x, k_lo, k_hi,
                    [&](const Solution& q) { sum += solution_term(p, q, cos_i, cos_o, ndf, alpha, F); });
  return sum;
}

double fresnel_along_path(const FresnelFn& F, double t_i, double theta_m, FacetSide first, int k, double c) {
  if (!F) return 1.0;
  double dx = std::sin(t_i), dy = -std::cos(t_i);  // travel direction (into the groove)
  const double sm = std::sin(theta_m), cm = std::cos(theta_m);
  bool left = first == FacetSide::left;
  double prod = 1.0;
  for (int j = 0; j < k; ++j) {
    // Left facet normal at 2D angle -theta_m: (sin, cos); right at +theta_m: (-sin, cos).
    const double nx = left ? sm : -sm, ny = cm;
    const double dn = dx * nx + dy * ny;
    prod *= F(c * std::abs(dn));
    dx -= 2.0 * dn * nx;
    dy -= 2.0 * dn * ny;
    left = !left;
  }
  return prod;
}

double beam_width_k(double t_i, double t_o, double theta_v, int k, FacetSide first) {
  const Ends e = ends_of(cross_section(t_i, t_o), first, k);
  if (!outcome_possible(e, theta_v, k)) return 0.0;
  return beam_width(e, theta_v, std::sin(0.5 * theta_v), std::cos(0.5 * theta_v), k);
}

double vgroove_brdf_k_reference(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha) {
  return brdf_range(i, o, k, k, ndf, alpha, FresnelFn{}, Pass::every_j);
}
double vgroove_brdf_reference(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k) {
  return brdf_range(i, o, 1, max_k, ndf, alpha, FresnelFn{}, Pass::every_j);
}
double vgroove_brdf_per_solution_reference(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k,
                                           const FresnelFn& F) {
  return brdf_range(i, o, 1, max_k, ndf, alpha, F, Pass::per_solution);
}
double vgroove_brdf_k_per_solution_reference(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha) {
  return brdf_range(i, o, k, k, ndf, alpha, FresnelFn{}, Pass::per_solution);
}

double vgroove_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha) {
  return brdf_range(i, o, k, k, ndf, alpha, FresnelFn{});
}
double vgroove_brdf_k(const Dir3& i, const Dir3& o, int k, NdfKind ndf, double alpha, const FresnelFn& F) {
  return brdf_range(i, o, k, k, ndf, alpha, F);
}
double vgroove_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k) {
  return brdf_range(i, o, 1, max_k, ndf, alpha, FresnelFn{});
}
double vgroove_brdf(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k, const FresnelFn& F) {
  return brdf_range(i, o, 1, max_k, ndf, alpha, F);
}
double cook_torrance(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha) {
  return ct_at(i, o, ndf, alpha, FresnelFn{});
}
double cook_torrance(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const FresnelFn& F) {
  return ct_at(i, o, ndf, alpha, F);
}

// The CDF and its inverse are each NDF's own (ndf_ggx.h, ndf_beckmann.h, ndf_phong.h); the inverse
// gives tan theta_m or 1 - cos theta_m, turned here into the angle or its cosine and sine.
double groove_cdf(NdfKind ndf, double alpha, double theta_m) {
  if (!(theta_m > 0.0)) return 0.0;
  if (!(theta_m < 0.5 * std::numbers::pi)) return 1.0;
  return visit_ndf(ndf, alpha, [&](const auto& n) { return n.cdf(theta_m); });
}

namespace {

// The NDF's inverse CDF at u in (0, 1) (log(1 - u) by log1p).
template <typename Ndf>
double inverse_cdf(const Ndf& n, double u) {
  return n.inverse_cdf(u, [u] { return std::log1p(-u); });
}

}  // namespace

void groove_cdf_inverse_cos_sin(NdfKind ndf, double alpha, double u, double& cos_m, double& sin_m) {
  if (!(u > 0.0)) {
    cos_m = 1.0, sin_m = 0.0;
  } else if (!(u < 1.0)) {
    cos_m = 0.0, sin_m = 1.0;
  } else {
    visit_ndf(ndf, alpha, [&](const auto& n) {
      if constexpr (std::remove_cvref_t<decltype(n)>::kInverseGivesTan) {
        ndf_math::cos_sin_of_atan(inverse_cdf(n, u), cos_m, sin_m);
      } else {
        ndf_math::cos_sin_of_one_minus_cos(inverse_cdf(n, u), cos_m, sin_m);
      }
    });
  }
}

double groove_cdf_inverse(NdfKind ndf, double alpha, double u, double& cos_m, double& sin_m) {
  if (!(u > 0.0)) {
    cos_m = 1.0, sin_m = 0.0;
    return 0.0;
  }
  if (!(u < 1.0)) {
    cos_m = 0.0, sin_m = 1.0;
    return 0.5 * std::numbers::pi;
  }
  return visit_ndf(ndf, alpha, [&](const auto& n) {
    const double v = inverse_cdf(n, u);
    if constexpr (std::remove_cvref_t<decltype(n)>::kInverseGivesTan) {
      ndf_math::cos_sin_of_atan(v, cos_m, sin_m);
      return std::atan(v);
    } else {
      ndf_math::cos_sin_of_one_minus_cos(v, cos_m, sin_m);
      return 2.0 * std::asin(std::sqrt(0.5 * v));
    }
  });
}

double groove_cdf_inverse(NdfKind ndf, double alpha, double u) {
  if (!(u > 0.0)) return 0.0;
  if (!(u < 1.0)) return 0.5 * std::numbers::pi;
  return visit_ndf(ndf, alpha, [&](const auto& n) {
    const double v = inverse_cdf(n, u);
    if constexpr (std::remove_cvref_t<decltype(n)>::kInverseGivesTan) {
      return std::atan(v);
    } else {
      return 2.0 * std::asin(std::sqrt(0.5 * v));
    }
  });
}

}  // namespace vgroove::analytic
