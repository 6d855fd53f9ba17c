#include "vgroove/analytic/sampling_3d.h"

#include "vgroove/analytic/sampler_failure_share.h"

#include "vgroove/analytic/detail/smith_vndf.h"
#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/analytic/kaleidoscope_solutions.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/vndf.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Dir3 mirror_of(const Dir3& i) { return {-i.x, -i.y, i.z}; }

VgrooveSample3d no_direction(const Dir3& i) { return {mirror_of(i), 0, 0.0, 0.0}; }

// The facet, from the strategy's density.
Dir3 sample_facet(const Dir3& i, const std::array<double, 4>& u, NdfKind ndf, double alpha, FacetStrategy s) {
  switch (s) {
    case FacetStrategy::printed:
      return sample_projected_ndf(ndf, alpha, u[0], u[1]);
    case FacetStrategy::vndf:
      return sample_vcavity_vndf(ndf, alpha, i, u[0], u[1], u[2]);
    case FacetStrategy::smith_vndf:
      return sample_smith_vndf(ndf, alpha, i, u[0], u[1]);
    case FacetStrategy::bounded_vndf:
      return sample_ggx_bounded_vndf(alpha, i, u[0], u[1]);
  }
  return {0.0, 0.0, 1.0};
}

// The groove whose left facet is s: its cross-section and the light's projected angle in it.
struct FacetGroove {
  double ax = 1.0, ay = 0.0;  // a: the horizontal direction of s
  double theta_v = std::numbers::pi;
  double t_i = 0.0, c = 1.0, iu = 0.0;
};
FacetGroove groove_of(const Dir3& i, const Dir3& s) {
  FacetGroove g;
  const double sin_m = std::hypot(s.x, s.y);
  if (sin_m > 0.0) g.ax = s.x / sin_m, g.ay = s.y / sin_m;  // theta_s = 0: a flat groove, any a
  g.theta_v = std::numbers::pi - 2.0 * std::atan2(sin_m, s.z);
  const double ia = i.x * g.ax + i.y * g.ay;
  g.iu = -i.x * g.ay + i.y * g.ax;  // u = n x a = (-a_y, a_x, 0)
  g.t_i = std::atan2(-ia, i.z);
  g.c = std::sqrt(ia * ia + i.z * i.z);
  return g;
}

// The facet density q(s) of a path with solution q in the frame f, times P(k | s): the strategy's
// probability per d s of drawing this facet and this outcome (sampling_3d.h, step 2). The
// facets' densities are vndf.h's, written with |i.s| = c f_a and D from the solution.
struct StrategyTerm {
  const Dir3& i;
  double alpha;
  FacetStrategy strategy;
  double smith_norm, bounded_norm;  // the denominators of Tokuyoshi and Eto 2024, Eq. (8), (10)
  StrategyTerm(const Dir3& i_, NdfKind ndf, double alpha_, FacetStrategy s)
      : i(i_),
        alpha(alpha_),
        strategy(s),
        smith_norm(s == FacetStrategy::smith_vndf ? smith_vndf_norm(ndf, alpha_, i_) : 1.0),
        bounded_norm(s == FacetStrategy::bounded_vndf ? ggx_bounded_vndf_norm(alpha_, i_) : 1.0) {}
  double operator()(const GrooveFrame& f, const Solution& q, double D) const {
    switch (strategy) {
      case FacetStrategy::vndf:
        // D(s) <i.s> G1(i, s) / <i.n> times W / (f_a - f_b), <i.s> G1 = c (f_a - f_b): D c W / cos(theta_i).
        return D * f.c * q.W / i.z;
      case FacetStrategy::printed:
        // |s.n| D(s) times G = W / f_a (Eq. 6).
        return D * q.S * q.W / q.f_a();
      case FacetStrategy::smith_vndf:
        // 2 D <i.s> / norm times W / (f_a - f_b).
        return 2.0 * D * f.c * q.f_a() / smith_norm * q.W / q.lit();
      case FacetStrategy::bounded_vndf: {
        const double m = q.first == FacetSide::left ? 1.0 : -1.0;
        if (!ggx_bounded_vndf_covers(alpha, i, Dir3{m * q.C * f.ax, m * q.C * f.ay, q.S})) return 0.0;
        return 2.0 * D * f.c * q.f_a() / bounded_norm * q.W / q.lit();
      }
    }
    return 0.0;
  }
};

// |ds/do| of Eq. (13) without sin(theta_s) / sin(theta_h) for k = 1 (s = h, the ratio is 1).
double jacobian(const GrooveFrame& f, const Solution& q) {
  const double ratio = q.k == 1 ? 1.0 : q.C / (q.k * f.sin_h);
  return ratio / (4.0 * f.cos_d);
}

}  // namespace

PdfAndBrdf vgroove_pdf_and_brdf_3d(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                   const FresnelFn& F) {
  if (!(i.z > 0.0 && o.z > 0.0)) return {};
  GrooveFrame f;
  if (!groove_frame(i, o, f)) return {kInf, kInf};
  PdfAndBrdf r;
  const StrategyTerm term(i, ndf, alpha, opt.strategy);
  for_each_solution(
      f.x, 1, opt.max_k,
      [&](const Solution& q) {
        const double D = D_cs(ndf, q.S, q.C, alpha);
        const double J = jacobian(f, q);
        const double theta_m = 0.5 * (std::numbers::pi - q.theta_v);
        // Lee et al. 2018, Eq. (16) times cos(theta_o): F |i.s| G D |ds/do| / cos(theta_i).
        r.rho_cos += fresnel_along_path(F, f.x.t_i, theta_m, q.first, q.k, f.c) * f.c * q.W * D * J / i.z;
        r.pdf += term(f, q, D) * J;
      },
      D_vanishing_aperture(ndf, alpha));
  return r;
}

double vgroove_pdf_3d_k(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const SamplerOptions& opt, int k_lo,
                        int k_hi) {
  if (!(i.z > 0.0 && o.z > 0.0)) return 0.0;
  GrooveFrame f;
  if (!groove_frame(i, o, f)) return k_hi >= 2 ? kInf : 0.0;
  double pdf = 0.0;
  const StrategyTerm term(i, ndf, alpha, opt.strategy);
  for_each_solution(
      f.x, std::max(1, k_lo), std::min(k_hi, opt.max_k),
      [&](const Solution& q) { pdf += term(f, q, D_cs(ndf, q.S, q.C, alpha)) * jacobian(f, q); },
      D_vanishing_aperture(ndf, alpha));
  return pdf;
}

double vgroove_pdf_3d(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, const SamplerOptions& opt) {
  return vgroove_pdf_3d_k(i, o, ndf, alpha, opt, 1, opt.max_k);
}

double printed_p_3d(const Dir3& i, const Dir3& o, NdfKind ndf, double alpha, int max_k) {
  if (!(i.z > 0.0 && o.z > 0.0)) return 0.0;
  GrooveFrame f;
  if (!groove_frame(i, o, f)) return 0.0;
  double p = 0.0;
  // Lee et al. 2018, Sec. 6: p(o) = |s.n| D(s) G(i, o, s), G = W / f_a, for each path to o.
  for_each_solution(f.x, 1, max_k, [&](const Solution& q) { p += q.S * D_cs(ndf, q.S, q.C, alpha) * q.W / q.f_a(); });
  return p;
}

VgrooveSample3d sample_vgroove_3d(const Dir3& i, const std::array<double, 4>& u, NdfKind ndf, double alpha,
                                  const SamplerOptions& opt, const FresnelFn& F) {
  if (!(i.z > 0.0)) return no_direction(i);
  // Step 1: the facet.
  const Dir3 s = sample_facet(i, u, ndf, alpha, opt.strategy);
  if (!(s.z > 0.0)) return no_direction(i);
  // Step 2: its groove's cross-section, Eq. (4)-(6) at the projected angle.
  const FacetGroove g = groove_of(i, s);
  const FacetPrediction p = G_kaleidoscopic(g.t_i, g.theta_v, FacetSide::left);
  if (!p.lit) return no_direction(i);
  const double w_fewer = p.f_a - p.f_k, w_more = p.f_k - p.f_b;
  const double total = opt.strategy == FacetStrategy::printed ? p.f_a : w_fewer + w_more;
  const double x = u[3] * total;
  const BounceShare* out = x < w_fewer ? &p.fewer : (x < w_fewer + w_more ? &p.more : nullptr);
  if (out == nullptr || out->n < 1) return no_direction(i);
  if (out->n > opt.max_k) {
    VgrooveSample3d lost = no_direction(i);
    lost.beyond_max_k = true;
    return lost;
  }
  // Step 3: Eq. (5) in the cross-section, lifted back (the component along u is kept).
  const double st = std::sin(out->theta_o), ct = std::cos(out->theta_o);
  const Dir3 o{-g.c * st * g.ax + g.iu * g.ay, -g.c * st * g.ay - g.iu * g.ax, g.c * ct};
  if (!(o.z > 0.0)) return no_direction(i);
  const PdfAndBrdf e = vgroove_pdf_and_brdf_3d(i, o, ndf, alpha, opt, F);
  if (!(e.pdf > 0.0 && e.pdf < kInf && e.rho_cos < kInf)) return no_direction(i);
  return {o, out->n, e.pdf, e.rho_cos / e.pdf};
}

// ---- The failure probability, over the facets -----------------------------------------------------

namespace {

// The failure probability, or (beyond_only) its part from the paths beyond max_k.
double failure_integral(const Dir3& i, NdfKind ndf, double alpha, const SamplerOptions& opt, double tol,
                        bool beyond_only) {
  if (!(i.z > 0.0)) return 1.0;
  const double phi_i = std::atan2(i.y, i.x);
  const bool printed = opt.strategy == FacetStrategy::printed;
  // Beyond max_k, the printed strategy fails only where the other strategies do.
  const bool whole_range = printed && !beyond_only;
  // q(s) P(no direction | s) at the facet (theta_v, psi) (psi the azimuth from i's), times
  // ds / (d theta_v d psi) = sin(theta_s) / 2. q is written with cos(theta_s) = sin(v/2) and
  // |i.s| = c f_a from Eq. (6), not from the vector s: near vertical facets (v -> 0) theta_s no
  // longer resolves v, and D ~ cos^p (Phong, p < 0) would carry the rounding into the integral.
  const double smith_norm = opt.strategy == FacetStrategy::smith_vndf ? smith_vndf_norm(ndf, alpha, i) : 1.0;
  const double bounded_norm = ggx_bounded_vndf_norm(alpha, i);
  auto integrand = [&](double theta_v, double psi) {
    const double S = std::sin(0.5 * theta_v), C = std::cos(0.5 * theta_v);  // cos, sin of theta_s
    const double theta_m = 0.5 * (std::numbers::pi - theta_v);
    const Dir3 s = dir3(theta_m, phi_i + psi);
    const FacetGroove g = groove_of(i, s);
    const FacetPrediction p = G_kaleidoscopic(g.t_i, theta_v, FacetSide::left);
    const double D = D_cs(ndf, S, C, alpha);
    if (!p.lit) return whole_range ? D * S * 0.5 * C : 0.0;  // only the printed strategy draws unlit facets
    double q = 0.0;
    switch (opt.strategy) {
      case FacetStrategy::printed:
        q = D * S;  // |s.n| D(s)
        break;
      case FacetStrategy::vndf:
        // D <i.s> G1 / <i.n>, <i.s> G1 = c (f_a - f_b) written as the product 2 sin(v/2) cos(t_i) when
        // f_b > 0: near grazing light both are close to 1 and their difference ~ v cos(t_i).
        q = D * g.c * (p.f_b > 0.0 ? 2.0 * S * std::cos(g.t_i) : p.f_a) / i.z;
        break;
      case FacetStrategy::smith_vndf:
        q = 2.0 * D * g.c * p.f_a / smith_norm;  // Tokuyoshi and Eto 2024, Eq. (8); smith_vndf.h
        break;
      case FacetStrategy::bounded_vndf:
        q = ggx_bounded_vndf_covers(alpha, i, s) ? 2.0 * D * g.c * p.f_a / bounded_norm : 0.0;  // Eq. (10)
        break;
    }
    const double fail = facet_failure_share(p, opt.max_k, printed, beyond_only);
    return q * fail * 0.5 * C;
  };
  // Only apertures below 2 pi / max_k can exceed max_k reflections (Eq. 4 with |t_i| < pi/2);
  // the printed strategy also fails over the whole range (shadowed and unlit facets).
  const double v_max = whole_range ? std::numbers::pi : std::min(std::numbers::pi, 2.0 * std::numbers::pi / opt.max_k);
  std::vector<double> cuts{0.0, v_max};
  const double v_tail = std::min(v_max, 2.0 * std::numbers::pi / opt.max_k);
  for (double v = v_tail; v > v_tail * 1e-12; v *= 0.5) cuts.push_back(v);
  for (double t = 1.0 / 64.0; t <= 64.0; t *= 2.0) {
    const double v = std::numbers::pi - 2.0 * std::atan(alpha * t);  // the NDF's width
    if (v < v_max) cuts.push_back(v);
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  const double v0 = cuts[1];
  // Pieces are capped so that a nested integral costs at most ~10^7 evaluations: where the tail
  // of a heavy NDF (Phong, alpha > 1) at grazing light keeps the estimate above a very small tol,
  // the result is still converged far beyond the validation's needs (1e-9 against 1e-6).
  AdaptiveOptions inner;
  inner.abs_tol = tol / (8.0 * std::numbers::pi);
  inner.max_pieces = 400;
  auto along = [&](double psi) {
    auto f = [&](double v) { return integrand(v, psi); };
    // The facet's lit edge (f_a = 0 at theta_v = 2 t_i) and the other rim's shadow edge (f_b = 0 at
    // theta_v = -2 t_i) at this azimuth, where the printed strategy's failure jumps, and where the
    // paths beyond max_k start (Eq. 4's K = max_k + 1 and max_k + 2 at theta_v = (pi + 2 t_i) / K).
    std::vector<double> at(cuts.begin() + 1, cuts.end());
    const FacetGroove g = groove_of(i, dir3(0.25 * std::numbers::pi, phi_i + psi));
    for (double v : {2.0 * g.t_i, -2.0 * g.t_i, (std::numbers::pi + 2.0 * g.t_i) / opt.max_k,
                     (std::numbers::pi + 2.0 * g.t_i) / (opt.max_k + 1.0)})
      if (v > at.front() && v < at.back()) at.push_back(v);
    std::sort(at.begin(), at.end());
    double r = integrate_adaptive(f, at, inner).value;
    // Below v0 (about 1e-12 of the tail's range) the integrand is a power law of theta_v (D of a
    // nearly vertical facet: Phong ~ theta_v^(p+1), GGX ~ theta_v, Beckmann 0): extrapolated.
    const double i1 = f(v0), i2 = f(0.5 * v0);
    if (i1 > 0.0 && i2 > 0.0) {
      const double e = std::log2(i1 / i2);
      if (e > -1.0) r += i1 * v0 / (e + 1.0);
    }
    return r;
  };
  std::vector<double> outer_cuts;
  for (int j = 0; j <= 8; ++j) outer_cuts.push_back(std::numbers::pi * j / 8.0);
  AdaptiveOptions outer;
  outer.abs_tol = 0.5 * tol;
  outer.max_pieces = 400;
  // Mirror symmetry about the plane of incidence: psi in [0, pi], twice.
  return 2.0 * integrate_adaptive(along, outer_cuts, outer).value;
}

}  // namespace

double sampler_failure_probability_3d(const Dir3& i, NdfKind ndf, double alpha, const SamplerOptions& opt, double tol) {
  return failure_integral(i, ndf, alpha, opt, tol, false);
}

double sampler_beyond_max_k_probability_3d(const Dir3& i, NdfKind ndf, double alpha, const SamplerOptions& opt,
                                           double tol) {
  return failure_integral(i, ndf, alpha, opt, tol, true);
}

Dir3 sample_cosine_hemisphere(double u0, double u1) {
  // Malley's method: a uniform point of the unit disk lifted to the hemisphere.
  const double r = std::sqrt(u0), phi = 2.0 * std::numbers::pi * u1;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u0))};
}

double cosine_hemisphere_pdf(const Dir3& o) { return o.z > 0.0 ? o.z / std::numbers::pi : 0.0; }

}  // namespace vgroove::analytic
