// libFuzzer target for the scene configuration (scene/config.hpp): the input up to the first
// NUL byte is scene.toml, each line after it one `--set` override. load_config must accept it or
// throw ConfigError; whatever it accepts must be what the scene writer may emit: finite numbers,
// colours in [0, 1] and identifiers of [A-Za-z0-9_].
#include "scene/config.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace {

namespace fs = std::filesystem;
using namespace toonwater;

void require_color(const Color& c) {
  for (const double v : c)
    if (!(v >= 0.0 && v <= 1.0)) std::abort();
}

void require_finite(const std::optional<toonwater::Vec3>& v) {
  if (v && !v->allFinite()) std::abort();
}

void check(const SceneConfig& c) {
  require_finite(c.camera.location);
  require_finite(c.camera.look_at);
  require_finite(c.light.direction);
  require_finite(c.light.position);
  for (const Color* color :
       {&c.light.color, &c.water.bright, &c.water.medium, &c.water.dark, &c.water.specular_color,
        &c.outline.color, &c.flow.ridge_color, &c.flow.valley_color, &c.render.background})
    require_color(*color);
  for (const double v : {c.camera.angle, c.water.t_bright, c.water.t_medium, c.water.ka, c.water.kd,
                         c.water.ks, c.water.phong_size, c.water.reflection, c.water.transmit,
                         c.water.ior, c.outline.width.value_or(1.0)})
    if (!std::isfinite(v)) std::abort();
  if (c.render.width < 1 || c.render.height < 1) std::abort();
  for (const ObjectConfig& o : c.objects) {
    require_color(o.color);
    if (o.name.empty() || o.name.size() > 40) std::abort();
    for (const char ch : o.name)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_')) std::abort();
  }
}

// scene.toml lives in memory (memfd), reached through /proc: writing a real file for every input
// would make disk I/O, not parsing, the fuzzer's bottleneck.
fs::path write_config_file(std::string_view text) {
  static const int fd = ::memfd_create("scene.toml", MFD_CLOEXEC);
  if (fd < 0 || ::ftruncate(fd, 0) != 0) std::abort();
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n =
        ::pwrite(fd, text.data() + done, text.size() - done, static_cast<off_t>(done));
    if (n <= 0) std::abort();
    done += static_cast<std::size_t>(n);
  }
  return "/proc/self/fd/" + std::to_string(fd);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  ConfigSources sources;
  sources.file = write_config_file(input.substr(0, nul));
  if (nul != std::string_view::npos) {
    std::string_view rest = input.substr(nul + 1);
    while (!rest.empty()) {
      const std::size_t end = rest.find('\n');
      sources.overrides.emplace_back(rest.substr(0, end));
      rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end + 1);
    }
  }
  try {
    check(load_config(sources));
  } catch (const ConfigError&) {
    // Rejected with a message naming the key: the expected outcome for most inputs.
  }
  return 0;
}
