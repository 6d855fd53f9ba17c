#include "vgroove/analytic/sampling_nonsymmetric.h"

#include "vgroove/analytic/brdf_nonsymmetric.h"
#include "vgroove/analytic/detail/smith_vndf.h"
#include "vgroove/analytic/kaleidoscope_nonsymmetric.h"
#include "vgroove/analytic/partner_distribution.h"
#include "vgroove/analytic/quadrature.h"
#include "vgroove/analytic/vndf.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace vgroove::analytic {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kHalfPi = 0.5 * std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();
// The absolute tolerance of a B-piece per unit of the relative one: pieces that carry nothing (most k
// at a given o) stop at once instead of refining towards a relative error of a near-zero integral.
constexpr double kAbsPerRel = 1e-3;
// The parts a B-piece starts from, as Eq. (23)'s evaluation (brdf_nonsymmetric.cpp). A zone of k
// reflections can hold light on a small part of a piece only (e.g. k = 3 from the mirrored facet
// for GGX 0.5, theta_i = 30 deg, theta_o = -28 deg: 7 % of the piece): one 15-point rule over the
// whole piece can have no node inside it, see zeros and stop (the pdf would be 2 % low there).
constexpr int kPieceParts = 4;

// ---- The facet's law ----------------------------------------------------------------------------

Dir3 sample_facet(const NonsymmetricSampler& S, const Dir3& i, const std::array<double, 5>& u) {
  switch (S.opt.strategy) {
    case FacetStrategy::printed:
      return sample_projected_ndf(S.ndf, S.alpha, u[0], u[1]);
    case FacetStrategy::vndf:
      return sample_vcavity_vndf(S.ndf, S.alpha, i, u[0], u[1], u[2]);
    case FacetStrategy::smith_vndf:
      return sample_smith_vndf(S.ndf, S.alpha, i, u[0], u[1]);
    case FacetStrategy::bounded_vndf:
      return sample_ggx_bounded_vndf(S.alpha, i, u[0], u[1]);
  }
  return {0.0, 0.0, 1.0};
}

double facet_pdf(const NonsymmetricSampler& S, const Dir3& i, const Dir3& s) {
  switch (S.opt.strategy) {
    case FacetStrategy::printed:
      return projected_ndf_pdf(S.ndf, S.alpha, s);
    case FacetStrategy::vndf:
      return vcavity_vndf_pdf(S.ndf, S.alpha, i, s);
    case FacetStrategy::smith_vndf:
      return smith_vndf_pdf(S.ndf, S.alpha, i, s);
    case FacetStrategy::bounded_vndf:
      return ggx_bounded_vndf_pdf(S.alpha, i, s);
  }
  return 0.0;
}

double sample_facet2(const NonsymmetricSampler& S, double theta_i, const std::array<double, 5>& u) {
  switch (S.opt.strategy) {
    case FacetStrategy::printed:
      return sample_projected_ndf2(S.ndf, S.alpha, u[0], u[1]);
    case FacetStrategy::vndf:
      return sample_vcavity_vndf2(S.ndf, S.alpha, theta_i, u[0], u[1], u[2]);
    case FacetStrategy::smith_vndf:
    case FacetStrategy::bounded_vndf:  // refused by make_nonsymmetric_sampler in flatland
      return sample_smith_vndf2(S.ndf, S.alpha, theta_i, u[0], u[1]);
  }
  return 0.0;
}

double facet_pdf2(const NonsymmetricSampler& S, double theta_i, double theta_s) {
  switch (S.opt.strategy) {
    case FacetStrategy::printed:
      return projected_ndf2_pdf(S.ndf, S.alpha, theta_s);
    case FacetStrategy::vndf:
      return vcavity_vndf2_pdf(S.ndf, S.alpha, theta_i, theta_s);
    case FacetStrategy::smith_vndf:
    case FacetStrategy::bounded_vndf:
      return smith_vndf2_pdf(S.ndf, S.alpha, theta_i, theta_s);
  }
  return 0.0;
}

// ---- The outcome: P(k | s, B) and the probability of no direction -------------------------------

// Eq. (9) for light at t_i aimed at the left facet (theta_l = -A) of the groove with partner B: the
// probability that the strategy's roulette (sampling_nonsymmetric.h, step 3) gives no direction.
double no_direction(const NonsymmetricPrediction& g, bool printed, int max_k) {
  if (!g.lit) return 1.0;
  const double total = printed ? 1.0 : 1.0 - g.shadow;
  if (!(total > 0.0)) return 1.0;
  double valid = 0.0;
  for (const BounceShare& z : g.share)
    if (z.n >= 1 && z.n <= max_k) valid += z.G;
  return std::clamp(1.0 - valid / total, 0.0, 1.0);
}

// The probability of the k-reflection outcome under the same roulette, from the zone widths alone (count_width: no exit
// angles, which the pdf does not need): width / f_a under the printed roulette, width / (f_a - f_b) under the others.
double p_count(double t_i, double theta_l, double B, int k, bool printed) {
  const CountWidth w = count_width(t_i, theta_l, B, k);
  if (!(w.width > 0.0)) return 0.0;
  const double total = printed ? w.f_a : w.f_a - w.f_b;
  return total > 0.0 ? w.width / total : 0.0;
}

// |d t_h / d theta_l| (Eq. 8): k/2 (k even), (k+1)/2 (k odd).
double half_slope(int k) { return std::abs(dtheta_h_dtheta_l(k)); }

bool inside_groove(double A, double B) { return A >= 0.0 && A < kHalfPi && B >= 0.0 && B < kHalfPi; }

}  // namespace

NonsymmetricSampler make_nonsymmetric_sampler(NdfKind ndf, double alpha, const SamplerOptions& opt, bool flatland,
                                              int table_cells) {
  if (!strategy_supports(opt.strategy, ndf, flatland))
    throw std::domain_error(std::string("strategy ") + strategy_name(opt.strategy) + " is not available for " +
                            ndf_name(ndf) + (flatland ? " in flatland" : ""));
  NonsymmetricSampler s;
  s.ndf = ndf;
  s.alpha = alpha;
  s.opt = opt;
  s.flatland = flatland;
  s.partner = make_partner_table(ndf, alpha, flatland, table_cells);
  return s;
}

// ---- 3D -------------------------------------------------------------------------------------------

double nonsymmetric_pdf_3d_k(const NonsymmetricSampler& S, const Dir3& i, const Dir3& o, int k_lo, int k_hi) {
  if (!(i.z > 0.0 && o.z > 0.0)) return 0.0;
  GrooveFrame frame;
  if (!groove_frame(i, o, frame)) return kInf;
  const double phi_a = std::atan2(frame.ay, frame.ax);  // the azimuth of a
  const bool printed = S.opt.strategy == FacetStrategy::printed;
  double sum = 0.0;
  for (int k = std::max(1, k_lo); k <= std::min(k_hi, S.opt.max_k); ++k) {
    // |ds/do| of Eq. (23) without sin(A) / sin(theta_h) (k = 1: s = h, the ratio is 1).
    const double jac = 1.0 / (half_slope(k) * 4.0 * frame.cos_d);
    for (int side = 0; side < 2; ++side) {
      // side 0: the first facet leans towards a (azimuth phi_a); side 1: away (mirrored).
      const double sgn = side == 0 ? 1.0 : -1.0, ti = sgn * frame.x.t_i, to = sgn * frame.x.t_o;
      const double phi_s = side == 0 ? phi_a : phi_a + kPi;
      const double cp = std::cos(phi_s), sp = std::sin(phi_s);
      for (const PartnerPiece& piece : partner_pieces(ti, to, k)) {
        auto f = [&](double B) {
          const double theta_l = piece.C + piece.beta * B, A = -theta_l;
          if (!inside_groove(A, B)) return 0.0;
          const double p_k = p_count(ti, theta_l, B, k, printed);
          if (!(p_k > 0.0)) return 0.0;
          const double pB = P_theta_r(S.ndf, B, S.alpha);
          const double sa = std::sin(A);
          const double q = facet_pdf(S, i, Dir3{sa * cp, sa * sp, std::cos(A)});
          return q * pB * p_k * (k == 1 ? 1.0 : sa / frame.sin_h);
        };
        sum += jac *
               integrate_adaptive_parts(f, piece.lo, piece.hi, S.tolerance, kAbsPerRel * S.tolerance, kPieceParts, 512);
      }
    }
  }
  return sum;
}

double nonsymmetric_pdf_3d(const NonsymmetricSampler& S, const Dir3& i, const Dir3& o) {
  return nonsymmetric_pdf_3d_k(S, i, o, 1, S.opt.max_k);
}

namespace {

// Eq. (9)'s roulette over the zones of the facet hit first: the zone whose cumulative share G
// passes u times the total (the lit fraction, or 1 with the printed strategy, whose facets include
// the shadowed ones); null when no path of 1..max_k reflections is drawn (*beyond set when the
// drawn path has more than max_k).
const BounceShare* roulette(const NonsymmetricPrediction& g, const SamplerOptions& opt, double u, bool* beyond) {
  const double total = opt.strategy == FacetStrategy::printed ? 1.0 : 1.0 - g.shadow;
  if (!(total > 0.0)) return nullptr;
  const double xu = u * total;
  double acc = 0.0;
  for (const BounceShare& z : g.share) {
    if (!(z.G > 0.0)) continue;
    acc += z.G;
    if (xu < acc) {
      *beyond = z.n > opt.max_k;
      return z.n >= 1 && z.n <= opt.max_k ? &z : nullptr;
    }
  }
  return nullptr;
}

}  // namespace

NonsymmetricDraw3d draw_nonsymmetric_3d(const NonsymmetricSampler& S, const Dir3& i, const std::array<double, 5>& u) {
  const NonsymmetricDraw3d none{{-i.x, -i.y, i.z}, 0}, lost{none.o, 0, true};
  if (!(i.z > 0.0)) return none;
  // Step 1: the facet hit first, leaning towards a.
  const Dir3 s = sample_facet(S, i, u);
  if (!(s.z > 0.0)) return none;
  const double sin_s = std::hypot(s.x, s.y);
  const double ax = sin_s > 0.0 ? s.x / sin_s : 1.0, ay = sin_s > 0.0 ? s.y / sin_s : 0.0;
  const double A = std::atan2(sin_s, s.z);
  // Step 2: the partner's tilt, by the table.
  const double B = sample_partner(S.partner, u[3]);
  // Step 3: the cross-section (a, n), Eq. (7)-(9), the roulette.
  const double ia = i.x * ax + i.y * ay, iu = -i.x * ay + i.y * ax, c = std::sqrt(ia * ia + i.z * i.z);
  const double t_i = std::atan2(-ia, i.z);
  const NonsymmetricPrediction g = G_nonsymmetric(t_i, -A, B, FacetSide::left);
  if (!g.lit) return none;
  bool beyond = false;
  const BounceShare* out = roulette(g, S.opt, u[4], &beyond);
  if (out == nullptr) return beyond ? lost : none;
  // Step 4: Eq. (8) in the cross-section, lifted back.
  const double st = std::sin(out->theta_o), ct = std::cos(out->theta_o);
  const Dir3 o{-c * st * ax + iu * ay, -c * st * ay - iu * ax, c * ct};
  if (!(o.z > 0.0)) return none;
  return {o, out->n};
}

VgrooveSample3d sample_nonsymmetric_3d(const NonsymmetricSampler& S, const Dir3& i, const std::array<double, 5>& u,
                                       const FresnelFn& F) {
  const VgrooveSample3d none{{-i.x, -i.y, i.z}, 0, 0.0, 0.0};
  const NonsymmetricDraw3d d = draw_nonsymmetric_3d(S, i, u);
  if (d.k == 0) return {none.o, 0, 0.0, 0.0, d.beyond_max_k};
  const Dir3& o = d.o;
  const double pdf = nonsymmetric_pdf_3d(S, i, o);
  if (!(pdf > 0.0 && pdf < kInf)) return none;
  NonsymmetricModel m;
  m.roughness = isotropic_roughness(S.ndf, S.alpha);
  m.tolerance = S.tolerance;
  const double rho_cos = nonsymmetric_brdf(i, o, S.opt.max_k, m, F) * o.z;
  if (!std::isfinite(rho_cos)) return none;
  return {o, d.k, pdf, rho_cos / pdf};
}

double nonsymmetric_failure_probability_3d(const NonsymmetricSampler& S, const Dir3& i, double tol) {
  if (!(i.z > 0.0)) return 1.0;
  const bool printed = S.opt.strategy == FacetStrategy::printed;
  const double phi_i = std::atan2(i.y, i.x);
  const double a = S.alpha;
  // Mapped variables: theta = atan(alpha tan(pi v / 2)) puts the nodes where D lives.
  auto mapped = [a](double v, double& d) {
    const double t = std::tan(kHalfPi * v), c2 = 1.0 + t * t;
    d = a * kHalfPi * c2 / (1.0 + a * a * t * t);
    return std::atan(a * t);
  };
  // P(no direction | s, B) integrated over B with P_tab (its nodes are the same map of B).
  auto over_partner = [&](double A, double t_i) {
    auto f = [&](double w) {
      double dB = 0.0;
      const double B = mapped(w, dB);
      const double pB = S.flatland ? P2_theta_r(S.ndf, B, S.alpha) : P_theta_r(S.ndf, B, S.alpha);
      if (!(pB > 0.0)) return 0.0;
      return pB * dB * no_direction(G_nonsymmetric(t_i, -A, B, FacetSide::left), printed, S.opt.max_k);
    };
    return integrate_adaptive_parts(f, 0.0, 1.0, 0.0, 0.1 * tol, 8, 128);
  };
  auto over_tilt = [&](double psi) {
    const double phi = phi_i + psi, ax = std::cos(phi), ay = std::sin(phi);
    const double ia = i.x * ax + i.y * ay, t_i = std::atan2(-ia, i.z);
    auto f = [&](double v) {
      double dA = 0.0;
      const double A = mapped(v, dA), sa = std::sin(A);
      const double q = facet_pdf(S, i, Dir3{sa * ax, sa * ay, std::cos(A)});
      if (!(q > 0.0)) return 0.0;
      return q * sa * dA * over_partner(A, t_i);
    };
    return integrate_adaptive_parts(f, 0.0, 1.0, 0.0, 0.2 * tol, 8, 128);
  };
  // Mirror symmetry about the plane of incidence.
  return 2.0 * integrate_adaptive_parts(over_tilt, 0.0, kPi, 0.0, 0.2 * tol, 8, 128);
}

// ---- Flatland ---------------------------------------------------------------------------------------

double nonsymmetric_pdf_flatland_k(const NonsymmetricSampler& S, double theta_i, double theta_o, int k_lo, int k_hi) {
  if (!(std::abs(theta_i) < kHalfPi && std::abs(theta_o) < kHalfPi)) return 0.0;
  const bool printed = S.opt.strategy == FacetStrategy::printed;
  double sum = 0.0;
  for (int k = std::max(1, k_lo); k <= std::min(k_hi, S.opt.max_k); ++k) {
    const double jac = 1.0 / (2.0 * half_slope(k));  // |d theta_s / d theta_o|
    for (int side = 0; side < 2; ++side) {
      // side 0: the left facet first (theta_s = -A); side 1: the right one (mirrored, theta_s = +A).
      const double sgn = side == 0 ? 1.0 : -1.0, ti = sgn * theta_i, to = sgn * theta_o;
      for (const PartnerPiece& piece : partner_pieces(ti, to, k)) {
        auto f = [&](double B) {
          const double theta_l = piece.C + piece.beta * B, A = -theta_l;
          if (!inside_groove(A, B)) return 0.0;
          const double p_k = p_count(ti, theta_l, B, k, printed);
          if (!(p_k > 0.0)) return 0.0;
          const double pB = P2_theta_r(S.ndf, B, S.alpha);
          return facet_pdf2(S, theta_i, -sgn * A) * pB * p_k;
        };
        sum += jac *
               integrate_adaptive_parts(f, piece.lo, piece.hi, S.tolerance, kAbsPerRel * S.tolerance, kPieceParts, 512);
      }
    }
  }
  return sum;
}

double nonsymmetric_pdf_flatland(const NonsymmetricSampler& S, double theta_i, double theta_o) {
  return nonsymmetric_pdf_flatland_k(S, theta_i, theta_o, 1, S.opt.max_k);
}

NonsymmetricDrawFlatland draw_nonsymmetric_flatland(const NonsymmetricSampler& S, double theta_i,
                                                    const std::array<double, 5>& u) {
  const NonsymmetricDrawFlatland none{-theta_i, 0}, lost{-theta_i, 0, true};
  if (!(std::abs(theta_i) < kHalfPi)) return none;
  const double theta_s = sample_facet2(S, theta_i, u);
  if (!(std::abs(theta_s) < kHalfPi)) return none;
  // theta_s < 0: the left facet hit first; otherwise the right one, in the mirrored frame.
  const double sgn = theta_s < 0.0 ? 1.0 : -1.0, A = std::abs(theta_s), ti = sgn * theta_i;
  const double B = sample_partner(S.partner, u[3]);
  const NonsymmetricPrediction g = G_nonsymmetric(ti, -A, B, FacetSide::left);
  if (!g.lit) return none;
  bool beyond = false;
  const BounceShare* out = roulette(g, S.opt, u[4], &beyond);
  if (out == nullptr) return beyond ? lost : none;
  const double theta_o = sgn * out->theta_o;
  if (!(std::abs(theta_o) < kHalfPi)) return none;
  return {theta_o, out->n};
}

VgrooveSampleFlatland sample_nonsymmetric_flatland(const NonsymmetricSampler& S, double theta_i,
                                                   const std::array<double, 5>& u) {
  const VgrooveSampleFlatland none{-theta_i, 0, 0.0, 0.0};
  const NonsymmetricDrawFlatland d = draw_nonsymmetric_flatland(S, theta_i, u);
  if (d.k == 0) return {none.theta_o, 0, 0.0, 0.0, d.beyond_max_k};
  const double theta_o = d.theta_o;
  const double pdf = nonsymmetric_pdf_flatland(S, theta_i, theta_o);
  if (!(pdf > 0.0 && pdf < kInf)) return none;
  NonsymmetricModel m;
  m.roughness = isotropic_roughness(S.ndf, S.alpha);
  m.tolerance = S.tolerance;
  const double rho_cos = flatland_nonsymmetric_brdf(theta_i, theta_o, S.opt.max_k, m) * std::cos(theta_o);
  if (!std::isfinite(rho_cos)) return none;
  return {theta_o, d.k, pdf, rho_cos / pdf};
}

double nonsymmetric_failure_probability_flatland(const NonsymmetricSampler& S, double theta_i, double tol) {
  if (!(std::abs(theta_i) < kHalfPi)) return 1.0;
  const bool printed = S.opt.strategy == FacetStrategy::printed;
  const double a = S.alpha;
  auto mapped = [a](double v, double& d) {
    const double t = std::tan(kHalfPi * v), c2 = 1.0 + t * t;
    d = a * kHalfPi * c2 / (1.0 + a * a * t * t);
    return std::atan(a * t);
  };
  double sum = 0.0;
  for (double sgn : {1.0, -1.0}) {
    // sgn = 1: theta_s = -A (the left facet first), -1: theta_s = +A (mirrored).
    const double ti = sgn * theta_i;
    auto over_tilt = [&](double v) {
      double dA = 0.0;
      const double A = mapped(v, dA);
      const double q = facet_pdf2(S, theta_i, -sgn * A);
      if (!(q > 0.0)) return 0.0;
      auto f = [&](double w) {
        double dB = 0.0;
        const double B = mapped(w, dB);
        const double pB = S.flatland ? P2_theta_r(S.ndf, B, S.alpha) : P_theta_r(S.ndf, B, S.alpha);
        if (!(pB > 0.0)) return 0.0;
        return pB * dB * no_direction(G_nonsymmetric(ti, -A, B, FacetSide::left), printed, S.opt.max_k);
      };
      return q * dA * integrate_adaptive_parts(f, 0.0, 1.0, 0.0, 0.1 * tol, 8, 256);
    };
    sum += integrate_adaptive_parts(over_tilt, 0.0, 1.0, 0.0, 0.2 * tol, 8, 256);
  }
  return sum;
}

}  // namespace vgroove::analytic
