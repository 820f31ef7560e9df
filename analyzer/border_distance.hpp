// The distance of each vertex of a region of the surface from the region's border, along the
// surface: the shortest path over mesh edges from any vertex outside the region (Dijkstra,
// started from all of them at once). On a marching-cubes mesh the edge paths are at most
// about 8 % longer than the straight line, which is well within what the distance is used for.
//
// The free surface's border is where it turns into a wall, the side of a column, or the
// meniscus around an object: a fillet a few cells wide as curved as a crest (flow_regions.hpp
// fades the flow field across it).
#pragma once

#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace toonwater {

// Per vertex: 0 outside `member`; inside, the edge-path distance to the nearest vertex outside
// it, or +infinity where the member's component has no such vertex.
std::vector<double> border_distance(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                    std::span<const std::uint8_t> member);

}  // namespace toonwater
