// The image codec (image_codec.hpp) on OpenImageIO. Encodes into memory through an IOProxy
// instead of a file, so that the caller decides how the bytes reach the disk.
#include "images/image_codec.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>

namespace toonwater {
namespace {

void add_metadata(OIIO::ImageSpec& spec, const std::vector<ImageText>& metadata) {
  for (const ImageText& entry : metadata) spec.attribute(entry.name, entry.value);
}

std::string reason(const std::unique_ptr<OIIO::ImageOutput>& out) {
  return out ? out->geterror() : OIIO::geterror();
}

std::vector<unsigned char> encode_exr(const FloatPlanes& image,
                                      const std::vector<ImageText>& metadata,
                                      const std::string& compression) {
  const std::size_t channels = image.planes.size();
  OIIO::ImageSpec spec(image.width, image.height, static_cast<int>(channels),
                       OIIO::TypeDesc::FLOAT);
  spec.channelnames = image.names;
  spec.alpha_channel = image.alpha_channel;
  spec.attribute("compression", compression);
  add_metadata(spec, metadata);

  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create("openexr");
  bool ok = out && out->set_ioproxy(&memory) && out->open("memory.exr", spec);
  // Interleaved a band of rows at a time, so no second copy of the whole image is made.
  constexpr int band_rows = 32;
  std::vector<float> band(static_cast<std::size_t>(band_rows) * image.width * channels);
  for (int y0 = 0; ok && y0 < image.height; y0 += band_rows) {
    const int y1 = std::min(image.height, y0 + band_rows);
    const std::size_t first = static_cast<std::size_t>(y0) * image.width;
    const std::size_t count = static_cast<std::size_t>(y1 - y0) * image.width;
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t c = 0; c < channels; ++c)
        band[i * channels + c] = image.planes[c][first + i];
    ok = out->write_scanlines(y0, y1, 0, OIIO::TypeDesc::FLOAT, band.data());
  }
  if (!ok || !out->close()) throw std::runtime_error(reason(out));
  return bytes;
}

std::vector<unsigned char> encode_png(int width, int height, const std::uint8_t* rgb,
                                      const std::vector<ImageText>& metadata, int compression_level,
                                      int filter) {
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("png:compressionLevel", compression_level);
  spec.attribute("png:filter", filter);
  add_metadata(spec, metadata);
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create("png");
  if (!out || !out->set_ioproxy(&memory) || !out->open("memory.png", spec) ||
      !out->write_image(OIIO::TypeDesc::UINT8, rgb) || !out->close())
    throw std::runtime_error(reason(out));
  return bytes;
}

void draw_text(Rgb8Canvas canvas, int x, int baseline, const std::string& text, int size,
               const std::string& font, std::array<float, 3> colour, TextAlign align) {
  OIIO::ImageBuf buffer(OIIO::ImageSpec(canvas.width, canvas.height, 3, OIIO::TypeDesc::UINT8),
                        canvas.rgb);
  const auto align_x = align == TextAlign::left     ? OIIO::ImageBufAlgo::TextAlignX::Left
                       : align == TextAlign::centre ? OIIO::ImageBufAlgo::TextAlignX::Center
                                                    : OIIO::ImageBufAlgo::TextAlignX::Right;
  if (!OIIO::ImageBufAlgo::render_text(buffer, x, baseline, text, size, font, colour, align_x))
    throw std::runtime_error(buffer.geterror());
}

RgbFloatImage read_rgb(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error(OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels < 3) throw std::runtime_error("fewer than 3 channels");
  std::vector<float> all(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data()))
    throw std::runtime_error(in->geterror());
  RgbFloatImage image{spec.width, spec.height, {}};
  image.rgb.reserve(static_cast<std::size_t>(spec.width) * spec.height * 3);
  for (std::size_t p = 0; p < all.size(); p += spec.nchannels)
    image.rgb.insert(image.rgb.end(), all.begin() + p, all.begin() + p + 3);
  return image;
}

}  // namespace
}  // namespace toonwater

extern "C" __attribute__((visibility("default"))) const toonwater::ImageCodec*
toonwater_image_codec_entry() {
  static const toonwater::ImageCodec codec{toonwater::image_codec_interface_version,
                                           toonwater::encode_exr, toonwater::encode_png,
                                           toonwater::draw_text, toonwater::read_rgb};
  return &codec;
}
