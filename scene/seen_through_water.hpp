// What lies under the water's see-through surface, coloured so that the picture shows what a
// cartoon draws there: an object in a tint of its own colour, its line in the line colour.
//
// POV-Ray composes a pixel seen through the water's surface (a pigment W with transmit t under
// a flat finish of gain e, and reflection r of the flat sky S) as
//   pixel = (1 − t)·e⊙W + r·S + t·X,
// X being what the refracted ray brings back (linear colours, ⊙ per channel). A dark line seen
// this way lowers the pixel by at most t·X: at the default t = kt = 0.4, over the water's dark
// floor, by less than a tenth, so the line is lost; and an object's colour is mixed with the
// water's into another hue (orange under blue turns mauve). Solving for X instead,
//   X = (wanted − (1 − t)·e⊙W − r·S) / t,
// the pixel is `wanted` wherever the surface above shows the band W. Under calm water (the
// medium band) an object shows its colour tinted by the water's, mixed in sRGB as a painter
// mixes; a line is solved against the bright and the dark band, the darker in each channel, so
// that it is nowhere lighter than its colour. X may leave [0, 1]: POV-Ray computes with such
// colours (a negative one takes light away) and clips only the finished pixel.
//
// The bright and medium bands pass t = kt; the dark band passes less. Under the medium band the
// pixel is P = (1 − kt)·e⊙M + r·S + kt·X (M the medium colour); under the dark band, passing
// t, with X from P,
//   (1 − t)·e⊙D + r·S + t·X = (t/kt)·P + a − t·b,
//   a = e⊙D + r·S,   b = e⊙D + (1 − kt)/kt·e⊙M + r·S/kt,
// whatever lies behind: the medium band's picture, darker, plus a leftover of the water's own
// colours, a − t·b. The dark band passes the t of the least leftover, ⟨a, b⟩/⟨b, b⟩ (at most
// kt): what shows through it is a darker shade of what shows through the medium band (exactly
// so without reflection where D is a shade of M: then t = kt·ρ / (1 − kt + kt·ρ), ρ = D/M).
// Passing kt there too leaves a − kt·b = −(1 − kt)·e⊙(M − D): the bands' difference taken from
// every channel, which clips an object whose colours take the water's blue away to saturated
// shards; passing much less shows the dark water's blue over it instead.
#pragma once

#include "scene/config.hpp"

namespace toonwater {

// Share of the water's medium colour in an object's colour under water (mixed in sRGB).
inline constexpr double kSubmergedTint = 0.25;

// A colour as POV-Ray computes with it: an sRGB colour of the configuration made linear.
Color linear_from_srgb(const Color& srgb);

// One band of the water's surface as it composes what is seen through it.
struct BandLook {
  Color shown{};          // e⊙W, as shown (linear)
  double transmit = 0.0;  // t: the share of what lies behind that it passes
};

// The water's surface as it composes what is seen through it: linear colours.
struct WaterSurfaceLook {
  Color gain{};  // e: the flat finish's, ka + kd·Id (Toon_flat_shading), of water and objects
  BandLook bright, medium, dark;
  Color reflected{};  // r·S
};
WaterSurfaceLook water_surface_look(const SceneConfig& config);

// What the dark band passes (above), for the water's transmit kt, its medium and dark colours
// as shown (e⊙M, e⊙D) and its reflection of the sky (r·S), all linear.
double dark_band_transmit(double transmit, const Color& medium, const Color& dark,
                          const Color& reflected);

// The pigment X (linear) that a surface of finish gain `gain` (linear, per channel) needs under
// the water for the pixel to show `wanted` (linear) where the surface above shows `band`.
Color seen_through_water(const Color& wanted, const Color& gain, const BandLook& band,
                         const WaterSurfaceLook& look);

// The pigment of a line (linear) under the water: no lighter than `line` (linear) under any
// band.
Color line_seen_through_water(const Color& line, const WaterSurfaceLook& look);

// An object's colour under water: its sRGB colour with kSubmergedTint of the water's medium.
Color submerged_tint(const Color& object_srgb, const Color& water_srgb);

}  // namespace toonwater
