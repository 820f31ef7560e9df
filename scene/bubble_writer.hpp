// POV-Ray text for a frame's bubbles (droplets under the water, spray_droplets.hpp):
//
//   #declare Water_bubbles = union {
//     Toon_bubble(<centre>, radius, line)
//     ...
//   }
//
// Toon_bubble (templates/toon.inc, the bubbles part) draws each as a flat disc with an outline
// shell `line` wide in world units (the outline's width in pixels at the bubble's distance),
// in colours that show through the water's surface as wanted (scene.pov declares them,
// seen_through_water.hpp). A bubble is round: it rises too slowly to stretch. A frame without
// bubbles declares an empty union.
#pragma once

#include "scene/spray_droplets.hpp"

#include <span>
#include <string>

namespace toonwater {

// `line_pixels` 0 draws no outline.
std::string bubble_include(std::span<const Droplet> bubbles, const ScreenProjection& screen,
                           double line_pixels);

}  // namespace toonwater
