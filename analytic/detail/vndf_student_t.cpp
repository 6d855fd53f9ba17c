#include "vgroove/analytic/detail/vndf_student_t.h"

#include "vgroove/common/log_gamma_ratio.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vgroove::analytic {

namespace {

constexpr double kVMax = 760.0;  // sech(760) = 0 in double
constexpr double kLn2 = std::numbers::ln2;

// sech v and log(sech v) without overflow: cosh v = e^|v| (1 + e^-2|v|) / 2.
double sech(double v) {
  const double e = std::exp(-std::abs(v));
  return 2.0 * e / (1.0 + e * e);
}
double log_sech(double v) {
  const double x = std::abs(v);
  return kLn2 - x - std::log1p(std::exp(-2.0 * x));
}

// The law of v (the header): the t CDF C(v) of p = k sinh v, the tilt s |M(v)|, and their density.
struct VisibleSlopeLaw {
  double a, k, s;
  double N = std::exp(log_gamma_ratio(a, 0.5)) / std::sqrt(std::numbers::pi);
  // I_z(a, 1/2) / 2 at z = sech^2 v, 1 - z = tanh^2 v (both without cancellation).
  double half_i(double v) const {
    const double sh = sech(v), th = std::tanh(v);
    return 0.5 * incomplete_beta(a, 0.5, sh * sh, th * th);
  }
  // s |M(v)| = s k N sech^(2a - 1) v / (2a - 1).
  double tilt(double v) const {
    return s > 0.0 ? s * k * N * std::exp((2.0 * a - 1.0) * log_sech(v)) / (2.0 * a - 1.0) : 0.0;
  }
  // C(v) + s |M(v)|.
  double below(double v) const { return (v < 0.0 ? half_i(v) : 1.0 - half_i(v)) + tilt(v); }
  // The same from v to v_mu (no 1 - F near the top): differences of like terms; within a fifth
  // of the density's scale of v_mu, where those differences cancel to the share (v_mu - v) / scale
  // of their size (the density vanishes linearly at v_mu), the density's 8-point Gauss-Legendre
  // sum (exact to rounding over a fifth of the scale).
  double above(double v, double v_mu) const {
    const double h = v_mu - v;
    if (h < 0.2 * scale(v_mu)) {
      // Abramowitz & Stegun 25.4.30, n = 8: nodes +-x_j, weights w_j on [-1, 1].
      constexpr double x[4] = {0.1834346424956498049, 0.5255324099163289858, 0.7966664774136267396,
                               0.9602898564975362317};
      constexpr double w[4] = {0.3626837833783619830, 0.3137066458778872873, 0.2223810344533744706,
                               0.1012285362903762591};
      const double mid = v + 0.5 * h;
      double sum = 0.0;
      for (int j = 0; j < 4; ++j) sum += w[j] * (density(mid - 0.5 * h * x[j]) + density(mid + 0.5 * h * x[j]));
      return 0.5 * h * sum;
    }
    const double dC = v < 0.0 ? 1.0 - half_i(v_mu) - half_i(v) : half_i(v) - half_i(v_mu);
    return dC - (tilt(v) - tilt(v_mu));
  }
  // The length over which log density changes by about 1 near v: its slopes 2a tanh v (the
  // sech power) and s k cosh v / (1 - s k sinh v) (the tilt, at most its value one scale below).
  double scale(double v) const {
    return 1.0 / (1.0 + std::sqrt(2.0 * a) + 2.0 * a * std::abs(std::tanh(v)) + s * k * std::cosh(v));
  }
  // d/dv of below: N sech^(2a) v (1 - s k sinh v) = N sech^(2a-1) v (sech v - s k tanh v).
  double density(double v) const {
    return N * std::exp((2.0 * a - 1.0) * log_sech(v)) * (sech(v) - s * k * std::tanh(v));
  }
};

// v <= 0 below which below(v) <= target: I_z(a, 1/2) <= z^a (1 - z)^(-1/2) / (a B(a, 1/2)) <=
// sqrt(2) N z^a / a for z <= 1/2, and s |M| = s k N z^(a - 1/2) / (2a - 1); each term at most half
// the target. From log z: |v| = acosh(z^(-1/2)) <= log 2 - log(z) / 2.
double lower_bracket(const VisibleSlopeLaw& L, double target) {
  double log_z = -kLn2;
  log_z = std::min(log_z, (std::log(0.5 * target) - std::log(L.N / (std::sqrt(2.0) * L.a))) / L.a);
  if (L.s > 0.0)
    log_z = std::min(log_z, (std::log(0.5 * target) - std::log(L.s * L.k * L.N / (2.0 * L.a - 1.0))) / (L.a - 0.5));
  return std::max(-kVMax, -(kLn2 - 0.5 * log_z));
}

// v in [lo, hi] with G(v) = target > 0, G = value(v) > 0 monotone (sign +1: increasing, -1:
// decreasing), G(lo) and G(hi) on either side of the target up to rounding, and G' = sign
// density(v): Newton's method on log G (nearly linear in v in the tails, where G is a power of
// sech v), a bisection whenever a step leaves the bracket.
template <class Value, class Density>
double solve(Value&& value, Density&& density, double sign, double target, double lo, double hi) {
  double v = std::clamp(0.0, lo, hi);
  if (v == lo || v == hi) v = 0.5 * (lo + hi);
  const double log_target = std::log(target);
  for (int it = 0; it < 200; ++it) {
    const double G = value(v);
    if (G == target) return v;
    ((G < target) == (sign > 0.0) ? lo : hi) = v;
    const double dG = sign * density(v);
    double next = G > 0.0 && dG != 0.0 ? v - (std::log(G) - log_target) * G / dG : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - v) <= 1e-15 * std::abs(next) || next == v || !(hi - lo > 1e-300)) return next;
    v = next;
  }
  return v;
}

double dot(const Dir3& a, const Dir3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// D(m) = y^gamma / (pi alpha^2 cos^4) (ndf_student_t.h), in logarithms where cos^4 underflows (a
// facet within ~1e-80 rad of vertical, which the sampler draws at gamma near 1.5; D_cs gives 0 / 0
// there): log y = log c + 2 log cos - log(c cos^2 + sin^2).
double D_of(const StudentT& t, double cos_m, double sin_m) {
  const double d = t.D_cs(cos_m, sin_m);
  if (std::isfinite(d)) return d;
  const double log_cos = std::log(cos_m);
  const double log_y = std::log(t.c) + 2.0 * log_cos - std::log(t.c * cos_m * cos_m + sin_m * sin_m);
  return std::exp(t.gamma * log_y - std::log(std::numbers::pi * t.alpha * t.alpha) - 4.0 * log_cos);
}

}  // namespace

double student_t_visible_slope_inverse(double a, double k, double s, double u) {
  if (!(u > 0.0)) return -kVMax;
  const double v_mu = s > 0.0 ? std::asinh(1.0 / (s * k)) : kVMax;
  if (!(s > 0.0) || !(v_mu < kVMax)) {
    // The t law alone, symmetric: the upper half from the lower one at 1 - u (exact for u > 1/2).
    if (u > 0.5) return -student_t_visible_slope_inverse(a, k, 0.0, 1.0 - u);
    const VisibleSlopeLaw T{a, k, 0.0};
    return solve([&](double v) { return T.below(v); }, [&](double v) { return T.density(v); }, 1.0, u,
                 lower_bracket(T, u), 0.0);
  }
  // Visible slopes end at p = 1 / s (the facets seen edge-on); 1 + Lambda is below(v_mu). The
  // upper half solves for the mass above v against 1 - u (exact for u > 1/2).
  const VisibleSlopeLaw L{a, k, s};
  const double den = L.below(v_mu);
  auto density = [&](double v) { return L.density(v); };
  if (u > 0.5)
    return solve([&](double v) { return L.above(v, v_mu); }, density, -1.0, (1.0 - u) * den,
                 lower_bracket(L, 0.5 * den), v_mu);
  return solve([&](double v) { return L.below(v); }, density, 1.0, u * den, lower_bracket(L, u * den), v_mu);
}

double student_t_smith_g1(const StudentT& t, double theta_i) { return 1.0 / (1.0 + t.Lambda(theta_i)); }

double student_t_vndf_norm(const StudentT& t, const Dir3& i) {
  return 2.0 * i.z * (1.0 + t.Lambda(std::atan2(std::hypot(i.x, i.y), i.z)));
}

double student_t_vndf_pdf(const StudentT& t, const Dir3& i, const Dir3& m) {
  const double im = dot(i, m);
  if (!(im > 0.0 && m.z > 0.0 && i.z > 0.0)) return 0.0;
  // G1(i) <i.m> D(m) / <i.n> (Heitz and d'Eon 2014), G1 = 1 / (1 + Lambda) (Heitz 2014, Eq. 10).
  const double theta_i = std::atan2(std::hypot(i.x, i.y), i.z);
  return student_t_smith_g1(t, theta_i) * im * D_of(t, m.z, std::hypot(m.x, m.y)) / i.z;
}

Dir3 sample_student_t_vndf(const StudentT& t, const Dir3& i, double u0, double u1) {
  if (!(i.z > 0.0)) return {0.0, 0.0, 1.0};
  const double r = std::hypot(i.x, i.y);
  const double k = std::sqrt(t.gamma - 1.0);
  // The stretched view's slope limit: s = alpha tan(theta_i).
  const double v = student_t_visible_slope_inverse(t.gamma - 1.0, k, t.alpha * r / i.z, u0);
  const double w = student_t_visible_slope_inverse(t.gamma - 0.5, 1.0, 0.0, u1);
  // m ~ (-p, -q, 1) alpha-scaled, p = k sinh v, q = k cosh v sinh w; times sech v sech w.
  const double sv = sech(v), sw = sech(w), ak = t.alpha * k;
  const double mx = -ak * std::tanh(v) * sw, my = -ak * std::tanh(w), mz = sv * sw;
  const double len = std::sqrt(mx * mx + my * my + mz * mz);
  const double ex = r > 0.0 ? i.x / r : 1.0, ey = r > 0.0 ? i.y / r : 0.0;
  return {(mx * ex - my * ey) / len, (mx * ey + my * ex) / len, mz / len};
}

double sample_student_t_vndf2(const StudentT& t, double theta_i, double u) {
  // i = (-sin theta_i, cos theta_i): its horizontal direction is -x for theta_i >= 0, and the
  // facet's angle -atan(p) (vndf.h's flatland_angle of the 3D facet), +atan(p) otherwise.
  const double k = std::sqrt(t.gamma - 1.0);
  const double v = student_t_visible_slope_inverse(t.gamma - 1.0, k, t.alpha * std::tan(std::abs(theta_i)), u);
  const double m = std::atan2(t.alpha * k * std::tanh(v), sech(v));
  return theta_i >= 0.0 ? -m : m;
}

double student_t_vndf2_pdf(const StudentT& t, double theta_i, double theta_s) {
  const double is = std::cos(theta_i - theta_s), ci = std::cos(theta_i);
  if (!(is > 0.0 && ci > 0.0 && std::abs(theta_s) < 0.5 * std::numbers::pi)) return 0.0;
  return student_t_smith_g1(t, theta_i) * is * t.D2(theta_s) / ci;
}

}  // namespace vgroove::analytic
