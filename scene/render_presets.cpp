#include "scene/render_presets.hpp"

namespace toonwater {

const std::vector<RenderPreset>& render_presets() {
  static const std::vector<RenderPreset> presets = {
      {"draft", 2, std::nullopt, 0},
      {"preview", 1, std::nullopt, 0},
      {"final", 1, 0.05, 3},
  };
  return presets;
}

const RenderPreset& render_preset(RenderQuality quality) {
  return render_presets()[static_cast<std::size_t>(quality)];
}

}  // namespace toonwater
