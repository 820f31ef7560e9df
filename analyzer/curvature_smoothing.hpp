// Smoothing of a curvature field: `steps` Jacobi iterations of a local area-weighted mean,
//   x_v ← Σ_{f∋v} Σ_{c∈f} A_c x_c / Σ_{f∋v} Σ_{c∈f} A_c      for x = K and x = H,
// over the faces f around v and their corners c (v included, with A the mixed area), then
// k1,2 = H ± sqrt(max(H² − K, 0)). A vertex weighs itself by its valence and each neighbour by
// two (the faces it shares with v), so one step mixes about a third of v's own value with its
// one-ring's. It damps the vertex-to-vertex noise of the cotangent H on irregular meshes (see
// curvature-notes.md) at the price of blurring features narrower than about sqrt(steps) edges.
// Undefined vertices neither change nor contribute.
#pragma once

#include "analyzer/curvature.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

namespace toonwater {

void smooth_curvature(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                      CurvatureField& field, int steps);

}  // namespace toonwater
