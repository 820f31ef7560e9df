// Colours under the water's surface (scene/seen_through_water.hpp): composed as POV-Ray
// composes them, they give back the colour wanted.
#include "scene/seen_through_water.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace toonwater::test {
namespace {

// POV-Ray's pixel through the surface: (1 − kt)·water + r·S + kt·gain⊙X.
Color composed(const Color& pigment, const Color& gain, const Color& water,
               const WaterSurfaceLook& look) {
  Color out{};
  for (int c = 0; c < 3; ++c)
    out[c] =
        (1 - look.transmit) * water[c] + look.reflected[c] + look.transmit * gain[c] * pigment[c];
  return out;
}

TEST(SeenThroughWater, TheComposedPixelIsTheColourWanted) {
  SceneConfig config;
  config.light.color = {1.0, 0.9, 0.8};
  for (const double transmit : {0.1, 0.4, 0.75}) {
    config.water.transmit = transmit;
    const WaterSurfaceLook look = water_surface_look(config);
    const Color gain{0.2 + 0.8 * 1.0, 0.2 + 0.8 * 0.9, 0.2 + 0.8 * 0.8};
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(look.gain[c], gain[c]);
    const Color wanted = linear_from_srgb(submerged_tint({0.92, 0.45, 0.18}, config.water.medium));
    const Color x = seen_through_water(wanted, gain, look.calm, look);
    const Color pixel = composed(x, gain, look.calm, look);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(pixel[c], wanted[c], 1e-12) << transmit << " channel " << c;
    EXPECT_LT(x[2], 0.0) << "the water's blue is taken away from an orange object";
  }
}

TEST(SeenThroughWater, TheTintKeepsTheObjectsHueAndNothingIsSeenThroughOpaqueWater) {
  const Color tint = submerged_tint({1.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
  EXPECT_DOUBLE_EQ(tint[0], 1.0 - kSubmergedTint);
  EXPECT_DOUBLE_EQ(tint[2], kSubmergedTint);
  SceneConfig config;
  config.water.transmit = 0.0;
  const WaterSurfaceLook look = water_surface_look(config);
  const Color x = seen_through_water({0.5, 0.5, 0.5}, {1, 1, 1}, look.calm, look);
  for (double c : x) EXPECT_EQ(c, 0.0);
  EXPECT_NEAR(linear_from_srgb({0.5, 0.5, 0.5})[0], 0.21404, 1e-5);
}

}  // namespace
}  // namespace toonwater::test
