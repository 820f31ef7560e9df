// Smoothing of per-vertex fields: `steps` Jacobi iterations of a local area-weighted mean,
//   x_v ← Σ_{f∋v} Σ_{c∈f} A_c x_c / Σ_{f∋v} Σ_{c∈f} A_c
// over the faces f around v and their corners c (v included, with A the mixed area). A vertex
// weighs itself by its valence and each neighbour by two (the faces it shares with v), so one
// step mixes about a third of v's own value with its one-ring's. It damps the vertex-to-vertex
// noise of the cotangent H on irregular meshes (docs/analyzer.md, "Accuracy") at the price
// of blurring features narrower than about sqrt(steps) edges.
#pragma once

#include "analyzer/curvature.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace toonwater {

// Smooths `values` in place. Only vertices with `member[v]` set change, and only they
// contribute; the others keep their values.
void smooth_vertex_field(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                         std::span<const double> vertex_area, std::span<const std::uint8_t> member,
                         std::vector<double>& values, int steps);
// The same for a field of vectors: each component smoothed as above.
void smooth_vertex_field(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                         std::span<const double> vertex_area, std::span<const std::uint8_t> member,
                         std::vector<Vec3>& values, int steps);

// K and H smoothed as above over the vertices whose curvature is not undefined (k1 and k2
// follow from them).
void smooth_curvature(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                      CurvatureField& field, int steps);

}  // namespace toonwater
