// Colours under the water's surface (scene/seen_through_water.hpp): composed as POV-Ray
// composes them, they give back the colour wanted.
#include "scene/seen_through_water.hpp"

#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace toonwater::test {
namespace {

// POV-Ray's pixel through a band of the surface: (1 − t)·shown + r·S + t·gain⊙X.
Color composed(const Color& pigment, const Color& gain, const BandLook& band,
               const WaterSurfaceLook& look) {
  Color out{};
  for (int c = 0; c < 3; ++c)
    out[c] = (1 - band.transmit) * band.shown[c] + look.reflected[c] +
             band.transmit * gain[c] * pigment[c];
  return out;
}

// The inverse of linear_from_srgb.
Color srgb_from_linear(const Color& linear) {
  Color out{};
  for (int c = 0; c < 3; ++c) {
    const double v = linear[c];
    out[c] = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
  }
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
    const Color x = seen_through_water(wanted, gain, look.medium, look);
    const Color pixel = composed(x, gain, look.medium, look);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(pixel[c], wanted[c], 1e-12) << transmit << " channel " << c;
    EXPECT_LT(x[2], 0.0) << "the water's blue is taken away from an orange object";
  }
}

// Where the dark colour is a shade of the medium one and the water reflects nothing, the dark
// band shows exactly what the medium band shows, scaled by t_dark/kt, whatever lies behind.
TEST(SeenThroughWater, TheDarkBandShowsWhatTheMediumBandShowsDarker) {
  SceneConfig config;
  config.water.reflection = 0.0;
  const double shade = 0.3;
  const Color medium = linear_from_srgb(config.water.medium);
  config.water.dark = srgb_from_linear({shade * medium[0], shade * medium[1], shade * medium[2]});
  for (const double transmit : {0.1, 0.4, 0.75}) {
    config.water.transmit = transmit;
    const WaterSurfaceLook look = water_surface_look(config);
    EXPECT_DOUBLE_EQ(look.medium.transmit, transmit);
    EXPECT_DOUBLE_EQ(look.bright.transmit, transmit);
    const double t = look.dark.transmit;
    EXPECT_NEAR(t, transmit * shade / (1 - transmit + transmit * shade), 1e-12);
    const Color wanted = linear_from_srgb(submerged_tint({0.92, 0.45, 0.18}, config.water.medium));
    for (const Color& behind : {seen_through_water(wanted, look.gain, look.medium, look),
                                Color{0.0, 0.0, 0.0}, Color{1.0, 1.0, 1.0}}) {
      const Color under_medium = composed(behind, look.gain, look.medium, look);
      const Color under_dark = composed(behind, look.gain, look.dark, look);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(under_dark[c], t / transmit * under_medium[c], 1e-12)
            << transmit << " channel " << c;
    }
  }
}

TEST(SeenThroughWater, TheDarkBandPassesFromNothingToAllWithTheWater) {
  const Color medium{0.2, 0.4, 0.8}, dark{0.05, 0.1, 0.3}, sky{0.02, 0.05, 0.1}, none{};
  EXPECT_EQ(dark_band_transmit(0.0, medium, dark, sky), 0.0);
  EXPECT_DOUBLE_EQ(dark_band_transmit(1.0, medium, dark, sky), 1.0);
  EXPECT_DOUBLE_EQ(dark_band_transmit(0.4, medium, medium, none), 0.4)
      << "no darker: as the medium";
  EXPECT_DOUBLE_EQ(dark_band_transmit(0.4, dark, medium, none), 0.4) << "lighter: at most kt";
  EXPECT_EQ(dark_band_transmit(0.4, medium, none, none), 0.0) << "black: opaque";
  const double t = dark_band_transmit(0.4, medium, dark, sky);
  EXPECT_GT(t, 0.0);
  EXPECT_LT(t, 0.4);
  EXPECT_LT(dark_band_transmit(0.2, medium, dark, sky), t);
  EXPECT_GT(dark_band_transmit(0.8, medium, dark, sky), t);
}

// Under the dark band an orange object shows a darker shade of itself: its hue, not the dark
// water's blue over it nor a saturated red.
TEST(SeenThroughWater, AnObjectUnderTheDarkBandKeepsItsHue) {
  SceneConfig config;
  const WaterSurfaceLook look = water_surface_look(config);
  auto hue_of = [](const Color& c) { return hue(c[0], c[1], c[2]); };
  auto clipped = [](Color c) {
    for (double& v : c) v = std::clamp(v, 0.0, 1.0);
    return c;
  };
  const Color wanted = linear_from_srgb(submerged_tint({0.92, 0.45, 0.18}, config.water.medium));
  const Color x = seen_through_water(wanted, look.gain, look.medium, look);
  const Color under_medium = clipped(composed(x, look.gain, look.medium, look));
  const Color under_dark = clipped(composed(x, look.gain, look.dark, look));
  EXPECT_LT(hue_distance(hue_of(under_dark), hue_of(under_medium)), 10.0)
      << hue_of(under_dark) << " against " << hue_of(under_medium);
  EXPECT_GT(*std::min_element(under_dark.begin(), under_dark.end()), 0.0) << "not clipped";
  EXPECT_LT(under_dark[0], under_medium[0]) << "darker";
}

// A line under the water is nowhere lighter than its colour, whichever band shows above it.
TEST(SeenThroughWater, ALineIsNoLighterThanItsColourUnderAnyBand) {
  SceneConfig config;
  for (const double transmit : {0.1, 0.4, 0.75}) {
    config.water.transmit = transmit;
    const WaterSurfaceLook look = water_surface_look(config);
    for (const Color& line : {Color{0.0, 0.0, 0.0}, Color{0.02, 0.03, 0.1}}) {
      const Color x = line_seen_through_water(line, look);
      for (const BandLook* band : {&look.bright, &look.medium, &look.dark}) {
        const Color pixel = composed(x, {1, 1, 1}, *band, look);
        for (int c = 0; c < 3; ++c) EXPECT_LE(pixel[c], line[c] + 1e-12) << transmit;
      }
      const Color under_bright = composed(x, {1, 1, 1}, look.bright, look);
      const Color under_dark = composed(x, {1, 1, 1}, look.dark, look);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(std::max(under_bright[c], under_dark[c]), line[c], 1e-12)
            << "as light as its colour under one of them";
    }
  }
}

TEST(SeenThroughWater, TheTintKeepsTheObjectsHueAndNothingIsSeenThroughOpaqueWater) {
  const Color tint = submerged_tint({1.0, 0.0, 0.0}, {0.0, 0.0, 1.0});
  EXPECT_DOUBLE_EQ(tint[0], 1.0 - kSubmergedTint);
  EXPECT_DOUBLE_EQ(tint[2], kSubmergedTint);
  SceneConfig config;
  config.water.transmit = 0.0;
  const WaterSurfaceLook look = water_surface_look(config);
  EXPECT_EQ(look.dark.transmit, 0.0);
  const Color x = seen_through_water({0.5, 0.5, 0.5}, {1, 1, 1}, look.medium, look);
  for (double c : x) EXPECT_EQ(c, 0.0);
  EXPECT_EQ(line_seen_through_water({0, 0, 0}, look), (Color{0, 0, 0}));
  EXPECT_NEAR(linear_from_srgb({0.5, 0.5, 0.5})[0], 0.21404, 1e-5);
}

}  // namespace
}  // namespace toonwater::test
