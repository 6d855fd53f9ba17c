// vgroove analytic: Kulla and Conty 2017's energy compensation of rough glass as DreamWorks MoonRay
// ships it (TransmissionCookTorranceEnergyCompensation.cc, Fresnel.h at commit 7330447a9fc2): a
// Kelemen-style lobe (1 - E(mu_i))(1 - E(mu_o)) / (pi (1 - E_avg)) added to reflection and to
// transmission, the missing energy split between them by x = t / (1 + t), and Kulla's F_avg fits.
// Flux convention of albedo_glass.h: light from i on the near side, eta = n_far / n_near; MoonRay's
// view direction wo is this i (its lobes carry the light side's index squared). Fed with exact E
// and F_avg, from outside (eta > 1) R' + T' = 1; from inside MoonRay's n^2 = eta^2 on the
// transmitted weight loses energy and breaks T_avg(eta) = eta^2 T_avg(1 / eta) (as derived in the doc).
// Tests: tests/analytic/compensation_glass_test.cpp (KullaContyGlass.FresnelFitsAgainstExactAverage,
// KullaContyGlass.ExactFresnelAverageKeepsTheFlatInterfaceIdentity, KullaContyGlass.WeightsByHand,
// KullaContyGlass.OutsideSumsToOneInsideLosesTheScale,
// KullaContyGlass.InsideScaleBreaksTheTransmittedReciprocity, KullaContyGlass.ExtremesAreFinite).
// Derivation, sources and measured errors: docs/derivations/energy_compensation.md.
#pragma once

#include "vgroove/analytic/albedo_single.h"

namespace vgroove::analytic {

// Kulla's fits of the dielectric Fresnel average F_avg = 2 int F(mu) mu dmu, N = n_high / n_low:
// lit from the lower index, (N - 1) / (4.08567 + 1.00071 N); lit from the higher, a cubic in r =
// 1 / N: 0.997118 + 0.1014 r - 0.965241 r^2 - 0.130607 r^3 (MoonRay's argument order).
double kulla_fresnel_average_outside_fit(double N);
double kulla_fresnel_average_inside_fit(double r);
// The exact average of optics' dielectric F(mu, eta), any eta > 0, cut at the critical cosine.
BoundedValue dielectric_fresnel_average(double eta, const AlbedoOptions& opt = {});

// What the form reads of one interface: out = lit from the lower index (eta = N > 1), in = lit
// from the higher (eta = 1 / N). E_avg = R_avg + T_avg of that side (albedo_glass_average).
struct KullaContyGlassAverages {
  double N = 1.5;
  double E_avg_out = 1.0, E_avg_in = 1.0;
  double F_avg_out = 0.0, F_avg_in = 0.0;
};
// (a) exact E_avg and exact F_avg; (b) the same E_avg with Kulla's fits for F_avg.
KullaContyGlassAverages kulla_conty_glass_averages_exact(const MicrofacetModel& m, double alpha, double N,
                                                         const AlbedoOptions& opt = {});
KullaContyGlassAverages with_kulla_fresnel_fits(KullaContyGlassAverages a);

// MoonRay's split x = t / (1 + t), t = N^2 (1 - E_avg_in)(1 - F_avg_in) / ((1 - E_avg_out)(1 - F_avg_out));
// E_avg_out = 1 gives 1 (its guard). with_N2 = false: t without N^2 (what MoonRay's inside scale n^2
// would need for the reciprocity of the transmitted averages; it still loses energy from inside).
double kulla_conty_glass_split(const KullaContyGlassAverages& a, bool with_N2 = true);

// The compensation's reflected and transmitted flux fractions per unit missing energy (1 - E(mu)),
// lit with eta (N or 1 / N): outside reflect = 1 - (1 - F_out) x, transmit = (1 - F_out) x; inside
// reflect = 1 - (1 - F_in)(1 - x), transmit = n^2 (1 - F_in)(1 - x), n = eta (MoonRay's etaT / etaI).
enum class KullaContyGlassForm { moonray, inside_scale_one };
struct KullaContyGlassWeights {
  double reflect = 0.0, transmit = 0.0;
};
// split_with_N2 = false: the weights from t without N^2 (a variant the tests keep to see checks fail).
KullaContyGlassWeights kulla_conty_glass_weights(double eta, const KullaContyGlassAverages& a,
                                                 KullaContyGlassForm form = KullaContyGlassForm::moonray,
                                                 bool split_with_N2 = true);

// The lobes (flux convention): f_R = w.reflect (1 - E_i)(1 - E_o) / (pi (1 - E_avg_near)), o on the
// near side; f_T = w.transmit (1 - E_i)(1 - E_o') / (pi (1 - E_avg_far)), E_o' the far side's E.
double kulla_conty_glass_f_ms(double weight, double E_i, double E_o, double E_avg_of_o_side);

// The compensated directional albedos at mu: R' = E_R + w.reflect (1 - E), T' = E_T + w.transmit (1 - E).
struct CompensatedGlass {
  double R = 0.0, T = 0.0;
};
CompensatedGlass kulla_conty_glass_albedo(double E_R, double E_T, const KullaContyGlassWeights& w);

}  // namespace vgroove::analytic
