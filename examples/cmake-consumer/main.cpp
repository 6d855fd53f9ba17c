// A renderer developer's view of vgroove: evaluate the validated multiple-scattering BRDF, then
// hold two BRDFs against vgroove's exact simulation of a rough V-groove surface: vgroove's own
// (which passes) and Cook-Torrance with the V-cavity G (which loses energy at high roughness and
// fails). Exit status 0 when both verdicts are as expected.
#include <vgroove/analytic/brdf_3d.h>
#include <vgroove/validation/check_brdf.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace va = vgroove::analytic;
namespace vv = vgroove::validation;

int main() {
  const double alpha = 1.0;
  const auto ndf = vgroove::NdfKind::ggx;
  constexpr double deg = std::numbers::pi / 180.0;

  // One evaluation: light 30 deg from the normal, looking back 40 deg on the other side.
  const va::Dir3 wi = va::dir3(30 * deg, std::numbers::pi), wo = va::dir3(40 * deg, 0.0);
  std::printf(
      "GGX alpha %.1f, theta_i 30, theta_o 40, phi_o 0 deg: vgroove %.6f /sr (k = 1: %.6f), "
      "Cook-Torrance %.6f /sr\n",
      alpha, va::vgroove_brdf(wi, wo, ndf, alpha, 1'000'000), va::vgroove_brdf_k(wi, wo, 1, ndf, alpha),
      va::cook_torrance(wi, wo, ndf, alpha));

  vv::CheckBrdfOptions opt;
  opt.ndf = ndf;
  opt.alpha = alpha;
  opt.theta_i_deg = {0, 45};
  opt.rays = 100'000;
  opt.grooves = 50'000;

  const vv::CheckBrdfResult ours = vv::check_brdf(
      [&](const va::Dir3& i, const va::Dir3& o) { return va::vgroove_brdf(i, o, ndf, alpha, 1'000'000); }, opt);
  const vv::CheckBrdfResult ct =
      vv::check_brdf([&](const va::Dir3& i, const va::Dir3& o) { return va::cook_torrance(i, o, ndf, alpha); }, opt);
  for (const auto* r : {&ours, &ct}) {
    std::printf("%s:\n", r == &ours ? "vgroove multiple scattering" : "Cook-Torrance (V-cavity G)");
    for (const auto& c : r->cases)
      std::printf("  theta_i %4.1f deg: albedo %.4f (traced %.4f, allowed +-%.4f), L1 %.4f (allowed %.4f): %s\n",
                  c.theta_i_deg, c.albedo_model, c.albedo_sim, c.albedo_threshold, c.l1, c.l1_threshold,
                  c.pass ? "pass" : "FAIL");
  }
  const bool expected = ours.pass && !ct.pass;
  std::printf("%s\n", expected ? "as expected: vgroove passes, Cook-Torrance fails" : "UNEXPECTED verdicts");
  return expected ? 0 : 1;
}
