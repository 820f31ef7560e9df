// POV-Ray text for a frame's spray droplets (spray_droplets.hpp):
//
//   #declare Spray_droplets = union {
//     Toon_droplet(<centre>, radius, <tail>, line, <light>)
//     ...
//   }
//
// Toon_droplet (templates/toon.inc, the droplets part) draws each in the toon bands of L·n with
// an outline shell `line` wide in world units: the outline's width in pixels at the droplet's
// distance from the camera. A frame without droplets declares an empty union.
#pragma once

#include "scene/scene_mesh.hpp"
#include "scene/spray_droplets.hpp"

#include <span>
#include <string>

namespace toonwater {

// `line_pixels` 0 draws no outline.
std::string spray_include(std::span<const Droplet> droplets, const ScreenProjection& screen,
                          const LightGeometry& light, double line_pixels);

}  // namespace toonwater
