// The image files toonwater writes and reads (curvature maps, rendered frames read back), behind
// an interface that does not include OpenImageIO. The codec only encodes, decodes and draws in
// memory; callers write the bytes themselves (write_file_atomically, atomic_file.hpp), so an
// OutputBatch covers images like every other output.
//
// Why an interface: OpenImageIO pulls in about 260 shared libraries, which cost the toonwater
// program about 0.17 s and 130 MB on every run, images or not. Its implementation
// (oiio_codec.cpp) is therefore built into the module toonwater-images.so, which the program
// loads from beside its executable on first use (image_module.cpp); a command that writes no image
// never loads it. Tests and benchmarks link the same implementation statically
// (toonwater_images_linked, linked_codec.cpp). A program links exactly one of the two, and
// image_codec() below is defined by whichever it links.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace toonwater {

// Metadata is all text: PNG keeps only text chunks, and one reader serves both formats.
struct ImageText {
  std::string name, value;
};

// width × height pixels, one row-major plane per channel.
struct FloatPlanes {
  int width = 0, height = 0;
  std::vector<std::string> names;
  std::vector<const float*> planes;
  int alpha_channel = -1;  // index into planes, or −1
};

// An 8-bit RGB image drawn on in place: row-major, 3 bytes a pixel.
struct Rgb8Canvas {
  int width = 0, height = 0;
  std::uint8_t* rgb = nullptr;
};

enum class TextAlign { left, centre, right };

struct RgbFloatImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, 3 channels in [0, 1] as encoded in the file
};

// Every function throws std::runtime_error with the library's reason on failure.
struct ImageCodec {
  int interface_version = 0;  // image_codec_interface_version of the code that built it
  // OpenEXR, float channels, with OpenEXR's compression by name ("rle", "zip", ...).
  std::vector<unsigned char> (*encode_exr)(const FloatPlanes& image,
                                           const std::vector<ImageText>& metadata,
                                           const std::string& compression) = nullptr;
  // 8-bit RGB PNG at zlib `compression_level` with libpng's row `filter` flags.
  std::vector<unsigned char> (*encode_png)(int width, int height, const std::uint8_t* rgb,
                                           const std::vector<ImageText>& metadata,
                                           int compression_level, int filter) = nullptr;
  // `text` in the TrueType `font` at `size` pixels, its baseline at row `baseline`, anchored at
  // column x as `align` says, in `colour` (linear 0..1 per channel).
  void (*draw_text)(Rgb8Canvas canvas, int x, int baseline, const std::string& text, int size,
                    const std::string& font, std::array<float, 3> colour,
                    TextAlign align) = nullptr;
  // The first three channels of any image file OpenImageIO reads.
  RgbFloatImage (*read_rgb)(const std::string& path) = nullptr;
};

inline constexpr int image_codec_interface_version = 1;

// The image module is missing or unusable: the installation is incomplete.
class ImageModuleError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The codec, loaded on first use. Throws ImageModuleError when it cannot be loaded.
const ImageCodec& image_codec();

}  // namespace toonwater

// The one symbol the module exports (and the static library defines).
extern "C" const toonwater::ImageCodec* toonwater_image_codec_entry();
