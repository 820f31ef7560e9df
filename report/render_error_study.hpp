// Rendering error against run time: one povgen scene rendered by POV-Ray at
// quality presets (scene/render_presets.hpp: draft, preview, final, as `[render] quality`
// offers them) and compared with a high-quality reference render of the same scene:
//   reference  full size, antialiasing threshold 0 (every pixel supersampled), depth 4
//
// Errors against the reference, after upsampling a smaller image by pixel replication:
// RMSE over the RGB channels in [0, 1], and the share of pixels whose band differs. A pixel's
// band is the nearest (in RGB) of the reference image's flat colours — the colours covering at
// least 1% of it, which on a toon render are the shading bands, the flow colours, the outline
// and the background — so the measure needs no knowledge of the lighting or the gamma.
// max_trace_level stays povgen's: POV-Ray sets it in the scene, not on the command line.
#pragma once

#include "scene/render_presets.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace toonwater::report {

const RenderPreset& reference_preset();

struct RenderQualitySample {
  std::string preset;
  int width = 0, height = 0;
  double seconds = 0;        // POV-Ray parse + trace
  double rmse = 0;           // against the reference
  double band_mismatch = 0;  // share of pixels
};

struct RenderQualityResult {
  std::vector<RenderQualitySample> presets;
  double reference_seconds = 0;
  std::size_t reference_bands = 0;  // flat colours found in the reference
};

// Renders the povgen scene in `scene_dir` (one frame, written for width × height) at every
// preset and at the reference quality. Throws std::runtime_error naming the preset when POV-Ray
// fails or its image cannot be read.
RenderQualityResult measure_render_quality(const std::filesystem::path& scene_dir, int width,
                                           int height);

}  // namespace toonwater::report
