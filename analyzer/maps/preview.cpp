// Preview images (see preview.hpp): map pixels coloured one to one, then a legend panel with a
// colour bar and its numeric range as text. Text is drawn by the image codec (OpenImageIO's
// FreeType, images/image_codec.hpp) with an explicitly named font: OpenImageIO has no usable
// default font on Debian.
#include "analyzer/maps/preview.hpp"

#include "images/image_codec.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <stdexcept>

namespace toonwater {
namespace {

constexpr int font_size = 13;

PreviewImage blank_preview(const MapView& view) {
  PreviewImage image;
  image.width = std::max(view.width, legend_min_width);
  image.height = view.height + legend_height;
  image.rgb.resize(3 * static_cast<std::size_t>(image.width) * image.height);
  for (std::size_t i = 0; i < image.rgb.size(); i += 3)
    std::copy(background_colour.begin(), background_colour.end(), image.rgb.begin() + i);
  return image;
}

void put(PreviewImage& image, int x, int y, const Rgb8& colour) {
  std::copy(colour.begin(), colour.end(),
            image.rgb.begin() + 3 * (static_cast<std::ptrdiff_t>(y) * image.width + x));
}

void fill_rect(PreviewImage& image, int x0, int y0, int x1, int y1, const Rgb8& colour) {
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) put(image, x, y, colour);
}

using Align = TextAlign;

void draw_text(PreviewImage& image, int x, int baseline, const std::string& text, Align align) {
  const ImageCodec& codec = image_codec();
  const std::array<float, 3> colour{text_colour[0] / 255.0f, text_colour[1] / 255.0f,
                                    text_colour[2] / 255.0f};
  try {
    codec.draw_text({image.width, image.height, image.rgb.data()}, x, baseline, text, font_size,
                    TOONWATER_MAP_FONT, colour, align);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("maps: cannot draw text with " TOONWATER_MAP_FONT ": " +
                             std::string(e.what()) + " (install fonts-dejavu-core)");
  }
}

std::string number(double value, bool sign = false) {
  char text[32];
  std::snprintf(text, sizeof text, sign ? "%+.3g" : "%.3g", value);
  return text;
}

}  // namespace

PreviewImage signed_preview(const TopDownMap& map, const std::vector<float>& values, double range,
                            const std::string& title) {
  PreviewImage image = blank_preview(map.view);
  for (int y = 0; y < map.view.height; ++y)
    for (int x = 0; x < map.view.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * map.view.width + x;
      if (map.alpha[i] > 0.0f) put(image, x, y, diverging_colour(values[i], range));
    }

  const int top = map.view.height;
  const int left = bar_left, right = bar_right(image.width);
  for (int x = left; x <= right; ++x) {
    const Rgb8 colour = diverging_colour(2.0 * (x - left) / (right - left) - 1.0);
    for (int y = top + bar_top_offset; y < top + bar_top_offset + bar_rows; ++y)
      put(image, x, y, colour);
  }
  std::string heading = title;
  heading += "   colour range ";
  heading += number(-range);
  heading += " to ";
  heading += number(range, true);
  draw_text(image, left, top + 17, heading, Align::left);
  const int baseline = top + bar_top_offset + bar_rows + 15;
  draw_text(image, left, baseline, number(-range), Align::left);
  draw_text(image, (left + right) / 2, baseline, "0", Align::centre);
  draw_text(image, right, baseline, number(range, true), Align::right);
  return image;
}

PreviewImage label_preview(const TopDownMap& map) {
  PreviewImage image = blank_preview(map.view);
  for (int y = 0; y < map.view.height; ++y)
    for (int x = 0; x < map.view.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * map.view.width + x;
      if (map.alpha[i] > 0.0f) put(image, x, y, label_colour(static_cast<int>(map.label[i])));
    }

  const int top = map.view.height;
  const int left = bar_left, right = bar_right(image.width);
  const int third = (right - left + 1) / 3;
  const std::array<std::pair<int, const char*>, 3> labels{
      {{-1, "valley"}, {0, "none"}, {1, "ridge"}}};
  draw_text(image, left, top + 17, "flow label", Align::left);
  for (int k = 0; k < 3; ++k) {
    const int x0 = left + k * third;
    fill_rect(image, x0, top + bar_top_offset, x0 + third - 2, top + bar_top_offset + bar_rows,
              label_colour(labels[k].first));
    draw_text(image, x0 + third / 2, top + bar_top_offset + bar_rows + 15, labels[k].second,
              Align::centre);
  }
  return image;
}

}  // namespace toonwater
