// Toon islands: the picture's flat patches without the specks the simulation's noise leaves.
//
// Each vertex of the water is painted in one toon class: a flow region where its flow
// coordinate v says so (valley where v <= Toon_flow_key(−1), ridge where v >= Toon_flow_key(1),
// toon.inc), else the band its band key u falls in (band b where limits[b−1] < u <= limits[b]).
// An island is a connected set of vertices of one class, joined through the mesh's edges;
// POV-Ray, interpolating u and v inside each triangle, paints each island as one patch.
//
// An island whose picture is smaller than a disc of `radius_pixels` pixels (the least a cartoon
// draws), or a band's island smaller than a disc of `radius_edges` median edge lengths, is
// merged into the class around it. The second is the scale the shading normals are smoothed at
// (flow_regions.hpp): a smaller patch of a band is what the smoothing left of the noise, not a
// wave. Flow regions have their own least size and fade in and out through it (flow_regions.hpp),
// so only the picture's limit applies to them: a region that shrinks is never cut off at a size
// that shows. Islands are merged smallest first into the neighbouring class they share the
// most edges with, and joined with that class's islands beside them, so an island that grows by
// a merge is judged again at its new size: an area opening (Vincent, "Morphological area
// openings and closings for grey-scale images", 1993) on the mesh. An island with no neighbour
// (a whole part of the mesh in one class) stays. A merged vertex's u and v move to just inside
// its new class's limits: the least change that paints it in that class.
//
// A flow region hides the bands under it, but not along its border, where u is interpolated
// from the region's vertices out to the water around it: a region's vertex next to the bands
// takes the band most of its neighbours outside the region have, so that no sliver of another
// band lines the region.
//
// An island's area is its own: the smoothing's scale is the data's, not the picture's. Its size
// in pixels is the sum over its vertices of area · max(0, n·view) / w², with `view` the
// direction to the camera and w the width of a pixel at the vertex: a patch seen edge-on is a
// sliver in the picture whatever its area, and one facing away is hidden by the water in front
// of it (a sheet's underside, by the sheet).
#pragma once

#include "analyzer/mesh.hpp"
#include "scene/scene_mesh.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace toonwater {

struct IslandLimits {
  double radius_edges = 1.5;   // median edge lengths of the mesh
  double radius_pixels = 2.0;  // pixels on screen
};

// Merges the islands of `label` (one class per vertex, 0 to min_area.size() − 1; vertices in no
// triangle are left alone) whose total `area` is below their class's `min_area` or whose total
// `pixels` is below `min_pixels`, as above. Returns the number of merges.
std::size_t merge_small_islands(std::span<const Triangle> triangles, std::span<const double> area,
                                std::span<const double> pixels, std::span<const double> min_area,
                                double min_pixels, std::vector<int>& label);

// The toon coordinates `uv` of `mesh` with its small islands merged and its regions' borders in
// the band around them, for a camera at `eye` whose pixels are `pixel_width` wide at each vertex
// (scene_writer.hpp). Returns the merges.
std::size_t merge_toon_islands(const SceneMesh& mesh, const Vec3& eye,
                               std::span<const double> pixel_width, const ToonLimits& limits,
                               const IslandLimits& island, std::vector<TextureCoordinate>& uv);

}  // namespace toonwater
