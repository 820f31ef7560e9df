// Jacobi smoothing of vertex fields; formula in curvature_smoothing.hpp. Each step reads the
// previous step's terms and writes the next step's to a second buffer, so the vertices split
// over the cores with no shared writes and the result does not depend on the vertex order.
#include "analyzer/curvature_smoothing.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

namespace toonwater {

void smooth_vertex_field(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                         std::span<const double> vertex_area, std::span<const std::uint8_t> member,
                         std::vector<double>& values, int steps) {
  if (steps <= 0) return;
  const std::size_t n = values.size();
  // Each vertex's two terms, zero off the members, side by side: a corner costs one 16-byte
  // load and no branch (a vertex is read as a corner of all its faces' neighbours, 18 times).
  // A step reads only the terms of the step before, so it writes the values in place and the
  // next step's terms beside them. (Left uninitialised by new: the threads that use them
  // first fill them.)
  struct Terms {
    double weight, weighted;
  };
  std::unique_ptr<Terms[]> terms(new Terms[n]), next_terms(new Terms[n]);
  auto terms_of = [&](std::size_t v, double value) {
    return member[v] ? Terms{vertex_area[v], vertex_area[v] * value} : Terms{0.0, 0.0};
  };
  const std::size_t workers = worker_count(n);
  parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) terms[v] = terms_of(v, values[v]);
  });
  for (int step = 0; step < steps; ++step) {
    const bool last = step + 1 == steps;
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
      for (std::size_t v = begin; v < end; ++v) {
        if (member[v]) {
          double weight = 0.0, weighted = 0.0;
          // Summed face by face: the three corners of a face are independent additions, so
          // the chain of dependent ones (which bounds the speed) is one per face, not per corner.
          for (std::int32_t f : vertex_faces.of(static_cast<std::int32_t>(v))) {
            const Terms &a = terms[mesh.triangles[f][0]], &b = terms[mesh.triangles[f][1]],
                        &c = terms[mesh.triangles[f][2]];
            weight += a.weight + b.weight + c.weight;
            weighted += a.weighted + b.weighted + c.weighted;
          }
          if (weight > 0.0) values[v] = weighted / weight;
        }
        if (!last) next_terms[v] = terms_of(v, values[v]);
      }
    });
    std::swap(terms, next_terms);
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
