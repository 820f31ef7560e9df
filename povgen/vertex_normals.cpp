#include "povgen/vertex_normals.hpp"

#include <cmath>

namespace toonwater::povgen {

std::vector<Vec3> angle_weighted_normals(const TriangleMesh& mesh) {
  std::vector<Vec3> normals(mesh.positions.size(), Vec3::Zero());
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Vec3& b = mesh.positions[t[1]];
    const Vec3& c = mesh.positions[t[2]];
    const Vec3 face = (b - a).cross(c - a);
    const double length = face.norm();
    if (!(length > 0.0)) continue;
    const Vec3 n = face / length;
    const Vec3* p[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      const Vec3 e1 = *p[(k + 1) % 3] - *p[k];
      const Vec3 e2 = *p[(k + 2) % 3] - *p[k];
      // atan2(|e1×e2|, e1·e2) stays accurate for needles and caps, unlike acos.
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      normals[t[k]] += angle * n;
    }
  }
  for (Vec3& n : normals) {
    const double length = n.norm();
    n = length > 0.0 ? Vec3(n / length) : Vec3::Zero();
  }
  return normals;
}

}  // namespace toonwater::povgen
