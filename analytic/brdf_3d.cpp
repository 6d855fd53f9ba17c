#include "vgroove/analytic/brdf_3d.h"

#include "vgroove/analytic/brdf_3d_terms.h"
#include "vgroove/analytic/kaleidoscope.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::analytic {

Dir3 dir3(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

namespace {

using namespace brdf_terms;

// Eq. (16) for one k, straightforwardly: every j with theta_v in (0, pi], both facets.
double brdf_k_every_j(const Plane& p, double cos_i, double cos_o, int k, NdfKind ndf, double alpha,
                      const FresnelFn& F) {
  double sum = 0.0;
  for (FacetSide side : {FacetSide::left, FacetSide::right}) {
    // k = 1: s = h is the left facet by the choice of a (t_h <= 0); the right facet's solution
    // theta_m = -theta_h exists only as the rounding image of theta_h = 0.
    if (k == 1 && side == FacetSide::right) continue;
    const Ends e = ends_of(p, side, k);
    const double d = e.a - e.b;
    const int j_lo = static_cast<int>(std::ceil((-d - std::numbers::pi) / (2.0 * std::numbers::pi)));
    const int j_hi =
        static_cast<int>(std::floor((k * std::numbers::pi - d - std::numbers::pi) / (2.0 * std::numbers::pi)));
    for (int j = j_lo; j <= j_hi; ++j) {
      const double theta_v = solution(d, j, k);
      if (!(theta_v > 0.0 && theta_v <= std::numbers::pi)) continue;
      sum += solution_term(p, e, side, k, theta_v, cos_i, cos_o, ndf, alpha, F);
    }
  }
  return sum;
}

}  // namespace

namespace brdf_terms {

// Eq. (16) summed over k = k_lo..k_hi in one pass over the solutions that can exist.
// For one facet and one parity of k the ends (a, b) are fixed, and theta_v = X / k with
// X = a - b + (2 j + 1) pi. Eq. (4) allows the k-outcome only for K in {k, k + 1}, i.e.
//   (k - 1) X <= k span < (k + 1) X,   span = pi + 2a   <=>   k |X - span| <= X (up to the ends),
// and theta_v <= pi needs k >= X / pi. With X - span = 2 pi j - (a + b) and |a + b| < pi, only
// j = 0 can meet both (|X - span| <= X / k <= pi), and then k runs over [X / pi, X / |a + b|]:
// a handful of k for most (i, o), all of them only near a = -b (the path equal to its reverse).
// So the pass visits the solutions that exist plus O(1) others, whatever max_k is; the j = +-1
// and one k beyond each end are visited too, against rounding (outcome_possible decides, as in
// brdf_k_every_j, so both sum the same terms). Each solution's term is computed on its own
// (solution_term): the previous evaluation, kept as vgroove_brdf_per_solution_reference beside
// the batched pass (brdf_3d_batch.cpp) that vgroove_brdf runs.
double brdf_per_solution(const Plane& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf, double alpha,
                         const FresnelFn& F) {
  double sum = 0.0;
  for (FacetSide side : {FacetSide::left, FacetSide::right}) {
    for (int k_first : {1, 2}) {
      const Ends e = ends_of(p, side, k_first);  // depends on the parity of k only
      const double d = e.a - e.b;
      const double span = std::numbers::pi + 2.0 * e.a;
      for (int j = -1; j <= 1; ++j) {
        const double X = d + (2.0 * j + 1.0) * std::numbers::pi;
        if (!(X > 0.0)) continue;
        const double dev = std::abs(X - span);
        // In double until clamped: X / dev may exceed any int.
        const double k_top = dev > 0.0 ? std::floor(X / dev) + 1.0 : static_cast<double>(k_hi);
        const int k_end = static_cast<int>(std::min(static_cast<double>(k_hi), k_top));
        int k = std::max(k_lo, static_cast<int>(std::ceil(X / std::numbers::pi)) - 1);
        if (k < 1) k = 1;
        if ((k - k_first) % 2 != 0) ++k;  // the parity of this pass
        for (; k <= k_end; k += 2) {
          // k = 1: s = h is the left facet (as in brdf_k_every_j).
          if (k == 1 && side == FacetSide::right) continue;
          const double theta_v = solution(d, j, k);
          if (!(theta_v > 0.0 && theta_v <= std::numbers::pi)) continue;
          sum += solution_term(p, e, side, k, theta_v, cos_i, cos_o, ndf, alpha, F);
        }
      }
    }
  }
  return sum;
}

}  // namespace brdf_terms

namespace {

using namespace brdf_terms;

double ct_at(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const FresnelFn& F) {
  const double cos_i = i.z, cos_o = o.z;
  if (!(cos_i > 0.0 && cos_o > 0.0)) return 0.0;
  Dir3 h{i.x + o.x, i.y + o.y, i.z + o.z};
  const double len = std::sqrt(dot(h, h));
  h = {h.x / len, h.y / len, h.z / len};
  const double theta_h = std::atan2(std::hypot(h.x, h.y), h.z);
  const double ih = dot(i, h), oh = dot(o, h);
  // Lee et al. 2018, Eq. (3) with the V-cavity G1 of Eq. (2).
  const double G = std::min(G1_vcavity(ih, cos_i, h.z), G1_vcavity(oh, cos_o, h.z));
  const double Fr = F ? F(ih) : 1.0;
  // Lee et al. 2018, Eq. (1).
  return Fr * D(ndf, theta_h, alpha) * G / (4.0 * cos_i * cos_o);
}

enum class Pass { batched, per_solution, every_j };

double brdf_range(const Dir3& i, const Dir3& o, int k_lo, int k_hi, NdfKind ndf, double alpha, const FresnelFn& F,
                  Pass pass = Pass::batched) {
  const double cos_i = i.z, cos_o = o.z;
  // Below or at the horizon: no flux (a set of measure zero; see the header).
  if (!(cos_i > 0.0 && cos_o > 0.0)) return 0.0;
  Plane p;
  if (!make_plane(i, o, p)) {
    // h = n: the limit of Eq. (16) is Cook-Torrance with G = 1 for k = 1 (sin theta_s / sin theta_h
    // -> 1) and diverges like 1 / sin(theta_h) for k >= 2.
    if (k_hi >= 2) return std::numeric_limits<double>::infinity();
    return k_lo <= 1 ? ct_at(i, o, ndf, alpha, F) : 0.0;
  }
  if (pass == Pass::batched) return brdf_batched(p, cos_i, cos_o, std::max(1, k_lo), k_hi, ndf, alpha, F);
  if (pass == Pass::per_solution) return brdf_per_solution(p, cos_i, cos_o, std::max(1, k_lo), k_hi, ndf, alpha, F);
  double sum = 0.0;
  for (int k = std::max(1, k_lo); k <= k_hi; ++k) sum += brdf_k_every_j(p, cos_i, cos_o, k, ndf, alpha, F);
  return sum;
}

}  // namespace

double beam_width_k(double t_i, double t_o, double theta_v, int k, FacetSide first) {
  Plane p;
  p.t_i = t_i;
  p.t_o = t_o;
  p.sin_ti = std::sin(t_i);
  p.cos_ti = std::cos(t_i);
  p.sin_to = std::sin(t_o);
  p.cos_to = std::cos(t_o);
  p.cos_half_sum = std::cos(0.5 * (t_i + t_o));
  p.cos_half_diff = std::cos(0.5 * (t_i - t_o));
  const Ends e = ends_of(p, first, k);
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

double groove_cdf(NdfKind ndf, double alpha, double theta_m) {
  if (!(theta_m > 0.0)) return 0.0;
  if (!(theta_m < 0.5 * std::numbers::pi)) return 1.0;
  const double t = std::tan(theta_m), t2 = t * t;
  switch (ndf) {
    case NdfKind::ggx:
      return t2 / (alpha * alpha + t2);
    case NdfKind::beckmann:
      return -std::expm1(-t2 / (alpha * alpha));
    case NdfKind::phong: {
      // 1 - cos^(p+2), p + 2 = 2 / alpha^2; log cos = log1p(-2 sin^2(theta/2)) keeps small angles exact.
      const double s = std::sin(0.5 * theta_m);
      return -std::expm1((phong_exponent(alpha) + 2.0) * std::log1p(-2.0 * s * s));
    }
  }
  return 0.0;
}

namespace {
// cos and sin of atan(t), t >= 0, without overflow.
void cos_sin_of_atan(double t, double& c, double& s) {
  if (t <= 1.0) {
    c = 1.0 / std::sqrt(1.0 + t * t);
    s = t * c;
  } else {
    const double r = 1.0 / t;
    s = 1.0 / std::sqrt(1.0 + r * r);
    c = r * s;
  }
}
}  // namespace

void groove_cdf_inverse_cos_sin(NdfKind ndf, double alpha, double u, double& cos_m, double& sin_m) {
  if (!(u > 0.0)) {
    cos_m = 1.0, sin_m = 0.0;
  } else if (!(u < 1.0)) {
    cos_m = 0.0, sin_m = 1.0;
  } else if (ndf == NdfKind::phong) {
    const double one_minus_cos = -std::expm1(std::log1p(-u) / (phong_exponent(alpha) + 2.0));
    cos_m = 1.0 - one_minus_cos;
    sin_m = std::sqrt(one_minus_cos * (2.0 - one_minus_cos));
  } else {
    cos_sin_of_atan(alpha * std::sqrt(ndf == NdfKind::ggx ? u / (1.0 - u) : -std::log1p(-u)), cos_m, sin_m);
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
  switch (ndf) {
    case NdfKind::ggx:
    case NdfKind::beckmann: {
      const double t = alpha * std::sqrt(ndf == NdfKind::ggx ? u / (1.0 - u) : -std::log1p(-u));
      cos_sin_of_atan(t, cos_m, sin_m);
      return std::atan(t);
    }
    case NdfKind::phong: {
      const double one_minus_cos = -std::expm1(std::log1p(-u) / (phong_exponent(alpha) + 2.0));
      cos_m = 1.0 - one_minus_cos;
      sin_m = std::sqrt(one_minus_cos * (2.0 - one_minus_cos));
      return 2.0 * std::asin(std::sqrt(0.5 * one_minus_cos));
    }
  }
  cos_m = 1.0, sin_m = 0.0;
  return 0.0;
}

double groove_cdf_inverse(NdfKind ndf, double alpha, double u) {
  if (!(u > 0.0)) return 0.0;
  if (!(u < 1.0)) return 0.5 * std::numbers::pi;
  switch (ndf) {
    case NdfKind::ggx:
      return std::atan(alpha * std::sqrt(u / (1.0 - u)));
    case NdfKind::beckmann:
      return std::atan(alpha * std::sqrt(-std::log1p(-u)));
    case NdfKind::phong: {
      const double one_minus_cos = -std::expm1(std::log1p(-u) / (phong_exponent(alpha) + 2.0));
      return 2.0 * std::asin(std::sqrt(0.5 * one_minus_cos));
    }
  }
  return 0.0;
}

}  // namespace vgroove::analytic
