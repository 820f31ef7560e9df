#include "tests/support/scene_config.hpp"

#include "tests/support/test_support.hpp"

namespace toonwater::test {

SceneConfig config_from(const std::string& toml, std::vector<std::string> overrides) {
  ScratchDir dir;
  write_text(dir / "scene.toml", toml);
  ConfigSources sources;
  sources.file = dir / "scene.toml";
  sources.overrides = std::move(overrides);
  return load_config(sources);
}

std::string config_error(const std::string& toml, std::vector<std::string> overrides) {
  try {
    config_from(toml, std::move(overrides));
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace toonwater::test
