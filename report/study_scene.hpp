// A study's scene: a water sequence written by povgen with a study's configuration and rendered
// by POV-Ray on both cores, as a user's would be.
#pragma once

#include "analyzer/mesh.hpp"
#include "scene/config.hpp"

#include <filesystem>
#include <string>

namespace toonwater::report {

// Writes the scene of `pattern` (relative to the working directory) into `scene_dir` and
// renders every frame. Throws std::runtime_error naming `study` and the first failed frame.
void write_and_render(const SceneConfig& config, const std::string& pattern, Axis up,
                      const std::filesystem::path& scene_dir, const std::string& study);

}  // namespace toonwater::report
