// Jacobi smoothing of vertex fields; formula in curvature_smoothing.hpp. Each step reads the
// previous step's values and writes a second buffer, so the vertices split over the cores with no
// shared writes and the result does not depend on the vertex order.
#include "analyzer/curvature_smoothing.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace toonwater {

void smooth_vertex_field(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                         std::span<const double> vertex_area, std::span<const std::uint8_t> member,
                         std::vector<double>& values, int steps) {
  if (steps <= 0) return;
  const std::size_t n = values.size();
  // Each vertex's two terms, zero off the members, side by side: a corner costs one 16-byte
  // load and no branch (a vertex is read as a corner of all its faces' neighbours, 18 times).
  struct Terms {
    double weight, weighted;
  };
  std::vector<Terms> terms(n);
  std::vector<double> next(n);
  const std::size_t workers = worker_count(n);
  for (int step = 0; step < steps; ++step) {
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v)
        terms[v] = member[v] ? Terms{vertex_area[v], vertex_area[v] * values[v]} : Terms{0.0, 0.0};
    });
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        next[v] = values[v];
        if (!member[v]) continue;
        double weight = 0.0, weighted = 0.0;
        for (std::int32_t f : vertex_faces.of(static_cast<std::int32_t>(v))) {
          for (std::int32_t c : mesh.triangles[f]) {
            weight += terms[c].weight;
            weighted += terms[c].weighted;
          }
        }
        if (weight > 0.0) next[v] = weighted / weight;
      }
    });
    std::swap(next, values);
  }
}

void smooth_curvature(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                      CurvatureField& field, int steps) {
  if (steps <= 0) return;
  const std::size_t n = field.gaussian.size();
  std::vector<std::uint8_t> defined(n);
  for (std::size_t v = 0; v < n; ++v) defined[v] = field.status[v] != CurvatureStatus::undefined;
  smooth_vertex_field(mesh, vertex_faces, field.area, defined, field.gaussian, steps);
  smooth_vertex_field(mesh, vertex_faces, field.area, defined, field.mean, steps);
  for (std::size_t v = 0; v < n; ++v) {
    const double root =
        std::sqrt(std::max(field.mean[v] * field.mean[v] - field.gaussian[v], 0.0));
    field.k1[v] = field.mean[v] + root;
    field.k2[v] = field.mean[v] - root;
  }
}

}  // namespace toonwater
