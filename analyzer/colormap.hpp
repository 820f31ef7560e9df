// Colours of the previews. Signed values use ColorBrewer's diverging RdBu scheme (Brewer,
// colorbrewer2.org; 11 classes, interpolated linearly in sRGB), symmetric about zero: blue for
// negative, near-white (247, 247, 247) for zero, red for positive. Labels use three distinct
// colours; pixels outside the surface and the legend panel use a dark grey.
#pragma once

#include <array>
#include <cstdint>

namespace toonwater {

using Rgb8 = std::array<std::uint8_t, 3>;

// t in [−1, 1] (clamped; NaN gives the zero colour, t is rounded to a multiple of 1/1024):
// −1 darkest blue, 0 white, 1 darkest red.
Rgb8 diverging_colour(double t);
// value / range mapped into the diverging colour map; a zero range maps everything to 0.
Rgb8 diverging_colour(double value, double range);

Rgb8 label_colour(int label);  // -1 valley blue, 0 none grey, 1 ridge orange

inline constexpr Rgb8 background_colour{40, 40, 40};
inline constexpr Rgb8 text_colour{255, 255, 255};

}  // namespace toonwater
