// What counts as a face without shape, named once for the analyzer and povgen.
//
// Two different failures, each tested by one predicate on what the caller has computed anyway:
//   shapeless   a repeated corner or a zero-length edge: the face has no angles at all, so the
//               curvature's angle sums and areas (curvature.cpp) leave it out;
//   degenerate  its doubled area |e1 × e2| is not above degenerate_area_ratio times its
//               longest squared edge: collinear or nearly so (shapeless faces included), with no
//               usable plane, so it gives no vertex normal (vertex_normals.hpp) and the scene
//               leaves it out (scene_mesh.hpp; POV-Ray, in single precision, drops such faces
//               anyway). The ratio is scale-free where |e1 × e2|² is a normal double
//               (coordinates within about 1e±75; the curvature first scales its positions
//               by a power of two, curvature.cpp); a NaN area is degenerate.
// A degenerate face that is not shapeless (a cap standing on edge) keeps its angles: the
// curvature takes its Laplacian from the intrinsic Delaunay triangulation there.
#pragma once

#include "analyzer/mesh.hpp"

#include <algorithm>

namespace toonwater {

constexpr double degenerate_area_ratio = 1e-12;

// From a face's three squared edge lengths.
inline bool is_shapeless_triangle(double edge0_squared, double edge1_squared,
                                  double edge2_squared) {
  return edge0_squared == 0.0 || edge1_squared == 0.0 || edge2_squared == 0.0;
}

// From a face's doubled area and its longest squared edge.
inline bool is_degenerate_triangle(double double_area, double longest_squared) {
  return !(double_area > degenerate_area_ratio * longest_squared);
}

inline bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a;
  return is_degenerate_triangle(
      ab.cross(ac).norm(), std::max({ab.squaredNorm(), ac.squaredNorm(), (c - b).squaredNorm()}));
}

}  // namespace toonwater
