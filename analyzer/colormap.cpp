// Preview colours (see colormap.hpp). RdBu control points from ColorBrewer 2.0, reversed so
// that negative values are blue; piecewise linear in sRGB between the 11 classes, sampled into
// a table.
#include "analyzer/colormap.hpp"

#include <algorithm>
#include <cmath>

namespace toonwater {
namespace {

constexpr std::array<Rgb8, 11> blue_white_red{{
    {5, 48, 97},
    {33, 102, 172},
    {67, 147, 195},
    {146, 197, 222},
    {209, 229, 240},
    {247, 247, 247},
    {253, 219, 199},
    {244, 165, 130},
    {214, 96, 77},
    {178, 24, 43},
    {103, 0, 31},
}};

// The map sampled at t = −1 + k/1024: previews colour a million pixels per image, and a step
// of 1/1024 in t changes a channel by at most one level.
constexpr int steps_per_unit = 1024;

std::array<Rgb8, 2 * steps_per_unit + 1> sample_diverging_map() {
  std::array<Rgb8, 2 * steps_per_unit + 1> table;
  for (std::size_t k = 0; k < table.size(); ++k) {
    const double position =
        static_cast<double>(k) / (table.size() - 1) * (blue_white_red.size() - 1);
    const std::size_t lower =
        std::min(static_cast<std::size_t>(position), blue_white_red.size() - 2);
    const double s = position - static_cast<double>(lower);
    for (int c = 0; c < 3; ++c) {
      const double value = (1.0 - s) * blue_white_red[lower][c] + s * blue_white_red[lower + 1][c];
      table[k][c] = static_cast<std::uint8_t>(value + 0.5);  // value in [0, 255]
    }
  }
  return table;
}

}  // namespace

Rgb8 diverging_colour(double t) {
  static const auto table = sample_diverging_map();
  if (std::isnan(t)) t = 0.0;
  const double k = (std::clamp(t, -1.0, 1.0) + 1.0) * steps_per_unit;
  return table[static_cast<std::size_t>(k + 0.5)];
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
