// Flow strokes as an animator draws them: one stroke along the crest of each narrow flow
// region (flow_regions.hpp), and the contour (flow_lines.hpp) only around the wide ones, where
// two strokes along a narrow crest would read as outlined confetti.
//
// A region is a connected set of free-surface vertices of one label (ridge or valley). One
// smaller than the flow stage's A_min (`min_region_area`) is a speck that the field fades in as
// it grows or out as it shrinks (flow_regions.hpp): its fill is faint, and its stroke would be a
// loop a few pixels across that pops in and out, so it has none.
//
// A region's spine is found by two sweeps of Dijkstra's algorithm over its edges: the vertex
// farthest from any vertex of the region is one end, the vertex farthest from that one the
// other, the ends of (nearly) its longest shortest path. The region is narrow when that path's
// length ℓ is at least `narrow_aspect` times the region's mean width A/ℓ (A its area):
// ℓ² >= 3A (a strip three times as long as wide; a disc has ℓ²/A = 4/π).
//
// The stroke runs between the spine's ends along the crest of the field: the path of least
// Σ |e| / |s̄| over the region's edges (s̄ the mean |s| of an edge's ends, >= 1 inside), so
// it keeps to where the field is strongest rather than cutting corners; from each end it
// drops the vertices that climb towards the crest (an end of the spine is often a corner of
// the region beside the crest). Each of its points then moves across the crest, in the tangent
// plane, to the peak of the parabola fitted by least squares to the field over its vertex and
// one-ring (held within half the ring's reach), as a sub-pixel peak is found in an image: the
// stroke lies where the crest lies between the vertices, and glides with a moving crest instead
// of stepping an edge at a time. It is smoothed by umbrella steps with its ends held, each
// step's move kept in the surface's tangent plane (the shading normal), so that a convex crest's
// stroke does not sink under the water, and tapers towards each end (set_taper,
// flow_lines.hpp).
#pragma once

#include "analyzer/flow_lines.hpp"
#include "analyzer/flow_regions.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <vector>

namespace toonwater {

inline constexpr double narrow_aspect = 3.0;      // ℓ / (A / ℓ) at least this: a narrow region
inline constexpr int stroke_smoothing_steps = 4;  // umbrella steps, weight 1/2, ends held

// A stroke along each narrow region's crest, and the contours of the wide ones. `vertex_faces`
// is the mesh's (topology.hpp).
std::vector<FlowLine> flow_strokes(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                   const FlowRegions& flow, double taper_length);

}  // namespace toonwater
