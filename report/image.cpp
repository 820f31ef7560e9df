#include "report/image.hpp"

#include "images/image_codec.hpp"

#include <stdexcept>

namespace toonwater::report {

Image read_rgb(const std::filesystem::path& path) {
  const ImageCodec& codec = image_codec();
  try {
    RgbFloatImage read = codec.read_rgb(path.string());
    return {read.width, read.height, std::move(read.rgb)};
  } catch (const std::runtime_error&) {
    throw std::runtime_error(path.string() + ": cannot read the rendered image");
  }
}

}  // namespace toonwater::report
