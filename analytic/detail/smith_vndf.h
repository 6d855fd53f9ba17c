// vgroove analytic: the Smith visible normals as the samplers' smith-vndf proposal, for the NDFs that
// have them (facet_strategy.h): GGX by its closed form (vndf.h, spherical caps), Student-T by the
// visible-slope inversion (vndf_student_t.h). Each a pair sample / pdf, the pdf written as
// 2 D(m) <i.m> / norm(i) with norm = 2 <i.n> (1 + Lambda(i)); flatland G1(theta_i) <i.s> D2 / cos.
#pragma once

#include "vgroove/analytic/detail/vndf_student_t.h"
#include "vgroove/analytic/vndf.h"

namespace vgroove::analytic {

inline Dir3 sample_smith_vndf(NdfKind ndf, double alpha, const Dir3& i, double u0, double u1) {
  if (ndf == NdfKind::student_t) return sample_student_t_vndf(StudentT{alpha, ndf.gamma}, i, u0, u1);
  return sample_ggx_vndf(alpha, i, u0, u1);
}
inline double smith_vndf_pdf(NdfKind ndf, double alpha, const Dir3& i, const Dir3& m) {
  if (ndf == NdfKind::student_t) return student_t_vndf_pdf(StudentT{alpha, ndf.gamma}, i, m);
  return ggx_vndf_pdf(alpha, i, m);
}
inline double smith_vndf_norm(NdfKind ndf, double alpha, const Dir3& i) {
  if (ndf == NdfKind::student_t) return student_t_vndf_norm(StudentT{alpha, ndf.gamma}, i);
  return ggx_vndf_norm(alpha, i);
}

inline double sample_smith_vndf2(NdfKind ndf, double alpha, double theta_i, double u0, double u1) {
  if (ndf == NdfKind::student_t) return sample_student_t_vndf2(StudentT{alpha, ndf.gamma}, theta_i, u0);
  return sample_ggx_vndf2(alpha, theta_i, u0, u1);
}
inline double smith_vndf2_pdf(NdfKind ndf, double alpha, double theta_i, double theta_s) {
  if (ndf == NdfKind::student_t) return student_t_vndf2_pdf(StudentT{alpha, ndf.gamma}, theta_i, theta_s);
  return ggx_vndf2_pdf(alpha, theta_i, theta_s);
}
// Smith's G1 at theta_i (the flatland pdf's factor).
inline double smith_g1(NdfKind ndf, double alpha, double theta_i) {
  if (ndf == NdfKind::student_t) return student_t_smith_g1(StudentT{alpha, ndf.gamma}, theta_i);
  return G1_smith_ggx(theta_i, alpha);
}

}  // namespace vgroove::analytic
