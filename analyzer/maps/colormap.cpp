// Preview colours (see colormap.hpp). RdBu control points from ColorBrewer 2.0, reversed so
// that negative values are blue; piecewise linear in sRGB between the 11 classes.
#include "analyzer/maps/colormap.hpp"

#include <algorithm>
#include <cmath>

namespace toonwater {
namespace {

constexpr std::array<Rgb8, 11> blue_white_red{{
    {5, 48, 97},     {33, 102, 172}, {67, 147, 195}, {146, 197, 222},
    {209, 229, 240}, {247, 247, 247}, {253, 219, 199}, {244, 165, 130},
    {214, 96, 77},   {178, 24, 43},  {103, 0, 31},
}};

}  // namespace

Rgb8 diverging_colour(double t) {
  if (std::isnan(t)) t = 0.0;
  const double position = (std::clamp(t, -1.0, 1.0) + 1.0) * 0.5 * (blue_white_red.size() - 1);
  const std::size_t lower = std::min(static_cast<std::size_t>(position), blue_white_red.size() - 2);
  const double s = position - static_cast<double>(lower);
  Rgb8 colour;
  for (int c = 0; c < 3; ++c) {
    const double value = (1.0 - s) * blue_white_red[lower][c] + s * blue_white_red[lower + 1][c];
    colour[c] = static_cast<std::uint8_t>(value + 0.5);  // value in [0, 255]
  }
  return colour;
}

Rgb8 diverging_colour(double value, double range) {
  return diverging_colour(range > 0.0 ? value / range : 0.0);
}

Rgb8 label_colour(int label) {
  if (label > 0) return {230, 97, 1};    // ridge: orange
  if (label < 0) return {33, 102, 172};  // valley: blue
  return {190, 190, 190};                // none: light grey
}

}  // namespace toonwater
