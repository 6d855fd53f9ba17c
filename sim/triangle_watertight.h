// vgroove sim: the watertight ray-triangle test in double precision.
//
// Woop, Benthin, Wald. "Watertight Ray/Triangle Intersection". Journal of Computer Graphics
// Techniques 2(1), 2013. The ray is made the z-axis of a sheared frame: kz is the axis of the
// direction's largest component, kx and ky the other two (swapped when d[kz] < 0, which keeps a
// triangle's winding), and a vertex p - org maps to (p_kx - S_x p_kz, p_ky - S_y p_kz) with
// S_x = d_kx / d_kz, S_y = d_ky / d_kz. The 2D edge functions of the sheared vertices,
//   U = C_x B_y - C_y B_x,   V = A_x C_y - A_y C_x,   W = B_x A_y - B_y A_x,
// are the scaled barycentric weights of A, B, C. Why no ray slips between two triangles: a shared
// edge's vertices are sheared by the same operations in both (the same doubles), and its edge
// function in the neighbour is the same two products subtracted the other way round, so it is
// exactly the negation (a - b = -(b - a) in IEEE arithmetic): a ray is strictly inside one, or
// exactly 0 in both. Zeros count as inside, so a ray through an edge hits both triangles and a ray
// through a vertex hits all around it; the caller sees which weights are exactly 0 (an edge or a
// vertex hit) and decides once. No epsilon anywhere. The products must not be fused into
// additions (sim/ builds with -ffp-contract=off): a fused C_x B_y - C_y B_x would round the two
// orders differently.
//
// Facing: with the swap, det = U + V + W > 0 exactly when the ray meets the triangle from the side
// its counter-clockwise winding faces (for the heightfield's triangles, from above: d . n < 0);
// det == 0 is a ray in the triangle's plane (no hit). The distance is t = T / det,
// T = U A_z + V B_z + W C_z with the z coordinates scaled by S_z = 1 / d_kz.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <utility>

namespace vgroove::sim {

struct WatertightRay {
  Eigen::Vector3d org;
  int kx = 0, ky = 1, kz = 2;
  double Sx = 0.0, Sy = 0.0, Sz = 1.0;
};

inline WatertightRay make_watertight_ray(const Eigen::Vector3d& org, const Eigen::Vector3d& d) {
  WatertightRay r;
  r.org = org;
  const Eigen::Vector3d a = d.cwiseAbs();
  r.kz = a.x() > a.y() ? (a.x() > a.z() ? 0 : 2) : (a.y() > a.z() ? 1 : 2);
  r.kx = (r.kz + 1) % 3;
  r.ky = (r.kx + 1) % 3;
  if (d[r.kz] < 0.0) std::swap(r.kx, r.ky);
  r.Sx = d[r.kx] / d[r.kz];
  r.Sy = d[r.ky] / d[r.kz];
  r.Sz = 1.0 / d[r.kz];
  return r;
}

// The unnormalized result: weights U, V, W (of the vertices a, b, c), det and T (t = T / det).
struct WatertightHit {
  double U = 0.0, V = 0.0, W = 0.0, det = 0.0, T = 0.0;
  double t() const { return T / det; }
  // Exactly zero weights: 0 an interior hit, 1 an edge, 2 a vertex.
  int zeros() const { return (U == 0.0) + (V == 0.0) + (W == 0.0); }
};

// A front-facing hit (det > 0) at 0 < t < t_max, or false. U, V, W >= 0 on a hit.
inline bool intersect_watertight(const WatertightRay& r, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                 const Eigen::Vector3d& c, double t_max, WatertightHit& hit) {
  const Eigen::Vector3d A = a - r.org, B = b - r.org, C = c - r.org;
  const double Ax = A[r.kx] - r.Sx * A[r.kz], Ay = A[r.ky] - r.Sy * A[r.kz];
  const double Bx = B[r.kx] - r.Sx * B[r.kz], By = B[r.ky] - r.Sy * B[r.kz];
  const double Cx = C[r.kx] - r.Sx * C[r.kz], Cy = C[r.ky] - r.Sy * C[r.kz];
  const double U = Cx * By - Cy * Bx;
  const double V = Ax * Cy - Ay * Cx;
  const double W = Bx * Ay - By * Ax;
  if (U < 0.0 || V < 0.0 || W < 0.0) return false;  // back faces (all <= 0) are not hits either
  const double det = U + V + W;
  if (!(det > 0.0)) return false;
  const double T = U * (r.Sz * A[r.kz]) + V * (r.Sz * B[r.kz]) + W * (r.Sz * C[r.kz]);
  if (!(T > 0.0) || !(T / det < t_max)) return false;
  hit = WatertightHit{U, V, W, det, T};
  return true;
}

}  // namespace vgroove::sim
