// What lies under the water's see-through surface, coloured so that the picture shows what a
// cartoon draws there: an object in a tint of its own colour, its line in the line colour.
//
// POV-Ray composes a pixel seen through the water's surface (a pigment W with transmit kt under
// a flat finish of gain e, and reflection r of the flat sky S) as
//   pixel = (1 − kt)·e⊙W + r·S + kt·X,
// X being what the refracted ray brings back (linear colours, ⊙ per channel). A dark line seen
// this way lowers the pixel by at most kt·X: at the default kt = 0.4, over the water's dark
// floor, by less than a tenth, so the line is lost; and an object's colour is mixed with the
// water's into another hue (orange under blue turns mauve). Solving for X instead,
//   X = (wanted − (1 − kt)·e⊙W − r·S) / kt,
// the pixel is `wanted` wherever the surface above shows the band W. Under calm water (the
// medium band) an object shows its colour tinted by the water's, mixed in sRGB as a painter
// mixes; a line is solved against the bright band, so that it is nowhere lighter than its
// colour. X may leave [0, 1]: POV-Ray computes with such colours (a negative one takes light
// away) and clips only the finished pixel.
#pragma once

#include "scene/config.hpp"

namespace toonwater {

// Share of the water's medium colour in an object's colour under water (mixed in sRGB).
inline constexpr double kSubmergedTint = 0.25;

// A colour as POV-Ray computes with it: an sRGB colour of the configuration made linear.
Color linear_from_srgb(const Color& srgb);

// The water's surface as it composes what is seen through it: linear colours.
struct WaterSurfaceLook {
  double transmit = 0.0;  // kt
  Color gain{};       // e: the flat finish's, ka + kd·Id (Toon_flat_shading), of water and objects
  Color calm{};       // e⊙W of the medium band, as shown
  Color brightest{};  // e⊙W of the bright band, as shown
  Color reflected{};  // r·S
};
WaterSurfaceLook water_surface_look(const SceneConfig& config);

// The pigment X (linear) that a surface of finish gain `gain` (linear, per channel) needs under
// the water for the pixel to show `wanted` (linear) where the surface above shows `water`.
Color seen_through_water(const Color& wanted, const Color& gain, const Color& water,
                         const WaterSurfaceLook& look);

// An object's colour under water: its sRGB colour with kSubmergedTint of the water's medium.
Color submerged_tint(const Color& object_srgb, const Color& water_srgb);

}  // namespace toonwater
