#include "vgroove/analytic/sampling_flatland.h"

#include "vgroove/analytic/detail/smith_vndf.h"
#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/kaleidoscope_solutions.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/sampler_failure_share.h"
#include "vgroove/analytic/vndf.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

double sample_facet2(double theta_i, const std::array<double, 4>& u, NdfKind ndf, double alpha, FacetStrategy s) {
  switch (s) {
    case FacetStrategy::printed:
      return sample_projected_ndf2(ndf, alpha, u[0], u[1]);
    case FacetStrategy::vndf:
      return sample_vcavity_vndf2(ndf, alpha, theta_i, u[0], u[1], u[2]);
    case FacetStrategy::smith_vndf:
    case FacetStrategy::bounded_vndf:  // no flatland bounded VNDF (facet_strategy.h): refused by the callers
      return sample_smith_vndf2(ndf, alpha, theta_i, u[0], u[1]);
  }
  return 0.0;
}

double facet_pdf2(double theta_i, double theta_s, NdfKind ndf, double alpha, FacetStrategy s) {
  switch (s) {
    case FacetStrategy::printed:
      return projected_ndf2_pdf(ndf, alpha, theta_s);
    case FacetStrategy::vndf:
      return vcavity_vndf2_pdf(ndf, alpha, theta_i, theta_s);
    case FacetStrategy::smith_vndf:
    case FacetStrategy::bounded_vndf:
      return smith_vndf2_pdf(ndf, alpha, theta_i, theta_s);
  }
  return 0.0;
}

// The paths to theta_o, in the frame where t_h <= 0 (the profile's mirror image otherwise): calls
// fn(solution, theta_s) with theta_s the facet's angle in the original frame.
template <class Fn>
void for_each_path(double theta_i, double theta_o, int k_lo, int k_hi, Fn&& fn) {
  const double m = theta_i + theta_o > 0.0 ? -1.0 : 1.0;
  const CrossSection x = cross_section(m * theta_i, m * theta_o);
  for_each_solution(x, k_lo, k_hi, [&](const Solution& q) {
    const double theta_m = 0.5 * (std::numbers::pi - q.theta_v);
    // The left facet's normal is at -theta_m in the frame, the right one's at +theta_m.
    const double in_frame = q.first == FacetSide::left ? -theta_m : theta_m;
    fn(q, m * in_frame);
  });
}

// q(theta_s) P(k | theta_s) for a path: the flatland forms of sampling_3d.cpp's StrategyTerm.
double strategy_term(double theta_i, const Solution& q, double theta_s, double D2v, NdfKind ndf, double alpha,
                     FacetStrategy s) {
  switch (s) {
    case FacetStrategy::vndf:
      return D2v * q.W / std::cos(theta_i);  // D2 (f_a - f_b) / cos(theta_i) times W / (f_a - f_b)
    case FacetStrategy::printed:
      return D2v * q.S * q.W / q.f_a();  // D2 cos(theta_s) times G = W / f_a
    case FacetStrategy::smith_vndf:
    case FacetStrategy::bounded_vndf:
      return facet_pdf2(theta_i, theta_s, ndf, alpha, s) * q.W / q.lit();
  }
  return 0.0;
}

}  // namespace

PdfAndBrdf2 vgroove_pdf_and_brdf_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha,
                                          const SamplerOptions& opt) {
  if (!(std::abs(theta_i) < kHalfPi && std::abs(theta_o) < kHalfPi)) return {};
  PdfAndBrdf2 r;
  const double ci = std::cos(theta_i);
  for_each_path(theta_i, theta_o, 1, opt.max_k, [&](const Solution& q, double theta_s) {
    const double D2v = D2_cs(ndf, q.S, q.C, alpha);
    const double J = 1.0 / (2.0 * q.k);  // |d theta_s / d theta_o|, brdf_flatland.h step (c)
    r.rho_cos += D2v * q.W * J / ci;     // brdf_flatland.h step (d) times cos(theta_o)
    r.pdf += strategy_term(theta_i, q, theta_s, D2v, ndf, alpha, opt.strategy) * J;
  });
  return r;
}

double vgroove_pdf_flatland_k(double theta_i, double theta_o, NdfKind ndf, double alpha, const SamplerOptions& opt,
                              int k_lo, int k_hi) {
  if (!(std::abs(theta_i) < kHalfPi && std::abs(theta_o) < kHalfPi)) return 0.0;
  double pdf = 0.0;
  for_each_path(theta_i, theta_o, std::max(1, k_lo), std::min(k_hi, opt.max_k), [&](const Solution& q, double theta_s) {
    pdf += strategy_term(theta_i, q, theta_s, D2_cs(ndf, q.S, q.C, alpha), ndf, alpha, opt.strategy) / (2.0 * q.k);
  });
  return pdf;
}

double vgroove_pdf_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha, const SamplerOptions& opt) {
  return vgroove_pdf_flatland_k(theta_i, theta_o, ndf, alpha, opt, 1, opt.max_k);
}

double printed_p_flatland(double theta_i, double theta_o, NdfKind ndf, double alpha, int max_k) {
  if (!(std::abs(theta_i) < kHalfPi && std::abs(theta_o) < kHalfPi)) return 0.0;
  double p = 0.0;
  for_each_path(theta_i, theta_o, 1, max_k,
                [&](const Solution& q, double) { p += q.S * D2_cs(ndf, q.S, q.C, alpha) * q.W / q.f_a(); });
  return p;
}

VgrooveSampleFlatland sample_vgroove_flatland(double theta_i, const std::array<double, 4>& u, NdfKind ndf, double alpha,
                                              const SamplerOptions& opt) {
  const VgrooveSampleFlatland none{-theta_i, 0, 0.0, 0.0};
  if (!(std::abs(theta_i) < kHalfPi)) return none;
  const double theta_s = sample_facet2(theta_i, u, ndf, alpha, opt.strategy);
  if (!(std::abs(theta_s) < kHalfPi)) return none;
  // theta_s < 0: the left facet of the groove of aperture pi - 2 |theta_s|; otherwise its right one.
  const FacetSide side = theta_s < 0.0 ? FacetSide::left : FacetSide::right;
  const double theta_v = std::numbers::pi - 2.0 * std::abs(theta_s);
  const FacetPrediction p = G_kaleidoscopic(theta_i, theta_v, side);
  if (!p.lit) return none;
  const double w_fewer = p.f_a - p.f_k, w_more = p.f_k - p.f_b;
  const double total = opt.strategy == FacetStrategy::printed ? p.f_a : w_fewer + w_more;
  const double x = u[3] * total;
  const BounceShare* out = x < w_fewer ? &p.fewer : (x < w_fewer + w_more ? &p.more : nullptr);
  if (out == nullptr || out->n < 1) return none;
  if (out->n > opt.max_k) {
    VgrooveSampleFlatland lost = none;
    lost.beyond_max_k = true;
    return lost;
  }
  if (!(std::abs(out->theta_o) < kHalfPi)) return none;
  const PdfAndBrdf2 e = vgroove_pdf_and_brdf_flatland(theta_i, out->theta_o, ndf, alpha, opt);
  if (!(e.pdf > 0.0 && std::isfinite(e.pdf) && std::isfinite(e.rho_cos))) return none;
  return {out->theta_o, out->n, e.pdf, e.rho_cos / e.pdf};
}

namespace {

// The failure probability, or (beyond_only) its part from the paths beyond max_k.
double failure_integral(double theta_i, NdfKind ndf, double alpha, const SamplerOptions& opt, double tol,
                        bool beyond_only) {
  if (!(std::abs(theta_i) < kHalfPi)) return 1.0;
  const bool printed = opt.strategy == FacetStrategy::printed;
  // Beyond max_k, the printed strategy fails only where the other strategies do.
  const bool whole_range = printed && !beyond_only;
  // q(theta_s) P(no direction | theta_s), over theta_s = -(pi - v)/2 (left) and +(pi - v)/2 (right).
  // q is written with cos(theta_s) = sin(v/2) and the facet's projected width f_a = <i.s> from
  // Eq. (6), not from theta_s: near vertical facets (v -> 0) theta_s = pi/2 - v/2 no longer
  // resolves v, and D2 ~ cos^p (Phong, p < 0) would carry the rounding into the tail's integral.
  const double ci = std::cos(theta_i);
  const double g1 = opt.strategy == FacetStrategy::smith_vndf ? smith_g1(ndf, alpha, theta_i) : 1.0;
  auto integrand = [&](double theta_v, FacetSide side) {
    const double S = std::sin(0.5 * theta_v), C = std::cos(0.5 * theta_v);  // cos, sin of theta_s
    const double D2v = D2_cs(ndf, S, C, alpha);
    const FacetPrediction p = G_kaleidoscopic(theta_i, theta_v, side);
    if (!p.lit) return whole_range ? D2v * S * 0.5 : 0.0;  // d theta_s = d theta_v / 2
    double q = 0.0;
    switch (opt.strategy) {
      case FacetStrategy::printed:
        q = D2v * S;  // D2 cos(theta_s)
        break;
      case FacetStrategy::vndf: {
        // D2 <i.s> G1 / cos(theta_i), <i.s> G1 = f_a - f_b written as the product 2 sin(v/2) cos(t)
        // when f_b > 0: near grazing light both are close to 1 and their difference ~ v cos(t).
        const double t = side == FacetSide::left ? theta_i : -theta_i;
        q = D2v * (p.f_b > 0.0 ? 2.0 * S * std::cos(t) : p.f_a) / ci;
        break;
      }
      case FacetStrategy::smith_vndf:
      case FacetStrategy::bounded_vndf:
        q = g1 * p.f_a * D2v / ci;  // G1(theta_i) <i.s> D2 / cos(theta_i)
        break;
    }
    const double fail = facet_failure_share(p, opt.max_k, printed, beyond_only);
    return q * 0.5 * fail;
  };
  const double v_max = whole_range ? std::numbers::pi : std::min(std::numbers::pi, 2.0 * std::numbers::pi / opt.max_k);
  const double v_tail = std::min(v_max, 2.0 * std::numbers::pi / opt.max_k);
  std::vector<double> cuts{v_max};
  for (double v = v_tail; v > v_tail * 1e-12; v *= 0.5) cuts.push_back(v);
  for (double s = 1.0 / 64.0; s <= 64.0; s *= 2.0) {
    const double v = std::numbers::pi - 2.0 * std::atan(alpha * s);
    if (v < v_max) cuts.push_back(v);
  }
  // f_b switches sign (one facet's rim shadows); the paths beyond max_k start (Eq. 4's K = max_k + 1
  // and max_k + 2 at theta_v = (pi + 2 t) / K, t = +-theta_i for the two facets): the failure
  // jumps or kinks there.
  for (double v :
       {2.0 * std::abs(theta_i), (std::numbers::pi + 2.0 * theta_i) / opt.max_k,
        (std::numbers::pi + 2.0 * theta_i) / (opt.max_k + 1.0), (std::numbers::pi - 2.0 * theta_i) / opt.max_k,
        (std::numbers::pi - 2.0 * theta_i) / (opt.max_k + 1.0)})
    if (v < v_max) cuts.push_back(v);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  AdaptiveOptions o;
  o.abs_tol = 0.25 * tol;
  double sum = 0.0;
  for (FacetSide side : {FacetSide::left, FacetSide::right}) {
    auto f = [&](double v) { return integrand(v, side); };
    sum += integrate_adaptive(f, cuts, o).value;
    // Below cuts[0] the integrand is a power law of theta_v: extrapolated (sampling_3d.cpp).
    const double v0 = cuts[0], i1 = f(v0), i2 = f(0.5 * v0);
    if (i1 > 0.0 && i2 > 0.0) {
      const double e = std::log2(i1 / i2);
      if (e > -1.0) sum += i1 * v0 / (e + 1.0);
    }
  }
  return sum;
}

}  // namespace

double sampler_failure_probability_flatland(double theta_i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                            double tol) {
  return failure_integral(theta_i, ndf, alpha, opt, tol, false);
}

double sampler_beyond_max_k_probability_flatland(double theta_i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                                 double tol) {
  return failure_integral(theta_i, ndf, alpha, opt, tol, true);
}

double sample_cosine_flatland(double u) { return std::asin(2.0 * u - 1.0); }
double cosine_flatland_pdf(double theta_o) { return std::abs(theta_o) < kHalfPi ? 0.5 * std::cos(theta_o) : 0.0; }

}  // namespace vgroove::analytic
