// Faces where the dark band meets the bright one directly.
//
// A vertex's band is that of its band key u (scene_mesh.hpp, toon.inc): dark where
// u <= key_medium, medium where key_medium < u <= key_bright, bright where u > key_bright.
// POV-Ray interpolates u linearly inside a face, so a face with a dark corner and a bright one
// passes through the medium band between them: a strip across the face whose width is the
// medium band's share of the u difference, a pixel or two where the surface turns sharply (the
// rim of a sheet, a fold seen edge-on). Such strips are specks in the picture, too thin to be a
// shape a cartoon draws. A face whose corners are dark and bright, none medium, is painted with
// two bands instead (toon.inc's Toon_two_bands), the edge where L·n is halfway between the
// thresholds. A face with a medium corner keeps its medium strip: it belongs to that corner's
// patch, whose size toon_islands.hpp judges.
#pragma once

#include "analyzer/mesh.hpp"
#include "scene/scene_mesh.hpp"

#include <array>
#include <span>
#include <vector>

namespace toonwater {

// Whether a face whose corners have band keys `u` is dark at one, bright at another and medium
// at none.
bool dark_meets_bright(const std::array<double, 3>& u, double key_medium, double key_bright);

// One mark per face of `triangles`: its corners' u (in `uv`) are dark and bright, none medium.
std::vector<bool> dark_bright_faces(std::span<const Triangle> triangles,
                                    std::span<const TextureCoordinate> uv, double key_medium,
                                    double key_bright);

}  // namespace toonwater
