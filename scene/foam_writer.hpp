// POV-Ray text for a frame's foam (foam_patches.hpp):
//
//   #declare Foam_patches = blob { threshold density
//     sphere { <centre>, radius, strength }
//     ...
//   }
//
// scene.pov paints the water's free surface with the foam's colour inside Foam_patches
// (Toon_foam_over, templates/toon.inc). A frame without foam declares nothing, and its water
// keeps its own textures.
#pragma once

#include "scene/foam_patches.hpp"

#include <span>
#include <string>

namespace toonwater {

std::string foam_include(std::span<const FoamComponent> components, double density);

}  // namespace toonwater
