#include "vgroove/analytic/smith_walk_3d.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>

namespace vgroove::analytic {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSqrtPi = 1.7724538509055160273;

// The flatland view of v in the frame turned to v's azimuth: theta_v = atan2(-|v_xy|, v_z).
double flatland_view(const Dir3& v) { return std::atan2(-std::hypot(v.x, v.y), v.z); }

// y >= 0 with erfc(y) = t, t in (0, 1]: Newton's method on log erfc(y) - log t (log erfc is
// concave and decreasing, so from the right of the root the steps decrease to it monotonically;
// one step from the left lands on the right), inside the bracket [0, 27] (erfc(27) underflows).
double erfc_inverse(double t) {
  if (t >= 1.0) return 0.0;
  double lo = 0.0, hi = 27.0;
  const double target = std::log(t);
  // A start from erfc(y) ~ e^{-y^2} / (y sqrt pi) for the tail, the series near 0.
  double y = t > 0.5 ? 0.5 * kSqrtPi * (1.0 - t) : std::sqrt(std::max(0.0, -target - 0.5 * std::log(-target * kPi)));
  y = std::clamp(y, lo, hi);
  for (int it = 0; it < 100; ++it) {
    const double e = std::erfc(y);
    const double g = std::log(e) - target;
    if (g == 0.0) return y;
    (g > 0.0 ? lo : hi) = y;
    const double dg = -2.0 * std::exp(-y * y) / (kSqrtPi * e);
    double next = y - g / dg;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - y) <= 1e-16 * std::max(1.0, y)) return next;
    y = next;
  }
  return y;
}

// delta - sin(delta) for delta in [0, pi], by its series below 1 (no cancellation).
double delta_minus_sin(double d) {
  if (d >= 1.0) return d - std::sin(d);
  // sum_{n >= 1} (-1)^(n+1) d^(2n+1) / (2n+1)!, 12 terms (d^25 / 25! < 1e-25 for d < 1), summed
  // from the largest term (the terms alternate and fall by d^2 / 20 at least).
  const double d2 = d * d;
  double term = d * d2 / 6.0, sum = 0.0;
  for (int n = 1; n <= 12; ++n) {
    sum += term;
    term *= -d2 / ((2.0 * n + 2.0) * (2.0 * n + 3.0));
  }
  return sum;
}

// delta in (0, pi] with delta - sin(delta) = w, w in (0, pi]: Newton's method from delta0 =
// (6 w)^(1/3) <= delta (delta - sin delta <= delta^3 / 6); g is convex and increasing, so after
// the first step the iterates decrease to the root; bisection keeps them in the bracket.
double solve_delta(double w) {
  double lo = 0.0, hi = kPi;
  double d = std::min(std::cbrt(6.0 * w), kPi);
  for (int it = 0; it < 100; ++it) {
    const double g = delta_minus_sin(d) - w;
    if (g == 0.0) return d;
    (g > 0.0 ? hi : lo) = d;
    const double s = std::sin(0.5 * d);
    const double dg = 2.0 * s * s;  // 1 - cos(delta)
    double next = dg > 0.0 ? d - g / dg : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - d) <= 4e-16 * d) return next;
    d = next;
  }
  return d;
}

// The half vector h = (v + o) / |v + o| of a reflection towards an upward o, and v.h; false where
// o is not upward or v does not face h (no next-event estimate).
bool reflection_half_vector(const Dir3& v, const Dir3& o, Dir3& h, double& vh) {
  if (!(o.z > 0.0)) return false;
  h = {v.x + o.x, v.y + o.y, v.z + o.z};
  const double len = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
  if (!(len > 0.0)) return false;
  h = {h.x / len, h.y / len, h.z / len};
  vh = v.x * h.x + v.y * h.y + v.z * h.z;
  return vh > 0.0;
}

}  // namespace

double visible_projected_area(NdfKind ndf, double alpha, const Dir3& v) {
  return visible_projected_length(ndf, alpha, flatland_view(v));
}

double visible_normal_pdf_3d(NdfKind ndf, double alpha, const Dir3& v, const Dir3& m) {
  if (!(m.z > 0.0)) return 0.0;
  const double c = v.x * m.x + v.y * m.y + v.z * m.z;
  if (!(c > 0.0)) return 0.0;
  return c * D(ndf, polar_angle(m), alpha) / visible_projected_area(ndf, alpha, v);
}

double sample_cross_slope(NdfKind ndf, double alpha, double p, double u) {
  assert(ndf == NdfKind::beckmann || ndf == NdfKind::ggx);
  const bool upper = u > 0.5;
  // min(u, 1 - u) without rounding 1 - u for u > 1/2 (exact there).
  const double tail = upper ? 1.0 - u : u;
  if (ndf == NdfKind::beckmann) {
    // q = alpha erfinv(2 u - 1): erfc(|x|) = 2 min(u, 1 - u).
    const double x = erfc_inverse(2.0 * tail);
    return upper ? alpha * x : -alpha * x;
  }
  const double delta = solve_delta(2.0 * kPi * tail);
  const double t = 1.0 / std::tan(0.5 * delta);
  const double c = std::hypot(1.0, p / alpha);
  return (upper ? alpha : -alpha) * c * t;
}

Dir3 sample_visible_normal_3d(NdfKind ndf, double alpha, const Dir3& v, double u0, double u1) {
  const double s = std::hypot(v.x, v.y);
  const double m2 = sample_visible_normal(ndf, alpha, std::atan2(-s, v.z), u0);
  const double p = std::tan(m2);
  const double q = sample_cross_slope(ndf, alpha, p, u1);
  // (-p, -q, 1) cos(m2) = (-sin m2, -q cos m2, cos m2), of length sqrt(1 + q^2 cos^2 m2): no
  // overflow for the steepest slopes.
  const double cm = std::cos(m2), qc = q * cm;
  const double len = std::hypot(1.0, qc);
  const double mx = -std::sin(m2) / len, my = -qc / len, mz = cm / len;
  const double ex = s > 0.0 ? v.x / s : 1.0, ey = s > 0.0 ? v.y / s : 0.0;
  return {mx * ex - my * ey, mx * ey + my * ex, mz};
}

double next_event_estimate(NdfKind ndf, double alpha, const Dir3& v, double lc, const Dir3& o) {
  Dir3 h;
  double vh = 0.0;
  if (!reflection_half_vector(v, o, h, vh)) return 0.0;
  const double phase = visible_normal_pdf_3d(ndf, alpha, v, h) / (4.0 * vh);
  // G1(o, h_j) = C1(h_j)^Lambda(o) (Heitz 2014 at a height; Heitz et al. 2016, Sec. 4).
  return phase * std::exp(Lambda(ndf, polar_angle(o), alpha) * lc);
}

// ---- Anisotropic roughness and the walk's heights ---------------------------------------------

double projected_roughness(const Roughness& r, const Dir3& d) {
  const double s2 = d.x * d.x + d.y * d.y;
  if (!(s2 > 0.0)) return r.alpha_x;  // vertical: no azimuth, and Lambda = 0 for every alpha
  // Heitz 2014, Eq. (11): alpha_o^2 = cos^2(phi) alpha_x^2 + sin^2(phi) alpha_y^2.
  const double ax = r.alpha_x * d.x, ay = r.alpha_y * d.y;
  return std::sqrt((ax * ax + ay * ay) / s2);
}

double Lambda_3d(const Roughness& r, const Dir3& d) { return Lambda(r.ndf, polar_angle(d), projected_roughness(r, d)); }

double visible_projected_area(const Roughness& r, const Dir3& v) {
  // The slope along v's azimuth has the isotropic marginal at alpha_o (the projection of the
  // stretched law), and only it enters <v, m> D d omega_m integrated over the cross slope.
  return visible_projected_length(r.ndf, projected_roughness(r, v), flatland_view(v));
}

double visible_normal_pdf_3d(const Roughness& r, const Dir3& v, const Dir3& m) {
  if (!(m.z > 0.0)) return 0.0;
  const double c = v.x * m.x + v.y * m.y + v.z * m.z;
  if (!(c > 0.0)) return 0.0;
  return c * D_anisotropic(r, polar_angle(m), std::atan2(m.y, m.x)) / visible_projected_area(r, v);
}

Dir3 sample_visible_normal_3d(const Roughness& r, const Dir3& v, double u0, double u1) {
  // (v_z - v_x p - v_y q) P22(p, q) dp dq with p = alpha_x p', q = alpha_y q' is (v_z - alpha_x v_x
  // p' - alpha_y v_y q') P22_1(p', q') dp' dq': the visible slopes at alpha = 1 seen from the
  // stretched view (a positive factor apart).
  Dir3 w{r.alpha_x * v.x, r.alpha_y * v.y, v.z};
  const double lw = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
  w = {w.x / lw, w.y / lw, w.z / lw};
  const Dir3 m1 = sample_visible_normal_3d(r.ndf, 1.0, w, u0, u1);
  // (-p, -q, 1) is parallel to (alpha_x m1_x, alpha_y m1_y, m1_z), since p' = -m1_x / m1_z.
  const Dir3 m{r.alpha_x * m1.x, r.alpha_y * m1.y, m1.z};
  const double lm = std::sqrt(m.x * m.x + m.y * m.y + m.z * m.z);
  return {m.x / lm, m.y / lm, m.z / lm};
}

double next_event_estimate(const Roughness& r, const Dir3& v, double lc, const Dir3& o) {
  Dir3 h;
  double vh = 0.0;
  if (!reflection_half_vector(v, o, h, vh)) return 0.0;
  const double phase = visible_normal_pdf_3d(r, v, h) / (4.0 * vh);
  // G1(o, h_j) = C1(h_j)^Lambda(o), Lambda at o's projected roughness.
  return phase * std::exp(Lambda_3d(r, o) * lc);
}

const char* walk_heights_name(WalkHeights law) {
  switch (law) {
    case WalkHeights::log_c1:
      return "log_c1";
    case WalkHeights::uniform:
      return "uniform";
    case WalkHeights::gaussian:
      return "gaussian";
  }
  return "?";
}

double walk_log_C1(WalkHeights law, double h) {
  switch (law) {
    case WalkHeights::log_c1:
      return h;
    case WalkHeights::uniform:
      // C1(h) = (1 + h) / 2 on [-1, 1] (Heitz et al. 2016's code, clamped as theirs).
      return std::log(std::clamp(0.5 * (1.0 + h), 0.0, 1.0));
    case WalkHeights::gaussian:
      // C1(h) = (1 + erf(h / sqrt 2)) / 2 = erfc(-h / sqrt 2) / 2.
      return std::log(0.5 * std::erfc(-h / std::numbers::sqrt2));
  }
  return h;
}

double walk_height(WalkHeights law, double lc) {
  switch (law) {
    case WalkHeights::log_c1:
      return lc;
    case WalkHeights::uniform:
      return 2.0 * std::exp(lc) - 1.0;
    case WalkHeights::gaussian: {
      if (!(lc < 0.0)) return std::numeric_limits<double>::infinity();
      const double c = std::exp(lc);
      if (c >= 1.0) return std::numeric_limits<double>::infinity();  // lc within 1e-16 of the top
      // erfc(-h / sqrt 2) = 2 c: the lower half from erfc directly, the upper from its symmetry
      // erfc(y) = 2 - erfc(-y) (1 - c loses the digits a double has near the top, as in their code).
      return c <= 0.5 ? -std::numbers::sqrt2 * erfc_inverse(2.0 * c)
                      : std::numbers::sqrt2 * erfc_inverse(2.0 - 2.0 * c);
    }
  }
  return lc;
}

}  // namespace vgroove::analytic
