// Welding of coincident vertices: triangle soups (every face with its own copies of its corners,
// as STL and some exporters write) become a connected surface, so curvature sees the real shape.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace toonwater {

struct WeldedMesh {
  TriangleMesh mesh;                        // one vertex per distinct position
  std::vector<std::int32_t> input_to_mesh;  // for each input vertex, its welded vertex
  std::size_t merged_vertex_count = 0;      // input vertices that were merged into another
};

// Merges vertices whose positions are exactly equal (+0 and -0 compare equal), in place: pass
// the mesh by std::move when it is not needed afterwards. Faces keep their order; a face whose
// corners become repeated is kept (the analyzer counts it as degenerate).
WeldedMesh weld_coincident_vertices(TriangleMesh mesh);

}  // namespace toonwater
