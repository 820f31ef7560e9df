// The median edge length of a mesh: the unit of the lengths that must follow its resolution
// (the free surface's depth limit, the coherence's search radius, the maps' pixels).
//
// It is taken from a deterministic sample of at most `max_samples` edges: every stride-th edge
// in face order, edge 3f + c running from corner c of face f to the next corner; lengths that
// are zero or not finite are left out. The free-surface selection measures the same edges
// (EdgeSample) in its own pass over the faces, which reads their corners anyway.
#pragma once

#include "analyzer/mesh.hpp"

#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace toonwater {

constexpr std::size_t edge_length_samples = 100000;

// Which edges are sampled, and what counts of them.
class EdgeSample {
 public:
  EdgeSample(std::size_t face_count, std::size_t max_samples = edge_length_samples);
  // The number of edges sampled; sample i is edge i · stride.
  std::size_t count() const { return (3 * face_count_ + stride_ - 1) / stride_; }
  std::size_t stride() const { return stride_; }
  // The first sampled edge of the faces from `face` on.
  std::size_t first_from(std::size_t face) const {
    return (3 * face + stride_ - 1) / stride_ * stride_;
  }
  // The squared length of edge e; zero or not finite ones are not counted. The median is taken
  // among the squares, which order as the lengths do, and one square root taken of it.
  static double squared_length(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                               std::size_t e) {
    const Triangle& t = triangles[e / 3];
    const int c = static_cast<int>(e % 3);
    return (positions[t[(c + 1) % 3]] - positions[t[c]]).squaredNorm();
  }
  static bool counts(double squared_length) {
    return squared_length > 0.0 && std::isfinite(squared_length);
  }

 private:
  std::size_t face_count_, stride_;
};

// The median (the middle element, nth_element's) of the sampled lengths, given their squares;
// 0 if there are none.
double median_length(std::vector<double>& squared_lengths);

double median_edge_length(std::span<const Vec3> positions, std::span<const Triangle> triangles,
                          std::size_t max_samples = edge_length_samples);
inline double median_edge_length(const TriangleMesh& mesh,
                                 std::size_t max_samples = edge_length_samples) {
  return median_edge_length(mesh.positions, mesh.triangles, max_samples);
}

}  // namespace toonwater
