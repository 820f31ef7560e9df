// Rendering error against run time; see render_error_study.hpp. Presets reach POV-Ray as command-
// line options after scene.ini (+W +H +A/-A +R), which override the ini's values.
#include "report/render_error_study.hpp"

#include "report/image.hpp"

#include "render/render.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace toonwater::report {
namespace {

namespace fs = std::filesystem;

struct Rendered {
  Image image;
  double seconds;
};

Rendered render(const fs::path& scene_dir, const RenderPreset& preset, int width, int height) {
  RenderRequest request;
  request.scene_dir = scene_dir;
  request.extra_arguments = {"+W" + std::to_string(width / preset.divisor),
                             "+H" + std::to_string(height / preset.divisor)};
  if (preset.antialias_threshold) {
    request.extra_arguments.push_back("+A" + std::to_string(*preset.antialias_threshold));
    request.extra_arguments.push_back("+R" + std::to_string(preset.antialias_depth));
  } else {
    request.extra_arguments.push_back("-A");
  }
  const RenderReport report = render_frames(request, {});
  if (!report.failures.empty())
    throw std::runtime_error("render preset " + preset.name + ": " + report.failures[0].message);
  // A single-frame povgen scene renders to frame.png (scene.ini's Output_File_Name).
  return {read_rgb(scene_dir / "frame.png"), report.seconds};
}

using Palette = std::vector<std::array<float, 3>>;

// Colours covering at least 1% of the image, after rounding to 1/32 per channel.
Palette flat_colours(const Image& image) {
  std::map<std::array<int, 3>, std::size_t> counts;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3)
    ++counts[{static_cast<int>(std::lround(image.rgb[i] * 32)),
              static_cast<int>(std::lround(image.rgb[i + 1] * 32)),
              static_cast<int>(std::lround(image.rgb[i + 2] * 32))}];
  Palette palette;
  const std::size_t pixels = image.rgb.size() / 3;
  for (const auto& [key, count] : counts)
    if (100 * count >= pixels)
      palette.push_back({static_cast<float>(key[0]) / 32, static_cast<float>(key[1]) / 32,
                         static_cast<float>(key[2]) / 32});
  return palette;
}

std::size_t band(const Palette& palette, const std::array<float, 3>& c) {
  std::size_t best = 0;
  float best_distance = std::numeric_limits<float>::max();
  for (std::size_t i = 0; i < palette.size(); ++i) {
    const float d = (c[0] - palette[i][0]) * (c[0] - palette[i][0]) +
                    (c[1] - palette[i][1]) * (c[1] - palette[i][1]) +
                    (c[2] - palette[i][2]) * (c[2] - palette[i][2]);
    if (d < best_distance) {
      best_distance = d;
      best = i;
    }
  }
  return best;
}

}  // namespace

const RenderPreset& reference_preset() {
  static const RenderPreset reference{"reference", 1, 0.0, 4};
  return reference;
}

RenderQualityResult measure_render_quality(const fs::path& scene_dir, int width, int height) {
  RenderQualityResult result;
  const Rendered reference = render(scene_dir, reference_preset(), width, height);
  result.reference_seconds = reference.seconds;
  const Palette palette = flat_colours(reference.image);
  result.reference_bands = palette.size();
  const Image& ref = reference.image;
  for (const RenderPreset& preset : render_presets()) {
    const Rendered r = render(scene_dir, preset, width, height);
    double squared = 0.0;
    std::size_t mismatched = 0;
    for (int y = 0; y < ref.height; ++y) {
      for (int x = 0; x < ref.width; ++x) {
        const auto a = ref.pixel(x, y);
        const auto b = r.image.pixel(std::min(x * r.image.width / ref.width, r.image.width - 1),
                                     std::min(y * r.image.height / ref.height, r.image.height - 1));
        for (int c = 0; c < 3; ++c) squared += double(a[c] - b[c]) * double(a[c] - b[c]);
        mismatched += band(palette, a) != band(palette, b);
      }
    }
    const double pixels = double(ref.width) * ref.height;
    result.presets.push_back({preset.name, r.image.width, r.image.height, r.seconds,
                              std::sqrt(squared / (3.0 * pixels)), double(mismatched) / pixels});
  }
  return result;
}

}  // namespace toonwater::report
