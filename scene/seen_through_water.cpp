// Colours under the water's surface; stated in seen_through_water.hpp.
#include "scene/seen_through_water.hpp"

#include <algorithm>
#include <cmath>

namespace toonwater {

Color linear_from_srgb(const Color& srgb) {
  // The sRGB transfer function (IEC 61966-2-1), as POV-Ray's `srgb` keyword applies it.
  Color out{};
  for (int c = 0; c < 3; ++c) {
    const double v = srgb[c];
    out[c] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  }
  return out;
}

double dark_band_transmit(double transmit, const Color& medium, const Color& dark,
                          const Color& reflected) {
  if (transmit <= 0.0) return 0.0;
  // The dark pixel is (t/kt)·(the medium pixel) + a − t·b: the least leftover a − t·b.
  double ab = 0.0, bb = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double a = dark[c] + reflected[c];
    const double b = dark[c] + (1.0 - transmit) / transmit * medium[c] + reflected[c] / transmit;
    ab += a * b;
    bb += b * b;
  }
  return bb > 0.0 ? std::clamp(ab / bb, 0.0, transmit) : transmit;
}

WaterSurfaceLook water_surface_look(const SceneConfig& config) {
  const WaterConfig& w = config.water;
  const Color bright = linear_from_srgb(w.bright), medium = linear_from_srgb(w.medium),
              dark = linear_from_srgb(w.dark);
  const Color sky = linear_from_srgb(w.sky.value_or(w.bright));
  WaterSurfaceLook look;
  for (int c = 0; c < 3; ++c) {
    // Toon_flat_shading's emission: ka·Ia + kd·Id, with a white ambient.
    look.gain[c] = w.ka + w.kd * config.light.color[c];
    look.bright.shown[c] = look.gain[c] * bright[c];
    look.medium.shown[c] = look.gain[c] * medium[c];
    look.dark.shown[c] = look.gain[c] * dark[c];
    look.reflected[c] = w.reflection * sky[c];
  }
  look.bright.transmit = look.medium.transmit = w.transmit;
  look.dark.transmit =
      dark_band_transmit(w.transmit, look.medium.shown, look.dark.shown, look.reflected);
  return look;
}

Color seen_through_water(const Color& wanted, const Color& gain, const BandLook& band,
                         const WaterSurfaceLook& look) {
  Color out{};
  for (int c = 0; c < 3; ++c) {
    const double weight = band.transmit * gain[c];
    out[c] = weight > 0.0
                 ? (wanted[c] - (1.0 - band.transmit) * band.shown[c] - look.reflected[c]) / weight
                 : 0.0;
  }
  return out;
}

Color line_seen_through_water(const Color& line, const WaterSurfaceLook& look) {
  Color out = seen_through_water(line, {1, 1, 1}, look.bright, look);
  if (look.dark.transmit <= 0.0) return out;  // nothing is seen through the dark band
  const Color under_dark = seen_through_water(line, {1, 1, 1}, look.dark, look);
  for (int c = 0; c < 3; ++c) out[c] = std::min(out[c], under_dark[c]);
  return out;
}

Color submerged_tint(const Color& object_srgb, const Color& water_srgb) {
  Color out{};
  for (int c = 0; c < 3; ++c)
    out[c] = (1.0 - kSubmergedTint) * object_srgb[c] + kSubmergedTint * water_srgb[c];
  return out;
}

}  // namespace toonwater
