// PNG previews of a top-down map for people: the map in colour above a legend panel with a
// colour bar and its numeric range drawn as text (DejaVu Sans through OpenImageIO).
//
// Layout: the map occupies the top-left width × height pixels (one pixel per map pixel); the
// panel below it is `legend_height` pixels high and the image at least `min_width` wide.
#pragma once

#include "analyzer/colormap.hpp"
#include "analyzer/maps/top_down_map.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace toonwater {

struct PreviewImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes a pixel
  Rgb8 at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

inline constexpr int legend_height = 64;
inline constexpr int legend_min_width = 400;

// K or H: `values` is one of the map's channels, coloured over [−range, range].
PreviewImage signed_preview(const TopDownMap& map, const std::vector<float>& values, double range,
                            const std::string& title);
PreviewImage label_preview(const TopDownMap& map);

// The colour bar of a signed preview spans these columns of the panel's bar rows:
// value −range at bar_left, +range at bar_right(image width), 0 half-way (an even span).
inline constexpr int bar_left = 12;
inline int bar_right(int image_width) {
  return bar_left + 2 * ((image_width - 2 * bar_left - 1) / 2);
}
inline constexpr int bar_top_offset = 24;  // rows below the map where the bar starts
inline constexpr int bar_rows = 16;

}  // namespace toonwater
