// vgroove sim: the watertight ray-triangle test in double precision. Woop, Benthin, Wald,
// "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013: the ray is the z-axis of a sheared
// frame and the 2D edge functions U, V, W of the sheared vertices are the scaled barycentric
// weights. A shared edge's edge function in the neighbour is exactly the negation, so no ray slips
// between two triangles; zeros count as inside and the caller sees which weights are exactly 0
// (an edge or a vertex hit). No epsilon anywhere; sim/ builds with -ffp-contract=off, which this
// relies on. det = U + V + W > 0 exactly when the ray meets the counter-clockwise front face.
// Tests: tests/sim/triangle_watertight_test.cpp (TriangleWatertight.HandValuesOfAVerticalRay,
// TriangleWatertight.FrontFacingIsDetPositive, TriangleWatertight.NoRaySlipsThroughASharedEdge).
// Derivation: docs/derivations/heightfield.md.
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
