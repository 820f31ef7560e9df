// The point of a triangle closest to a given point, with its barycentric weights (Ericson,
// "Real-Time Collision Detection", 2005, section 5.1.5): the point's projection on the
// triangle's plane when it falls inside the triangle, else the closest point of the edge or
// corner whose Voronoi region holds it. Weights are non-negative and sum to 1, so a value
// interpolated with them lies within the corners' values. A triangle with two corners at one
// place may give weights that are not numbers, and then a distance that is none either: a caller
// that keeps the face of least distance (`<`) passes over it.
#pragma once

#include "analyzer/mesh.hpp"

namespace toonwater {

struct TrianglePoint {
  Vec3 weights;      // of the corners a, b, c
  double distance2;  // squared distance from the given point
};

TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace toonwater
