// Jacobi smoothing of K and H; formula in curvature_smoothing.hpp. Each step reads the previous
// step's values and writes a second buffer, so the vertices split over the cores with no shared
// writes and the result does not depend on the vertex order.
#include "analyzer/curvature_smoothing.hpp"

#include "analyzer/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace toonwater {

void smooth_curvature(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                      CurvatureField& field, int steps) {
  if (steps <= 0) return;
  const std::size_t n = field.gaussian.size();
  std::vector<double> gaussian(n), mean(n);
  const std::size_t workers = worker_count(n);
  for (int step = 0; step < steps; ++step) {
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        gaussian[v] = field.gaussian[v];
        mean[v] = field.mean[v];
        if (field.status[v] == CurvatureStatus::undefined) continue;
        double weight = 0.0, weighted_gaussian = 0.0, weighted_mean = 0.0;
        for (std::int32_t f : vertex_faces.of(static_cast<std::int32_t>(v))) {
          for (std::int32_t c : mesh.triangles[f]) {
            if (field.status[c] == CurvatureStatus::undefined) continue;
            weight += field.area[c];
            weighted_gaussian += field.area[c] * field.gaussian[c];
            weighted_mean += field.area[c] * field.mean[c];
          }
        }
        if (weight > 0.0) {
          gaussian[v] = weighted_gaussian / weight;
          mean[v] = weighted_mean / weight;
        }
      }
    });
    std::swap(gaussian, field.gaussian);
    std::swap(mean, field.mean);
  }
  for (std::size_t v = 0; v < n; ++v) {
    const double root =
        std::sqrt(std::max(field.mean[v] * field.mean[v] - field.gaussian[v], 0.0));
    field.k1[v] = field.mean[v] + root;
    field.k2[v] = field.mean[v] - root;
  }
}

}  // namespace toonwater
