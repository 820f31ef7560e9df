// Angle-weighted vertex normals (Thürmer and Wüthrich 1998): n_v = normalize(Σ θ_f n_f) over the
// faces f around v, with θ_f the face's angle at v and n_f its unit normal (by its winding). The
// curvature gather (curvature.cpp) computes the same normal with the same per-corner term, so
// meshes shaded with or without curvature get the same normals (to round-off where the gather's
// AVX2 copy runs with fused multiply-adds).
#pragma once

#include "analyzer/geometry_tolerances.hpp"
#include "analyzer/lanes.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace toonwater {

// atan2(y, x) for y >= 0 by a polynomial, absolute error below 1e-5 rad: plenty for a weight,
// and several times cheaper than std::atan2. For a double or vector lanes (lanes.hpp), with the
// same bits in each lane as for a double.
template <class Real>
[[gnu::always_inline]] inline Real approximate_angle(Real y, Real x) {
  const Real ax = absolute(x);
  const Real ratio =
      minimum(ax, y) / maximum(maximum(ax, y), splat<Real>(std::numeric_limits<double>::min()));
  const Real r2 = ratio * ratio;
  Real angle =
      ratio * (0.99997726 +
               r2 * (-0.33262347 +
                     r2 * (0.19354346 + r2 * (-0.11643287 + r2 * (0.05265332 - r2 * 0.01172120)))));
  angle = select(y > ax, std::numbers::pi / 2 - angle, angle);
  return select(x < 0.0, std::numbers::pi - angle, angle);
}

// One face's term θ n_f at the corner x of face (x, a, b), axis by axis, given xa × xb, its
// length, xa · xb and the face's longest squared edge (xa = a − x, xb = b − x): zero for a
// degenerate face (geometry_tolerances.hpp), which has no usable normal. For doubles, or two or
// four faces in vector lanes (the curvature's face pass).
template <class Real>
[[gnu::always_inline]] inline void corner_normal_term(const Real (&cross)[3], Real double_area,
                                                      Real dot, Real longest2, Real (&term)[3]) {
  const auto degenerate = is_degenerate_triangle(double_area, longest2);
  // Times the reciprocal, which the curvature's face pass needs as well and computes once.
  const Real weight = approximate_angle(double_area, dot) * (1.0 / double_area);
  for (int axis = 0; axis < 3; ++axis)
    term[axis] = select(degenerate, Real{}, weight * cross[axis]);
}

inline Vec3 corner_normal_term(const Vec3& xa, const Vec3& xb) {
  const Vec3 c = xa.cross(xb);
  const double cross[3] = {c.x(), c.y(), c.z()};
  double term[3];
  corner_normal_term(cross, c.norm(), xa.dot(xb),
                     std::max({xa.squaredNorm(), xb.squaredNorm(), (xb - xa).squaredNorm()}), term);
  return Vec3(term[0], term[1], term[2]);
}

// Unit normals per vertex; zero where no face has a usable normal.
std::vector<Vec3> angle_weighted_normals(const TriangleMesh& mesh, const VertexFaces& vertex_faces);

}  // namespace toonwater
