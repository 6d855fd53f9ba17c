// vgroove analytic: one symmetric dielectric V-groove with flat rims lit from BELOW (medium 2, eta =
// n2 / n1) by a parallel beam: the facet f a ray meets first (all of it is lit: f_a = cos at hit 0),
// hit 0's F(., 1/eta) reflected down (or via the rim's underside), and the refracted light that
// enters the groove at every point of f and runs Lee et al. 2018's kaleidoscope (Eq. 4-6) in medium 1
// from a source spread over the facet: a share clamp(cos gamma_m / cos alpha_t, 0, 1) makes hit m,
// gamma_m = m theta_v + alpha_t (KD-5..KD-8), each hit keeping F and refracting 1 - F downward or via
// the rim. Every path class (the tracer's signature) with its energy and exit angle in closed form.
// Holds: all lobes sum to 1 to rounding; eta = 1 leaves all light up along theta_i; the exact split
// tracer per signature to 1e-12. Tests: tests/analytic/kaleidoscope_dielectric_below_test.cpp
// (KaleidoscopeDielectricBelow.SharesSumToOne, KaleidoscopeDielectricBelow.EtaOnePassesStraightThrough,
// KaleidoscopeDielectricBelow.ChainIsLeesWithoutTheShadow, KaleidoscopeDielectricBelow.ConductorLimitReflectsAll,
// KaleidoscopeDielectricBelowTracer.MatchesSplitTracingToRounding, KaleidoscopeDielectricBelowTracer.BrokenModelsFail).
// Derivation: docs/derivations/kaleidoscope_dielectric.md ("Light from below on one groove with flat rims").
#pragma once

#include "vgroove/analytic/kaleidoscope.h"
#include "vgroove/optics/fresnel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace vgroove::analytic {

// One path class of the light aimed at a facet from below: sim::DielectricExit's signature.
struct BelowLobe {
  std::uint64_t path = 0;  // bit l set: interaction l (0-based; hit 0 is the facet met first) refracted
  int k = 0;               // interactions
  bool up = false;         // left into medium 1 (above); else into medium 2, back to the light's side
  double share = 0.0;      // of the rays aimed at the facet
  double theta = 0.0;      // exit angle from the exit side's normal (sim::exit_angle's convention)
};

// Hit j >= 1 of the chain in medium 1 (KD-6, KD-7).
struct BelowChainHit {
  int j = 0;
  double reaching = 0.0;   // A_j: share of the facet's rays whose chain makes hit j (KD-6)
  double cos_theta = 0.0;  // cos gamma_j
  double F = 1.0;          // F(cos gamma_j, eta)
  bool tir = false;
  double theta_t = 0.0;  // refracted direction's angle below (0 when tir)
  bool direct = false;   // leaves downward at once; else meets the rim's underside on its own side
};

struct DielectricBelowPrediction {
  bool lit = false;
  double f_a = 0.0;                  // the facet's width across the beam (unit facet) = cos at hit 0
  double F0 = 1.0;                   // F(f_a, 1/eta) at hit 0
  bool tir0 = false;                 // total internal reflection at hit 0 (eta > 1)
  double alpha_t = 0.0;              // the refracted ray's signed angle from the facet's normal (KD-5)
  int n_max = 0;                     // the most hits of the chain in medium 1 (near the apex)
  std::vector<BelowChainHit> hits;   // j = 1..n_max
  std::vector<BelowLobe> lobes;      // every path class of positive share
  double reflected_total() const;    // left into medium 2
  double transmitted_total() const;  // left into medium 1
};

// The flat rim lit from below at theta_i: F(cos theta_i, 1/eta) back down to -theta_i, the rest up
// to asin(eta sin theta_i) (none under total internal reflection).
struct FlatBelowPrediction {
  double F = 1.0;
  bool tir = false;
  double theta_r = 0.0, theta_t = 0.0;
};
FlatBelowPrediction flat_rim_below(double theta_i, double eta);

// Where the rays aimed at `side` from below cross the rim line (the same lines as sim::aimed_at's):
// between the rim x_f and -cos(theta_v/2) tan(theta_i). lo >= hi when the facet is not lit.
void rim_line_interval_below(double theta_i, double theta_v, FacetSide side, double& lo, double& hi);

// A beam from below crossing the rim line over [lo, hi]: the fractions of its rays that meet each
// facet first (by Side) and the flat rims (the rest).
struct BelowBeamShares {
  double facet[2] = {0.0, 0.0};
  double flat = 0.0;
};
BelowBeamShares below_beam_shares(double theta_i, double theta_v, double lo, double hi);

// Where the chain in medium 1 starts (KD-6). `facet` is the model; `rim_line_beam` is the from-above
// construction (a parallel beam entering at the rim line, its shadowed part dropped: Eq. 6's f_b),
// wrong wherever that beam is shadowed, kept for KaleidoscopeDielectricBelowTracer.BrokenModelsFail.
enum class BelowChainSource : unsigned char { facet, rim_line_beam };

// The model for light from below at theta_i (from -n, counter-clockwise positive: the light travels
// along (-sin theta_i, cos theta_i)) aimed at `first`, with any reflectance F(cos, eta_rel) (eta_rel
// = n_out / n_in of the hit: 1/eta from medium 2, eta from medium 1). eta > 0, |theta_i| < pi/2.
template <class Reflectance>
DielectricBelowPrediction kaleidoscope_dielectric_below_with(double theta_i, double theta_v, double eta,
                                                             FacetSide first, const Reflectance& F,
                                                             BelowChainSource source = BelowChainSource::facet);

DielectricBelowPrediction kaleidoscope_dielectric_below(double theta_i, double theta_v, double eta, FacetSide first);

// ---- implementation of the template ----

namespace detail {
// Total internal reflection at local cosine c from a medium into one eta_rel = n_out / n_in times
// as dense, as kaleidoscope_dielectric.cpp writes it ((1 - c)(1 + c) / eta_rel^2 >= 1).
inline bool total_internal_reflection(double c, double eta_rel) {
  return (1.0 - c) * (1.0 + c) / (eta_rel * eta_rel) >= 1.0;
}
// A ray in medium 2 travelling up at angle a (direction_at) meets the rim's underside: its two
// lobes appended after `path` with `share` (KD-8).
template <class Reflectance>
void rim_from_below(double a, double eta, std::uint64_t path, int k, double share, const Reflectance& F,
                    std::vector<BelowLobe>& out) {
  const double c = std::cos(a);
  const bool tir = total_internal_reflection(c, 1.0 / eta);
  const double Fr = tir ? 1.0 : F(c, 1.0 / eta);
  out.push_back({path, k + 1, false, share * Fr, std::remainder(-a, 2.0 * std::numbers::pi)});
  if (!tir && Fr < 1.0)
    out.push_back({path | (std::uint64_t{1} << k), k + 1, true, share * (1.0 - Fr),
                   std::asin(std::clamp(eta * std::sin(a), -1.0, 1.0))});
}
}  // namespace detail

template <class Reflectance>
DielectricBelowPrediction kaleidoscope_dielectric_below_with(double theta_i, double theta_v, double eta,
                                                             FacetSide first, const Reflectance& F,
                                                             BelowChainSource source) {
  constexpr double pi = std::numbers::pi;
  DielectricBelowPrediction p;
  // The left facet first; the right one by mirroring (theta_i -> -theta_i, every exit angle negated).
  const double th = first == FacetSide::left ? theta_i : -theta_i;
  const double h = 0.5 * theta_v, s = 0.5 * (pi - theta_v);
  p.f_a = std::sin(h - th);  // KD-5: cos alpha_i = d . m_L, and the width across the beam
  p.lit = p.f_a > 0.0;
  if (!p.lit) return p;
  std::vector<BelowLobe>& L = p.lobes;
  // Hit 0 from medium 2 (KD-5).
  p.tir0 = detail::total_internal_reflection(p.f_a, 1.0 / eta);
  p.F0 = p.tir0 ? 1.0 : F(p.f_a, 1.0 / eta);
  // Its reflection travels at 2h - th (direction_at): down, it leaves; up, it meets the left rim.
  const double r0 = theta_v - th;
  if (p.F0 > 0.0) {
    if (std::cos(r0) > 0.0)
      detail::rim_from_below(r0, eta, 0, 1, p.F0, F, L);
    else
      L.push_back({0, 1, false, p.F0, std::remainder(r0 + pi, 2.0 * pi)});
  }
  if (!p.tir0) {
    p.alpha_t = std::asin(std::clamp(eta * std::cos(th - h), -1.0, 1.0));  // Snell: sin alpha_i = cos(th - h)
    const double cos0 = std::cos(p.alpha_t);
    // The broken source: Eq. (6)'s shadow of a rim-line beam along the chain, f_b = cos(theta_v - alpha_t).
    const double f_b = source == BelowChainSource::rim_line_beam ? std::max(0.0, std::cos(theta_v - p.alpha_t)) : 0.0;
    // KD-6: A_m = clamp(cos gamma_m / cos gamma_0, 0, 1), gamma_m = m theta_v + alpha_t.
    for (int m = 1;; ++m) {
      const double gamma = m * theta_v + p.alpha_t;
      if (!(gamma < 0.5 * pi) || !(std::cos(gamma) > 0.0)) break;
      BelowChainHit c;
      c.j = m;
      c.cos_theta = std::cos(gamma);
      c.reaching = cos0 > f_b ? std::clamp((c.cos_theta - f_b) / (cos0 - f_b), 0.0, 1.0) : 0.0;
      c.tir = detail::total_internal_reflection(c.cos_theta, eta);
      c.F = c.tir ? 1.0 : F(c.cos_theta, eta);
      if (!c.tir) {
        const double sj = (m % 2 == 1) ? 1.0 : -1.0;                                     // odd hits on the right facet
        c.theta_t = sj * (s + std::asin(std::clamp(std::sin(gamma) / eta, -1.0, 1.0)));  // KD-7
        c.direct = std::cos(c.theta_t) > 0.0;
      }
      p.hits.push_back(c);
    }
    p.n_max = static_cast<int>(p.hits.size());
    const double w = 1.0 - p.F0;
    double kept = 1.0;  // prod_{l<=n} F_l
    for (int n = 0; n <= p.n_max; ++n) {
      if (n > 0) {
        const BelowChainHit& c = p.hits[static_cast<std::size_t>(n - 1)];
        const double tj = c.tir ? 0.0 : w * c.reaching * kept * (1.0 - c.F);  // KD-7
        const std::uint64_t path = 1u | (std::uint64_t{1} << n);
        if (tj > 0.0) {
          if (c.direct)
            L.push_back({path, n + 1, false, tj, c.theta_t});
          else  // up in medium 2 along theta_t + pi (direction_at): the rim on its own side (KD-8)
            detail::rim_from_below(c.theta_t + pi, eta, path, n + 1, tj, F, L);
        }
        kept *= c.F;
      }
      // KD-6: G_n = A_n - A_{n+1} leave through the opening after n reflections, along Eq. (5)'s
      // (-1)^n (tau + n theta_v), tau = alpha_t - s the refracted direction.
      const double a_n = n == 0 ? 1.0 : p.hits[static_cast<std::size_t>(n - 1)].reaching;
      const double a_next = n == p.n_max ? 0.0 : p.hits[static_cast<std::size_t>(n)].reaching;
      const double g = w * (a_n - a_next) * kept;
      if (g > 0.0)
        L.push_back(
            {1u, n + 1, true, g, std::remainder((n % 2 == 0 ? 1.0 : -1.0) * (p.alpha_t - s + n * theta_v), 2.0 * pi)});
    }
  }
  if (first == FacetSide::right) {
    for (BelowLobe& l : L) l.theta = -l.theta;
    for (BelowChainHit& c : p.hits) c.theta_t = -c.theta_t;
    p.alpha_t = -p.alpha_t;
  }
  return p;
}

}  // namespace vgroove::analytic
