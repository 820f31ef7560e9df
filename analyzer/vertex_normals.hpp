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
// and several times cheaper than std::atan2. For a double or four lanes (lanes.hpp), with the
// same bits in each lane as for a double.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // always inlined: no call passes the lanes (lanes.hpp)
template <class Real>
[[gnu::always_inline]] inline Real approximate_angle(Real y, Real x) {
  const Real ax = absolute(x);
  const Real ratio =
      minimum(ax, y) / maximum(maximum(ax, y), splat<Real>(std::numeric_limits<double>::min()));
  const Real r2 = ratio * ratio;
  Real angle = ratio * (0.99997726 + r2 * (-0.33262347 + r2 * (0.19354346 +
                        r2 * (-0.11643287 + r2 * (0.05265332 - r2 * 0.01172120)))));
  angle = select(y > ax, std::numbers::pi / 2 - angle, angle);
  return select(x < 0.0, std::numbers::pi - angle, angle);
}
#pragma GCC diagnostic pop

// One face's term θ n_f at the corner x of face (x, a, b), given xa × xb, its length, xa · xb
// and the face's longest squared edge (xa = a − x, xb = b − x): zero for a degenerate face
// (geometry_tolerances.hpp), which has no usable normal.
inline Vec3 corner_normal_term(const Vec3& cross, double double_area, double dot, double longest2) {
  if (is_degenerate_triangle(double_area, longest2)) return Vec3::Zero();
  // Times the reciprocal, which the curvature gather needs as well and computes once.
  return approximate_angle(double_area, dot) * (1.0 / double_area) * cross;
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
