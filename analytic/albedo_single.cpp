// vgroove analytic: single-scattering albedos by nested Gauss-Kronrod quadrature (albedo_single.h).
#include "vgroove/analytic/albedo_single.h"

#include "vgroove/analytic/brdf_3d.h"
#include "vgroove/analytic/ndf.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

bool model_supported(const MicrofacetModel& m) { return masking_supported(m.masking, m.ndf); }

namespace {

constexpr double kPi = std::numbers::pi;

// What multiplies f cos in the integral, a function of i.h: 1 (E_ss), 1 - Fc (the split sum's
// scale), Fc (its bias), or a reflectance F(i.h) (albedo_single_fresnel).
struct One {
  double operator()(double) const { return 1.0; }
};
// Karis 2013: Fc = (1 - v.h)^5.
double schlick_fc(double ih) {
  const double c = 1.0 - ih, c2 = c * c;
  return c2 * c2 * c;
}
struct OneMinusSchlick {
  double operator()(double ih) const { return 1.0 - schlick_fc(ih); }
};
struct Schlick {
  double operator()(double ih) const { return schlick_fc(ih); }
};

// Smith's Lambda from tan^2 of the direction (the forms of ndf.cpp, Heitz 2014 Sec. 3.2, without
// the angle: the integrand has cos and sin, not theta). The test Albedo.LambdaIsNdfsLambda holds
// them to ndf.h's.
double lambda_tan2(NdfKind ndf, double alpha, double tan2) {
  if (ndf == NdfKind::ggx) {
    // x / (2 (1 + sqrt(1 + x))), x = alpha^2 tan^2: (-1 + sqrt(1 + x)) / 2 without cancellation.
    const double x = alpha * alpha * tan2;
    return x / (2.0 * (1.0 + std::sqrt(1.0 + x)));
  }
  if (!(tan2 > 0.0)) return 0.0;  // a = infinity: nothing is masked at normal view
  const double a = 1.0 / (alpha * std::sqrt(tan2));
  return -0.5 * std::erfc(a) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
}

// The incident direction's constants.
struct Incidence {
  double mu = 1.0, sin_i = 0.0;
  double lambda_i = 0.0;
};

// G2 (i.h) / (mu cos theta_h) times the weight at the normal h = (sin_h cos phi, sin_h sin phi,
// cos_h): the integrand against dP(h) (albedo_single.h).
template <class Weight>
double integrand(const MicrofacetModel& m, double alpha, const Incidence& in, const Weight& w, double cos_h,
                 double sin_h, double cos_phi) {
  const double ih = in.sin_i * sin_h * cos_phi + in.mu * cos_h;
  const double mu_o = 2.0 * ih * cos_h - in.mu;
  // Beyond the horizon (the pieces end there; rounding may put a node a little past it).
  if (!(mu_o > 0.0 && ih > 0.0)) return 0.0;
  double G2 = 0.0;
  if (m.masking == MaskingKind::vcavity) {
    // Lee et al. 2018, Eq. (3) with the V-cavity G1 of Eq. (2); o.h = i.h.
    G2 = std::min(G1_vcavity(ih, in.mu, cos_h), G1_vcavity(ih, mu_o, cos_h));
  } else {
    const double lambda_o = lambda_tan2(m.ndf, alpha, (1.0 - mu_o) * (1.0 + mu_o) / (mu_o * mu_o));
    G2 = m.masking == MaskingKind::smith_height_correlated
             ? 1.0 / (1.0 + in.lambda_i + lambda_o)             // Heitz 2014, Eq. (21)
             : 1.0 / ((1.0 + in.lambda_i) * (1.0 + lambda_o));  // Heitz 2014, Eq. (20)
  }
  return G2 * ih / (in.mu * cos_h) * w(ih);
}

// Each piece between consecutive points split into `refine` equal parts.
std::vector<double> refined(std::vector<double> cuts, int refine) {
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  if (refine <= 1 || cuts.size() < 2) return cuts;
  std::vector<double> out;
  for (std::size_t j = 0; j + 1 < cuts.size(); ++j)
    for (int r = 0; r < refine; ++r) out.push_back(cuts[j] + (cuts[j + 1] - cuts[j]) * r / refine);
  out.push_back(cuts.back());
  return out;
}

// The rounding of the sums (each piece's 15 terms, the pieces, the outer level), beside the rules'
// estimates: 64 ulps of the value, above what reordering the sums moves (~2 ulps seen).
double rounding(double value) { return 64.0 * std::numeric_limits<double>::epsilon() * std::abs(value); }

template <class Weight>
BoundedValue integrate_albedo(const MicrofacetModel& m, double alpha, double mu, const Weight& w,
                              const AlbedoOptions& opt) {
  assert(model_supported(m) && alpha > 0.0 && mu > 0.0 && mu <= 1.0);
  Incidence in;
  in.mu = mu;
  in.sin_i = std::sqrt((1.0 - mu) * (1.0 + mu));
  if (m.masking != MaskingKind::vcavity) in.lambda_i = lambda_tan2(m.ndf, alpha, in.sin_i * in.sin_i / (mu * mu));
  const bool vcavity = m.masking == MaskingKind::vcavity;

  AdaptiveOptions inner;
  inner.abs_tol = 0.5 * opt.tol;
  inner.max_pieces = opt.max_pieces;
  double inner_error = 0.0;
  bool converged = true;
  long evaluations = 0;
  // int_0^{u_max(phi)} integrand du at one azimuth of h.
  auto along = [&](double phi) {
    const double cos_phi = std::cos(phi);
    // o.n = 0 at theta_h = psi / 2 (albedo_single.h).
    const double psi = std::atan2(mu, -in.sin_i * cos_phi);
    const double theta_max = 0.5 * psi;
    std::vector<double> thetas{theta_max};
    // The NDF's scale: theta_h = alpha 2^j (in u they sit at 0.2, 0.5, 0.8, 0.94, ... for GGX).
    // Beyond a cut whose remaining mass 1 - u is below a thousandth of the tolerance more cuts
    // change nothing (the adaptive rule still integrates the rest).
    const double u_max = groove_cdf(m.ndf, alpha, theta_max), negligible = 1e-3 * opt.tol;
    for (int j = -1; j < 64; ++j) {
      const double t = std::atan(alpha * std::ldexp(1.0, j));
      if (!(t < theta_max)) break;
      thetas.push_back(t);
      if (u_max - groove_cdf(m.ndf, alpha, t) < negligible) break;
    }
    // Smith's G2 falls to 0 at the horizon through a layer where o.n is comparable with alpha
    // (Lambda(o) ~ alpha / (2 o.n)) and with mu (Lambda(o) ~ Lambda(i)); o.n ~ 2 (theta_max -
    // theta_h) there, so the pieces are graded towards theta_max down to a hundredth of both.
    if (!vcavity) {
      const double layer = 0.01 * std::min(alpha, mu);
      for (double d = 0.25 * theta_max; d > layer; d *= 0.25) {
        thetas.push_back(theta_max - d);
        if (u_max - groove_cdf(m.ndf, alpha, theta_max - d) < negligible) break;
      }
    }
    if (vcavity) {
      // G1(o, h) = 1, G1(i, h) = 1 and G1(i, h) = G1(o, h): the kinks of the min (albedo_single.h).
      for (double t : {psi / 3.0, kPi - psi, psi - 0.5 * kPi})
        if (t > 0.0 && t < theta_max) thetas.push_back(t);
    }
    std::vector<double> cuts{0.0};
    for (double t : thetas) cuts.push_back(groove_cdf(m.ndf, alpha, t));
    const AdaptiveResult r = integrate_adaptive(
        [&](double u) {
          double cos_h = 1.0, sin_h = 0.0;
          groove_cdf_inverse_cos_sin(m.ndf, alpha, u, cos_h, sin_h);
          return integrand(m, alpha, in, w, cos_h, sin_h, cos_phi);
        },
        refined(cuts, opt.refine), inner);
    inner_error = std::max(inner_error, r.error);
    converged = converged && r.converged;
    evaluations += r.evaluations;
    return r.value;
  };

  // phi in [0, pi]: 4 equal pieces, and where the V-cavity kinks meet (cos phi = k cot theta_i).
  std::vector<double> phis{0.0, 0.25 * kPi, 0.5 * kPi, 0.75 * kPi, kPi};
  // Near grazing incidence the normals' domain shrinks from theta_max ~ pi / 2 (phi < pi / 2) to
  // theta_max ~ mu / (2 |cos phi|) (phi > pi / 2) within |cos phi| ~ mu: pieces graded about pi / 2.
  for (double d = 0.25 * mu; d < 0.1; d *= 4.0) {
    phis.push_back(0.5 * kPi - d);
    phis.push_back(0.5 * kPi + d);
  }
  if (vcavity && in.sin_i > 0.0) {
    for (double k : {1.0 / std::sqrt(3.0), 1.0}) {
      const double c = k * mu / in.sin_i;
      if (c < 1.0) phis.push_back(std::acos(c));
    }
  }
  AdaptiveOptions outer;
  outer.abs_tol = 0.5 * kPi * opt.tol;
  outer.max_pieces = opt.max_pieces;
  const AdaptiveResult r = integrate_adaptive(along, refined(phis, opt.refine), outer);
  // E = (1 / 2 pi) int_0^{2 pi} = (1 / pi) int_0^pi (even in phi).
  const double value = r.value / kPi;
  return {value, r.error / kPi + inner_error + rounding(value), converged && r.converged, evaluations};
}

}  // namespace

BoundedValue albedo_single(const MicrofacetModel& m, double alpha, double mu, const AlbedoOptions& opt) {
  return integrate_albedo(m, alpha, mu, One{}, opt);
}

BoundedValue albedo_single_fresnel(const MicrofacetModel& m, double alpha, double mu,
                                   const std::function<double(double)>& F, const AlbedoOptions& opt) {
  return integrate_albedo(m, alpha, mu, F, opt);
}

SplitSum dfg_split_sum(const MicrofacetModel& m, double alpha, double mu, const AlbedoOptions& opt) {
  return {integrate_albedo(m, alpha, mu, OneMinusSchlick{}, opt), integrate_albedo(m, alpha, mu, Schlick{}, opt)};
}

BoundedValue albedo_average(const MicrofacetModel& m, double alpha, const AlbedoOptions& opt) {
  double inner_error = 0.0;
  bool converged = true;
  long evaluations = 0;
  auto g = [&](double mu) {
    // E_ss enters weighted by 2 mu: to tol / (4 mu), so that 2 mu e(mu) <= tol / 2 at every node.
    AlbedoOptions in = opt;
    in.tol = std::min(0.25 * opt.tol / mu, 1e-3);
    const BoundedValue e = albedo_single(m, alpha, mu, in);
    inner_error = std::max(inner_error, 2.0 * mu * e.error);
    converged = converged && e.converged;
    evaluations += e.evaluations;
    return e.value;
  };
  // Four equal pieces to start: 2 mu E_ss(mu) vanishes at grazing, where E_ss changes fastest.
  const std::vector<double> mus{0.0, 0.25, 0.5, 0.75, 1.0};
  AdaptiveOptions o;
  o.abs_tol = 0.5 * opt.tol;
  o.max_pieces = opt.max_pieces;
  const AdaptiveResult r = integrate_adaptive([&](double mu) { return 2.0 * mu * g(mu); }, refined(mus, opt.refine), o);
  // int_0^1 2 mu e(mu) dmu <= max 2 mu e(mu).
  return {r.value, r.error + inner_error + rounding(r.value), converged && r.converged, evaluations};
}

}  // namespace vgroove::analytic
