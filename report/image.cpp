#include "report/image.hpp"

#include <OpenImageIO/imageio.h>

#include <stdexcept>

namespace toonwater::report {

namespace fs = std::filesystem;

Image read_rgb(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw std::runtime_error(path.string() + ": cannot read the rendered image");
  const OIIO::ImageSpec& spec = in->spec();
  Image image{spec.width, spec.height, {}};
  std::vector<float> all(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (spec.nchannels < 3 || !in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
    throw std::runtime_error(path.string() + ": cannot read the rendered image");
  image.rgb.reserve(static_cast<std::size_t>(spec.width) * spec.height * 3);
  for (std::size_t p = 0; p < all.size(); p += spec.nchannels)
    image.rgb.insert(image.rgb.end(), all.begin() + p, all.begin() + p + 3);
  return image;
}

}  // namespace toonwater::report
