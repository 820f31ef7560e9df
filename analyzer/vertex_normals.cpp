#include "analyzer/vertex_normals.hpp"

#include "common/parallel.hpp"

namespace toonwater {

std::vector<Vec3> angle_weighted_normals(const TriangleMesh& mesh,
                                         const VertexFaces& vertex_faces) {
  const std::size_t n = mesh.positions.size();
  std::vector<Vec3> normals(n, Vec3::Zero());
  parallel_chunks(n, chunk_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const Vec3& x = mesh.positions[v];
      Vec3 sum = Vec3::Zero();
      for (std::int32_t f : vertex_faces.of(static_cast<std::int32_t>(v))) {
        const Triangle& t = mesh.triangles[f];
        const int corner = t[0] == static_cast<std::int32_t>(v)   ? 0
                           : t[1] == static_cast<std::int32_t>(v) ? 1
                                                                  : 2;
        sum += corner_normal_term(mesh.positions[t[(corner + 1) % 3]] - x,
                                  mesh.positions[t[(corner + 2) % 3]] - x);
      }
      const double length = sum.norm();
      if (length > 0.0 && std::isfinite(length)) normals[v] = sum / length;
    }
  });
  return normals;
}

}  // namespace toonwater
