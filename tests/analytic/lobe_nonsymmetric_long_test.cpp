// The longer tests of analytic/lobe_nonsymmetric.h (ctest label `long`): the lobes' quadrature
// error at the suites' options against refined runs, which is what the nonsymmetric suite's
// model_tolerance stands for (data/suites/nonsymmetric_brdf.json).
#include "vgroove/analytic/lobe_nonsymmetric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <vector>

namespace va = vgroove::analytic;

namespace {

double l1(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0.0;
  for (std::size_t n = 0; n < a.size(); ++n) s += std::abs(a[n] - b[n]);
  return s;
}

va::NonsymmetricModel model(va::NdfKind ndf, double alpha) {
  va::NonsymmetricModel m;
  m.roughness = va::isotropic_roughness(ndf, alpha);
  return m;
}

va::NonsymmetricLobeOptions refined() {
  va::NonsymmetricLobeOptions o;
  o.phi_panels = 96;
  o.partner_panels = 32;
  o.order = 4;
  o.tilt_panels = 16;
  return o;
}

// The suites' model tolerance: the lobe at the default options against a refined run, joint
// (k, bin) L1 (flatland: 90 bins; 3D: 15 x 12).
TEST(NonsymmetricLobeLong, QuadratureErrorWithinTheSuitesTolerance) {
  for (auto [ndf, alpha, ti] : {std::tuple{va::NdfKind::ggx, 0.5, 0.7}, std::tuple{va::NdfKind::beckmann, 1.0, 1.4},
                                std::tuple{va::NdfKind::ggx, 1.0, 0.0}}) {
    const va::NonsymmetricModel m = model(ndf, alpha);
    const va::FlatlandLobe a = va::flatland_nonsymmetric_lobe(m, ti, 90, 16);
    const va::FlatlandLobe b = va::flatland_nonsymmetric_lobe(m, ti, 90, 16, refined());
    EXPECT_LT(l1(a.theta_o_by_k, b.theta_o_by_k), 1e-3) << va::ndf_name(ndf) << " alpha=" << alpha << " ti=" << ti;
    const va::Lobe3d c = va::nonsymmetric_lobe_3d(m, ti, 0.0, 15, 12, 16);
    const va::Lobe3d d = va::nonsymmetric_lobe_3d(m, ti, 0.0, 15, 12, 16, refined());
    EXPECT_LT(l1(c.hist_by_k, d.hist_by_k), 3e-3) << va::ndf_name(ndf) << " alpha=" << alpha << " ti=" << ti;
  }
}

// Anisotropic, strongly (alpha_x / alpha_y = 0.1 / 1.0), along and across the axes.
TEST(NonsymmetricLobeLong, AnisotropicQuadratureError) {
  va::NonsymmetricModel m = model(va::NdfKind::beckmann, 0.1);
  m.roughness.alpha_y = 1.0;
  for (double axes : {0.0, 0.5 * 3.141592653589793}) {
    const va::Lobe3d c = va::nonsymmetric_lobe_3d(m, 0.7, axes, 15, 12, 16);
    const va::Lobe3d d = va::nonsymmetric_lobe_3d(m, 0.7, axes, 15, 12, 16, refined());
    EXPECT_LT(l1(c.hist_by_k, d.hist_by_k), 3e-3) << "axes " << axes;
  }
}

}  // namespace
