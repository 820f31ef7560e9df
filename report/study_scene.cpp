// A study's scene written and rendered; see study_scene.hpp.
#include "report/study_scene.hpp"

#include "pipeline/generate_scene.hpp"
#include "render/render.hpp"

#include <stdexcept>

namespace toonwater::report {

void write_and_render(const SceneConfig& config, const std::string& pattern, Axis up,
                      const std::filesystem::path& scene_dir, const std::string& study) {
  PovgenRequest request;
  request.water_pattern = pattern;
  request.base_dir = std::filesystem::current_path();
  request.up = up;
  request.out_dir = scene_dir;
  generate_scene(config, request, {}, nullptr);
  RenderRequest render;
  render.scene_dir = scene_dir;
  render.jobs = 2;
  const RenderReport rendered = render_frames(render, {});
  if (!rendered.failures.empty())
    throw std::runtime_error(study + ": frame " + std::to_string(rendered.failures[0].frame) +
                             ": " + rendered.failures[0].message);
}

}  // namespace toonwater::report
