#include "vgroove/analytic/vndf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

namespace {

double dot(const Dir3& a, const Dir3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// v / |v|, or n when v vanishes (a cap point opposite to i, reached only by rounding).
Dir3 normalized_or_n(double x, double y, double z) {
  const double len = std::sqrt(x * x + y * y + z * z);
  if (!(len > 0.0) || !std::isfinite(len)) return {0.0, 0.0, 1.0};
  return {x / len, y / len, z / len};
}

double theta_of(const Dir3& s) { return std::atan2(std::hypot(s.x, s.y), s.z); }

// The incident direction in the unit-roughness space (Tokuyoshi and Eto 2024, Sec. 2.2, step 1).
Dir3 stretched(double alpha, const Dir3& i) { return normalized_or_n(alpha * i.x, alpha * i.y, i.z); }

// A point of the cap z in (lower, 1] around n, uniform (z = lower u1 + (1 - u1)), and the facet it
// defines: the half vector of i and the point, unstretched (Sec. 2.2, steps 2-4).
Dir3 cap_facet(double alpha, const Dir3& i, double lower, double u0, double u1) {
  const Dir3 wi = stretched(alpha, i);
  const double phi = 2.0 * std::numbers::pi * u0;
  const double z = lower * u1 + (1.0 - u1);
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double mx = wi.x + sin_t * std::cos(phi), my = wi.y + sin_t * std::sin(phi), mz = wi.z + z;
  return normalized_or_n(alpha * mx, alpha * my, mz);
}

// The reflection of the stretched i about the stretched m: the cap point that m came from.
double cap_z_of(double alpha, const Dir3& i, const Dir3& m) {
  const Dir3 wi = stretched(alpha, i);
  const Dir3 wm = normalized_or_n(m.x / alpha, m.y / alpha, m.z);
  return 2.0 * dot(wi, wm) * wm.z - wi.z;
}

// Tokuyoshi and Eto 2024, Eq. (5)-(6) for isotropic roughness: k of the lower bound -k i_z.
double bounded_k(double alpha, const Dir3& i) {
  const double ixy = std::hypot(i.x, i.y);
  const double s = 1.0 + (alpha < 1.0 ? ixy : (alpha > 1.0 ? -ixy : 0.0));
  const double a2 = alpha * alpha, s2 = s * s;
  const double den = s2 + a2 * i.z * i.z;
  return den > 0.0 ? (1.0 - a2) * s2 / den : 0.0;
}

}  // namespace

Dir3 sample_projected_ndf(NdfKind ndf, double alpha, double u0, double u1) {
  // Lee et al. 2018, Sec. 6: p(s) = |s.n| D(s); its theta-marginal 2 pi D cos sin has the
  // closed-form CDF of brdf_3d.h.
  return dir3(groove_cdf_inverse(ndf, alpha, u0), 2.0 * std::numbers::pi * u1);
}

double projected_ndf_pdf(NdfKind ndf, double alpha, const Dir3& s) {
  if (!(s.z > 0.0)) return 0.0;
  return s.z * D(ndf, theta_of(s), alpha);
}

Dir3 sample_vcavity_vndf(NdfKind ndf, double alpha, const Dir3& i, double u0, double u1, double u2) {
  // Heitz and d'Eon 2014 (V-cavity): s from |s.n| D(s), then s or its mirror image s' by their
  // projected areas towards i. Per groove the light splits between its facets as their lit
  // widths, <i.s> G1(i, s) = min(<i.s>, 2 <s.n> <i.n>), which is this choice: when both facets
  // face i nothing is shadowed and the widths are <i.s>, <i.s'>; when s' faces away the whole
  // opening lights s.
  const Dir3 s = sample_projected_ndf(ndf, alpha, u0, u1);
  const Dir3 sm{-s.x, -s.y, s.z};
  const double a = std::max(0.0, dot(i, s)), b = std::max(0.0, dot(i, sm));
  if (!(a + b > 0.0)) return {0.0, 0.0, 1.0};
  return u2 * (a + b) < b ? sm : s;
}

double vcavity_vndf_pdf(NdfKind ndf, double alpha, const Dir3& i, const Dir3& s) {
  const double is = dot(i, s);
  if (!(is > 0.0 && s.z > 0.0 && i.z > 0.0)) return 0.0;
  // Heitz and d'Eon 2014: D(s) <i.s> G1(i, s) / <i.n>, G1 the V-cavity's (Lee et al. 2018, Eq. 2):
  // <i.s> G1 = min(<i.s>, 2 <s.n> <i.n>).
  return D(ndf, theta_of(s), alpha) * std::min(is, 2.0 * s.z * i.z) / i.z;
}

double ggx_smith_g1(double alpha, const Dir3& i) {
  // Heitz 2014, Eq. (10) and Sec. 3.2: G1 = 2 i_z / (i_z + sqrt(alpha^2 |i_xy|^2 + i_z^2)).
  if (!(i.z > 0.0)) return 0.0;
  return 2.0 * i.z / (i.z + std::sqrt(alpha * alpha * (i.x * i.x + i.y * i.y) + i.z * i.z));
}

Dir3 sample_ggx_vndf(double alpha, const Dir3& i, double u0, double u1) {
  // Dupuy and Benyoub 2023 (Tokuyoshi and Eto 2024, Sec. 2.2): the cap z in (-wi_z, 1].
  return cap_facet(alpha, i, -stretched(alpha, i).z, u0, u1);
}

double ggx_vndf_norm(double alpha, const Dir3& i) {
  return i.z + std::sqrt(alpha * alpha * (i.x * i.x + i.y * i.y) + i.z * i.z);
}

double ggx_bounded_vndf_norm(double alpha, const Dir3& i) {
  return bounded_k(alpha, i) * i.z + std::sqrt(alpha * alpha * (i.x * i.x + i.y * i.y) + i.z * i.z);
}

bool ggx_bounded_vndf_covers(double alpha, const Dir3& i, const Dir3& m) {
  return cap_z_of(alpha, i, m) > ggx_bounded_vndf_lower_bound(alpha, i);
}

double ggx_vndf_pdf(double alpha, const Dir3& i, const Dir3& m) {
  const double im = dot(i, m);
  if (!(im > 0.0 && m.z > 0.0 && i.z > 0.0)) return 0.0;
  // Tokuyoshi and Eto 2024, Eq. (8).
  return 2.0 * D_ggx(theta_of(m), alpha) * im / ggx_vndf_norm(alpha, i);
}

double ggx_bounded_vndf_lower_bound(double alpha, const Dir3& i) {
  const Dir3 wi = stretched(alpha, i);
  return i.z > 0.0 ? -bounded_k(alpha, i) * wi.z : -wi.z;
}

Dir3 sample_ggx_bounded_vndf(double alpha, const Dir3& i, double u0, double u1) {
  // Tokuyoshi and Eto 2024, Listing 1 with the isotropic bound of Eq. (6) (both signs of 1 - alpha).
  return cap_facet(alpha, i, ggx_bounded_vndf_lower_bound(alpha, i), u0, u1);
}

double ggx_bounded_vndf_pdf(double alpha, const Dir3& i, const Dir3& m) {
  const double im = dot(i, m);
  if (!(im > 0.0 && m.z > 0.0 && i.z > 0.0)) return 0.0;
  // Eq. (10): zero outside the cap.
  if (!ggx_bounded_vndf_covers(alpha, i, m)) return 0.0;
  return 2.0 * D_ggx(theta_of(m), alpha) * im / ggx_bounded_vndf_norm(alpha, i);
}

// ---- Flatland -----------------------------------------------------------------------------------

namespace {
// The flatland angle of a 3D normal in the (x, z) plane's marginal: slope s_x = -m_x / m_z.
double flatland_angle(const Dir3& m) { return std::atan2(-m.x, m.z); }
Dir3 flatland_dir(double theta) { return {-std::sin(theta), 0.0, std::cos(theta)}; }
}  // namespace

double sample_projected_ndf2(NdfKind ndf, double alpha, double u0, double u1) {
  // D2 cos d theta = P(s) ds, P the x-marginal of the 3D slope law (ndf.h).
  return flatland_angle(sample_projected_ndf(ndf, alpha, u0, u1));
}

double projected_ndf2_pdf(NdfKind ndf, double alpha, double theta_s) {
  return D2(ndf, theta_s, alpha) * std::max(0.0, std::cos(theta_s));
}

double sample_vcavity_vndf2(NdfKind ndf, double alpha, double theta_i, double u0, double u1, double u2) {
  const double t = sample_projected_ndf2(ndf, alpha, u0, u1);
  const double a = std::max(0.0, std::cos(theta_i - t)), b = std::max(0.0, std::cos(theta_i + t));
  if (!(a + b > 0.0)) return 0.0;
  return u2 * (a + b) < b ? -t : t;
}

double vcavity_vndf2_pdf(NdfKind ndf, double alpha, double theta_i, double theta_s) {
  const double is = std::cos(theta_i - theta_s), ci = std::cos(theta_i), cs = std::cos(theta_s);
  if (!(is > 0.0 && ci > 0.0 && cs > 0.0)) return 0.0;
  return D2(ndf, theta_s, alpha) * std::min(is, 2.0 * cs * ci) / ci;
}

double sample_ggx_vndf2(double alpha, double theta_i, double u0, double u1) {
  return flatland_angle(sample_ggx_vndf(alpha, flatland_dir(theta_i), u0, u1));
}

double ggx_vndf2_pdf(double alpha, double theta_i, double theta_s) {
  const double is = std::cos(theta_i - theta_s), ci = std::cos(theta_i);
  if (!(is > 0.0 && ci > 0.0 && std::abs(theta_s) < 0.5 * std::numbers::pi)) return 0.0;
  return G1_smith_ggx(theta_i, alpha) * is * D2_ggx(theta_s, alpha) / ci;
}

}  // namespace vgroove::analytic
