// Render quality presets, chosen by `[render] quality` and measured against a reference by
// `toonwater report` (report/render_error_study.hpp):
//
//   preset    size              antialiasing
//   draft     half width/height off
//   preview   full              off
//   final     full              on: threshold 0.05, depth 3 (POV-Ray's adaptive method 1; its
//                               default threshold 0.3 leaves the flat toon bands' edges jagged)
//
// max_trace_level is not a preset's: the scene sets what its reflections and refraction need.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace toonwater {

enum class RenderQuality { draft, preview, final };

struct RenderPreset {
  std::string name;
  int divisor;                                // of the width and height
  std::optional<double> antialias_threshold;  // none: antialiasing off
  int antialias_depth;
};

const RenderPreset& render_preset(RenderQuality quality);

// The presets in order of cost: draft, preview, final.
const std::vector<RenderPreset>& render_presets();

}  // namespace toonwater
