// The closest point of a triangle; stated in closest_point.hpp.
#include "analyzer/closest_point.hpp"

namespace toonwater {

TrianglePoint closest_point_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b,
                                        const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {Vec3(1, 0, 0), ap.squaredNorm()};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {Vec3(0, 1, 0), bp.squaredNorm()};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return {Vec3(1 - t, t, 0), (p - (a + t * ab)).squaredNorm()};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {Vec3(0, 0, 1), cp.squaredNorm()};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return {Vec3(1 - t, 0, t), (p - (a + t * ac)).squaredNorm()};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {Vec3(0, 1 - t, t), (p - (b + t * (c - b))).squaredNorm()};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {Vec3(1 - v - w, v, w), (p - (a + ab * v + ac * w)).squaredNorm()};
}

}  // namespace toonwater
