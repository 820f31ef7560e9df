// The texture each face of the water needs so that no sliver of a band is drawn where none is.
//
// A corner's class is its toon_class (scene_mesh.hpp): a band, dark, medium or bright, by its
// band key u, or, where flow regions are drawn, a region by its flow key v, which hides u. POV-Ray
// interpolates u and v linearly inside a face, so:
//
// - a face whose band corners are dark and bright, none medium, passes through the medium band
//   between them: a strip across the face whose width is the medium band's share of the u
//   difference, a pixel or two where the surface turns sharply (the rim of a sheet, a fold seen
//   edge-on). It is drawn with two bands instead (toon.inc's Toon_two_bands), the edge where
//   L·n is halfway between the thresholds.
// - a face across a region's edge shows, outside the region, the bands u passes on its way from
//   the region corner's hidden u to the band corners': slivers of other bands along the edge.
//   When its band corners are all in one band, it is drawn in that band alone outside the region
//   (Toon_flow_over a flat band).
//
// A face with a medium band corner keeps its medium strip: it belongs to that corner's patch,
// whose size toon_islands.hpp judges.
#pragma once

#include "analyzer/mesh.hpp"
#include "scene/scene_mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace toonwater {

enum class FaceBands : std::uint8_t {
  three,        // the water's own texture
  two,          // dark and bright band corners, none medium
  only_dark,    // across a region's edge, band corners all dark
  only_medium,  // ... all medium
  only_bright,  // ... all bright
};

// Per face of `triangles`, as above, for the limits of three bands (two on u).
std::vector<FaceBands> face_bands(std::span<const Triangle> triangles,
                                  std::span<const TextureCoordinate> uv, const ToonLimits& limits);

}  // namespace toonwater
