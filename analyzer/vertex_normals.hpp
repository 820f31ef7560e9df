// Angle-weighted vertex normals (Thürmer and Wüthrich 1998): n_v = normalize(Σ θ_f n_f) over the
// faces f around v, with θ_f the face's angle at v and n_f its unit normal (by its winding). The
// curvature gather (curvature.cpp) computes the same normal with the same per-corner term, so
// meshes shaded with or without curvature get the same normals.
#pragma once

#include "analyzer/geometry_tolerances.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace toonwater {

// atan2(y, x) for y >= 0 by a polynomial, absolute error below 1e-5 rad: plenty for a weight,
// and several times cheaper than std::atan2.
inline double approximate_angle(double y, double x) {
  const double ax = std::abs(x);
  const double ratio = std::min(ax, y) / std::max({ax, y, std::numeric_limits<double>::min()});
  const double r2 = ratio * ratio;
  double angle =
      ratio * (0.99997726 +
               r2 * (-0.33262347 +
                     r2 * (0.19354346 + r2 * (-0.11643287 + r2 * (0.05265332 - r2 * 0.01172120)))));
  if (y > ax) angle = std::numbers::pi / 2 - angle;
  return x < 0.0 ? std::numbers::pi - angle : angle;
}

// One face's term θ n_f at the corner x of face (x, a, b), given xa × xb, its length, xa · xb
// and the face's longest squared edge (xa = a − x, xb = b − x): zero for a degenerate face
// (geometry_tolerances.hpp), which has no usable normal.
inline Vec3 corner_normal_term(const Vec3& cross, double double_area, double dot, double longest2) {
  if (is_degenerate_triangle(double_area, longest2)) return Vec3::Zero();
  // Times the reciprocal, which the curvature's face pass needs as well and computes once.
  const double weight = approximate_angle(double_area, dot) * (1.0 / double_area);
  return weight * cross;
}

inline Vec3 corner_normal_term(const Vec3& xa, const Vec3& xb) {
  const Vec3 cross = xa.cross(xb);
  return corner_normal_term(
      cross, cross.norm(), xa.dot(xb),
      std::max({xa.squaredNorm(), xb.squaredNorm(), (xb - xa).squaredNorm()}));
}

// Unit normals per vertex; zero where no face has a usable normal.
std::vector<Vec3> angle_weighted_normals(const TriangleMesh& mesh, const VertexFaces& vertex_faces);

}  // namespace toonwater
