#include "vgroove/analytic/walter_sampling.h"

#include "vgroove/analytic/detail/smith_vndf.h"
#include "vgroove/analytic/vndf.h"
#include "vgroove/analytic/walter.h"
#include "vgroove/optics/fresnel.h"
#include "vgroove/optics/snell.h"

#include <cmath>

namespace vgroove::analytic {
namespace {

double dot(const Dir3& a, const Dir3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

bool has_smith_vndf(NdfKind ndf) { return ndf == NdfKind::ggx || ndf == NdfKind::student_t; }

}  // namespace

double walter_facet_pdf(NdfKind ndf, double alpha, const Dir3& i, const Dir3& m) {
  if (!(m.z > 0.0)) return 0.0;
  return has_smith_vndf(ndf) ? smith_vndf_pdf(ndf, alpha, i, m) : projected_ndf_pdf(ndf, alpha, m);
}

WalterSample sample_walter(NdfKind ndf, double alpha, double eta, MaskingKind g, const Dir3& i, double u0, double u1,
                           double u2) {
  WalterSample s;
  const Dir3 m =
      has_smith_vndf(ndf) ? sample_smith_vndf(ndf, alpha, i, u0, u1) : sample_projected_ndf(ndf, alpha, u0, u1);
  const double im = dot(i, m);
  if (!(im > 0.0 && m.z > 0.0)) return s;  // a facet facing away from the light (projected NDF only)
  const double F = optics::fresnel_dielectric(im, eta);
  if (u2 < F) {
    s.o = Dir3{2.0 * im * m.x - i.x, 2.0 * im * m.y - i.y, 2.0 * im * m.z - i.z};
    if (!(s.o.z > 0.0)) return s;
  } else {
    // Snell at m (optics/snell.h's formula): t = -i / eta + (cos_i / eta - cos_t) m.
    const double cos_t = optics::snell_cos_transmitted(im, eta);
    const double inv = 1.0 / eta, b = inv * im - cos_t;
    s.o = Dir3{-inv * i.x + b * m.x, -inv * i.y + b * m.y, -inv * i.z + b * m.z};
    s.transmitted = true;
    if (!(s.o.z < 0.0)) return s;
  }
  s.pdf = walter_pdf(ndf, alpha, eta, i, s.o);
  if (!(s.pdf > 0.0)) return s;  // at a facet's grazing edge the density rounds to 0
  s.ok = true;
  s.weight = walter_bsdf(i, s.o, ndf, alpha, eta, g) * std::abs(s.o.z) / s.pdf;
  return s;
}

double walter_pdf(NdfKind ndf, double alpha, double eta, const Dir3& i, const Dir3& o) {
  if (!(i.z > 0.0) || o.z == 0.0) return 0.0;
  const Dir3 h = walter_half_vector(i, o, eta);  // h_r above, h_t below (Walter Eq. 13, 16)
  const double ih = dot(i, h);
  if (o.z > 0.0) {
    if (!(ih > 0.0)) return 0.0;
    // |d omega_h / d omega_o| = 1 / (4 |o.h|), Walter Eq. (14); o.h = i.h for a reflection.
    return walter_facet_pdf(ndf, alpha, i, h) * optics::fresnel_dielectric(ih, eta) / (4.0 * ih);
  }
  const double oh = dot(o, h);
  if (!(ih > 0.0 && oh < 0.0 && h.z > 0.0)) return 0.0;
  const double F = optics::fresnel_dielectric(ih, eta);
  if (!(F < 1.0)) return 0.0;
  return walter_facet_pdf(ndf, alpha, i, h) * (1.0 - F) * walter_jacobian_t(i, o, eta);
}

}  // namespace vgroove::analytic
