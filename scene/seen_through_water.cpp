// Colours under the water's surface; stated in seen_through_water.hpp.
#include "scene/seen_through_water.hpp"

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

WaterSurfaceLook water_surface_look(const SceneConfig& config) {
  const WaterConfig& w = config.water;
  WaterSurfaceLook look;
  look.transmit = w.transmit;
  // Toon_flat_shading's emission: ka·Ia + kd·Id, with a white ambient.
  const Color medium = linear_from_srgb(w.medium), bright = linear_from_srgb(w.bright);
  const Color sky = linear_from_srgb(w.sky.value_or(w.bright));
  for (int c = 0; c < 3; ++c) {
    look.gain[c] = w.ka + w.kd * config.light.color[c];
    look.calm[c] = look.gain[c] * medium[c];
    look.brightest[c] = look.gain[c] * bright[c];
    look.reflected[c] = w.reflection * sky[c];
  }
  return look;
}

Color seen_through_water(const Color& wanted, const Color& gain, const Color& water,
                         const WaterSurfaceLook& look) {
  Color out{};
  for (int c = 0; c < 3; ++c) {
    const double weight = look.transmit * gain[c];
    out[c] = weight > 0.0
                 ? (wanted[c] - (1.0 - look.transmit) * water[c] - look.reflected[c]) / weight
                 : 0.0;
  }
  return out;
}

Color submerged_tint(const Color& object_srgb, const Color& water_srgb) {
  Color out{};
  for (int c = 0; c < 3; ++c)
    out[c] = (1.0 - kSubmergedTint) * object_srgb[c] + kSubmergedTint * water_srgb[c];
  return out;
}

}  // namespace toonwater
