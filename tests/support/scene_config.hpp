// Scene configurations for the tests: load_config on TOML text written as a scratch scene.toml,
// so that errors name "scene.toml" and its lines as they do for a user's file.
#pragma once

#include "scene/config.hpp"

#include <string>
#include <vector>

namespace toonwater::test {

SceneConfig config_from(const std::string& toml, std::vector<std::string> overrides = {});

// The ConfigError message config_from throws, or "accepted".
std::string config_error(const std::string& toml, std::vector<std::string> overrides = {});

}  // namespace toonwater::test
