// vgroove analytic: Eq. (16)-(17) summed over k in one pass, the facet solutions evaluated four
// at a time without branches.
//
// The same terms as the per-solution pass (brdf_3d.cpp, vgroove_brdf_per_solution_reference):
// the same solutions theta_v = X / k of Eq. (5) (the same bits), the same Eq. (4) test
// (outcome_possible), the same ends and sine arguments of the width of Eq. (6) (beam_width;
// all three in kaleidoscope_solutions.h).
// What changes is how the work is arranged, since a loop over solutions spends its time on
// unpredictable branches, on divisions a branch waits for, and on library sines:
//   - the four families (facet hit first x parity of k) are the lanes of a vector (GCC/clang
//     vector extensions; an AVX2 copy is picked at start-up, the generic one uses SSE2 pairs);
//     each family's candidates k run from k_lo of its parity (for_each_solution's lower bound
//     ceil(X / pi) - 1 is at most 1, X = a - b + pi < 2 pi) while k m <= X, a division-free
//     bound that keeps exactly the k outcome_possible can accept (see below);
//   - the first two candidates of each family are packed into lanes by a table (one vector for
//     three in four pairs at max_k 4), further ones (max_k > 4) four at a time;
//   - per vector every lane is computed and masked: theta_v and Eq. (4); sin and cos of the
//     half-aperture by polynomials (sin_batch.h, within 2 ulp); the width's ends and form by
//     selects; its one remaining sine (where the outcome's lower end is 0 or its two ends come
//     from different offsets) by the polynomial at the same argument; for GGX, D and the term;
//   - Beckmann's exp by a polynomial (exp_batch, exp_log_batch.h): in every lane (BeckmannTails::vector,
//     below), or where tan^2 / alpha^2 <= 32 (exact); the exact mode's other lanes, Phong's power
//     and the Fresnel product run over the live lanes one at a time;
//   - the factors common to every term, c / (4 (i.h) cos_i cos_o) and 1 / sin(theta_h), are
//     formed once, off the terms' path;
//   - only j = 0 of Eq. (5) is enumerated: for j = +-1, |X - span| = |2 pi j - (a + b)| > pi
//     while theta_v <= pi needs X / k <= pi, so Eq. (4)'s k |X - span| <= X fails by far more
//     than rounding unless |a + b| is within 1e-9 of pi (both directions grazing); such pairs go
//     to the per-solution pass.
// The angles t_i, t_o are the frame's: the width's sine arguments and theta_v = X / k keep their
// bits, so in the library's frame (groove_frame) the only differences from the per-solution pass
// are the polynomial sines (2 ulp, relative) and the order of products. Two D amplify the ulp of
// theta_m's sine and cosine: Phong's cos^p theta_m, p = 2 / alpha^2 - 2, by p (2e-12 at
// alpha = 0.01), and Beckmann's exp(-tan^2 theta_m / alpha^2) by 2 tan^2 / alpha^2 (up to
// 1500). Phong always takes them from std::sin and std::cos, as the per-solution pass does.
// Beckmann has two modes (BeckmannTails, brdf_3d_passes.h):
//   - exact (in groove_frame): the lanes where tan^2 / alpha^2 > 32 from std::sin, std::cos
//     and std::exp;
//   - vector (in groove_frame_fast, brdf_range): every lane from the polynomials, and with it
//     a bound on how far the sum can be from the per-solution pass. In a term, x = tan^2 / alpha^2
//     moves by 2 x d / (sin cos) when theta_m moves by d, and the fast frame's angles are within
//     ~5 ulp of the library's (atan2_pair's 3, atan2's 1, the frame's roundings): d <= 1.1e-15 / k
//     (|t| < pi / 2); the polynomial sines move x by <= 1.3e-15 x relative, and exp and the
//     products add a few ulp. A term is then within 2.2e-15 y + 1.3e-15 x + 1e-15 ~ 3e-15 y + 1e-15
//     of the per-solution pass's, y = x / (sin cos) = cos / (sin^3 alpha^2) >= 2 x (sin and cos
//     of the half-aperture). The pass keeps the terms' y-weighted sum beside their sum and
//     declines (NaN) a pair whose weighted mean y exceeds 64 (a deviation of up to ~2e-13; the
//     lobe's far tail, where brdf_range evaluates it again in exact mode), and a pair with a
//     term whose exponent is below -708 (exp under 2^-1022, left out: under ~1e-300 W / sin_h)
//     unless the sum is far above such a term; and pairs with both directions grazing.
//
// Values: the same as the per-solution pass within 1e-12 relative (tests/analytic/brdf_3d_test.cpp,
// BatchedPassEqualsPerSolutionPass). Cost: bench/brdf_bench.cpp.
#include "vgroove/analytic/brdf_3d_passes.h"
#include "vgroove/analytic/exp_log_batch.h"
#include "vgroove/analytic/kaleidoscope_solutions.h"
#include "vgroove/analytic/ndf_visit.h"
#include "vgroove/analytic/sin_batch.h"
#include "vgroove/common/simd.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>

namespace vgroove::analytic::brdf_passes {

namespace {

// Four doubles (common/simd.h): the families (left facet odd k, left even, right odd, right
// even; ends_of) or four candidates. Comparisons give masks of 64-bit integers.
using V = simd::V4;
using simd::select;
using simd::splat;

// The packing of up to eight candidates into lanes: candidate c = 4 w + f is family f's
// k_first + 2 w (w = 0, 1); for each 8-bit set of kept candidates, the kept ones in order.
struct PackTable {
  signed char c[256][8];
  constexpr PackTable() : c{} {
    for (int m = 0; m < 256; ++m) {
      int n = 0;
      for (int b = 0; b < 8; ++b)
        if (m & (1 << b)) c[m][n++] = static_cast<signed char>(b);
    }
  }
};
constexpr PackTable kPack;

// A vector's outcomes, per lane.
struct Slots {
  double k[4], half[4];       // k, theta_v / 2
  double cos_m[4], sin_m[4];  // cos(theta_m) = sin(theta_v/2), sin(theta_m) = cos(theta_v/2)
  double W[4];                // the width G f_a of Eq. (6), 0 where the lane holds no outcome
  bool left[4];               // the facet hit first
};

// The terms of the live slots that need D evaluated one at a time (Beckmann, Phong, Fresnel).
void add_terms(const GrooveFrame& p, const Slots& sl, NdfKind ndf, double alpha, const FresnelFn& F, double& sum_1,
               double& sum_k) {
  int live[4], n = 0;
  for (int s = 0; s < 4; ++s) {
    live[n] = s;
    n += sl.W[s] > 0.0;
  }
  for (int m = 0; m < n; ++m) {
    const int s = live[m];
    const double C = sl.sin_m[s], k = sl.k[s];
    double S_D = sl.cos_m[s], C_D = C;  // cos and sin of theta_m for D
    if (ndf == NdfKind::phong) {
      S_D = std::sin(sl.half[s]);
    } else if (ndf == NdfKind::student_t) {
      // D = y^gamma turns the polynomial's ulp of tan theta_m into up to 2 gamma ulp: std::sin, std::cos.
      S_D = std::sin(sl.half[s]);
      C_D = std::cos(sl.half[s]);
    } else if (ndf == NdfKind::beckmann && C * C > 32.0 * alpha * alpha * (S_D * S_D)) {
      // exp(-x), x = tan^2 / alpha^2 > 32, turns the polynomial's ulp into x ulp: std::sin, std::cos.
      S_D = std::sin(sl.half[s]);
      C_D = std::cos(sl.half[s]);
    }
    double t = sl.W[s] * D_cs(ndf, S_D, C_D, alpha);
    if (F) {
      const FacetSide side = sl.left[s] ? FacetSide::left : FacetSide::right;
      const double theta_m = 0.5 * (std::numbers::pi - 2.0 * sl.half[s]);  // as solution_term's
      t *= fresnel_along_path(F, p.x.t_i, theta_m, side, static_cast<int>(k), p.c);
    }
    if (k == 1.0) {
      sum_1 += t;
    } else {
      sum_k += C * t / k;
    }
  }
}

}  // namespace

// A vector per instruction in the AVX2 copy (common/simd.h).
VGROOVE_TARGET_CLONES
double brdf_batched(const GrooveFrame& p, double cos_i, double cos_o, int k_lo, int k_hi, NdfKind ndf, double alpha,
                    const FresnelFn& F, BeckmannTails tails) {
  constexpr double pi = std::numbers::pi;
  const V zero = splat(0.0), one = splat(1.0);
  // Lee et al. 2018, Eq. (16) with the Jacobian of Eq. (13): each term is |i.s| G = c W times D
  // and the ratio sin(theta_s) / sin(theta_h) / k (1 for k = 1: s = h, Eq. 25), over
  // 4 (i.h) cos_i cos_o; the factors common to every term are formed here, off the terms' path.
  const double common = p.c / (4.0 * p.cos_d * (cos_i * cos_o)), inv_sin_h = 1.0 / p.sin_h;
  const double ggx_norm = alpha * alpha / std::numbers::pi;  // D_cs's alpha^2 / pi, for GGX
  // The families, one per lane: a = m t_i, b = (-1)^k m t_o, m = +-1 for left/right (ends_of).
  const V m_a = {1.0, 1.0, -1.0, -1.0}, m_b = {-1.0, 1.0, 1.0, -1.0};
  const V fa = splat(p.x.t_i) * m_a, fb = splat(p.x.t_o) * m_b;
  // Both directions grazing: the j = +-1 solutions need the per-solution pass (header).
  const auto grazing = !(pi - select(fa + fb < 0.0, -(fa + fb), fa + fb) > 1e-9);
  const bool beckmann = ndf == NdfKind::beckmann && !F;
  const bool beckmann_vector = beckmann && tails == BeckmannTails::vector;
  if (simd::any(grazing)) {
    if (beckmann_vector) return std::numeric_limits<double>::quiet_NaN();
    return brdf_per_solution(p, cos_i, cos_o, k_lo, k_hi, ndf, alpha, F);
  }
  // Each family's k that can pass outcome_possible, from k_first in steps of 2 (its parity):
  //  - k_first: k_lo of the lane's parity (for_each_solution's ceil(X / pi) - 1 is at most 1 for
  //    X = a - b + pi < 2 pi); k = 1 only for the left facet (s = h, kaleidoscope_solutions.h);
  //  - up to k_hi and while k m <= X, m = max(|X - span|, 2a, -2b): outcome_possible's
  //    k |X - span| <= X (Eq. 4 for the path and its reverse, whose span differs from X by
  //    a + b as well), theta_v > 2a and theta_v > -2b. Its comparisons hold up to rounding of
  //    relative size ~k eps X / |X - span|, so the test carries a slack of 1e-8 relative and
  //    ignores |X - span| below 1e-6; a k beyond it fails outcome_possible by far more than
  //    rounding. Every k kept is then checked by outcome_possible itself, below.
  const V X = (fa - fb) + pi, span = pi + 2.0 * fa;
  const V dev = select(X - span < 0.0, span - X, X - span);
  const V m1 = select(dev > 1e-6, dev, zero), m2 = select(fa > -fb, 2.0 * fa, -2.0 * fb);
  const V m = select(m1 > m2, m1, m2), X_slack = X * (1.0 + 1e-8);
  const V k_hi_v = splat(k_hi);
  const double k_odd = k_lo % 2 == 1 ? k_lo : k_lo + 1, k_even = k_lo % 2 == 0 ? k_lo : k_lo + 1;
  V k_first = {k_odd, k_even, k_odd, k_even};
  k_first = select((k_first == 1.0) & (m_a < 0.0), k_first + 2.0, k_first);
  auto in_range = [&](V k) __attribute__((always_inline)) { return (k <= k_hi_v) & (k * m <= X_slack); };
  const auto keep_0 = in_range(k_first), keep_2 = in_range(k_first + 2.0), keep_4 = in_range(k_first + 4.0);
  // The candidates (family, k): k_first and k_first + 2 of each family where in range, packed
  // into lanes by a table (no branch per candidate).
  int kept = 0;
  for (int f = 0; f < 4; ++f) kept |= static_cast<int>(keep_0[f] & 1) << f | static_cast<int>(keep_2[f] & 1) << (f + 4);
  const int n = __builtin_popcount(static_cast<unsigned>(kept));
  const bool more = simd::any(keep_4);
  const V kf0 = splat(k_first[0]), kf1 = splat(k_first[1]), kf2 = splat(k_first[2]), kf3 = splat(k_first[3]);
  const bool ggx = ndf == NdfKind::ggx && !F;
  const double beckmann_norm = std::numbers::pi * alpha * alpha;  // D_cs's pi alpha^2, for Beckmann
  const double inv_beckmann_norm = 1.0 / beckmann_norm, inv_alpha2 = 1.0 / (alpha * alpha);
  V t_1 = zero, t_k = zero;     // GGX: the terms without the common factors (k = 1, k >= 2)
  V y_1 = zero, y_k = zero;     // Beckmann vector: the terms times y (header)
  auto underflow = V{} < zero;  // Beckmann vector: a live lane's exponent below -708
  double sum_1 = 0.0;           // k = 1: W D (F)
  double sum_k = 0.0;           // k >= 2: sin(theta_m) / k W D (F)
  Slots sl;
  // A vector of up to four candidates: k and family f per lane, the first `count` lanes live.
  // Inlined: a lambda is its own function, which would not be compiled for AVX2 with this one.
  auto run = [&](V k, V f, int count) __attribute__((always_inline)) {
    const V lane = {0.0, 1.0, 2.0, 3.0};
    const auto left = f < 1.5, odd = (f == 0.0) | (f == 2.0);
    const V sa = select(left, one, -one), sb = select((f == 0.0) | (f == 3.0), -one, one);
    // ends_of, lane by lane (products by +-1 are exact).
    const V a = splat(p.x.t_i) * sa, b = splat(p.x.t_o) * sb;
    const V sin_a = splat(p.x.sin_ti) * sa, sin_b = splat(p.x.sin_to) * sb;
    const V cos_a = splat(p.x.cos_ti), cos_b = splat(p.x.cos_to);
    const V chd2 = 2.0 * select(odd, splat(p.x.cos_half_sum), splat(p.x.cos_half_diff));  // 2 cos((a - b)/2)
    const V chs = select(odd, splat(p.x.cos_half_diff), splat(p.x.cos_half_sum));         // cos((a + b)/2)
    const V Xk = (a - b) + pi;
    const V theta_v = Xk / k;  // solution_theta_v(d, 0, k), bitwise
    // outcome_possible, every comparison made.
    const V span_k = pi + 2.0 * a, span_rev = pi - 2.0 * b;
    const V below = (k - 1.0) * theta_v, above = (k + 1.0) * theta_v;
    const auto valid = (lane < count) & (theta_v > 0.0) & (theta_v <= pi) & (theta_v > 2.0 * a) & (theta_v > -2.0 * b) &
                       (below <= span_k) & (span_k < above) & (below <= span_rev) & (span_rev < above);
    // theta_v in (0, 2 pi) in every lane (X < 2 pi, k >= 1); in (0, pi] where the lane is valid.
    const V half = 0.5 * theta_v;
    V S, C;
    sin_cos_quadrant(half, S, C);
    // beam_width with selects: the width is value, or factor sin(arg).
    const V f_a = S * cos_a - C * sin_a;      // sin(theta_v/2 - a)
    const V g_lo = S * cos_b + C * sin_b;     // sin(theta_v/2 + b)
    const V f_b = -(S * cos_a + C * sin_a);   // -sin(theta_v/2 + a)
    const V g_hi = -(S * cos_b - C * sin_b);  // -sin(theta_v/2 - b)
    const V fb_gh = select(f_b > g_hi, f_b, g_hi);
    const V lower = select(fb_gh > 0.0, fb_gh, zero);  // std::max(0, std::max(f_b, g_hi))
    const auto k1 = k == 1.0;
    const auto upper_a = f_a <= g_lo;
    const auto low_zero = lower == 0.0, low_fb = f_b >= g_hi;
    // k = 1: the smaller of the two (equal) upper ends, std::min(f_a, g_lo); else the chosen one.
    const V upper = select(k1, select(g_lo < f_a, g_lo, f_a), select(upper_a, f_a, g_lo));
    const auto live = valid & (upper > lower);
    const V two_s_cos = 2.0 * S * select(low_fb, cos_a, cos_b);
    // k >= 2 takes a sine where the lower end is 0 or the two ends come from different offsets.
    const auto sine = ~k1 & (low_zero | (low_fb ^ upper_a));
    const V value = select(k1 & low_zero, chs, two_s_cos);
    const V ab2 = 0.5 * (a + b);
    const V arg = select(low_zero, select(upper_a, half - a, half + b), select(low_fb, half + ab2, half - ab2));
    const V factor = select(low_zero, one, chd2);
    // A dead lane's sine argument is replaced by 0 (inside the polynomial's range).
    const V sine_value = factor * sin_full(select(live & sine, arg, zero));
    const V w = select(live, select(sine, sine_value, value), zero);
    const V W = select(w > 0.0, w, zero);
    if (ggx) {
      // GGX's D = alpha^2 / (pi q^2) (ndf_ggx.h) without alpha^2 / pi, and sin(theta_m) / k for
      // k >= 2. (The quotient does not wait for the width.)
      const V qd = Ggx{alpha}.q(S, C);
      const V t = W * (select(k1, one, C) / (qd * qd * k));
      t_1 += select(k1, t, zero);
      t_k += select(k1, zero, t);
      return;
    }
    V W_scalar = W;  // the lanes add_terms takes
    if (beckmann_vector) {
      // Every lane from the polynomials (header), with one quotient, r = 1 / (S^2 k), S = cos
      // theta_m and C = sin theta_m: x = C^2 r k / alpha^2, the term W D (C / k for k >= 2) =
      // W exp(-x) r^2 k (C for k >= 2) / (pi alpha^2), y = C / (S^3 alpha^2) = (C / alpha^2) r k (S r k).
      const V S_live = select(live, S, one);
      const V r = one / ((S_live * S_live) * k), rk = r * k;
      const V x = (C * C) * rk * inv_alpha2;
      const auto under = live & ~(x <= 708.0);
      underflow |= under;
      const V e = batch::exp_batch(select(under, zero, -x));
      const V term = select(live & ~under, W, zero) * e * (rk * r) * select(k1, one, C) * inv_beckmann_norm;
      t_1 += select(k1, term, zero);
      t_k += select(k1, zero, term);
      const V y = (C * inv_alpha2) * rk * (S_live * rk);
      y_1 += select(k1, term * y, zero);
      y_k += select(k1, zero, term * y);
      return;
    }
    if (beckmann) {
      // Beckmann's D (ndf_beckmann.h) with exp by the polynomial, where tan^2 / alpha^2 <= 32; the
      // other lanes (add_terms' exact sines) one at a time.
      const auto exact = C * C > 32.0 * alpha * alpha * (S * S);
      const auto here = live & ~exact;
      const V S_here = select(here, S, one);  // other lanes' D stay finite
      const V w_d = select(here, W, zero) * Beckmann{alpha}.D_cs(S_here, C);
      t_1 += select(k1, w_d, zero);
      t_k += select(k1, zero, C * w_d / k);
      W_scalar = select(exact, W, zero);
      if (!(W_scalar[0] > 0.0 || W_scalar[1] > 0.0 || W_scalar[2] > 0.0 || W_scalar[3] > 0.0)) return;
    }
    for (int l = 0; l < 4; ++l) {
      sl.k[l] = k[l];
      sl.half[l] = half[l];
      sl.cos_m[l] = S[l];
      sl.sin_m[l] = C[l];
      sl.W[l] = W_scalar[l];
      sl.left[l] = f[l] < 1.5;
    }
    add_terms(p, sl, ndf, alpha, F, sum_1, sum_k);
  };
  // The packed candidates, four per vector (lanes past the count hold candidate 0: masked).
  for (int j = 0; j < n; j += 4) {
    typedef signed char C4 __attribute__((vector_size(4)));
    C4 c4;
    std::memcpy(&c4, &kPack.c[kept][j], sizeof c4);
    const V c = __builtin_convertvector(c4, V);
    const V w = select(c >= 4.0, one, zero), f = c - 4.0 * w;
    const V k_f = select(f == 0.0, kf0, select(f == 1.0, kf1, select(f == 2.0, kf2, kf3)));
    run(k_f + 2.0 * w, f, n - j);
  }
  if (more) {
    // Families with more than two k (max_k > 4): the rest, four at a time.
    for (int f = 0; f < 4; ++f) {
      const double k_top = k_hi, m_f = m[f], X_f = X_slack[f];
      for (double k = k_first[f] + 4.0; k <= k_top && k * m_f <= X_f;) {
        // Lanes past the count hold k_first of the family: masked.
        double ks[4] = {k_first[f], k_first[f], k_first[f], k_first[f]};
        int count = 0;
        for (; count < 4 && k <= k_top && k * m_f <= X_f; ++count, k += 2.0) ks[count] = k;
        run(V{ks[0], ks[1], ks[2], ks[3]}, splat(f), count);
      }
    }
  }
  if (ggx) {
    sum_1 = ((t_1[0] + t_1[1]) + (t_1[2] + t_1[3])) * ggx_norm;
    sum_k = ((t_k[0] + t_k[1]) + (t_k[2] + t_k[3])) * ggx_norm;
  } else if (beckmann) {
    sum_1 += (t_1[0] + t_1[1]) + (t_1[2] + t_1[3]);
    sum_k += (t_k[0] + t_k[1]) + (t_k[2] + t_k[3]);
    if (beckmann_vector) {
      // Declined (header): the weighted mean of y above 64; a term left out (exponent below
      // -708) and the sum not far above it.
      const double sum = sum_1 + sum_k * inv_sin_h;
      const double y_sum =
          ((y_1[0] + y_1[1]) + (y_1[2] + y_1[3])) + ((y_k[0] + y_k[1]) + (y_k[2] + y_k[3])) * inv_sin_h;
      const bool under = simd::any(underflow);
      if (!(y_sum <= kBeckmannMeanAmplification * sum) || (under && !(sum > 1e-270 * std::max(1.0, inv_sin_h)))) {
        return std::numeric_limits<double>::quiet_NaN();
      }
    }
  }
  return (sum_1 + sum_k * inv_sin_h) * common;
}

}  // namespace vgroove::analytic::brdf_passes
